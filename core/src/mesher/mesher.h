// wqmesh: the state WQMESH keeps while it runs (private; paper, section 4.3):
// the vertex set V in a RegularTriangulation (weights 0 until PUMP), the
// subcomplex (subsegments, subfacets in the facets' planar triangulations),
// the protecting balls and the work queues. Each phase has its own file:
//   initialize.cpp  INITIALIZE (section 4.1)
//   conform.cpp     CONFORM: rules 1-3, then the protecting balls
//   refine.cpp      REFINE: rules 4-7 (6: rule6_split_skinny_tet, 7: rule7_pass)
//   pump.cpp        PUMP (class Pump, pump.h)
// and the pieces they share: subcomplex.cpp (insertion into V, encroachment,
// SPLITE, SPLITF, ENCROACH), queues.cpp (the queued rules 1-2 and 4-6),
// protecting_balls.cpp, extract.cpp (the tets inside), mesher.cpp (steps,
// work units, progress) and mesh_polyhedron.cpp (WQMESH(P): the phases in
// order).
// docs/paper-map.md maps every rule and procedure to its function.
//
// Vocabulary of the paper (section 4): P is the input PLC together with the
// bounding box B (domain.h); V the vertex set; the edges of P are divided into
// subsegments, the arcs of the vertex balls into shield subsegments (section
// 4.1); the facets of P into subfacets (subcomplex.h).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <functional>
#include <string>
#include <unordered_map>
#include <vector>

#include "geometry.h"
#include "mesher/domain.h"
#include "mesher/protecting_balls.h"
#include "mesher/rules.h"
#include "mesher/subcomplex.h"
#include "triangulation.h"
#include "wqmesh/analysis.h"
#include "wqmesh/mesher.h"
#include "wqmesh/types.h"

namespace wqmesh::mesher {

// The shared geometry (vectors, circumcenters) under the mesher's names.
using namespace geometry;

enum class Phase { initialize, conform, refine, pump, done };

/// The loop caps of the mesher (beyond the paper: each bounds a loop the
/// paper lets run to its end). Reaching one is counted in caps_reached.
struct Caps {
  /// Rule 3 passes in CONFORM, until one inserts nothing.
  static constexpr int kRule3Passes = 1000;
  /// Rule 7 passes in REFINE, until one inserts nothing.
  static constexpr int kRule7Passes = 100;
  /// Times a subfacet (or a tet, by three of its vertices) is looked at again
  /// after its split was deferred to another feature.
  static constexpr int kRetries = 16;
};

/// The work queues of CONFORM and REFINE (queues.cpp).
struct Queues {
  std::deque<std::uint64_t> segments;        ///< rules 1 and 4
  std::deque<Subfacet> subfacets;            ///< rules 2 and 5
  std::deque<std::pair<Tet, CellRef>> tets;  ///< rule 6
};

class Mesher {
 public:
  Mesher(const Domain& domain, const MeshOptions& options, const ProgressCallback& progress);

  // ---- the phases (section 4.3), one file each ----
  void initialize();     ///< initialize.cpp (section 4.1)
  void conform();        ///< conform.cpp, rules 1-3
  void refine();         ///< refine.cpp, rules 4-7
  void pump();           ///< pump.cpp
  /// extract.cpp: interior tets, classes, statistics. `stoppable`: poll
  /// while extracting (the count of QMESH's slivers before PUMP), so that a
  /// cancel takes effect within a bounded amount of work; the result is then
  /// empty, with `stopped` set, once the run must stop.
  MeshResult extract(bool stoppable = false);

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
  // units (and every kPollSteps steps) calls the progress callback, so that a
  // cancel, the vertex limit or the memory cap (the wasm callback) takes
  // effect within kPollWork units whatever the mesher does.
  static constexpr std::uint64_t kPollWork = 256;
  static constexpr std::size_t kPollSteps = 256;
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
  /// A step (an insertion by a rule, a PUMP vertex) is done: counts it, ends
  /// the watchdog's step, polls (a progress call at least every kPollSteps
  /// steps). False once the run must stop.
  bool tick();
  std::uint64_t work() const { return work_; }
  std::vector<PhaseStats> phases;
  std::size_t slivers_before_pump = 0, pumped_vertices = 0;
  /// How many points each rule inserted, by rule_number (1..7); [0]: INITIALIZE.
  std::array<std::size_t, kRules> rule_count{};
  /// How often a loop cap was reached: Caps, Pump::kLabelRounds,
  /// Pump::kCriticalSteps, and the ray-parity budget of extract.cpp.
  std::size_t caps_reached = 0;

  // ---- what PUMP and the tests read ----
  const RegularTriangulation& triangulation() const { return tri_; }
  /// PUMP changes the weights of V (and nothing else of the mesher's state).
  RegularTriangulation& weighted_triangulation() { return tri_; }
  const Domain& domain() const { return dom_; }
  const MeshOptions& options() const { return opt_; }
  const std::vector<MVertex>& vertices() const { return verts_; }
  const std::unordered_map<std::uint64_t, Subsegment>& subsegments() const { return segs_; }
  const Subsegment& subsegment(std::uint64_t key) const { return segs_.at(key); }
  /// The keys of the subsegments with endpoint v.
  const std::vector<std::uint64_t>& subsegments_at(int v) const { return vertex_segs_[v]; }
  const std::vector<ProtectingBall>& protecting_balls() const { return balls_.all(); }
  const ProtectingBalls& balls() const { return balls_; }
  std::vector<Subfacet> subfacets() const;
  /// N(v): the distance from v to its nearest neighbour in Del V.
  double nearest_neighbour(int v) const;
  /// N(v) for every vertex, as PUMP measured it at the end of REFINE (extract
  /// reports these; it measures them itself when they are missing).
  void set_nearest_neighbours(std::vector<double> nn) { nn_ = std::move(nn); }
  /// 1 for the cells of g inside the polyhedron. `scan`: poll while
  /// labelling (a phase's scan); the labels are then unusable if it stops.
  std::vector<char> interior_labels(const RegularTriangulation::CellGraph& g, bool scan = false);
  /// cell_graph() polling every kPollWork cells (a phase's scan); empty if
  /// the run stops meanwhile.
  RegularTriangulation::CellGraph scan_cell_graph();
  /// All four vertices on one input facet: a flat tet lying in the facet
  /// (rounding of the points inserted on it), inside neither region.
  bool flat_on_facet(const Tet& t) const;
  /// The point ENCROACH (section 4.3) returns for c.
  Insertion encroach(const Point3& c, int hint);
  /// Whether every subsegment and subfacet is in the triangulation.
  bool conforms() const;
  /// Inserts a point; returns its id or -1 when nothing was inserted.
  int insert(const Insertion& ins);
  /// Inserts a point for `rule` and counts it there.
  int insert(const Insertion& ins, Rule rule) {
    const int id = insert(ins);
    if (id >= 0) ++rule_count[rule_number(rule)];
    if (trace_) trace(ins, rule, id);
    if (observer) observer(ins, rule_number(rule), id);
    return id;
  }
  /// Called after every insertion by a rule, with the rule's number (tests
  /// watch the rules with it).
  std::function<void(const Insertion&, int rule, int id)> observer;
  /// With WQMESH_TRACE set in the environment, every insertion is printed on
  /// stderr (rule, where, the subsegment split): a tool for developers.
  void trace(const Insertion& ins, Rule rule, int id) const;

 private:
  // subcomplex.cpp: subsegments, subfacets, SPLITE, SPLITF, encroachment.
  void add_segment(const Subsegment& s);
  std::vector<std::uint64_t> shield_keys(int sector) const;
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
  /// A subfacet whose diametric ball lies inside a protecting ball.
  bool guarded(const Subfacet& h) const;

  // initialize.cpp
  int edge_between(int u, int w) const;

  // queues.cpp: rules 1-2 (CONFORM) and 4-6 (REFINE) as the queues hold them.
  void enqueue_around(int v);
  bool process_queues(bool refine_phase);  ///< false if stopped
  /// Rules 1 and 4: SPLITE of the queued subsegment k if it is encroached.
  void split_encroached_subsegment(std::uint64_t k, Rule rule);
  /// Rule 2: a subfacet of B that is encroached, or one of the input that does
  /// not appear in Del V.
  bool rule2_needs_split(const Subfacet& h) const;
  /// Rule 5: a non-guarded subfacet that is encroached, or a guarded one that
  /// does not appear in Del V.
  bool rule5_needs_split(const Subfacet& h) const;
  /// SPLITF(h) for rule 2 or 5; h is queued again when SPLITF split a
  /// subsegment instead (at most Caps::kRetries times).
  void split_subfacet(const Subfacet& h, Rule rule);

  // conform.cpp
  /// The keys of the sharp subsegments, in increasing order.
  std::vector<std::uint64_t> sharp_subsegment_keys() const;
  /// One pass of rule 3 over the sharp subsegments; whether it inserted.
  bool rule3_pass();
  /// With max_size: splits sharp subsegments longer than 2/3 max_size before
  /// the protecting balls are fixed; false if stopped.
  bool split_long_sharp_subsegments();
  void make_protecting_balls();  ///< end of CONFORM (section 4.3)

  // refine.cpp
  /// Rule 6 for the queued tet t; whether a point was inserted.
  bool rule6_split_skinny_tet(const Tet& t, CellRef ref);
  /// One pass of rule 7 over the sliver vertices; whether it inserted.
  bool rule7_pass();

  // mesher.cpp
  void report_progress();

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
  ProtectingBalls balls_;
  std::vector<double> nn_;  ///< N(v) at the end of REFINE
  Phase phase_ = Phase::initialize;
  bool trace_ = false;
  Queues queues_;
  std::size_t inserted_ = 0, steps_ = 0;
  std::uint64_t work_ = 0, next_poll_ = kPollWork, step_work_ = 0;
  /// How often a subfacet (or a tet, by three of its vertices) was looked at
  /// again after its split was deferred to another feature; bounded by
  /// Caps::kRetries so that no feature keeps the refinement busy forever.
  std::unordered_map<Tri, int, TriHash> retries_;
  std::string stop_reason_, stop_message_;
};

}  // namespace wqmesh::mesher
