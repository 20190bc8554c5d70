// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of exact.h: each of exact::sign's three stages (error-bounded double,
// expansion, MP_Float) against MP_Float's exact value, on random, nearly
// degenerate and exactly degenerate inputs at several scales, and the
// expansion's fallback where two-product cannot stay exact; ExactRing (the
// wasm build's exact ring type of Epick) in CGAL's own predicates against
// MP_Float.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include <CGAL/Simple_cartesian.h>

#include "exact.h"
#include "exact_ring.h"

namespace wqmesh {
namespace {

using exact::detail::Approx;
using exact::detail::Expansion;
using MP = CGAL::MP_Float;

/// The expansion's components summed exactly.
MP value(const Expansion& x) {
  MP s(0);
  for (int i = 0; i < x.size(); ++i) s = s + MP(x[i]);
  return s;
}

/// Smallest magnitude first, no zero, no two components overlapping (the
/// smaller one below half an ulp of the larger one's lowest set bit is what
/// Shewchuk's algorithms give; strictly increasing magnitudes is the part
/// the sign relies on).
bool well_formed(const Expansion& x) {
  for (int i = 0; i < x.size(); ++i) {
    if (x[i] == 0 || !std::isfinite(x[i])) return false;
    if (i > 0 && !(std::fabs(x[i - 1]) < std::fabs(x[i]))) return false;
  }
  return true;
}

// Predicates of the degrees the mesher uses: 2D orientation (2), the facets'
// in-circle test under a metric (4), 3D orientation (3) and the 3D power test
// of five weighted points (5, through the lifted 4x4 determinant).
template <class NT>
NT orient2(const std::array<double, 8>& c) {
  return (NT(c[2]) - NT(c[0])) * (NT(c[5]) - NT(c[1])) - (NT(c[3]) - NT(c[1])) * (NT(c[4]) - NT(c[0]));
}
template <class NT>
NT incircle(const std::array<double, 8>& c, double A = 1, double B = 0, double C = 1) {
  const NT tx(c[6]), ty(c[7]), a(A), b(B), cc(C);
  const NT px = NT(c[0]) - tx, py = NT(c[1]) - ty, qx = NT(c[2]) - tx, qy = NT(c[3]) - ty;
  const NT rx = NT(c[4]) - tx, ry = NT(c[5]) - ty;
  const NT pq = a * px * px + b * px * py + cc * py * py;
  const NT qq = a * qx * qx + b * qx * qy + cc * qy * qy;
  const NT rq = a * rx * rx + b * rx * ry + cc * ry * ry;
  return px * (qy * rq - ry * qq) - py * (qx * rq - rx * qq) + pq * (qx * ry - rx * qy);
}
template <class NT>
NT orient3(const std::array<Point3, 5>& p) {
  NT u[3], v[3], w[3];
  for (int i = 0; i < 3; ++i) {
    u[i] = NT(p[1][i]) - NT(p[0][i]);
    v[i] = NT(p[2][i]) - NT(p[0][i]);
    w[i] = NT(p[3][i]) - NT(p[0][i]);
  }
  return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0]);
}
template <class NT>
NT power5(const std::array<Point3, 5>& p, const std::array<double, 5>& w) {
  NT m[4][4];
  for (int r = 0; r < 4; ++r) {
    NT l(0);
    for (int i = 0; i < 3; ++i) {
      m[r][i] = NT(p[r][i]) - NT(p[4][i]);
      l = l + m[r][i] * m[r][i];
    }
    m[r][3] = l - NT(w[r]) + NT(w[4]);
  }
  auto det3 = [&](int r0, int r1, int r2, int c0, int c1, int c2) {
    return m[r0][c0] * (m[r1][c1] * m[r2][c2] - m[r1][c2] * m[r2][c1]) -
           m[r0][c1] * (m[r1][c0] * m[r2][c2] - m[r1][c2] * m[r2][c0]) +
           m[r0][c2] * (m[r1][c0] * m[r2][c1] - m[r1][c1] * m[r2][c0]);
  };
  return m[0][3] * det3(1, 2, 3, 0, 1, 2) - m[1][3] * det3(0, 2, 3, 0, 1, 2) + m[2][3] * det3(0, 1, 3, 0, 1, 2) -
         m[3][3] * det3(0, 1, 2, 0, 1, 2);
}

struct Counts {
  int decided = 0, expansion = 0, fallback = 0, cases = 0;
};

/// Checks every stage of one expression against MP_Float and tallies which
/// stage would decide it.
template <class Expr>
void check(const Expr& expr, Counts& n) {
  const MP exact = expr(MP(0));
  const int s = static_cast<int>(CGAL::sign(exact));
  ++n.cases;
  const Approx a = expr(Approx(0));
  if (a.decided()) {
    ++n.decided;
    ASSERT_EQ(a.v > 0 ? 1 : -1, s) << "the error bound decided a wrong sign";
    ASSERT_LE(std::fabs(CGAL::to_double(exact) - a.v), a.e + std::fabs(a.v) * 0x1p-52)
        << "exact value outside the bound";
  }
  const Expansion x = expr(Expansion(0));
  if (x.exact()) {
    if (!a.decided()) ++n.expansion;
    ASSERT_TRUE(well_formed(x));
    ASSERT_TRUE(value(x) == exact) << "the expansion is not the exact value";
    ASSERT_EQ(x.sign(), s);
  } else if (!a.decided()) {
    ++n.fallback;
  }
  ASSERT_EQ(exact::sign(expr), s);
}

TEST(Exact, TwoProductAndSumsAreErrorFree) {
  // Full 53-bit mantissas, where a contracted (fused) a * b - c in
  // two_product would lose the low part.
  std::mt19937_64 g(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < 20000; ++k) {
    const double a = u(g) * std::ldexp(1.0, int(g() % 200) - 100), b = u(g) * std::ldexp(1.0, int(g() % 200) - 100);
    const double c = u(g) * std::ldexp(1.0, int(g() % 400) - 200);
    const Expansion p = Expansion(a) * Expansion(b);
    ASSERT_TRUE(p.exact());
    ASSERT_TRUE(well_formed(p));
    ASSERT_TRUE(value(p) == MP(a) * MP(b)) << a << " * " << b;
    const Expansion q = p - Expansion(c) + p * p;
    ASSERT_TRUE(well_formed(q));
    ASSERT_TRUE(value(q) == MP(a) * MP(b) - MP(c) + MP(a) * MP(b) * MP(a) * MP(b));
  }
}

TEST(Exact, EveryStageGivesTheExactSignOnRandomAndDegenerateInput) {
  std::mt19937_64 g(11);
  std::uniform_real_distribution<double> u(-1, 1), t(0, 6.283185307179586);
  Counts n;
  for (const double scale : {1.0, 0x1p-30, 0x1p40, 3.7e-5}) {
    for (int k = 0; k < 1500; ++k) {
      // Random, nearly cocircular (rounded points of one circle) and exactly
      // cocircular (the corners of an axis-parallel rectangle) 2D points.
      std::array<double, 8> r, circle, box;
      for (double& x : r) x = scale * u(g);
      const double cx = scale * u(g), cy = scale * u(g), rad = scale * (0.1 + std::fabs(u(g)));
      for (int i = 0; i < 4; ++i) {
        const double a = t(g);
        circle[2 * i] = cx + rad * std::cos(a);
        circle[2 * i + 1] = cy + rad * std::sin(a);
      }
      const double x0 = scale * u(g), x1 = scale * u(g), y0 = scale * u(g), y1 = scale * u(g);
      box = {x0, y0, x1, y0, x1, y1, x0, y1};
      for (const auto* c : {&r, &circle, &box}) {
        check([&](auto z) { return z + orient2<decltype(z)>(*c); }, n);
        check([&](auto z) { return z + incircle<decltype(z)>(*c); }, n);
        check([&](auto z) { return z + incircle<decltype(z)>(*c, 1.25, 0.5, 0.875); }, n);
      }
      // 3D: random, four coplanar points (a parallelogram), and five points
      // on one sphere about a lattice centre with equal weights.
      std::array<Point3, 5> p, flat, sphere;
      for (auto& q : p)
        for (double& x : q) x = scale * u(g);
      for (int i = 0; i < 3; ++i) {
        flat[0][i] = p[0][i];
        flat[1][i] = p[1][i];
        flat[2][i] = p[2][i];
        flat[3][i] = p[1][i] + p[2][i] - p[0][i];  // rounded: nearly coplanar
        flat[4][i] = p[4][i];
      }
      const std::array<std::array<double, 3>, 5> axis = {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {-1, 0, 0}, {0, -1, 0}}};
      for (int j = 0; j < 5; ++j)
        for (int i = 0; i < 3; ++i) sphere[j][i] = p[0][i] + rad * axis[j][i];
      const std::array<double, 5> w = {scale * scale * std::fabs(u(g)), 0, 0, 0, 0}, w0 = {0, 0, 0, 0, 0};
      for (const auto* q : {&p, &flat, &sphere}) {
        check([&](auto z) { return z + orient3<decltype(z)>(*q); }, n);
        check([&](auto z) { return z + power5<decltype(z)>(*q, w0); }, n);
        check([&](auto z) { return z + power5<decltype(z)>(*q, w); }, n);
      }
    }
  }
  // The inputs reach every stage but the last (those are normal-range doubles).
  EXPECT_GT(n.decided, n.cases / 3);
  EXPECT_GT(n.expansion, n.cases / 10);
  EXPECT_EQ(n.fallback, 0);
}

TEST(Exact, TinyAndHugeValuesFallBackToMpFloat) {
  // Products under 2^-960 lose their low part in two-product, operands
  // above 2^995 overflow its split: the expansion says so and MP_Float
  // decides. Both predicates are exactly degenerate (value 0), so the
  // error bound cannot decide either.
  Counts n;
  for (const double scale : {0x1p-500, 0x1p-530, 0x1p520}) {
    const std::array<double, 8> box = {0, 0, 3 * scale, 0, 3 * scale, 5 * scale, 0, 5 * scale};
    const std::array<double, 8> shifted = {scale, scale, 4 * scale, scale, 4 * scale, 6 * scale, scale, 6 * scale};
    for (const auto* c : {&box, &shifted}) {
      const Expansion x = incircle<Expansion>(*c);
      EXPECT_FALSE(x.exact()) << scale;
      check([&](auto z) { return z + incircle<decltype(z)>(*c); }, n);
    }
  }
  EXPECT_EQ(n.fallback, n.cases);
  // One more ulp on one corner: not cocircular, a sign only MP_Float gets
  // right at these scales.
  for (const double scale : {0x1p-530, 0x1p520}) {
    const std::array<double, 8> c = {scale, scale,    4 * scale, scale, 4 * scale, std::nextafter(6 * scale, 0.0),
                                     scale, 6 * scale};
    check([&](auto z) { return z + incircle<decltype(z)>(c); }, n);
  }
}

TEST(Exact, ErrorBoundOfAnOverflowNeverDecides) {
  const Approx big(1e300);
  EXPECT_FALSE((big * big).decided());
  EXPECT_FALSE((big * big - big * big).decided());
  EXPECT_FALSE((Approx(0) * (big * big)).decided());
  EXPECT_TRUE((big - Approx(1e299)).decided());
}

TEST(Exact, ExactRingGivesMpFloatsAnswersInCgalsPredicates) {
  using KR = CGAL::Simple_cartesian<exact::ExactRing>;
  using KM = CGAL::Simple_cartesian<MP>;
  std::mt19937_64 g(5);
  std::uniform_real_distribution<double> u(-1, 1);
  const KR kr;
  const KM km;
  int zeros = 0, cases = 0;
  for (const double scale : {1.0, 0x1p-30, 0x1p40, 0x1p-520, 0x1p510}) {
    for (int k = 0; k < 300; ++k) {
      // A lattice cube's corners and centre (cospherical, coplanar) and a
      // random point; weights 0 or one random weight.
      const double h = scale * (1 + std::fabs(u(g))), x = scale * u(g), y = scale * u(g), z = scale * u(g);
      std::vector<std::array<double, 4>> p;
      for (int c = 0; c < 8; ++c) p.push_back({x + (c & 1) * h, y + (c >> 1 & 1) * h, z + (c >> 2) * h, 0});
      p.push_back({scale * u(g), scale * u(g), scale * u(g), scale * scale * std::fabs(u(g))});
      auto pr = [&](int i) { return KR::Weighted_point_3(KR::Point_3(p[i][0], p[i][1], p[i][2]), p[i][3]); };
      auto pm = [&](int i) { return KM::Weighted_point_3(KM::Point_3(p[i][0], p[i][1], p[i][2]), p[i][3]); };
      int i[5];
      for (int& v : i) v = int(g() % 9);
      ++cases;
      const auto o = km.orientation_3_object()(pm(i[0]).point(), pm(i[1]).point(), pm(i[2]).point(), pm(i[3]).point());
      if (o == CGAL::COPLANAR) ++zeros;
      ASSERT_EQ(kr.orientation_3_object()(pr(i[0]).point(), pr(i[1]).point(), pr(i[2]).point(), pr(i[3]).point()), o);
      ASSERT_EQ(kr.coplanar_orientation_3_object()(pr(i[0]).point(), pr(i[1]).point(), pr(i[2]).point()),
                km.coplanar_orientation_3_object()(pm(i[0]).point(), pm(i[1]).point(), pm(i[2]).point()));
      ASSERT_EQ(kr.power_side_of_oriented_power_sphere_3_object()(pr(i[0]), pr(i[1]), pr(i[2]), pr(i[3]), pr(i[4])),
                km.power_side_of_oriented_power_sphere_3_object()(pm(i[0]), pm(i[1]), pm(i[2]), pm(i[3]), pm(i[4])));
      ASSERT_EQ(kr.compare_power_distance_3_object()(pr(i[0]).point(), pr(i[1]), pr(i[2])),
                km.compare_power_distance_3_object()(pm(i[0]).point(), pm(i[1]), pm(i[2])));
    }
  }
  EXPECT_GT(zeros, cases / 10);  // the degenerate configurations are reached
}

}  // namespace
}  // namespace wqmesh
