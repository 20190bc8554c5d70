// wqmesh: the state shared by the phases of WQMESH (private).
//
// Vocabulary of the paper (section 4): P is the input PLC together with the
// bounding box B; V the vertex set, kept in a RegularTriangulation whose
// weights stay 0 until PUMP; the edges of P are divided into subsegments, the
// arcs of the vertex balls into shield subsegments (section 4.1); the facets
// of P into subfacets, the triangles of the planar Delaunay triangulation of
// V ∩ F that lie in F.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <functional>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "triangulation.h"
#include "wqmesh/analysis.h"
#include "wqmesh/mesher.h"
#include "wqmesh/types.h"

namespace wqmesh::mesher {

using Tri = std::array<int, 3>;

// ---- Small vector helpers ----------------------------------------------------
inline Point3 sub(const Point3& a, const Point3& b) { return {{a[0] - b[0], a[1] - b[1], a[2] - b[2]}}; }
inline Point3 add(const Point3& a, const Point3& b) { return {{a[0] + b[0], a[1] + b[1], a[2] + b[2]}}; }
inline Point3 mul(const Point3& a, double s) { return {{a[0] * s, a[1] * s, a[2] * s}}; }
inline double dot(const Point3& a, const Point3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Point3 cross(const Point3& a, const Point3& b) {
  return {{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}};
}
inline double dist2(const Point3& a, const Point3& b) { return dot(sub(a, b), sub(a, b)); }
inline Point3 midpoint(const Point3& a, const Point3& b) {
  return {{0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.5 * (a[2] + b[2])}};
}
/// Circumcenter of triangle abc (in its plane) and the squared circumradius.
Point3 circumcenter(const Point3& a, const Point3& b, const Point3& c, double& r2);
/// Circumcenter of tet abcd and the squared circumradius (r2 = inf if flat).
Point3 circumcenter(const Point3& a, const Point3& b, const Point3& c, const Point3& d, double& r2);

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

// ---- Shield sectors (section 4.1) ----------------------------------------------
/// The sector of facet `facet` at sharp vertex u inside the vertex ball:
/// points u + r (cos t e1 + sin t e2), t in [0, span], t = 0 on the first
/// edge of the sector, t = span on the second.
struct Sector {
  int u = -1, facet = -1;
  Point3 center, e1, e2;
  double r = 0, span = 0;
  Point3 at(double t) const;
};

// ---- P: the input PLC with the bounding box B (section 2) --------------------
struct Domain {
  PLC p;  ///< input elements first, then B's 8 vertices, 12 edges, 6 facets
  int input_vertices = 0, input_edges = 0, input_facets = 0;
  std::vector<std::vector<int>> vertex_facets;  ///< facets whose loops hold a P vertex
  std::vector<std::vector<int>> vertex_edges;
  std::vector<char> sharp_vertex, sharp_edge;
  std::vector<double> ball_radius;  ///< f(u)/4 at sharp vertices, else 0
  struct Frame {
    Point3 origin, e1, e2, n;
    std::vector<std::vector<std::array<double, 2>>> loops;  ///< 2D loops
  };
  std::vector<Frame> frames;  ///< per facet
  Box box;                    ///< B
  Box input_box;

  Domain(const PLC& plc, const Analysis& analysis);
  bool is_box_facet(int f) const { return f >= input_facets; }
  std::array<double, 2> to2d(int f, const Point3& x) const;
  /// Whether x (projected on the plane of facet f) lies inside f (even-odd rule
  /// over its loops).
  bool inside_facet(int f, const Point3& x) const;
  bool facet_has_vertex(int f, int v) const;
  /// The sector of facet f at the sharp vertex u, whose loop runs prev, u,
  /// next: it turns counter-clockwise about the facet normal from the edge
  /// u-next (t = 0) to the edge u-prev (t = span), inside the vertex ball.
  Sector sector(int u, int f, int prev, int next) const;
  /// Calls fn(f, prev, next) for every corner at u of a loop of a facet at
  /// u (one per sector), in the order INITIALIZE makes the shield
  /// subsegments; initialize_points counts along the same walk.
  template <class F>
  void for_each_corner(int u, F&& fn) const {
    for (int f : vertex_facets[u])
      for (const auto& loop : p.facets[f].loops)
        for (std::size_t i = 0, m = loop.size(); i < m; ++i)
          if (loop[i] == u) fn(f, loop[(i + m - 1) % m], loop[(i + 1) % m]);
  }
  /// The number of vertices INITIALIZE inserts (section 4.1): the vertices of
  /// P and B, one ball point per edge end at a sharp vertex, and one SOS split
  /// per sector of angle pi or more. Known before meshing, so a vertex limit
  /// below it is refused at once.
  std::size_t initialize_points() const;
};

// ---- Mesh vertices -------------------------------------------------------------
/// Where a vertex of V lies: on a vertex, edge or facet of P, or free (inside a
/// volume: circumcenters of tets).
enum class On : char { vertex, edge, facet, free };
struct MVertex {
  On on = On::free;
  int element = -1;  ///< P vertex, edge or facet index
  int sector = -1;   ///< on a vertex-ball arc (shield subsegment endpoint)
  double angle = 0;  ///< its angle on that arc
  int ball = -1;     ///< the sharp vertex u when the vertex lies on the sphere of û
};

// ---- Subsegments ---------------------------------------------------------------
/// A subsegment ab of a P edge, or a shield subsegment (a chord of a sector's
/// arc, sector >= 0, with the arc angles ta of a and tb of b).
struct Subsegment {
  int a = -1, b = -1;
  int edge = -1;
  int sector = -1;
  double ta = 0, tb = 0;
  bool in_ball = false;  ///< inside a vertex ball: protected, never split
  bool sharp = false;    ///< on a sharp edge, outside the vertex balls
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
  double angle = 0;
  int ball = -1;
  int hint = -1;
  bool none = false;  ///< nothing to insert (see SPLITF in a vertex ball)
};

enum class Phase { initialize, conform, refine, pump, done };

class Mesher {
 public:
  Mesher(const Domain& domain, const MeshOptions& options, const ProgressCallback& progress);

  // ---- phases (one file each) ----
  void initialize();  ///< protection.cpp (section 4.1)
  void conform();     ///< refinement.cpp, rules 1-3
  void refine();      ///< refinement.cpp, rules 4-7
  void pump();        ///< pump.cpp
  MeshResult extract();  ///< mesher.cpp: interior tets, classes, statistics

  bool stopped() const { return !stop_reason_.empty(); }
  void cancel() {
    if (stop_reason_.empty()) stop_reason_ = "cancelled";
  }
  const std::string& stop_reason() const { return stop_reason_; }
  /// Why the run stopped in words, when the mesher knows (for "stalled").
  const std::string& stop_message() const { return stop_message_; }

  // ---- stops that reach every step (beyond the paper, issue 10) ----
  // Work is counted in units: one per queue element looked at, per cell of
  // an inserted vertex's star, per feature or walk of an insertion's upkeep,
  // per cell of a PUMP weight change, per element of a whole-mesh scan. Every
  // unit is bounded by the size of a star (see the loop bounds in
  // triangulation.cpp). poll() counts units, and at least every kPollWork
  // units (and every 256 steps) calls the progress callback, so that a
  // cancel, the vertex limit or the memory cap (the wasm callback) takes
  // effect within kPollWork units whatever the mesher does.
  static constexpr std::uint64_t kPollWork = 256;
  /// Counts `units` of work; `in_step`: work of the current step (a step is
  /// one insertion with its upkeep, one queue element, one rule-3 or rule-7
  /// candidate, one PUMP vertex), which the watchdog bounds: a step past
  /// MeshOptions::stall_work units ends the run with stopped = "stalled".
  /// Whole-mesh scans count with in_step = false (they are bounded by the
  /// mesh's size). Returns false once the run must stop. Never throws, unless
  /// the progress callback does (the wasm memory cap): it is never called
  /// from inside a CGAL insertion.
  bool poll(std::uint64_t units, bool in_step = true);
  /// INITIALIZE's insertions are steps too: polls, and says whether the
  /// run was cancelled or stalled (INITIALIZE then ends early; the vertex
  /// limit never stops it: a limit below its count is refused beforehand).
  bool interrupted() {
    step_done();
    poll(1);
    return !stop_reason_.empty() && stop_reason_ != "limit";
  }
  /// A step ended: the watchdog starts again.
  void step_done() { step_work_ = 0; }
  std::uint64_t work() const { return work_; }
  std::vector<PhaseStats> phases;
  std::size_t slivers_before_pump = 0, pumped_vertices = 0;
  /// How many points each rule (1..7) inserted; [0]: INITIALIZE.
  std::array<std::size_t, 8> rule_count{};

  // ---- exposed for tests ----
  const RegularTriangulation& triangulation() const { return tri_; }
  const std::vector<MVertex>& vertices() const { return verts_; }
  const std::unordered_map<std::uint64_t, Subsegment>& subsegments() const { return segs_; }
  const std::vector<ProtectingBall>& protecting_balls() const { return balls_; }
  std::vector<Subfacet> subfacets() const;
  /// The point ENCROACH (section 4.3) returns for c.
  Insertion encroach(const Point3& c, int hint);
  /// Whether every subsegment and subfacet is in the triangulation.
  bool conforms() const;
  /// Inserts a point; returns its id or -1 when nothing was inserted.
  int insert(const Insertion& ins);
  int insert(const Insertion& ins, int rule) {
    const int id = insert(ins);
    if (id >= 0) ++rule_count[rule];
    if (trace_) trace(ins, rule, id);
    if (observer) observer(ins, rule, id);
    return id;
  }
  /// Called after every insertion by a rule (tests watch the rules with it).
  std::function<void(const Insertion&, int rule, int id)> observer;
  /// With WQMESH_TRACE set in the environment, every insertion is printed on
  /// stderr (rule, where, the subsegment split): a tool for developers.
  void trace(const Insertion& ins, int rule, int id) const;

 private:
  // subcomplex.cpp: subsegments, subfacets, SPLITE, SPLITF, encroachment.
  void add_segment(const Subsegment& s);
  std::vector<std::uint64_t> shield_keys(int sector) const;
  int edge_between(int u, int w) const;
  Insertion splite(const Subsegment& e) const;
  Insertion splitf(const Subfacet& h);
  bool segment_encroached(const Subsegment& e) const;  ///< by a vertex of V (on or inside)
  bool subfacet_present(const Subfacet& h) const;
  bool subfacet_encroached(const Subfacet& h) const;  ///< by a vertex (strictly inside)
  bool is_subfacet(int f, const Tri& t) const;
  bool lies_in_facet(int f, const Tri& t) const;
  bool on_one_edge(int v, int e) const;  ///< v lies on edge e of P (or is an endpoint)
  void subfacets_at(int f, int v, std::vector<Tri>& out) const;
  void facets_of(int v, std::vector<int>& out) const;
  /// Subsegments and subfacets encroached by a point, among the features of
  /// the cells the point conflicts with (see the argument in subcomplex.cpp).
  void encroached_by_point(const Point3& c, int hint, std::vector<std::uint64_t>& segs,
                           std::vector<Subfacet>& facets) const;
  bool guarded(const Subfacet& h) const;
  /// All four vertices on one input facet: a flat tet lying in the facet
  /// (rounding of the points inserted on it), inside neither region.
  bool flat_on_facet(const Tet& t) const;
  bool in_protecting_ball(const Point3& x) const;  ///< on or inside
  /// |v - c|^2 <= (2r)^2 + w for some protecting ball (c, r).
  bool encroaches_expanded_ball(const Point3& v, double w) const;
  double nearest_neighbour(int v) const;

  // refinement.cpp
  void enqueue_around(int v);
  bool process_queues(bool refine_phase);  ///< rules 1-2 / 4-6; false if stopped
  bool rule3();
  /// With max_size: splits sharp subsegments longer than 2/3 max_size before
  /// the protecting balls are fixed; false if stopped.
  bool split_long_sharp_subsegments();
  bool rule7_pass();
  bool check_tet(const Tet& t, CellRef ref);
  void make_protecting_balls();  ///< end of CONFORM (section 4.3)
  /// A step (an insertion by a rule, a PUMP vertex) is done: counts it, ends
  /// the watchdog's step, polls (a progress call at least every 256 steps).
  /// False once the run must stop.
  bool tick();
  /// 1 for the cells of g inside the polyhedron. `scan`: poll while
  /// labelling (a phase's scan); the labels are then unusable if it stops.
  std::vector<char> interior_labels(const RegularTriangulation::CellGraph& g, bool scan = false);
  /// cell_graph() polling every kPollWork cells (a phase's scan); empty if
  /// the run stops meanwhile.
  RegularTriangulation::CellGraph scan_cell_graph();

  const Domain& dom_;
  const MeshOptions& opt_;
  const ProgressCallback& progress_;
  RegularTriangulation tri_;
  std::vector<MVertex> verts_;
  std::unordered_map<std::uint64_t, Subsegment> segs_;
  std::vector<std::vector<std::uint64_t>> vertex_segs_;
  std::vector<std::vector<std::uint64_t>> sector_segs_;  ///< shield subsegments per sector
  std::vector<PlanarDelaunay> facet_dt_;
  std::vector<Sector> sectors_;
  std::vector<std::vector<int>> vertex_sectors_;  ///< per P vertex
  std::vector<ProtectingBall> balls_;
  // A uniform grid over the two-times expansions of the protecting balls.
  double ball_cell_ = 1;
  std::unordered_map<std::uint64_t, std::vector<int>> ball_grid_;
  void index_balls();
  template <class F>
  void for_balls_near(const Point3& x, double reach, F&& f) const;
  std::vector<double> nn_;  ///< N(v) at the end of REFINE
  Phase phase_ = Phase::initialize;
  bool trace_ = false;
  bool protecting_ = false;  ///< protecting balls exist (REFINE)
  std::deque<std::uint64_t> seg_queue_;
  std::deque<Subfacet> facet_queue_;
  std::deque<std::pair<Tet, CellRef>> tet_queue_;
  std::size_t inserted_ = 0, steps_ = 0;
  std::uint64_t work_ = 0, next_poll_ = kPollWork, step_work_ = 0;
  void report_progress();
  /// How often a subfacet (or a tet, by three of its vertices) was looked at
  /// again after its split was deferred to another feature; bounded by
  /// kRetries so that no feature keeps the refinement busy forever.
  std::unordered_map<Tri, int, TriHash> retries_;
  static constexpr int kRetries = 16;
  std::string stop_reason_, stop_message_;
  friend class Pump;
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

/// PUMP (pump.cpp): the inside/outside labels of cells kept as the weighted
/// triangulation changes, the walls (input subfacets) and, per vertex, the
/// subfacets whose presence must be kept.
class Pump {
 public:
  explicit Pump(Mesher& m);
  /// N(v) for every vertex, cell labels, walls. Called by run().
  void prepare();
  void run();
  /// (smallest dihedral, vertex) for the vertices of inside tets with a
  /// dihedral angle <= theta, worst first, as found by prepare().
  std::vector<std::pair<double, int>> candidates() const;
  /// N(v)^2/9.
  double weight_bound(int v) const;

  struct Features {
    std::vector<std::uint64_t> segments;
    std::vector<Tri> subfacets;
  };
  /// The features whose presence a weight change of v must keep.
  Features features_around(int v) const;
  /// Sets v's weight to w; returns the smallest dihedral angle of the inside
  /// tets around v, or -1 when w hides v or removes one of `f`.
  double evaluate(int v, double w, const Features& f);

  struct Choice {
    double weight = 0, quality = -1, base = -1;
  };
  /// Chooses, and sets, the weight of v in [0, N(v)^2/9] maximising the
  /// smallest dihedral angle around v, searching the interval at its critical
  /// weights; keeps the old weight unless the new one is strictly better.
  Choice pump_vertex(int v);

 private:
  double angle_of(const Tet& t) const;
  bool is_wall(int a, int b, int c) const;
  char label(const Tet& t);
  double next_critical(int v, double w, double cap) const;
  bool present(const Features& f) const;

  Mesher& m_;
  RegularTriangulation& tri_;
  std::unordered_map<TetKey, char, TetKeyHash> labels_;
  std::unordered_set<Tri, TriHash> walls_;
  std::vector<std::vector<Tri>> vertex_facets_;
  std::vector<std::pair<double, int>> candidates_;
};

}  // namespace wqmesh::mesher
