// wqmesh: the pieces WQMESH keeps while it runs (private; paper, section 4.3),
// each handed to the phases that use it:
//   V               the vertex set in a RegularTriangulation (weights 0 until
//                   PUMP) and where each vertex lies (MVertex, subcomplex.h)
//   Subcomplex      the subsegments, sectors and subfacets, with SPLITE,
//                   SPLITF, ENCROACH and the encroachment tests (subcomplex.h)
//   ProtectingBalls the protecting balls (protecting_balls.h)
//   Queues          the work queues of rules 1-2 and 4-6 (queues.h)
//   Inserter        the insertion of a point into V with its upkeep (below)
//   WorkMeter       steps, work units, progress, why the run stopped
//                   (work_meter.h)
// Each phase has its own file and class (phases.h, pump.h, extract.h):
//   initialize.cpp  Initialize: INITIALIZE (section 4.1)
//   conform.cpp     Conform: CONFORM, rules 1-3, then the protecting balls
//   refine.cpp      Refine: REFINE, rules 4-7 (6: rule6_split_skinny_tet,
//                   7: rule7_pass)
//   pump.cpp        Pump: PUMP
//   extract.cpp     Extract: the tets inside, their classes, statistics
// and class Mesher (mesher.cpp) owns the pieces and runs the phases in
// mesh_polyhedron.cpp's order (WQMESH(P)).
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
#include <functional>
#include <memory>
#include <vector>

#include "mesher/domain.h"
#include "mesher/protecting_balls.h"
#include "mesher/queues.h"
#include "mesher/rules.h"
#include "mesher/subcomplex.h"
#include "mesher/work_meter.h"
#include "triangulation.h"
#include "wqmesh/mesher.h"
#include "wqmesh/types.h"

namespace wqmesh::mesher {

class Pump;
class Conform;

/// Inserts the points the rules decide into V, with the upkeep every
/// insertion needs: the subcomplex (a split subsegment, the facets'
/// triangulations), the queues around the new vertex, the vertex limit.
class Inserter {
 public:
  Inserter(const MeshOptions& options, RegularTriangulation& tri, std::vector<MVertex>& vertices, Subcomplex& sub,
           Queues& queues, WorkMeter& meter);
  /// Inserts a point; returns its id or -1 when nothing was inserted.
  int insert(const Insertion& ins);
  /// Inserts a point for `rule` and counts it there.
  int insert(const Insertion& ins, Rule rule) {
    const int id = insert(ins);
    if (id >= 0) ++rule_count_[rule_number(rule)];
    if (trace_) trace(ins, rule, id);
    if (observer) observer(ins, rule_number(rule), id);
    return id;
  }
  /// How many points each rule inserted, by rule_number (1..7); [0]: INITIALIZE.
  const std::array<std::size_t, kRules>& rule_count() const { return rule_count_; }
  /// Called after every insertion by a rule, with the rule's number (tests
  /// watch the rules with it).
  std::function<void(const Insertion&, int rule, int id)> observer;

 private:
  /// With WQMESH_TRACE set in the environment, every insertion is printed on
  /// stderr (rule, where, the subsegment split): a tool for developers.
  void trace(const Insertion& ins, Rule rule, int id) const;

  const MeshOptions& opt_;
  RegularTriangulation& tri_;
  std::vector<MVertex>& verts_;
  Subcomplex& sub_;
  Queues& queues_;
  WorkMeter& meter_;
  bool trace_ = false;
  std::array<std::size_t, kRules> rule_count_{};
};

/// Beyond the paper (issue 15, the peak memory): hands the free pages of the
/// C heap back to the system (glibc's malloc_trim), so that the process's
/// resident memory follows the live heap down when a phase's pieces are freed
/// (glibc keeps the pages of the many small blocks REFINE frees). Nothing
/// under Emscripten, whose heap never shrinks.
void trim_heap();

/// The pieces of one run, and the phases in order (section 4.3). Tests run
/// the phases one by one and look at the pieces in between.
class Mesher {
 public:
  Mesher(const Domain& domain, const MeshOptions& options, const ProgressCallback& progress);
  Mesher(const Mesher&) = delete;  ///< its pieces refer to each other
  Mesher& operator=(const Mesher&) = delete;

  // ---- the phases (section 4.3), one file each ----
  void initialize();  ///< initialize.cpp (section 4.1)
  void conform();     ///< conform.cpp, rules 1-3
  void refine();      ///< refine.cpp, rules 4-7
  void pump();        ///< pump.cpp
  /// extract.cpp (Extract::run): interior tets, classes, statistics.
  MeshResult extract();
  /// extract.cpp (Extract::mesh): the interior tets without their measures
  /// and classes (classify_tets adds them), nothing in it referring to the
  /// pieces, so that release() may follow.
  MeshResult extract_mesh();
  /// V is final (REFINE is done): the subcomplex keeps its subfacets as a
  /// list and frees the facets' planar triangulations (Subcomplex::freeze;
  /// issue 15, the peak memory), and the freed memory goes back to the
  /// system (trim_heap). pump() and the extraction may follow; a phase that
  /// inserts points (initialize, conform, refine) may not.
  void freeze_subcomplex();
  /// Frees the large pieces once the mesh is extracted (issue 15, the peak
  /// memory): V's triangulation, the subcomplex (subsegments, the facets'
  /// planar triangulations), the queues, N(v), the count's scan, and V's
  /// MVertex list; the protecting balls, the meter and the inserter's counts
  /// stay, and the freed memory goes back to the system (trim_heap). No
  /// phase and no extraction may run after it. Tests check released().
  void release();
  /// Whether release() ran: V's triangulation then holds no vertex.
  bool released() const { return released_; }
  /// The inside slivers extract() would count now (QMESH's, before PUMP),
  /// without building the mesh (Extract::count_qmesh_slivers); its scan (or
  /// the labels it left in the cells) is kept for the next pump() of the
  /// same triangulation.
  std::size_t count_qmesh_slivers();
  /// PUMP over this run's pieces (pump() runs it; tests drive it by hand).
  Pump make_pump();
  /// CONFORM over this run's pieces, the meter in its phase (conform() runs
  /// it; tests run it by hand to read its rule 3 records).
  Conform make_conform();

  // ---- the pieces (all but domain, options, balls and meter: not after release()) ----
  const Domain& domain() const { return dom_; }
  const MeshOptions& options() const { return opt_; }
  const RegularTriangulation& triangulation() const { return live().tri; }
  /// V: where each vertex lies, by id.
  const std::vector<MVertex>& vertices() const { return verts_; }
  const Subcomplex& subcomplex() const { return live().sub; }
  const ProtectingBalls& balls() const { return balls_; }
  WorkMeter& meter() { return meter_; }
  const WorkMeter& meter() const { return meter_; }
  Inserter& inserter() { return live().ins; }
  const Inserter& inserter() const { return live().ins; }
  /// The vertices PUMP gave a weight.
  std::size_t pumped_vertices() const { return pumped_vertices_; }

 private:
  /// The pieces release() frees together (each refers to those before it
  /// and to V's MVertex list, the balls and the meter, which stay).
  struct Pieces {
    Pieces(const Domain& domain, const MeshOptions& options, std::vector<MVertex>& vertices,
           const ProtectingBalls& balls, WorkMeter& meter);
    RegularTriangulation tri;
    Subcomplex sub;
    Queues queues;
    Inserter ins;
  };
  /// The pieces; throws std::logic_error after release().
  Pieces& live() const;

  const Domain& dom_;
  const MeshOptions& opt_;
  std::vector<MVertex> verts_;
  ProtectingBalls balls_;
  WorkMeter meter_;
  std::unique_ptr<Pieces> pieces_;
  std::vector<double> nn_;  ///< N(v) at the end of REFINE
  std::size_t pumped_vertices_ = 0;
  bool released_ = false;
  /// count_qmesh_slivers' scan for pump(), made at this many vertices (-1:
  /// none).
  RegularTriangulation::CellGraph sliver_scan_;
  std::vector<char> sliver_scan_labels_;
  bool sliver_scan_in_cells_ = false;  ///< the scan's labels are in the cells' label bytes
  long sliver_scan_vertices_ = -1;
};

}  // namespace wqmesh::mesher
