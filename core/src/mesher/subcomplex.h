// wqmesh: the subcomplex (private; paper, section 4): the vertices of V and
// where they lie, subsegments (of the edges of P, and the shield subsegments
// of the vertex balls, section 4.1), subfacets (the triangles of the planar
// Delaunay triangulation of V ∩ F that lie in F), the point SPLITE, SPLITF or
// ENCROACH decides to insert, and class Subcomplex, which keeps them as V
// grows and answers the encroachment tests of the rules.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <unordered_map>
#include <utility>
#include <vector>

#include "geometry.h"
#include "mesher/domain.h"
#include "mesher/protecting_balls.h"
#include "triangulation.h"
#include "wqmesh/types.h"

namespace wqmesh::mesher {

// The shared geometry (vectors, circumcenters) under the mesher's names.
using namespace geometry;

using Tri = std::array<int, 3>;

/// The key of the edge (subsegment) ab, the same for ba.
inline std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b);
}
inline Tri sorted(Tri t) {
  if (t[0] > t[1]) std::swap(t[0], t[1]);
  if (t[1] > t[2]) std::swap(t[1], t[2]);
  if (t[0] > t[1]) std::swap(t[0], t[1]);
  return t;
}
struct TriHash {
  std::size_t operator()(const Tri& t) const {
    std::uint64_t h = std::uint64_t(std::uint32_t(t[0])) * 0x9E3779B97F4A7C15ull;
    h ^= std::uint64_t(std::uint32_t(t[1])) + 0x632BE59BD9B4E019ull + (h << 6) + (h >> 2);
    h ^= std::uint64_t(std::uint32_t(t[2])) + 0x85157AF5ull + (h << 6) + (h >> 2);
    return std::size_t(h);
  }
};

/// A cell named by its sorted vertex ids.
using TetKey = std::array<int, 4>;
struct TetKeyHash {
  std::size_t operator()(const TetKey& t) const {
    std::uint64_t h = 1469598103934665603ull;
    for (int x : t) h = (h ^ std::uint64_t(std::uint32_t(x))) * 1099511628211ull;
    return std::size_t(h);
  }
};

// ---- Mesh vertices -------------------------------------------------------------
/// Where a vertex of V lies: on a vertex, edge or facet of P, or free (inside a
/// volume: circumcenters of tets).
enum class On : char { vertex, edge, facet, free };
struct MVertex {
  On on = On::free;
  int element = -1;  ///< P vertex, edge or facet index
  int sector = -1;   ///< on a vertex-ball arc (shield subsegment endpoint)
  int ball = -1;     ///< the sharp vertex u when the vertex lies on the sphere of û
};

// ---- Subsegments ---------------------------------------------------------------
/// A subsegment ab of a P edge, or a shield subsegment (a chord of a sector's
/// arc, sector >= 0, from a counter-clockwise to b, with the unit directions
/// da of a and db of b from the sector's center: Sector).
struct Subsegment {
  int a = -1, b = -1;
  int edge = -1;
  int sector = -1;
  Point3 da{{0, 0, 0}}, db{{0, 0, 0}};
  bool in_ball = false;  ///< inside a vertex ball: protected, never split
  bool sharp = false;    ///< on a sharp edge, outside the vertex balls
  /// A cell that held ab when its encroachment was last tested (a hint for
  /// RegularTriangulation::edge_ring, checked there before use; beyond the
  /// paper, issue 15: the O(1) way to the subsegment in Del V instead of a
  /// walk of the stars of its ends). Only a cache: never part of the answer.
  mutable CellRef cell = nullptr;
  /// Queues' record of the rule 1/4 test (beyond the paper, issue 15): the
  /// size of V when the subsegment was last queued and when it was last
  /// tested (0: never), and that test's answer. The answer depends only on
  /// the cells around ab, and every insertion that changes them queues ab
  /// (Queues::enqueue_around), so a test after the last queueing is still
  /// valid: the queue's repeats of ab cost a comparison.
  mutable std::uint32_t queued_at = 0, tested_at = 0;
  mutable bool encroached = false;
  /// Beyond the paper (issue 15): whether a vertex inserted since the last
  /// test, whose insertion queued ab, counts for ab's encroachment
  /// (Subcomplex::counts_for_segment), noted when it queued ab
  /// (Queues::queue) and cleared by the test. Every vertex that joined ab's
  /// ring since the test queued ab, so while this is false no new vertex of
  /// the ring lies in the ball (segment_encroached_update).
  mutable bool ball_entered = false;
};

/// A subfacet: a triangle of facet f's planar Delaunay triangulation lying in f.
struct Subfacet {
  int facet = -1;
  Tri v{{-1, -1, -1}};
};

/// A point to insert, as decided by SPLITE, SPLITF or ENCROACH.
struct Insertion {
  Point3 p{{0, 0, 0}};
  On on = On::free;
  int element = -1;
  std::uint64_t split_segment = 0;  ///< the subsegment it splits (if has_segment)
  bool has_segment = false;
  int sector = -1;
  Point3 dir{{0, 0, 0}};  ///< on a sector's arc: its unit direction from the center
  int ball = -1;
  int hint = -1;
  bool none = false;  ///< nothing to insert (see SPLITF in a vertex ball)
};

/// N(v): the distance from v to its nearest neighbour in Del V.
double nearest_neighbour(const RegularTriangulation& tri, int v);
/// N(v) of every vertex v of tri, in `out` (by id): the values
/// nearest_neighbour gives, bit for bit (the minimum of the same squared
/// lengths, then its root), from one pass over the cells, each of whose six
/// edges offers its length to both ends (beyond the paper, issue 15: a star
/// walk per vertex was 40% of PUMP on mpi.off). `poll`, when given, is
/// called with a count of cells every 1024 cells; when it returns false the
/// pass stops and returns false (`out` then incomplete).
bool nearest_neighbours(const RegularTriangulation& tri, std::vector<double>& out,
                        const std::function<bool(std::size_t)>& poll = {});

// ---- The subcomplex ------------------------------------------------------------
/// The subsegments (with the shield subsegments of each sector), the sectors,
/// and the planar triangulations of the facets whose triangles lying in the
/// facet are the subfacets; SPLITE, SPLITF (section 4.2), ENCROACH (section
/// 4.3) and the encroachment tests (section 4). It reads V (the triangulation
/// and where each vertex lies) and the protecting balls, which others own,
/// and changes only when told of a new vertex (insert_vertex) or feature.
class Subcomplex {
 public:
  Subcomplex(const Domain& domain, const RegularTriangulation& tri, const std::vector<MVertex>& vertices,
             const ProtectingBalls& balls);

  // ---- building it (INITIALIZE) and keeping it as V grows ----
  /// Adds subsegment s; returns its key (to be queued for rules 1 and 4).
  std::uint64_t add_segment(const Subsegment& s);
  /// Adds sector s of the vertex ball of u (section 4.1); returns its id.
  int add_sector(int u, const Sector& s);
  /// Vertex id joined V (its MVertex is vertices[id]): the subsegment
  /// ins.split_segment, if any, is split at it, and id joins the planar
  /// triangulations of its facets. `new_segments` gets the keys of the two
  /// halves (to be queued), in order.
  void insert_vertex(int id, const Insertion& ins, std::vector<std::uint64_t>& new_segments);
  /// V is final (REFINE is done; PUMP changes weights only, and the planar
  /// triangulations depend on the points alone): keeps the subfacets as a
  /// list and frees the facets' planar triangulations (issue 15, the peak
  /// memory: about 56 bytes per output tet beside V's triangulation through
  /// PUMP and the extraction). Afterwards subfacets() and conforms() answer
  /// as before; insert_vertex, facet_triangulation, subfacets_at and
  /// is_subfacet (so SPLITF, ENCROACH and the encroachment tests of
  /// subfacets) throw std::logic_error. Tests check frozen().
  void freeze();
  bool frozen() const { return frozen_; }

  // ---- what it holds ----
  const std::unordered_map<std::uint64_t, Subsegment>& subsegments() const { return segs_; }
  const Subsegment& subsegment(std::uint64_t key) const { return segs_.at(key); }
  /// The keys of the subsegments with endpoint v.
  const std::vector<std::uint64_t>& subsegments_at(int v) const { return vertex_segs_[v]; }
  const Sector& sector(int sid) const { return sectors_[sid]; }
  /// Facet f's planar Delaunay triangulation of V ∩ f.
  const PlanarDelaunay& facet_triangulation(int f) const { return live_facet_dt(f); }
  std::vector<Subfacet> subfacets() const;
  /// The facets of P holding vertex v.
  void facets_of(int v, std::vector<int>& out) const;
  /// Whether v (kInfinite allowed) lies on a vertex, edge or facet of P: only
  /// such vertices join the facets' planar triangulations (insert_vertex
  /// puts a vertex into the facets facets_of gives it, none for a free one)
  /// and end subsegments, so a triangle or edge with another vertex is no
  /// subfacet or subsegment, without a look-up.
  /// Read from a byte per vertex kept beside V (issue 15: the MVertex list is
  /// 32 bytes a vertex, and this test runs on every vertex of every conflict
  /// zone and ring: a cache miss each).
  bool on_p(int v) const { return (p_marks(v) & kOnP) != 0; }
  /// False only when ab is no subsegment; true when it is one, and also when
  /// a has more than two subsegments (then only the map can tell). a must
  /// be a vertex of V (inserted: insert_vertex). O(1): a read of a's record
  /// of the other ends of its subsegments (beyond the paper, issue 15: more
  /// than half of ENCROACH's look-ups of edges between ends of subsegments
  /// missed the map).
  bool may_be_subsegment(int a, int b) const {
    const std::array<int, 2>& r = segment_ends_[a];
    return r[0] == b || r[1] == b || r[0] == kManySegments;
  }
  /// Appends the triangles (sorted) of cells whose vertices are all on P
  /// (on_p), and the edges (edge_key) whose two ends each end a subsegment
  /// (now or before: a mark set by add_segment and never cleared) and that
  /// may_be_subsegment lets through: a superset of the subfacets and
  /// subsegments among them (issue 15: most edges and triangles of a refined
  /// mesh are left out before any look-up, and the edges between vertices
  /// inside a facet too, most of those on P, and the edges between two
  /// subsegments' ends that are none). Unsorted, with repeats.
  void on_p_features(const std::vector<Tet>& cells, std::vector<std::uint64_t>& edges, std::vector<Tri>& tris) const;
  /// The subfacets of facet f at vertex v.
  void subfacets_at(int f, int v, std::vector<Tri>& out) const;
  bool is_subfacet(int f, const Tri& t) const;
  bool lies_in_facet(int f, const Tri& t) const;
  /// All four vertices on one input facet: a flat tet lying in the facet
  /// (rounding of the points inserted on it), inside neither region.
  bool flat_on_facet(const Tet& t) const;

  // ---- the procedures and tests of the rules ----
  Insertion splite(const Subsegment& e) const;
  Insertion splitf(const Subfacet& h) const;
  /// The point ENCROACH (section 4.3) returns for c.
  /// `start`, when given, is a cell whose circumsphere may hold c (rule 6:
  /// the tet whose circumcenter c is), where the search of the cells c
  /// conflicts with starts without a point location; same answer.
  Insertion encroach(const Point3& c, int hint, CellRef start = nullptr) const;
  bool segment_encroached(const Subsegment& e) const;  ///< by a vertex of V (on or inside)
  /// Whether vertex x, were it in the ring of e's edge, would make
  /// segment_encroached(e) true: x lies on or inside e's diametric ball and
  /// not on the sphere of the vertex ball e is a shield subsegment of (the
  /// choice segment_encroached explains). O(1); false for an e in a ball.
  bool counts_for_segment(const Subsegment& e, int x) const;
  /// segment_encroached(e), from e's record of its last test (tested_at,
  /// encroached, ball_entered) when that said "not encroached" and no vertex
  /// that queued e since counts for it: then only the edge's presence is
  /// tested (beyond the paper, issue 15; see subcomplex.cpp). The record must
  /// be of a test of this V with only insertions since (CONFORM and REFINE:
  /// V grows by unweighted insertions, none hidden), each of which noted
  /// itself in ball_entered when it queued e (Queues::queue).
  bool segment_encroached_update(const Subsegment& e) const;
  bool subfacet_present(const Subfacet& h) const;
  /// By a vertex (strictly inside its diametric ball), or missing from Del
  /// V; `missing`, when given, says which.
  bool subfacet_encroached(const Subfacet& h, bool* missing = nullptr) const;
  /// Subsegments and subfacets encroached by a point, among the features of
  /// the cells the point conflicts with (see the argument in subcomplex.cpp).
  /// `zone`, when given, gets the finite vertices of those cells (sorted,
  /// no repeats; Conform's rule 3 records them).
  /// `keep`: also keep the zone's features for the upkeep of c's insertion
  /// (zone_features; ENCROACH's call); same answers.
  void encroached_by_point(const Point3& c, int hint, std::vector<std::uint64_t>& segs, std::vector<Subfacet>& facets,
                           CellRef start = nullptr, std::vector<int>* zone = nullptr, bool keep = false) const;
  /// The features of the zone ENCROACH last searched, kept for the upkeep
  /// of the free insertion of its point (beyond the paper, issue 15: the
  /// same zone's edges and triangles were read, sorted and looked up again
  /// by Queues::enqueue_from_cavity): the subsegments among the zone's edges
  /// in key order, and its triangles with every vertex on P that some facet
  /// of P holds whole, sorted, without repeats.
  struct ZoneFeatures {
    std::vector<const Subsegment*> segments;
    std::vector<Tri> tris;
  };
  /// zone_features(p, cavity) when `cavity` is the cavity of the insertion
  /// of p just made (RegularTriangulation::last_cavity) and ENCROACH's last
  /// search was of p's zone in V before that insertion, with no other
  /// search since: then the cavity is that zone and these are its features
  /// (a free insertion changes no subsegment). Else nullptr.
  const ZoneFeatures* zone_features(const Point3& p, const std::vector<Tet>& cavity) const;
  /// A subfacet whose diametric ball lies inside a protecting ball.
  bool guarded(const Subfacet& h) const;
  /// Whether every subsegment and subfacet is in the triangulation.
  bool conforms() const;

 private:
  std::vector<std::uint64_t> shield_keys(int sector) const;
  /// facet_dt_[f]; throws std::logic_error after freeze().
  const PlanarDelaunay& live_facet_dt(int f) const;
  bool on_one_edge(int v, int e) const;  ///< v lies on edge e of P (or is an endpoint)

  const Domain& dom_;
  const RegularTriangulation& tri_;
  const std::vector<MVertex>& verts_;
  const ProtectingBalls& balls_;
  std::unordered_map<std::uint64_t, Subsegment> segs_;
  std::vector<std::vector<std::uint64_t>> vertex_segs_;
  /// By vertex id: kOnP when verts_[id].on != On::free (on_p), kEndsSegment
  /// once id ends a subsegment (add_segment; on_p_features).
  std::vector<char> on_p_;
  static constexpr char kOnP = 1, kEndsSegment = 2;
  /// By vertex id: the other ends of its subsegments (vertex_segs_) when it
  /// has at most two (-1 in the unused places), else {kManySegments, -1}
  /// (may_be_subsegment). Set from vertex_segs_ whenever that changes
  /// (note_segment_ends).
  std::vector<std::array<int, 2>> segment_ends_;
  static constexpr int kManySegments = -2;
  void note_segment_ends(int v);
  char p_marks(int v) const {
    if (static_cast<std::size_t>(v) < on_p_.size()) return on_p_[v];
    return v >= 0 && verts_[v].on != On::free ? kOnP : 0;  // (not yet inserted: ends no subsegment)
  }
  /// encroached_by_point's working storage, kept across calls so that a call
  /// allocates nothing once the vectors have grown (issue 15). Not
  /// reentrant: one Subcomplex serves one run on one thread.
  struct EncroachScratch {
    std::vector<Tet> cells;
    std::vector<std::uint64_t> edges;
    std::vector<Tri> tris;
    std::vector<Tri> hits;
    std::vector<int> f0, f1, f2, fs;
  };
  mutable EncroachScratch scratch_;
  /// encroached_by_point's kept zone (keep): its point, the size of V and
  /// the number of cells then (vertices -1: none kept).
  mutable ZoneFeatures zone_features_;
  mutable Point3 zone_point_{{0, 0, 0}};
  mutable int zone_vertices_ = -1;
  mutable std::size_t zone_cells_ = 0;
  std::vector<std::vector<std::uint64_t>> sector_segs_;  ///< shield subsegments per sector
  std::vector<PlanarDelaunay> facet_dt_;
  bool frozen_ = false;
  std::vector<Subfacet> frozen_subfacets_;  ///< subfacets() at freeze()
  std::vector<Sector> sectors_;
  std::vector<std::vector<int>> vertex_sectors_;  ///< per P vertex
};

}  // namespace wqmesh::mesher
