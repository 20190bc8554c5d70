// wqmesh: REFINE's runaway guard (beyond the paper; Caps::kBoundaryRunFactor,
// WorkMeter::refine_insertion): a run whose rules 4-5 split the boundary
// without end stops with stopped == "stalled" and a message naming the rules
// and the input feature, instead of refining towards the vertex limit; a
// long but finite run (points kept apart, Caps::kRunawaySpacing) goes on.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "mesh_invariants.h"
#include "mesher/rules.h"
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
  // Stopped at the count cap by its spacing, not at the backstop.
  EXPECT_NE(r.stop_message.find("times the smallest protecting ball's radius"), std::string::npos) << r.stop_message;
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

/// A wedge prism along x (length 4) over the triangle (0, 0), (4, 0),
/// (4 cos a, 4 sin a) in (y, z), its sharp edge y = z = 0 at a dihedral angle
/// of a degrees, with the bottom square next to that edge split into 4
/// triangles at its centre lifted by d: a nearly flat facet fan.
std::string fan_wedge_off(double a_deg, double d) {
  const double a = a_deg * std::acos(-1.0) / 180;
  const double y = 4 * std::cos(a), z = 4 * std::sin(a);
  char t[600];
  std::snprintf(t, sizeof t,
                "OFF\n7 8 0\n0 0 0\n0 4 0\n0 %.17g %.17g\n4 0 0\n4 4 0\n4 %.17g %.17g\n2 2 %.17g\n"
                "3 0 2 1\n3 3 4 5\n4 1 2 5 4\n4 0 3 5 2\n3 0 1 6\n3 1 4 6\n3 4 3 6\n3 3 0 6\n",
                y, z, y, z, d);
  return t;
}

// The fan next to a 1.5-degree sharp edge (BENCHMARKS.md, session 16, h2):
// CONFORM splits the edge's sharp subsegments short, so its protecting balls
// are small, and rule 5 refines the wedge outside them towards the facets'
// gap, a run of about 40,000 rule-5 points from about 500 vertices, past the
// count cap but keeping its points apart: the run goes on and the mesh is
// made, with every invariant. (Before the spacing test it stopped "stalled".)
TEST(RunawayGuard, AFiniteRunPastTheCapGoesOn) {
  const invariants::Input in = invariants::from_off(fan_wedge_off(1.5, 1e-4));
  ASSERT_FALSE(in.analysis.sharp_edges.empty());
  const MeshResult r = mesh_polyhedron(in.plc, in.analysis);
  EXPECT_EQ(r.stopped, "") << r.stop_message;
  EXPECT_EQ(r.caps_reached, 0u);
  EXPECT_GT(r.rule_points[5], std::size_t(mesher::Caps::kBoundaryRunSlack)) << "the run did not pass the count cap";
  invariants::expect_invariants("fan at a 1.5-degree edge", in, r);
}

}  // namespace
}  // namespace wqmesh
