// wqmesh: the phases INITIALIZE, CONFORM and REFINE of WQMESH (private; paper,
// section 4.3), one class and file each; PUMP is in pump.h, the extraction in
// extract.h. Each is handed the pieces it uses (mesher.h lists them) and
// runs once, in Mesher's order.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <unordered_map>
#include <vector>

#include "mesher/domain.h"
#include "mesher/mesher.h"
#include "mesher/protecting_balls.h"
#include "mesher/queues.h"
#include "mesher/subcomplex.h"
#include "mesher/work_meter.h"
#include "triangulation.h"
#include "wqmesh/mesher.h"

namespace wqmesh::mesher {

/// Sets `inserter`'s observer to `observer`, which also calls the one it
/// replaces first, for the scope's life; the replaced one is back when the
/// scope ends, however it ends (CONFORM's rule-3 marks, REFINE's runaway
/// guard).
class ScopedObserver {
 public:
  using Observer = std::function<void(const Insertion&, int rule, int id)>;
  ScopedObserver(Inserter& inserter, Observer observer) : ins_(inserter), saved_(inserter.observer) {
    ins_.observer = [saved = saved_, observer = std::move(observer)](const Insertion& ins, int rule, int id) {
      if (saved) saved(ins, rule, id);
      observer(ins, rule, id);
    };
  }
  ~ScopedObserver() { ins_.observer = saved_; }
  ScopedObserver(const ScopedObserver&) = delete;
  ScopedObserver& operator=(const ScopedObserver&) = delete;

 private:
  Inserter& ins_;
  Observer saved_;
};

/// INITIALIZE (sections 4.1, 4.3; initialize.cpp): the vertices of P, the
/// vertex-ball points on its edges, the subsegments, the sectors with their
/// shield subsegments and the SOS splits.
class Initialize {
 public:
  Initialize(const Domain& domain, Subcomplex& sub, Queues& queues, Inserter& inserter, WorkMeter& meter)
      : dom_(domain), sub_(sub), queues_(queues), ins_(inserter), meter_(meter) {}
  void run();

 private:
  int edge_between(int u, int w) const;

  const Domain& dom_;
  Subcomplex& sub_;
  Queues& queues_;
  Inserter& ins_;
  WorkMeter& meter_;
};

/// CONFORM (section 4.3; conform.cpp): rules 1-3 until the edges and facets
/// of P are unions of Delaunay edges and triangles, then the protecting balls.
class Conform {
 public:
  Conform(const Domain& domain, const MeshOptions& options, const RegularTriangulation& tri, const Subcomplex& sub,
          Queues& queues, Inserter& inserter, WorkMeter& meter, ProtectingBalls& balls)
      : dom_(domain),
        opt_(options),
        tri_(tri),
        sub_(sub),
        queues_(queues),
        ins_(inserter),
        meter_(meter),
        balls_(balls) {}
  void run();
  /// Tests' view of rule 3's records (rule3_pass) after run(): how many
  /// tests they skipped, and whether every record still standing, whose
  /// subsegment would be skipped now, agrees with a fresh test (it finds
  /// nothing to split).
  std::size_t rule3_skipped() const { return state_.skipped; }
  bool rule3_records_hold() const;

 private:
  /// What rule 3 found at a sharp subsegment's midpoint m when it found
  /// nothing: V's size then and the vertices of the cells m conflicted with
  /// (see rule3_pass).
  struct Rule3Record {
    std::uint32_t tested_at = 0;
    std::vector<int> zone;
  };
  /// The rule 3 passes' state: the records by subsegment key, and for each
  /// vertex the largest id of a vertex inserted next to it (0: none).
  struct Rule3State {
    std::unordered_map<std::uint64_t, Rule3Record> records;
    std::vector<int> touched;
    std::size_t skipped = 0;
  };
  /// Whether the record of subsegment k says its test would find nothing.
  bool rule3_unchanged(const Rule3Record& r) const;
  /// Rule 3's test's working storage, kept across a pass's tests so that a
  /// test allocates nothing once the vectors have grown: the features the
  /// midpoint encroaches, and the vertices of its conflict cells.
  struct Rule3Scratch {
    std::vector<std::uint64_t> segs;
    std::vector<Subfacet> facets;
    std::vector<int> zone;
  };
  /// Rule 3's test at sharp subsegment s (key k): whether its midpoint
  /// encroaches a feature in an element of P disjoint from s's edge, and
  /// then the point to insert; `w.zone` gets the vertices of the midpoint's
  /// conflict cells.
  bool rule3_test(std::uint64_t k, const Subsegment& s, Insertion& ins, Rule3Scratch& w) const;
  /// One pass of rule 3 over the sharp subsegments; whether it inserted.
  bool rule3_pass();
  Rule3State state_;
  /// The keys of the sharp subsegments, in increasing order.
  std::vector<std::uint64_t> sharp_subsegment_keys() const;
  /// With max_size: splits sharp subsegments longer than 2/3 max_size before
  /// the protecting balls are fixed; false if stopped.
  bool split_long_sharp_subsegments();
  void make_protecting_balls();  ///< end of CONFORM (section 4.3)

  const Domain& dom_;
  const MeshOptions& opt_;
  const RegularTriangulation& tri_;
  const Subcomplex& sub_;
  Queues& queues_;
  Inserter& ins_;
  WorkMeter& meter_;
  ProtectingBalls& balls_;
};

/// REFINE (section 4.3; refine.cpp): rules 4-5 (in the queues), rule 6
/// (skinny tets) and rule 7 (preparing PUMP).
class Refine {
 public:
  Refine(const Domain& domain, const MeshOptions& options, const RegularTriangulation& tri,
         const std::vector<MVertex>& vertices, const Subcomplex& sub, const ProtectingBalls& balls, Queues& queues,
         Inserter& inserter, WorkMeter& meter)
      : dom_(domain),
        opt_(options),
        tri_(tri),
        verts_(vertices),
        sub_(sub),
        balls_(balls),
        queues_(queues),
        ins_(inserter),
        meter_(meter) {}
  void run();

 private:
  /// Rule 6 for the queued tet t; whether a point was inserted.
  bool rule6_split_skinny_tet(const Tet& t, CellRef ref);
  /// One pass of rule 7 over the sliver vertices; whether it inserted.
  bool rule7_pass();
  /// The queued rules 4-6 (Queues::process with rule 6); false if stopped.
  bool process_queues();
  /// The input feature an insertion lies on, in words (the runaway guard's
  /// message): "input edge E (vertices a-b)", "input facet F", ...
  std::string input_feature(const Insertion& ins) const;

  const Domain& dom_;
  const MeshOptions& opt_;
  const RegularTriangulation& tri_;
  const std::vector<MVertex>& verts_;
  const Subcomplex& sub_;
  const ProtectingBalls& balls_;
  Queues& queues_;
  Inserter& ins_;
  WorkMeter& meter_;
};

}  // namespace wqmesh::mesher
