// wqmesh: the work queues of CONFORM and REFINE (private; paper, section
// 4.3): the subsegments, subfacets and tets that rules 1-2 (CONFORM) and 4-6
// (REFINE) may have to split, filled around every inserted vertex, and the
// loop that applies the queued rules in priority order (queues.cpp).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <functional>
#include <unordered_map>
#include <utility>
#include <vector>

#include "mesher/domain.h"
#include "mesher/rules.h"
#include "mesher/subcomplex.h"
#include "mesher/work_meter.h"
#include "triangulation.h"

namespace wqmesh::mesher {

class Inserter;

class Queues {
 public:
  Queues(const Domain& domain, const RegularTriangulation& tri, const Subcomplex& sub, WorkMeter& meter)
      : dom_(domain), tri_(tri), sub_(sub), meter_(meter) {}

  /// Queues subsegment k (rules 1 and 4).
  void push_segment(std::uint64_t k);
  /// Queues tet t again (rule 6).
  void push_tet(const Tet& t, CellRef ref) { tets_.push_back({t, ref}); }
  /// The start of CONFORM (and, with the tets, of REFINE): every subsegment,
  /// in key order, and every subfacet; with `tets`, every finite cell.
  void fill(bool tets);
  /// The upkeep of an insertion: queues the features and (in REFINE) the
  /// cells around the new vertex v that a rule may have to split.
  void enqueue_around(int v);
  /// Rule 5: a non-guarded subfacet that is encroached, or a guarded one that
  /// does not appear in Del V.
  bool rule5_needs_split(const Subfacet& h) const;
  /// Rule 6 for a queued tet; whether a point was inserted (refine.cpp).
  using Rule6 = std::function<bool(const Tet& t, CellRef ref)>;
  /// Applies the queued rules until the queues are empty: rules 1-2, or with
  /// `rule6` (REFINE) rules 4-6, each only when no smaller one applies.
  /// Inserts through `inserter`. False if the run stopped.
  bool process(Inserter& inserter, const Rule6& rule6 = {});
  /// A feature (a subfacet, or a tet by three of its vertices) whose split
  /// was deferred to another: whether it may be looked at again (at most
  /// Caps::kRetries times; past that the cap is counted).
  bool may_retry(const Tri& t);
  /// Rule 7's record of its last pass (Refine::rule7_pass; beyond the paper,
  /// issue 15): every finite cell of V's triangulation whose smallest
  /// dihedral angle was at most theta when the record was last updated, with
  /// its CellRef and that angle (tet_min_dihedral_deg_upto's double, bound
  /// theta), whatever its label; and the number of vertices then. Kept here,
  /// beside rule 6's queue of tets, from one pass to the next.
  struct SliverRecord {
    struct Cell {
      Tet t;
      CellRef ref;
      double angle;
    };
    std::vector<Cell> cells;
    int vertices = 0;
    bool valid = false;  ///< updated, and V only grew by insertions since
    /// Brings the record up to date with `tri` and appends (angle, v) to
    /// `candidates` for each vertex v of every recorded cell labelled 1 (the
    /// labels in the cells must be set: label_cells_in_place). The same
    /// record and candidates (as multisets) as a read of every cell; when
    /// `valid`, reads only the recorded cells that live on and the stars of
    /// the vertices inserted since (queues.cpp says why that is enough),
    /// which needs V to have changed by unhidden insertions only since the
    /// last update (REFINE). `poll` (as a phase's scan) may stop it: false,
    /// and the record is then invalid.
    bool update(const RegularTriangulation& tri, double theta_deg, std::vector<std::pair<double, int>>& candidates,
                const std::function<bool(std::size_t)>& poll);
    /// Forgets the cells and frees their memory (valid = false).
    void clear() { *this = SliverRecord{}; }
  };
  SliverRecord& sliver_record() { return sliver_record_; }

 private:
  /// Rules 1 and 4: SPLITE of the queued subsegment k if it is encroached.
  void split_encroached_subsegment(Inserter& inserter, std::uint64_t k, Rule rule);
  /// Rule 2: a subfacet of B that is encroached, or one of the input that does
  /// not appear in Del V.
  bool rule2_needs_split(const Subfacet& h) const;
  /// SPLITF(h) for rule 2 or 5; h is queued again when SPLITF split a
  /// subsegment instead (at most Caps::kRetries times).
  void split_subfacet(Inserter& inserter, const Subfacet& h, Rule rule);

  const Domain& dom_;
  const RegularTriangulation& tri_;
  const Subcomplex& sub_;
  WorkMeter& meter_;
  std::deque<std::uint64_t> segments_;  ///< rules 1 and 4
  SliverRecord sliver_record_;
  /// A queued subfacet and `facet_size`, the number of vertices of its
  /// facet's planar triangulation when it was queued as one of that
  /// triangulation's subfacets (kUnknownSize when not known to be one then).
  /// Beyond the paper (issue 15): vertices only join a planar triangulation
  /// (a point already there changes nothing), so while that number is the
  /// same the triangulation is the same and the triangle is still a
  /// subfacet, without is_subfacet's walk when it is taken off the queue.
  struct QueuedSubfacet {
    Subfacet h;
    std::size_t facet_size;
  };
  static constexpr std::size_t kUnknownSize = static_cast<std::size_t>(-1);
  /// Queues h, a subfacet of its facet's planar triangulation as it is now.
  void queue_subfacet(const Subfacet& h);
  std::deque<QueuedSubfacet> subfacets_;      ///< rules 2 and 5
  std::deque<std::pair<Tet, CellRef>> tets_;  ///< rule 6
  /// How often a subfacet (or a tet, by three of its vertices) was looked at
  /// again after its split was deferred to another feature; bounded by
  /// Caps::kRetries so that no feature keeps the refinement busy forever.
  std::unordered_map<Tri, int, TriHash> retries_;
  /// enqueue_around's ring of the new vertex, and its marks by vertex id
  /// (== stamp_ for the vertices of the current ring).
  /// Queues subsegment s under its key k, noting when (Subsegment::queued_at)
  /// and, when `by` is the vertex whose insertion queues it (-1: none, as at
  /// the start of a phase and for a new subsegment), whether that vertex
  /// counts for its encroachment (Subsegment::ball_entered).
  void queue(std::uint64_t k, const Subsegment& s, int by);
  /// enqueue_around for a free vertex v inserted in REFINE whose cavity (the
  /// cells it destroyed) is known: the features are read from the cavity
  /// instead of the ring (queues.cpp says why that suffices).
  void enqueue_from_cavity(int v, const std::vector<Tet>& cavity);
  /// Rule 6's queue gets the finite cells of `cells` (with their refs).
  void queue_finite_cells(const std::vector<Tet>& cells, const std::vector<CellRef>& refs);
  /// enqueue_around and enqueue_from_cavity walk a facet vertex's whole star
  /// only when it holds at most kFan triangles (a long fan's apex otherwise).
  static constexpr std::size_t kFan = 48;
  std::vector<std::uint64_t> cavity_edges_;  ///< enqueue_from_cavity's buffers
  std::vector<Tri> cavity_tris_;
  std::vector<const Subsegment*> cavity_segs_;  ///< the subsegments found, by the keys' order
  std::vector<Subfacet> cavity_subfacets_;
  std::vector<std::pair<std::array<int, 3>, std::size_t>> cavity_order_;  ///< (ring walk's order, index)
  std::vector<int> ring_;
  // enqueue_around's other buffers, kept from call to call (issue 15).
  std::vector<Tet> star_;
  std::vector<CellRef> star_refs_;
  std::vector<Tri> seen_, around_, pair_;
  std::vector<int> fs_, f1_, f2_;
  std::vector<std::pair<int, int>> ring_facets_;      ///< (ring vertex, facet)
  std::vector<std::pair<int, int>> ring_facet_list_;  ///< (facet, ring vertex), sorted
  std::vector<unsigned> ring_mark_;
  unsigned stamp_ = 0;
};

}  // namespace wqmesh::mesher
