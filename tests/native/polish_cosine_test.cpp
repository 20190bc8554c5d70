// wqmesh: Improver::largest_cosine_within, the polish's cosine of a tet's smallest dihedral angle under a bound.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "geometry.h"
#include "mesh_invariants.h"
#include "mesher/improve.h"
#include "wqmesh/quality.h"

namespace wqmesh {
namespace {

using mesher::Improver;

// On every tet of slit.off's mesh as PUMP leaves it, and bounds on both sides
// of the tet's largest cosine c: below the bound, largest_cosine_within gives
// c bit for bit and the largest |cosine| of the six dihedral angles (those of
// tet_quality, to rounding); at or above it, a value at least the bound.
// A degenerate face gives 1 both ways.
TEST(PolishCosine, WithinABoundIsTheLargestCosineBitForBitOrAtLeastTheBound) {
  const invariants::Input in = invariants::load(std::string(WQMESH_EXAMPLE_MODELS) + "/slit.off");
  MeshOptions off;
  off.improve = false;
  MeshResult r = mesh_polyhedron(in.plc, in.analysis, off);
  const TetMesh m = r.mesh;
  ASSERT_GT(m.tets.size(), 100u);
  Improver im(r, 2.2, 0);
  std::size_t below = 0, above = 0;
  for (const auto& t : m.tets) {
    const double c = im.largest_cosine(t);
    const TetQuality q = tet_quality(m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]], m.vertices[t[3]]);
    double largest_abs = 0;
    for (double d : q.dihedral_deg) largest_abs = std::max(largest_abs, std::fabs(std::cos(d * geometry::kPi / 180)));
    for (double bound : {HUGE_VAL, 1.0, c + 1e-9, std::nextafter(c, 2.0), c, c - 1e-9, 0.5, 0.0, -1.0}) {
      double a = -5;
      const double w = im.largest_cosine_within(t, bound, a);
      if (c < bound) {
        ++below;
        EXPECT_EQ(w, c) << bound;
        EXPECT_NEAR(a, largest_abs, 1e-12) << bound;
      } else {
        ++above;
        EXPECT_GE(w, bound) << c;
      }
    }
  }
  EXPECT_GT(below, 0u);
  EXPECT_GT(above, 0u);
  const Improver::Tet flat{{m.tets[0][0], m.tets[0][0], m.tets[0][1], m.tets[0][2]}};
  double a = 0;
  EXPECT_EQ(im.largest_cosine_within(flat, HUGE_VAL, a), 1.0);
  EXPECT_EQ(a, 1.0);
}

}  // namespace
}  // namespace wqmesh
