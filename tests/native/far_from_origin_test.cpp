// Inputs far from the origin (beyond the paper, core/src/scaling.h): the
// normalisation translates them by a per-axis centre before its power-of-two
// scaling, exactly, so that they are meshed as at the origin and the input
// points come back bit for bit. Models generated here: a tapered prism with a
// spike (sharp edges, small input angles) at the origin and moved by about
// 1e6, a box whose y coordinates cannot be translated exactly.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "mesh_invariants.h"
#include "scaling.h"
#include "wqmesh/mesher.h"

namespace wqmesh {
namespace {

using invariants::from_off;
using invariants::Input;

std::string num(double x) {
  char t[40];
  std::snprintf(t, sizeof t, "%.17g", x);
  return t;
}

/// A tapered prism: a hexagon of radius 1 with a spike of 5 degrees on one
/// side, at z = 0, and the same polygon times 0.625 at z = 0.046875 (acute
/// dihedral angles at the bottom edges), all times 0.25. Coordinates are
/// multiples of 2^-24 and the box is symmetric about the origin, so the
/// model moved by whole numbers up to 2^24 is exact.
std::vector<Point3> tapered_prism_points() {
  const double pi = std::acos(-1.0);
  std::vector<std::array<double, 2>> poly;
  for (int k = 0; k < 6; ++k) poly.push_back({std::cos(0.3 + pi * k / 3), std::sin(0.3 + pi * k / 3)});
  const auto a = poly[0], b = poly[1];
  const double m[2] = {(a[0] + b[0]) / 2, (a[1] + b[1]) / 2};
  const double e[2] = {b[0] - a[0], b[1] - a[1]}, el = std::hypot(e[0], e[1]);
  const double out[2] = {e[1] / el, -e[0] / el}, t[2] = {e[0] / el, e[1] / el};
  const double half = std::tan(2.5 * pi / 180) * 0.8, tip = 0.8;
  poly.insert(poly.begin() + 1, {{m[0] - t[0] * half, m[1] - t[1] * half},
                                 {m[0] + out[0] * tip, m[1] + out[1] * tip},
                                 {m[0] + t[0] * half, m[1] + t[1] * half}});
  std::vector<Point3> pts;
  for (double z : {0.0, 0.046875})
    for (const auto& p : poly) {
      const double s = z == 0 ? 0.25 : 0.25 * 0.625;
      pts.push_back({std::ldexp(std::nearbyint(std::ldexp(p[0], 20)), -20) * s,
                     std::ldexp(std::nearbyint(std::ldexp(p[1], 20)), -20) * s, z * 0.25});
    }
  Point3 lo = pts[0], hi = pts[0];
  for (const Point3& p : pts)
    for (int q = 0; q < 3; ++q) {
      lo[q] = std::min(lo[q], p[q]);
      hi[q] = std::max(hi[q], p[q]);
    }
  for (Point3& p : pts)
    for (int q = 0; q < 3; ++q) p[q] -= (lo[q] + hi[q]) / 2;  // exact: dyadic, few bits
  return pts;
}

/// The prism's OFF with every point moved by `d`.
std::string prism_off(const Point3& d) {
  const std::vector<Point3> pts = tapered_prism_points();
  const int n = static_cast<int>(pts.size()) / 2;
  std::string s = "OFF\n" + std::to_string(2 * n) + " " + std::to_string(n + 2) + " 0\n";
  for (const Point3& p : pts) s += num(p[0] + d[0]) + " " + num(p[1] + d[1]) + " " + num(p[2] + d[2]) + "\n";
  return s + testing::prism_faces_off(n);
}

const Point3 kFar{{1000000, -650000, 850000}};

// The prism at the origin and moved by about 1e6 both mesh with every
// invariant (conforming, positive tets, the volume, the facets covered, the
// input edges as chains, the input points bit for bit), and the far mesh is
// the origin's moved: the same tets, each point the origin's plus the move
// (rounded once). Without the translation the far run sees coordinates of
// 1e6 with units in the last place of 1.2e-10 and meshes another shape.
TEST(FarFromOrigin, AFarModelIsMeshedAsAtTheOrigin) {
  const Input origin = from_off(prism_off({{0, 0, 0}}));
  const Input far = from_off(prism_off(kFar));
  ASSERT_EQ(origin.plc.vertices.size(), far.plc.vertices.size());
  for (std::size_t v = 0; v < far.plc.vertices.size(); ++v)
    for (int q = 0; q < 3; ++q)
      ASSERT_EQ(far.plc.vertices[v][q] - kFar[q], origin.plc.vertices[v][q]) << "the model is not moved exactly";
  EXPECT_FALSE(origin.analysis.sharp_edges.empty());
  const MeshResult a = mesh_polyhedron(origin.plc, origin.analysis);
  const MeshResult b = mesh_polyhedron(far.plc, far.analysis);
  invariants::expect_invariants("prism at the origin", origin, a);
  invariants::expect_invariants("prism moved by 1e6", far, b);
  ASSERT_EQ(b.mesh.tets, a.mesh.tets);
  ASSERT_EQ(b.mesh.vertices.size(), a.mesh.vertices.size());
  for (std::size_t v = 0; v < a.mesh.vertices.size(); ++v)
    for (int q = 0; q < 3; ++q) EXPECT_EQ(b.mesh.vertices[v][q], a.mesh.vertices[v][q] + kFar[q]) << "vertex " << v;
  // Angles do not move with the model.
  const MeshStats sa = mesh_stats(a.mesh, a.quality), sb = mesh_stats(b.mesh, b.quality);
  EXPECT_EQ(sb.inverted, 0u);
  EXPECT_NEAR(sb.min_dihedral_deg, sa.min_dihedral_deg, 1e-6);
  // The written mesh, measured afresh (its points rounded at 1e6): no tet
  // inverted.
  for (const TetQuality& q : mesh_quality(b.mesh)) EXPECT_GT(q.volume, 0);
}

// The normalisation of a far model: every input coordinate x comes back
// bit for bit from the normalised one as x' 2^E + c, x - c is exact
// (checked with long double, 64 bits of mantissa, against the double
// difference), and the normalised coordinates are at most 2.
TEST(FarFromOrigin, TheTranslationIsExactForEveryInputPoint) {
  // Moved by a non-whole amount: coordinates with all 53 bits used.
  const Point3 d{{1e6 / 3, -2e6 / 7, 9e5 / 11}};
  const Input far = from_off(prism_off(d));
  const Normalisation n = normalisation(far.plc);
  ASSERT_TRUE(n.translated());
  const PLC normalised = normalised_plc(far.plc, n);
  for (std::size_t v = 0; v < far.plc.vertices.size(); ++v) {
    const Point3& x = far.plc.vertices[v];
    EXPECT_EQ(input_point(normalised.vertices[v], n), x) << "vertex " << v;
    for (int q = 0; q < 3; ++q) {
      EXPECT_EQ(static_cast<long double>(x[q]) - static_cast<long double>(n.centre[q]),
                static_cast<long double>(x[q] - n.centre[q]))
          << "vertex " << v << " axis " << q;
      EXPECT_LE(std::fabs(normalised.vertices[v][q]), 2.0);
    }
  }
  const MeshResult r = mesh_polyhedron(far.plc, far.analysis);
  invariants::expect_invariants("prism moved by a third of 1e6", far, r);
}

// A box far out along x whose y coordinates run from 1e-30 to 1: y - c would
// round for any centre c of its box, so y is not translated (c = 0 there)
// while x and z are, and the mesh keeps 1e-30 bit for bit.
TEST(FarFromOrigin, AnAxisThatCannotBeTranslatedExactlyIsNot) {
  std::string s = "OFF\n8 6 0\n";
  for (int i = 0; i < 8; ++i)
    s += num(i & 4 ? 1e6 + 1 : 1e6) + " " + num(i & 2 ? 1 : 1e-30) + " " + num(i & 1 ? 1 : 0) + "\n";
  s += "4 0 1 3 2\n4 4 6 7 5\n4 0 4 5 1\n4 2 3 7 6\n4 0 2 6 4\n4 1 5 7 3\n";
  const Input in = from_off(s);
  const Normalisation n = normalisation(in.plc);
  EXPECT_NE(n.centre[0], 0);
  EXPECT_EQ(n.centre[1], 0);
  EXPECT_NE(n.centre[2], 0);
  const MeshResult r = mesh_polyhedron(in.plc, in.analysis);
  invariants::expect_invariants("box at 1e6 with y from 1e-30", in, r);
}

// Models near the origin are not translated (their meshes stay as they
// were): boxes from 0 and across 0, and the far prism brought back.
TEST(FarFromOrigin, AModelNearTheOriginIsNotTranslated) {
  for (const auto& [lo, hi] : {std::pair{0.0, 1.0}, {-1.0, 1.0}, {0.0, 1e6}, {-3e-5, 2e-5}}) {
    std::string s = "OFF\n8 6 0\n";
    for (int i = 0; i < 8; ++i)
      s += num(i & 4 ? hi : lo) + " " + num(i & 2 ? hi : lo) + " " + num(i & 1 ? hi : lo) + "\n";
    s += "4 0 1 3 2\n4 4 6 7 5\n4 0 4 5 1\n4 2 3 7 6\n4 0 2 6 4\n4 1 5 7 3\n";
    const Input in = from_off(s);
    EXPECT_FALSE(normalisation(in.plc).translated()) << lo << " to " << hi;
  }
  EXPECT_FALSE(normalisation(from_off(prism_off({{0, 0, 0}})).plc).translated());
  EXPECT_TRUE(normalisation(from_off(prism_off(kFar)).plc).translated());
}

}  // namespace
}  // namespace wqmesh
