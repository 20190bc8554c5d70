// wqmesh: REFINE's runaway guard (beyond the paper; Caps::kBoundaryRunFactor,
// WorkMeter::refine_insertion): a run whose rules 4-5 split the boundary
// without end stops with stopped == "stalled" and a message naming the rules
// and the input feature, instead of refining towards the vertex limit.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "mesh_invariants.h"
#include "wqmesh/mesher.h"

namespace wqmesh {
namespace {

// edge_facet.off's two edges at the column foot have an external dihedral
// angle of 29.7 degrees: sharp, so CONFORM's rule 3 and the protecting balls
// cover them. With them left out of the analysis (what the wasm module built
// with -msimd128 computed: BENCHMARKS.md, session 9, h4), the subfacets of
// their facets encroach each other's and rule 5 splits them without end.
// Without the guard this run goes on to the vertex limit (stopped "limit");
// with it, it stops far below, naming rule 5 and an input element.
TEST(RunawayGuard, AMissedSharpEdgeStopsRefineWithAMessage) {
  const invariants::Input in = invariants::load(std::string(WQMESH_EXAMPLE_MODELS) + "/edge_facet.off");
  ASSERT_FALSE(in.analysis.sharp_edges.empty());
  Analysis missed = in.analysis;
  missed.sharp_edges.clear();
  MeshOptions o;
  o.max_vertices = 200000;
  const MeshResult r = mesh_polyhedron(in.plc, missed, o);
  EXPECT_EQ(r.stopped, "stalled");
  EXPECT_LT(r.all_vertices, o.max_vertices);
  EXPECT_GE(r.caps_reached, 1u);
  EXPECT_NE(r.stop_message.find("runaway"), std::string::npos) << r.stop_message;
  EXPECT_NE(r.stop_message.find("rule 5: "), std::string::npos) << r.stop_message;
  EXPECT_NE(r.stop_message.find("input "), std::string::npos) << r.stop_message;
  // Rules 4 and 5 made the points past REFINE's start (rule 6 barely ran).
  EXPECT_GT(r.rule_points[5], r.all_vertices / 2) << r.stop_message;
  // Deterministic: a second run stops at the same vertex with the same words.
  const MeshResult again = mesh_polyhedron(in.plc, missed, o);
  EXPECT_EQ(again.all_vertices, r.all_vertices);
  EXPECT_EQ(again.stop_message, r.stop_message);
  // The input's own analysis meshes to the end: the guard does not fire.
  const MeshResult full = mesh_polyhedron(in.plc, in.analysis);
  EXPECT_EQ(full.stopped, "");
  EXPECT_EQ(full.caps_reached, 0u);
  EXPECT_TRUE(full.conforming);
}

}  // namespace
}  // namespace wqmesh
