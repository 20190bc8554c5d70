// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of the shape measures of section 3 of the paper (radius-edge ratio,
// orthoradius, normalized volume, angles) and of the Table 2 statistics.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "geometry.h"
#include "wqmesh/quality.h"

namespace wqmesh {
namespace {

using geometry::kPi;
const double kInf = std::numeric_limits<double>::infinity();

double deg(double rad) { return rad * 180.0 / kPi; }

double dist2(const Point3& p, const Point3& q) {
  double s = 0;
  for (int k = 0; k < 3; ++k) s += (p[k] - q[k]) * (p[k] - q[k]);
  return s;
}

/// Every field of a TetQuality is a number (no NaN), angles in [0, 180].
void expect_well_defined(const TetQuality& q) {
  EXPECT_FALSE(std::isnan(q.volume));
  EXPECT_FALSE(std::isnan(q.radius));
  EXPECT_FALSE(std::isnan(q.shortest_edge));
  EXPECT_FALSE(std::isnan(q.longest_edge));
  EXPECT_FALSE(std::isnan(q.radius_edge));
  EXPECT_FALSE(std::isnan(q.normalized_volume));
  EXPECT_FALSE(std::isnan(q.inradius));
  EXPECT_FALSE(std::isnan(q.aspect_ratio));
  for (double a : q.dihedral_deg) {
    EXPECT_GE(a, 0);
    EXPECT_LE(a, 180);
  }
  for (double a : q.face_angle_deg) {
    EXPECT_GE(a, 0);
    EXPECT_LE(a, 180);
  }
  EXPECT_FALSE(std::isnan(q.min_dihedral_deg));
  EXPECT_FALSE(std::isnan(q.max_dihedral_deg));
  EXPECT_FALSE(std::isnan(q.min_face_angle_deg));
}

// The regular tetrahedron with edge 2 sqrt 2 inscribed in the cube [-1,1]^3,
// ordered so that its signed volume is positive (det = +16, vol = 8/3).
const Point3 kR0{{1, 1, 1}}, kR1{{-1, 1, -1}}, kR2{{1, -1, -1}}, kR3{{-1, -1, 1}};

TEST(Quality, RegularTetrahedron) {
  const TetQuality q = tet_quality(kR0, kR1, kR2, kR3);
  expect_well_defined(q);
  const double l = 2 * std::sqrt(2.0);
  EXPECT_NEAR(q.volume, 8.0 / 3.0, 1e-14);
  EXPECT_NEAR(q.shortest_edge, l, 1e-14);
  EXPECT_NEAR(q.longest_edge, l, 1e-14);
  EXPECT_NEAR(q.radius, std::sqrt(3.0), 1e-14);  // center 0, |(1,1,1)|
  EXPECT_NEAR(q.radius_edge, std::sqrt(6.0) / 4, 1e-14);
  EXPECT_NEAR(q.normalized_volume, 1 / (6 * std::sqrt(2.0)), 1e-14);
  EXPECT_NEAR(q.inradius, std::sqrt(3.0) / 3, 1e-14);  // R / 3
  EXPECT_NEAR(q.aspect_ratio, 3, 1e-13);
  const double dihedral = deg(std::acos(1.0 / 3.0));  // ~70.528779 degrees
  for (double a : q.dihedral_deg) EXPECT_NEAR(a, dihedral, 1e-12);
  EXPECT_NEAR(q.min_dihedral_deg, dihedral, 1e-12);
  EXPECT_NEAR(q.max_dihedral_deg, dihedral, 1e-12);
  for (double a : q.face_angle_deg) EXPECT_NEAR(a, 60, 1e-12);
  EXPECT_NEAR(q.min_face_angle_deg, 60, 1e-12);
}

TEST(Quality, OrientationSign) {
  const TetQuality pos = tet_quality(kR0, kR1, kR2, kR3);
  const TetQuality neg = tet_quality(kR1, kR0, kR2, kR3);  // one swap
  EXPECT_GT(pos.volume, 0);
  EXPECT_LT(neg.volume, 0);
  EXPECT_DOUBLE_EQ(neg.volume, -pos.volume);
  EXPECT_DOUBLE_EQ(neg.normalized_volume, -pos.normalized_volume);
  // Unsigned measures do not depend on the orientation.
  EXPECT_NEAR(neg.radius, pos.radius, 1e-14);
  EXPECT_NEAR(neg.inradius, pos.inradius, 1e-14);
  EXPECT_NEAR(neg.aspect_ratio, pos.aspect_ratio, 1e-13);
  EXPECT_NEAR(neg.min_dihedral_deg, pos.min_dihedral_deg, 1e-12);
  // The unit right-corner tet: positive in the right-handed sense.
  const Point3 o{{0, 0, 0}}, x{{1, 0, 0}}, y{{0, 1, 0}}, z{{0, 0, 1}};
  EXPECT_NEAR(tet_quality(o, x, y, z).volume, 1.0 / 6.0, 1e-16);
  EXPECT_NEAR(tet_quality(o, y, x, z).volume, -1.0 / 6.0, 1e-16);
  // An even permutation keeps the sign.
  EXPECT_NEAR(tet_quality(x, y, o, z).volume, 1.0 / 6.0, 1e-16);
}

TEST(Quality, RightCornerTetrahedron) {
  const Point3 o{{0, 0, 0}}, x{{1, 0, 0}}, y{{0, 1, 0}}, z{{0, 0, 1}};
  const TetQuality q = tet_quality(o, x, y, z);
  expect_well_defined(q);
  // Edges at o: between two coordinate planes, 90 degrees. Edges of the
  // slanted face: between a coordinate plane (normal e_k) and the face of
  // normal (1,1,1)/sqrt 3, arccos(1/sqrt 3) = arctan(sqrt 2) ~ 54.7356.
  const double slanted = deg(std::atan(std::sqrt(2.0)));
  EXPECT_NEAR(q.dihedral_deg[0], 90, 1e-12);       // 01 = ox
  EXPECT_NEAR(q.dihedral_deg[1], 90, 1e-12);       // 02 = oy
  EXPECT_NEAR(q.dihedral_deg[2], 90, 1e-12);       // 03 = oz
  EXPECT_NEAR(q.dihedral_deg[3], slanted, 1e-12);  // 12 = xy
  EXPECT_NEAR(q.dihedral_deg[4], slanted, 1e-12);  // 13 = xz
  EXPECT_NEAR(q.dihedral_deg[5], slanted, 1e-12);  // 23 = yz
  EXPECT_NEAR(q.min_dihedral_deg, slanted, 1e-12);
  EXPECT_NEAR(q.max_dihedral_deg, 90, 1e-12);
  // Circumcenter (1/2,1/2,1/2): R = sqrt 3 / 2; l = 1, longest sqrt 2.
  EXPECT_NEAR(q.radius, std::sqrt(3.0) / 2, 1e-15);
  EXPECT_NEAR(q.shortest_edge, 1, 1e-15);
  EXPECT_NEAR(q.longest_edge, std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(q.radius_edge, std::sqrt(3.0) / 2, 1e-15);
  EXPECT_NEAR(q.normalized_volume, 1.0 / 6.0, 1e-15);
  // Area 3/2 + sqrt 3 / 2, so r = 3 (1/6) / area = 1 / (3 + sqrt 3).
  const double r = 1 / (3 + std::sqrt(3.0));
  EXPECT_NEAR(q.inradius, r, 1e-15);
  EXPECT_NEAR(q.aspect_ratio, (std::sqrt(3.0) / 2) / r, 1e-14);
  // Face 0 = xyz is equilateral; face 3 = oxy has its right angle at o.
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(q.face_angle_deg[k], 60, 1e-12);
  EXPECT_NEAR(q.face_angle_deg[9], 90, 1e-12);
  EXPECT_NEAR(q.face_angle_deg[10], 45, 1e-12);
  EXPECT_NEAR(q.face_angle_deg[11], 45, 1e-12);
  EXPECT_NEAR(q.face_angle_deg[3], 90, 1e-12);  // face 1 = oyz, corner o
  EXPECT_NEAR(q.face_angle_deg[6], 90, 1e-12);  // face 2 = oxz, corner o
  EXPECT_NEAR(q.min_face_angle_deg, 45, 1e-12);
}

// A sliver: the four corners of the unit square, one diagonal lifted by h.
// Circumcenter (1/2, 1/2, h/2): R^2 = 1/2 + h^2/4; l = sqrt(1 + h^2);
// vol = h/3. The four side edges carry the small dihedral angle theta, with
// sin theta = 3 vol |e| / (2 A1 A2) and both faces of area sqrt(1 + 2h^2)/2:
// sin theta = 2h sqrt(1 + h^2) / (1 + 2h^2).
TEST(Quality, Sliver) {
  const double h = 1e-3;
  const Point3 a{{0, 0, 0}}, b{{1, 0, h}}, c{{1, 1, 0}}, d{{0, 1, h}};
  const TetQuality q = tet_quality(a, b, c, d);
  expect_well_defined(q);
  EXPECT_NEAR(q.volume, h / 3, 1e-18);
  EXPECT_NEAR(q.radius, std::sqrt(0.5 + h * h / 4), 1e-14);
  EXPECT_NEAR(q.shortest_edge, std::sqrt(1 + h * h), 1e-15);
  EXPECT_NEAR(q.radius_edge, std::sqrt(0.5 + h * h / 4) / std::sqrt(1 + h * h), 1e-12);
  EXPECT_NEAR(q.radius_edge, 1 / std::sqrt(2.0), 1e-6);  // good R/l ...
  const double theta = deg(std::asin(2 * h * std::sqrt(1 + h * h) / (1 + 2 * h * h)));
  EXPECT_NEAR(q.min_dihedral_deg, theta, 1e-9);  // ... but a tiny dihedral
  EXPECT_LT(q.min_dihedral_deg, 0.2);
  // The side edges are 01 (ab), 03 (ad), 12 (bc), 23 (cd); the diagonals
  // 02 (ac) and 13 (bd) carry dihedrals close to 180.
  for (int i : {0, 2, 3, 5}) EXPECT_NEAR(q.dihedral_deg[i], theta, 1e-9);
  EXPECT_GT(q.dihedral_deg[1], 179.5);
  EXPECT_GT(q.dihedral_deg[4], 179.5);
  EXPECT_NEAR(q.normalized_volume, (h / 3) / std::pow(1 + h * h, 1.5), 1e-15);
  EXPECT_GT(q.aspect_ratio, 100);  // bad aspect ratio, good radius-edge ratio
}

// A cap: the apex lies just above the centroid of the opposite face. Huge
// circumradius, three dihedrals near 180 at the apex edges, apex angles ~120.
TEST(Quality, Cap) {
  const double eps = 1e-4;
  const Point3 a{{0, 0, 0}}, b{{1, 0, 0}}, c{{0, 1, 0}}, d{{1.0 / 3, 1.0 / 3, eps}};
  const TetQuality q = tet_quality(a, b, c, d);
  expect_well_defined(q);
  EXPECT_NEAR(q.volume, eps / 6, 1e-18);
  EXPECT_GT(q.radius_edge, 2.2);
  EXPECT_GT(q.aspect_ratio, 1000);
  // Apex edges 03, 13, 23: dihedral near 180; base edges 01, 02, 12: near 0.
  for (int i : {2, 4, 5}) EXPECT_GT(q.dihedral_deg[i], 179);
  for (int i : {0, 1, 3}) EXPECT_LT(q.dihedral_deg[i], 1);
  // The apex angles of faces 0 (bcd), 1 (acd), 2 (abd) surround the
  // projection of d, inside abc: their sum tends to 360 as eps -> 0.
  const double apex_sum = q.face_angle_deg[2] + q.face_angle_deg[5] + q.face_angle_deg[8];
  EXPECT_NEAR(apex_sum, 360, 1e-3);
  // Circumradius from the definition: center x with 2 x.e_i = |e_i|^2; for
  // e1 = (1,0,0), e2 = (0,1,0) this gives x = (1/2, 1/2, z) with
  // 2 (d . x) = |d|^2.
  const double z = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - d[0] - d[1]) / (2 * d[2]);
  EXPECT_NEAR(q.radius / std::sqrt(0.5 + z * z), 1, 1e-9);
}

// A needle: a tiny base triangle and a far apex.
TEST(Quality, Needle) {
  const double eps = 1e-3;
  const Point3 a{{0, 0, 0}}, b{{eps, 0, 0}}, c{{0, eps, 0}}, d{{0, 0, 1}};
  const TetQuality q = tet_quality(a, b, c, d);
  expect_well_defined(q);
  // Circumcenter (eps/2, eps/2, 1/2).
  EXPECT_NEAR(q.radius, std::sqrt(eps * eps / 2 + 0.25), 1e-15);
  EXPECT_NEAR(q.shortest_edge, eps, 1e-18);
  EXPECT_NEAR(q.radius_edge, std::sqrt(eps * eps / 2 + 0.25) / eps, 1e-9);
  EXPECT_NEAR(q.longest_edge, std::sqrt(1 + eps * eps), 1e-15);
  // Apex angle of face abd (face 2, corner 2) is arctan(eps).
  EXPECT_NEAR(q.face_angle_deg[8], deg(std::atan(eps)), 1e-10);
  EXPECT_LT(q.min_face_angle_deg, deg(std::atan(eps)) + 1e-10);
  EXPECT_NEAR(q.dihedral_deg[2], 90, 1e-10);  // edge ad between x=0 and y=0
}

TEST(Quality, InvariantsOnRandomTets) {
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int n = 0; n < 200; ++n) {
    Point3 p[4];
    for (auto& v : p)
      for (double& x : v) x = u(rng);
    const TetQuality q = tet_quality(p[0], p[1], p[2], p[3]);
    expect_well_defined(q);
    // Angles of each face sum to 180.
    for (int f = 0; f < 4; ++f)
      EXPECT_NEAR(q.face_angle_deg[3 * f] + q.face_angle_deg[3 * f + 1] + q.face_angle_deg[3 * f + 2], 180, 1e-9);
    // Every edge is a chord of the circumsphere.
    EXPECT_GE(q.radius, q.longest_edge / 2 * (1 - 1e-12));
    // R/l >= sqrt(6)/4 and r <= R/3 for every tetrahedron.
    EXPECT_GE(q.radius_edge, std::sqrt(6.0) / 4 * (1 - 1e-12));
    EXPECT_GE(q.aspect_ratio, 3 * (1 - 1e-12));
    // Dihedral at edge 01: sin theta = 3 |vol| |e01| / (2 A2 A3), where A2,
    // A3 are the areas of faces 013 (opposite 2) and 012 (opposite 3).
    auto area = [](const Point3& x, const Point3& y, const Point3& z) {
      const double a2 = dist2(x, y), b2 = dist2(y, z), c2 = dist2(z, x);
      // Heron in the form 16 A^2 = 4 a^2 b^2 - (a^2 + b^2 - c^2)^2.
      return 0.25 * std::sqrt(std::max(0.0, 4 * a2 * b2 - (a2 + b2 - c2) * (a2 + b2 - c2)));
    };
    const double s =
        3 * std::fabs(q.volume) * std::sqrt(dist2(p[0], p[1])) / (2 * area(p[0], p[1], p[3]) * area(p[0], p[1], p[2]));
    EXPECT_NEAR(std::sin(q.dihedral_deg[0] * kPi / 180), s, 1e-8);
    // Unweighted is the same as all-zero weights.
    const std::array<double, 4> zero{};
    EXPECT_DOUBLE_EQ(tet_quality(p[0], p[1], p[2], p[3], &zero).radius, q.radius);
  }
}

TEST(Quality, DegenerateTetsAreWellDefined) {
  const Point3 a{{0, 0, 0}}, b{{1, 0, 0}}, c{{1, 1, 0}}, d{{0, 1, 0}}, m{{0.5, 0, 0}};
  // Four coplanar points (the sliver with h = 0).
  TetQuality q = tet_quality(a, b, c, d);
  expect_well_defined(q);
  EXPECT_EQ(q.volume, 0);
  EXPECT_EQ(q.inradius, 0);
  EXPECT_EQ(q.radius, kInf);
  EXPECT_EQ(q.radius_edge, kInf);
  EXPECT_EQ(q.aspect_ratio, kInf);
  for (double x : q.dihedral_deg) EXPECT_TRUE(x == 0 || x == 180) << x;
  EXPECT_EQ(q.min_dihedral_deg, 0);
  EXPECT_EQ(q.max_dihedral_deg, 180);
  // Collinear points and a flat triangle with a vertex on an edge.
  expect_well_defined(tet_quality(a, m, b, c));
  expect_well_defined(tet_quality(a, m, b, Point3{{2, 0, 0}}));
  // Coincident vertices.
  q = tet_quality(a, a, b, c);
  expect_well_defined(q);
  EXPECT_EQ(q.shortest_edge, 0);
  EXPECT_EQ(q.radius_edge, kInf);
  EXPECT_EQ(q.normalized_volume, 0);
  q = tet_quality(a, a, a, a);
  expect_well_defined(q);
  EXPECT_EQ(q.min_face_angle_deg, 0);
  EXPECT_EQ(q.max_dihedral_deg, 0);
  // Weighted degenerate tet.
  const std::array<double, 4> w{{0.1, 0.2, 0.3, 0.4}};
  expect_well_defined(tet_quality(a, b, c, d, &w));
}

// Random tets, flat and nearly flat ones, needles, coincident points and tets
// far from 1 in scale.
std::vector<std::array<Point3, 4>> awkward_tets() {
  std::mt19937_64 rng(777);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<std::array<Point3, 4>> tets;
  for (int n = 0; n < 500; ++n) {
    std::array<Point3, 4> p;
    for (auto& v : p)
      for (double& x : v) x = u(rng);
    if (n % 5 == 1) p[3][2] = p[0][2] + 1e-9 * u(rng);  // nearly flat
    if (n % 5 == 2) p[3] = {{(p[0][0] + p[1][0]) / 2, (p[0][1] + p[1][1]) / 2, (p[0][2] + p[1][2]) / 2}};
    if (n % 5 == 3)
      for (auto& v : p)
        for (double& x : v) x = std::ldexp(x, (n % 2 ? 600 : -600));
    tets.push_back(p);
  }
  const Point3 a{{0, 0, 0}}, b{{1, 0, 0}}, c{{1, 1, 0}}, d{{0, 1, 0}};
  tets.push_back({{a, b, c, d}});
  tets.push_back({{a, a, b, c}});
  tets.push_back({{a, a, a, a}});
  tets.push_back({{a, b, Point3{{2, 0, 0}}, Point3{{3, 0, 0}}}});
  return tets;
}

TEST(Quality, MinDihedralAloneIsTetQualitysBitForBit) {
  // The mesher's sliver scans use tet_min_dihedral_deg in place of
  // tet_quality: the same double (compared by ==).
  int small = 0;
  for (const auto& p : awkward_tets()) {
    const double m = tet_min_dihedral_deg(p[0], p[1], p[2], p[3]);
    EXPECT_EQ(m, tet_quality(p[0], p[1], p[2], p[3]).min_dihedral_deg);
    small += m < 3;
  }
  EXPECT_GT(small, 50);  // the nearly flat ones are slivers
}

TEST(Quality, RadiusEdgeAloneIsTetQualitysBitForBit) {
  // classify_tets' weighted view keeps only R/l: tet_radius_edge gives
  // tet_quality's double, with and without weights (compared by ==).
  std::mt19937 rng(14);
  std::uniform_real_distribution<double> weight(0, 0.5);
  int weighted = 0;
  for (const auto& p : awkward_tets()) {
    EXPECT_EQ(tet_radius_edge(p[0], p[1], p[2], p[3]), tet_quality(p[0], p[1], p[2], p[3]).radius_edge);
    const std::array<double, 4> w{{weight(rng), weight(rng), weight(rng), weight(rng)}};
    const double rho = tet_radius_edge(p[0], p[1], p[2], p[3], &w),
                 full = tet_quality(p[0], p[1], p[2], p[3], &w).radius_edge;
    EXPECT_TRUE(rho == full || (std::isnan(rho) && std::isnan(full))) << rho << " " << full;
    weighted += std::isfinite(full) && full != tet_quality(p[0], p[1], p[2], p[3]).radius_edge;
  }
  EXPECT_GT(weighted, 50);  // the weights moved R/l on most of them
}

TEST(Quality, MinDihedralUpToABoundIsTheFullMeasureAtOrBelowIt) {
  // Rule 7's scan (issue 15) skips the angles certainly above theta: at or
  // below the bound the answer is tet_min_dihedral_deg's double, above it
  // any value above the bound. Bounds at the tet's own angle and one ulp on
  // either side probe the certificate's margin.
  int at_or_below = 0, above = 0;
  for (const auto& p : awkward_tets()) {
    const double m = tet_min_dihedral_deg(p[0], p[1], p[2], p[3]);
    std::vector<double> bounds{0, 1e-3, 0.5, 3, 5, 15, 45, 88.9, 89, 120};
    for (double b : {m, std::nextafter(m, 0.0), std::nextafter(m, 180.0)})
      if (b >= 0) bounds.push_back(b);
    for (double b : bounds) {
      const double u = tet_min_dihedral_deg_upto(p[0], p[1], p[2], p[3], b);
      if (m <= b) {
        EXPECT_EQ(u, m) << "bound " << b;
        ++at_or_below;
      } else {
        EXPECT_GT(u, b) << "angle " << m;
        ++above;
      }
    }
  }
  EXPECT_GT(at_or_below, 500);
  EXPECT_GT(above, 500);
}

TEST(Quality, EqualWeightsGiveOrthoradiusSquaredRMinusW) {
  // Section 3: |z - p_i|^2 - W - Z^2 = 0 with the circumcenter z, so
  // Z^2 = R^2 - W = 3 - W for the regular tetrahedron (R^2 = 3).
  for (double w : {0.0, 0.25, 1.0, 2.5}) {
    const std::array<double, 4> ws{{w, w, w, w}};
    const TetQuality q = tet_quality(kR0, kR1, kR2, kR3, &ws);
    EXPECT_NEAR(q.radius * q.radius, 3 - w, 1e-13) << w;
    EXPECT_NEAR(q.radius_edge, std::sqrt(3 - w) / (2 * std::sqrt(2.0)), 1e-14);
    // The aspect ratio stays the unweighted one.
    EXPECT_NEAR(q.aspect_ratio, 3, 1e-13);
  }
  // A negative orthosphere weight (W > R^2) reports radius 0.
  const std::array<double, 4> big{{4, 4, 4, 4}};
  const TetQuality q = tet_quality(kR0, kR1, kR2, kR3, &big);
  EXPECT_EQ(q.radius, 0);
  EXPECT_EQ(q.radius_edge, 0);
}

/// Solves the 3x3 system M x = r by Gaussian elimination with partial pivoting.
Point3 solve3(double M[3][3], double r[3]) {
  for (int col = 0; col < 3; ++col) {
    int piv = col;
    for (int row = col + 1; row < 3; ++row)
      if (std::fabs(M[row][col]) > std::fabs(M[piv][col])) piv = row;
    for (int k = 0; k < 3; ++k) std::swap(M[col][k], M[piv][k]);
    std::swap(r[col], r[piv]);
    for (int row = col + 1; row < 3; ++row) {
      const double f = M[row][col] / M[col][col];
      for (int k = col; k < 3; ++k) M[row][k] -= f * M[col][k];
      r[row] -= f * r[col];
    }
  }
  Point3 x;
  for (int row = 2; row >= 0; --row) {
    double s = r[row];
    for (int k = row + 1; k < 3; ++k) s -= M[row][k] * x[k];
    x[row] = s / M[row][row];
  }
  return x;
}

TEST(Quality, WeightedOrthosphereSatisfiesDefinition) {
  // Right-corner tet by hand: 2 z_i = 1 - W_{i+1} + W_0, so z = (0.55, 0.45,
  // 0.5) and Z^2 = |z|^2 - W_0 = 0.655 for W = (0.1, 0, 0.2, 0.1); checked
  // against the definition |z - p_i|^2 - W_i = Z^2 for all four i.
  const Point3 p[4] = {{{0, 0, 0}}, {{1, 0, 0}}, {{0, 1, 0}}, {{0, 0, 1}}};
  const std::array<double, 4> w{{0.1, 0.0, 0.2, 0.1}};
  const Point3 z{{(1 - w[1] + w[0]) / 2, (1 - w[2] + w[0]) / 2, (1 - w[3] + w[0]) / 2}};
  const double Z2 = dist2(z, p[0]) - w[0];
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(dist2(z, p[i]) - w[i], Z2, 1e-15);
  const TetQuality q = tet_quality(p[0], p[1], p[2], p[3], &w);
  EXPECT_NEAR(Z2, 0.655, 1e-15);
  EXPECT_NEAR(q.radius, std::sqrt(Z2), 1e-15);
  EXPECT_NEAR(q.radius_edge, std::sqrt(Z2), 1e-15);  // l = 1

  // Random weighted tets: solve the definition independently (Gaussian
  // elimination), check its residuals and compare.
  std::mt19937_64 rng(777);
  std::uniform_real_distribution<double> u(-1, 1), uw(0, 0.3);
  for (int n = 0; n < 100; ++n) {
    Point3 v[4];
    std::array<double, 4> W;
    for (int i = 0; i < 4; ++i) {
      for (double& x : v[i]) x = u(rng);
      W[i] = uw(rng);
    }
    const TetQuality t = tet_quality(v[0], v[1], v[2], v[3], &W);
    if (std::fabs(t.normalized_volume) < 1e-3) continue;  // ill-conditioned
    double M[3][3], r[3];
    for (int i = 0; i < 3; ++i) {
      for (int k = 0; k < 3; ++k) M[i][k] = 2 * (v[i + 1][k] - v[0][k]);
      r[i] = dist2(v[i + 1], Point3{{0, 0, 0}}) - dist2(v[0], Point3{{0, 0, 0}}) - W[i + 1] + W[0];
    }
    const Point3 c = solve3(M, r);
    const double c2 = dist2(c, v[0]) - W[0];
    for (int i = 1; i < 4; ++i) EXPECT_NEAR(dist2(c, v[i]) - W[i], c2, 1e-9 * (1 + c2));
    EXPECT_NEAR(t.radius, c2 > 0 ? std::sqrt(c2) : 0.0, 1e-9 * (1 + t.radius));
  }
}

TEST(Quality, MeshQualityUsesWeightsAndChecksSizes) {
  TetMesh mesh;
  mesh.vertices = {kR0, kR1, kR2, kR3};
  mesh.tets = {{{0, 1, 2, 3}}};
  std::vector<TetQuality> q = mesh_quality(mesh);
  ASSERT_EQ(q.size(), 1u);
  EXPECT_NEAR(q[0].radius, std::sqrt(3.0), 1e-14);
  mesh.weights = {0.5, 0.5, 0.5, 0.5};
  q = mesh_quality(mesh);
  EXPECT_NEAR(q[0].radius, std::sqrt(2.5), 1e-14);
  mesh.weights = {0.5};
  EXPECT_THROW(mesh_quality(mesh), std::invalid_argument);
  mesh.weights.clear();
  mesh.tets = {{{0, 1, 2, 4}}};
  EXPECT_THROW(mesh_quality(mesh), std::out_of_range);
  EXPECT_THROW(mesh_stats(mesh, {}), std::invalid_argument);
}

/// A TetQuality with only the fields mesh_stats bins on.
TetQuality fake(double rho, double min_dihedral, double volume = 1) {
  TetQuality q;
  q.volume = volume;
  q.normalized_volume = volume;  // the same sign, as tet_quality gives
  q.radius_edge = rho;
  q.min_dihedral_deg = min_dihedral;
  q.max_dihedral_deg = 100;
  q.min_face_angle_deg = 30;
  q.aspect_ratio = 4;
  return q;
}

TEST(Quality, StatsBinBoundaries) {
  // Table 2 bins: R/l in [0.6, 1.4], (1.4, 2.2], > 2.2; smallest dihedral in
  // [0, 3), [3, 5), [5, 10).
  const double up = std::nextafter(1.4, 2.0), up2 = std::nextafter(2.2, 3.0);
  std::vector<TetQuality> q = {
      fake(0.59, 50),  // below 0.6
      fake(0.6, 50),   // [0.6, 1.4]
      fake(1.4, 50),   // [0.6, 1.4] (closed)
      fake(up, 50),    // (1.4, 2.2]
      fake(2.2, 50),   // (1.4, 2.2] (closed)
      fake(up2, 50),   // > 2.2
      fake(kInf, 50),  // > 2.2 (flat tet)
      fake(1, 0),      // dihedral [0, 3)
      fake(1, std::nextafter(3.0, 0.0)),
      fake(1, 3),  // [3, 5)
      fake(1, std::nextafter(5.0, 0.0)),
      fake(1, 5),  // [5, 10)
      fake(1, std::nextafter(10.0, 0.0)),
      fake(1, 10),      // not binned
      fake(3, 1),       // R/l > 2.2 with a small dihedral: not a sliver
      fake(1, 60, 0),   // zero volume: inverted
      fake(1, 60, -2),  // negative volume: inverted
  };
  TetMesh mesh;
  mesh.vertices.resize(5);
  mesh.tets.resize(q.size());
  const MeshStats s = mesh_stats(mesh, q);
  EXPECT_EQ(s.vertices, 5u);
  EXPECT_EQ(s.tets, q.size());
  EXPECT_EQ(s.radius_edge_below, 1u);
  EXPECT_EQ(s.radius_edge_bins[0], 2u + 9u);  // 0.6, 1.4 and the 9 with rho = 1
  EXPECT_EQ(s.radius_edge_bins[1], 2u);
  EXPECT_EQ(s.radius_edge_bins[2], 3u);
  EXPECT_EQ(s.dihedral_bins[0], 3u);  // 0, 3^-, and the rho = 3 tet
  EXPECT_EQ(s.dihedral_bins[1], 2u);
  EXPECT_EQ(s.dihedral_bins[2], 2u);
  EXPECT_EQ(s.slivers, 2u);
  EXPECT_EQ(s.inverted, 2u);
  EXPECT_DOUBLE_EQ(s.volume, 15.0 - 2.0);
  EXPECT_EQ(s.min_dihedral_deg, 0);
  EXPECT_EQ(s.max_dihedral_deg, 100);
  EXPECT_EQ(s.min_face_angle_deg, 30);
  EXPECT_EQ(s.max_radius_edge, kInf);
  EXPECT_EQ(s.max_aspect_ratio, 4);
  // Histogram: k <= angle < k + 1.
  EXPECT_EQ(s.min_dihedral_histogram[0], 1u);
  EXPECT_EQ(s.min_dihedral_histogram[1], 1u);
  EXPECT_EQ(s.min_dihedral_histogram[2], 1u);  // 3^-
  EXPECT_EQ(s.min_dihedral_histogram[3], 1u);
  EXPECT_EQ(s.min_dihedral_histogram[4], 1u);
  EXPECT_EQ(s.min_dihedral_histogram[5], 1u);
  EXPECT_EQ(s.min_dihedral_histogram[9], 1u);
  EXPECT_EQ(s.min_dihedral_histogram[10], 1u);
  EXPECT_EQ(s.min_dihedral_histogram[50], 7u);
  EXPECT_EQ(s.min_dihedral_histogram[60], 2u);
  std::size_t total = 0;
  for (std::size_t c : s.min_dihedral_histogram) total += c;
  EXPECT_EQ(total, q.size());
  EXPECT_EQ(s.min_face_angle_histogram[30], q.size());
  EXPECT_EQ(histogram_bin(-1, 90), 0u);
  EXPECT_EQ(histogram_bin(std::nan(""), 90), 0u);
  EXPECT_EQ(histogram_bin(90, 90), 89u);
}

TEST(Quality, StatsOnSmallMeshOfKnownTets) {
  TetMesh mesh;
  const double h = 1e-3;
  mesh.vertices = {kR0,         kR1,         kR2,         kR3,                          // regular
                   {{0, 0, 0}}, {{1, 0, 0}}, {{0, 1, 0}}, {{0, 0, 1}},                  // corner
                   {{0, 0, 0}}, {{1, 0, h}}, {{1, 1, 0}}, {{0, 1, h}},                  // sliver
                   {{0, 0, 0}}, {{1, 0, 0}}, {{0, 1, 0}}, {{1.0 / 3, 1.0 / 3, 1e-4}}};  // cap
  mesh.tets = {{{0, 1, 2, 3}}, {{4, 5, 6, 7}}, {{8, 9, 10, 11}}, {{12, 13, 14, 15}}};
  const MeshStats s = mesh_stats(mesh, mesh_quality(mesh));
  EXPECT_EQ(s.tets, 4u);
  EXPECT_EQ(s.vertices, 16u);
  EXPECT_EQ(s.inverted, 0u);
  EXPECT_NEAR(s.volume, 8.0 / 3 + 1.0 / 6 + h / 3 + 1e-4 / 6, 1e-14);
  EXPECT_EQ(s.radius_edge_below, 0u);
  EXPECT_EQ(s.radius_edge_bins[0], 3u);  // sqrt(6)/4, sqrt(3)/2, ~1/sqrt 2
  EXPECT_EQ(s.radius_edge_bins[1], 0u);
  EXPECT_EQ(s.radius_edge_bins[2], 1u);         // the cap
  EXPECT_EQ(s.dihedral_bins[0], 2u);            // sliver and cap
  EXPECT_EQ(s.slivers, 1u);                     // the cap has R/l > 2.2
  EXPECT_EQ(s.min_dihedral_histogram[70], 1u);  // 70.53
  EXPECT_EQ(s.min_dihedral_histogram[54], 1u);  // 54.74
  EXPECT_EQ(s.min_dihedral_histogram[0], 2u);
  // Smallest face angles 60, 45, ~45 (bins 59/60 and 44/45 depending on the
  // last bit) and, for the cap, the angle at b in face bcd between c - b =
  // (-1, 1) and d - b = (-2/3, 1/3): (180 - atan(1/2)) - 135 ~ 18.43.
  EXPECT_EQ(s.min_face_angle_histogram[18], 1u);
  std::size_t faces = 0;
  for (std::size_t c : s.min_face_angle_histogram) faces += c;
  EXPECT_EQ(faces, 4u);
  EXPECT_NEAR(s.max_dihedral_deg, 180, 0.5);
}

// Scale safety (beyond the paper): a tet and the same tet scaled by 10^k or
// 2^k, for every k where its coordinates stay finite, give the same angles,
// R/l, sigma and aspect ratio, and lengths and volumes scaled by s and s^3
// wherever those are doubles. Before the scaled evaluation, 1e60 gave 90
// degrees for a dihedral of 19.47 (|u x v|^2 overflowed) and 1e-120 gave
// radius 0.
TEST(TetQuality, ScaleFreeMeasuresAreTheSameAtEveryScale) {
  const Point3 a{{0, 0, 0}}, b{{1, 0, 0}}, c{{0.3, 0.9, 0}}, d{{0.2, 0.4, 0.7}};
  const std::array<double, 4> w{{0.01, 0.02, 0.0, 0.03}};
  const TetQuality q0 = tet_quality(a, b, c, d);
  const TetQuality w0 = tet_quality(a, b, c, d, &w);
  auto close = [](double x, double y) { return std::fabs(x - y) <= 1e-12 * std::max(std::fabs(y), 1e-300); };
  for (int k = -320; k <= 307; k += 7) {
    for (bool binary : {false, true}) {
      const double s = binary ? std::ldexp(1.0, 3 * k) : std::pow(10.0, k);
      if (!(s > 0) || !std::isfinite(s)) continue;
      auto S = [&](const Point3& p) { return Point3{{p[0] * s, p[1] * s, p[2] * s}}; };
      const std::array<double, 4> ws{{w[0] * s * s, w[1] * s * s, w[2] * s * s, w[3] * s * s}};
      const TetQuality q = tet_quality(S(a), S(b), S(c), S(d));
      SCOPED_TRACE("scale " + std::to_string(s));
      expect_well_defined(q);
      if (s < 1e-300) continue;  // 0.3 s, 0.9 s ... are subnormal: not the same tet
      EXPECT_TRUE(close(q.min_dihedral_deg, q0.min_dihedral_deg)) << q.min_dihedral_deg;
      EXPECT_TRUE(close(q.max_dihedral_deg, q0.max_dihedral_deg)) << q.max_dihedral_deg;
      EXPECT_TRUE(close(q.min_face_angle_deg, q0.min_face_angle_deg));
      EXPECT_TRUE(close(q.radius_edge, q0.radius_edge)) << q.radius_edge;
      EXPECT_TRUE(close(q.normalized_volume, q0.normalized_volume));
      EXPECT_TRUE(close(q.aspect_ratio, q0.aspect_ratio));
      EXPECT_TRUE(close(q.radius, q0.radius * s));
      EXPECT_TRUE(close(q.shortest_edge, q0.shortest_edge * s));
      EXPECT_TRUE(close(q.inradius, q0.inradius * s));
      const double v = q0.volume * s * s * s;
      if (std::fabs(v) > 1e-290 && std::isfinite(v)) EXPECT_TRUE(close(q.volume, v)) << q.volume << " vs " << v;
      EXPECT_EQ(tet_orientation(S(a), S(b), S(c), S(d)), 1);
      // Weights scale with s^2: the orthoradius with s, while s^2 is a double.
      if (s * s > 1e-300 && std::isfinite(s * s)) {
        const TetQuality qw = tet_quality(S(a), S(b), S(c), S(d), &ws);
        EXPECT_TRUE(close(qw.radius, w0.radius * s)) << qw.radius << " vs " << w0.radius * s;
        EXPECT_TRUE(close(qw.radius_edge, w0.radius_edge));
      }
    }
  }
}

// Corners near the largest double: coordinates of 1e308 and -1e308 (their
// differences overflow) still give the unit tet's angles.
TEST(TetQuality, CornersAtTheLargestDoublesGiveTheRightAngles) {
  const double s = 1e308;
  const TetQuality q = tet_quality({{-s, -s, -s}}, {{s, -s, -s}}, {{-s, s, -s}}, {{-s, -s, s}});
  const TetQuality q0 = tet_quality({{0, 0, 0}}, {{1, 0, 0}}, {{0, 1, 0}}, {{0, 0, 1}});
  EXPECT_NEAR(q.min_dihedral_deg, q0.min_dihedral_deg, 1e-12);
  EXPECT_NEAR(q.radius_edge, q0.radius_edge, 1e-12);
  EXPECT_EQ(q.volume, kInf);         // (2e308)^3 / 6 is beyond double range
  EXPECT_EQ(q.shortest_edge, kInf);  // 2e308: beyond double range too
  const TetQuality h = tet_quality({{-s / 2, -s / 2, -s / 2}}, {{s / 2, -s / 2, -s / 2}}, {{-s / 2, s / 2, -s / 2}},
                                   {{-s / 2, -s / 2, s / 2}});
  EXPECT_NEAR(h.shortest_edge / s, q0.shortest_edge, 1e-12);
  EXPECT_NEAR(h.radius / s, q0.radius, 1e-12);
  EXPECT_EQ(tet_orientation({{-s, -s, -s}}, {{s, -s, -s}}, {{-s, s, -s}}, {{-s, -s, s}}), 1);
}

// Points that differ only by subnormal amounts: the measures are those of
// the tet scaled up (no product of subnormals underflows), and the sign of a
// volume too small for doubles is exact.
TEST(TetQuality, SubnormalTetsAreMeasuredLikeTheirScaledCopies) {
  const double t = 1e-310;
  const TetQuality q = tet_quality({{0, 0, 0}}, {{t, 0, 0}}, {{0, t, 0}}, {{0, 0, t}});
  const TetQuality q0 = tet_quality({{0, 0, 0}}, {{1, 0, 0}}, {{0, 1, 0}}, {{0, 0, 1}});
  EXPECT_NEAR(q.min_dihedral_deg, q0.min_dihedral_deg, 1e-9);
  EXPECT_NEAR(q.radius_edge, q0.radius_edge, 1e-9);
  EXPECT_EQ(q.volume, 0);  // 1.7e-931: underflows in the input's units
  EXPECT_GT(q.normalized_volume, 0);
  EXPECT_EQ(tet_orientation({{0, 0, 0}}, {{t, 0, 0}}, {{0, t, 0}}, {{0, 0, t}}), 1);
  TetMesh m;
  m.vertices = {{{0, 0, 0}}, {{t, 0, 0}}, {{0, t, 0}}, {{0, 0, t}}};
  m.tets = {{{0, 1, 2, 3}}, {{0, 2, 1, 3}}};
  const MeshStats st = mesh_stats(m, mesh_quality(m));
  EXPECT_EQ(st.inverted, 1u);  // the second, by its exact sign
}

TEST(Quality, MeshQualityUsesTheWeightsOnlyWhenAskedTo) {
  TetMesh m;
  m.vertices = {{{0, 0, 0}}, {{1, 0, 0}}, {{0, 1, 0}}, {{0, 0, 1}}};
  m.tets = {{{0, 1, 2, 3}}};
  m.weights = {0.2, 0, 0, 0};
  const TetQuality plain = tet_quality(m.vertices[0], m.vertices[1], m.vertices[2], m.vertices[3]);
  const std::array<double, 4> w{{0.2, 0, 0, 0}};
  const TetQuality weighted = tet_quality(m.vertices[0], m.vertices[1], m.vertices[2], m.vertices[3], &w);
  ASSERT_NE(plain.radius, weighted.radius);
  EXPECT_EQ(mesh_quality(m)[0].radius, weighted.radius);
  EXPECT_EQ(mesh_quality(m, {}, true)[0].radius_edge, weighted.radius_edge);
  EXPECT_EQ(mesh_quality(m, {}, false)[0].radius, plain.radius);
  EXPECT_EQ(mesh_quality(m, {}, false)[0].radius_edge, plain.radius_edge);
  // Unweighted, mismatched weights are not looked at.
  m.weights = {1};
  EXPECT_THROW(mesh_quality(m), std::invalid_argument);
  EXPECT_NO_THROW(mesh_quality(m, {}, false));
}

TEST(Quality, RadiusEdgeBinIsTable2s) {
  EXPECT_EQ(radius_edge_bin(0.59), -1);
  EXPECT_EQ(radius_edge_bin(0.6), 0);
  EXPECT_EQ(radius_edge_bin(1.4), 0);
  EXPECT_EQ(radius_edge_bin(std::nextafter(1.4, 2.0)), 1);
  EXPECT_EQ(radius_edge_bin(2.2), 1);
  EXPECT_EQ(radius_edge_bin(std::nextafter(2.2, 3.0)), 2);
  EXPECT_EQ(radius_edge_bin(kInf), 2);
  EXPECT_EQ(radius_edge_bin(std::nan("")), 2);
}

}  // namespace
}  // namespace wqmesh
