// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of the input analysis (paper, section 2): angles, sharp elements,
// phi_m, f(u) and the boxes, on PLCs built by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "geometry.h"
#include "wqmesh/analysis.h"
#include "wqmesh/error.h"
#include "wqmesh/input.h"
#include "wqmesh/json.h"
#include "wqmesh/types.h"

namespace wqmesh {
namespace {

using geometry::kPi;
double deg(double radians) { return radians * 180 / kPi; }

/// A PLC from vertices and facets given by their outer loops (counter-
/// clockwise from outside); the edges are derived, with both facets.
/// Each facet is a list of loops: the outer one first, then holes (clockwise
/// from outside).
PLC make_plc_with_holes(std::vector<Point3> vertices, const std::vector<std::vector<std::vector<int>>>& facets) {
  PLC plc;
  plc.vertices = std::move(vertices);
  std::map<std::pair<int, int>, int> edge_of;
  for (int f = 0; f < static_cast<int>(facets.size()); ++f) {
    PlcFacet facet;
    facet.loops = facets[f];
    plc.facets.push_back(facet);
    for (const auto& loop : facets[f])
      for (std::size_t i = 0; i < loop.size(); ++i) {
        int a = loop[i], b = loop[(i + 1) % loop.size()];
        if (a > b) std::swap(a, b);
        auto it = edge_of.find({a, b});
        if (it == edge_of.end()) {
          PlcEdge e;
          e.a = a, e.b = b;
          e.facets = {{f, -1}};
          edge_of[{a, b}] = static_cast<int>(plc.edges.size());
          plc.edges.push_back(e);
        } else {
          plc.edges[it->second].facets[1] = f;
        }
      }
  }
  for (const auto& e : plc.edges) EXPECT_GE(e.facets[1], 0) << "open surface in a test PLC";
  return plc;
}

PLC make_plc(std::vector<Point3> vertices, const std::vector<std::vector<int>>& loops) {
  std::vector<std::vector<std::vector<int>>> facets;
  for (const auto& loop : loops) facets.push_back({loop});
  return make_plc_with_holes(std::move(vertices), facets);
}

/// A prism: the polygon `xy` (counter-clockwise seen from +z) at z = 0,
/// extruded to z = h. Vertex i is xy[i] at z = 0, vertex n + i at z = h.
PLC make_prism(const std::vector<std::array<double, 2>>& xy, double h) {
  const int n = static_cast<int>(xy.size());
  std::vector<Point3> v;
  for (const auto& p : xy) v.push_back({{p[0], p[1], 0}});
  for (const auto& p : xy) v.push_back({{p[0], p[1], h}});
  std::vector<std::vector<int>> loops;
  std::vector<int> bottom, top;
  for (int i = n - 1; i >= 0; --i) bottom.push_back(i);
  for (int i = 0; i < n; ++i) top.push_back(n + i);
  loops.push_back(bottom);
  loops.push_back(top);
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    loops.push_back({i, j, n + j, n + i});
  }
  return make_plc(v, loops);
}

/// A tetrahedron on four points in positive orientation
/// (det[p1 - p0, p2 - p0, p3 - p0] > 0), facets oriented outwards.
PLC make_tet(const std::array<Point3, 4>& p) {
  return make_plc({p.begin(), p.end()}, {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}});
}

int find_edge(const PLC& plc, int a, int b) {
  if (a > b) std::swap(a, b);
  for (int e = 0; e < static_cast<int>(plc.edges.size()); ++e)
    if (plc.edges[e].a == a && plc.edges[e].b == b) return e;
  ADD_FAILURE() << "no edge " << a << "-" << b;
  return -1;
}

double dist(const Point3& a, const Point3& b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

/// f(u) by brute force, independently of the library's search: the minimum
/// over every vertex, edge and facet not containing u, and the boundary of B.
/// A facet counts by its plane distance when the projection of u has a non-zero
/// winding number (sum of signed angles) with respect to its loops.
double brute_force_lfs(const PLC& plc, int u, const Box& b) {
  const Point3& p = plc.vertices[u];
  double best = 1e300;
  for (int k = 0; k < 3; ++k) best = std::min({best, p[k] - b.lo[k], b.hi[k] - p[k]});
  for (int w = 0; w < static_cast<int>(plc.vertices.size()); ++w)
    if (w != u) best = std::min(best, dist(p, plc.vertices[w]));
  for (const auto& e : plc.edges) {
    if (e.a == u || e.b == u) continue;
    const Point3 &a = plc.vertices[e.a], &c = plc.vertices[e.b];
    double num = 0, den = 0;
    for (int k = 0; k < 3; ++k) num += (p[k] - a[k]) * (c[k] - a[k]), den += (c[k] - a[k]) * (c[k] - a[k]);
    const double t = std::clamp(num / den, 0.0, 1.0);
    const Point3 q{{a[0] + t * (c[0] - a[0]), a[1] + t * (c[1] - a[1]), a[2] + t * (c[2] - a[2])}};
    best = std::min(best, dist(p, q));
  }
  for (const auto& f : plc.facets) {
    bool contains = false;
    for (const auto& loop : f.loops) contains = contains || std::count(loop.begin(), loop.end(), u) > 0;
    if (contains) continue;
    // Normal: Newell over the outer loop.
    Point3 n{{0, 0, 0}};
    const auto& outer = f.loops[0];
    for (std::size_t i = 0; i < outer.size(); ++i) {
      const Point3 &a = plc.vertices[outer[i]], &c = plc.vertices[outer[(i + 1) % outer.size()]];
      n[0] += (a[1] - c[1]) * (a[2] + c[2]);
      n[1] += (a[2] - c[2]) * (a[0] + c[0]);
      n[2] += (a[0] - c[0]) * (a[1] + c[1]);
    }
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    const Point3& o = plc.vertices[outer[0]];
    const double h = ((p[0] - o[0]) * n[0] + (p[1] - o[1]) * n[1] + (p[2] - o[2]) * n[2]) / len;
    if (std::fabs(h) >= best) continue;
    int drop = 0;
    for (int k = 1; k < 3; ++k)
      if (std::fabs(n[k]) > std::fabs(n[drop])) drop = k;
    const int x = drop == 0 ? 1 : 0, y = drop == 2 ? 1 : 2;
    Point3 q = p;  // the orthogonal projection of u on the plane
    for (int k = 0; k < 3; ++k) q[k] -= h * n[k] / len;
    double winding = 0;
    for (const auto& loop : f.loops)
      for (std::size_t i = 0; i < loop.size(); ++i) {
        const Point3 &a = plc.vertices[loop[i]], &c = plc.vertices[loop[(i + 1) % loop.size()]];
        const double ax = a[x] - q[x], ay = a[y] - q[y], cx = c[x] - q[x], cy = c[y] - q[y];
        winding += std::atan2(ax * cy - ay * cx, ax * cx + ay * cy);
      }
    if (std::fabs(winding) > kPi) best = std::min(best, std::fabs(h));
  }
  return best;
}

/// Invariants every analysis must satisfy.
/// f(u) is compared with brute force at every `brute_stride`-th sharp vertex.
void check_invariants(const PLC& plc, const Analysis& a, std::size_t brute_stride = 1) {
  ASSERT_EQ(a.dihedral.size(), plc.edges.size());
  double phi = 180;
  for (std::size_t e = 0; e < a.dihedral.size(); ++e) {
    const auto& d = a.dihedral[e];
    EXPECT_EQ(d.edge, static_cast<int>(e));
    EXPECT_GT(d.internal_degrees, 0);
    EXPECT_LT(d.internal_degrees, 360);
    EXPECT_NEAR(d.internal_degrees + d.external_degrees, 360, 1e-9);
    if (d.sharp)
      EXPECT_LT(std::min(d.internal_degrees, d.external_degrees), 90 + 1e-9);
    else
      EXPECT_GE(std::min(d.internal_degrees, d.external_degrees), 90 - 1e-9);
    EXPECT_EQ(d.sharp, std::binary_search(a.sharp_edges.begin(), a.sharp_edges.end(), d.edge));
    phi = std::min({phi, d.internal_degrees, d.external_degrees});
  }
  // Edge-edge and edge-facet angles alike.
  auto check_angles = [&](const auto& angles, const char* what) {
    for (const auto& x : angles) {
      EXPECT_GE(x.degrees, 0);
      EXPECT_LE(x.degrees, 180);
      // acute is exact, degrees rounded: they agree up to rounding.
      if (x.acute)
        EXPECT_LT(x.degrees, 90 + 1e-9) << what;
      else
        EXPECT_GT(x.degrees, 90 - 1e-9) << what;
      if (x.acute) EXPECT_TRUE(std::binary_search(a.sharp_vertices.begin(), a.sharp_vertices.end(), x.vertex));
      phi = std::min(phi, x.degrees);
    }
  };
  check_angles(a.edge_edge, "edge-edge");
  check_angles(a.edge_facet, "edge-facet");
  EXPECT_DOUBLE_EQ(a.phi_m_degrees, phi);
  EXPECT_TRUE(std::is_sorted(a.sharp_vertices.begin(), a.sharp_vertices.end()));
  EXPECT_TRUE(std::is_sorted(a.sharp_edges.begin(), a.sharp_edges.end()));
  ASSERT_EQ(a.lfs.size(), a.sharp_vertices.size());
  for (std::size_t i = 0; i < a.lfs.size(); ++i) {
    const int u = a.sharp_vertices[i];
    EXPECT_GT(a.lfs[i], 0);
    double nearest = 1e300;
    for (int w = 0; w < static_cast<int>(plc.vertices.size()); ++w)
      if (w != u) nearest = std::min(nearest, dist(plc.vertices[u], plc.vertices[w]));
    EXPECT_LE(a.lfs[i], nearest * (1 + 1e-12)) << "vertex " << u;
    if (i % brute_stride != 0) continue;
    const double brute = brute_force_lfs(plc, u, a.bounding_box);
    EXPECT_NEAR(a.lfs[i], brute, 1e-9 * brute) << "vertex " << u;
  }
}

const DihedralAngle& dihedral(const PLC& plc, const Analysis& a, int v, int w) {
  return a.dihedral[find_edge(plc, v, w)];
}

TEST(Analysis, UnitCube) {
  const PLC plc = make_prism({{{0, 0}}, {{1, 0}}, {{1, 1}}, {{0, 1}}}, 1);
  const Analysis a = analyze(plc);
  check_invariants(plc, a);
  EXPECT_TRUE(a.sharp_vertices.empty());
  EXPECT_TRUE(a.sharp_edges.empty());
  EXPECT_TRUE(a.lfs.empty());
  for (const auto& d : a.dihedral) {
    EXPECT_DOUBLE_EQ(d.internal_degrees, 90);
    EXPECT_DOUBLE_EQ(d.external_degrees, 270);
    EXPECT_FALSE(d.sharp);
  }
  EXPECT_EQ(a.edge_edge.size(), 24u);  // 3 pairs at each of 8 corners
  for (const auto& x : a.edge_edge) {
    EXPECT_DOUBLE_EQ(x.degrees, 90);
    EXPECT_FALSE(x.acute);
  }
  // At a corner each edge lies in two of the three facets; the third is
  // perpendicular to it.
  EXPECT_EQ(a.edge_facet.size(), 24u);
  for (const auto& x : a.edge_facet) {
    EXPECT_DOUBLE_EQ(x.degrees, 90);
    EXPECT_FALSE(x.acute);
  }
  EXPECT_DOUBLE_EQ(a.phi_m_degrees, 90);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(a.input_box.lo[k], 0);
    EXPECT_EQ(a.input_box.hi[k], 1);
    EXPECT_EQ(a.bounding_box.lo[k], -0.5);
    EXPECT_EQ(a.bounding_box.hi[k], 1.5);
  }
  EXPECT_EQ(a.box_margin, 0.5);
}

TEST(Analysis, BoxMarginUsesLargestExtent) {
  const PLC plc = make_prism({{{0, 0}}, {{4, 0}}, {{4, 1}}, {{0, 1}}}, 2);
  AnalysisOptions options;
  options.box_margin = 0.25;
  const Analysis a = analyze(plc, options);
  EXPECT_EQ(a.box_margin, 0.25);
  EXPECT_EQ(a.bounding_box.lo[0], -1);
  EXPECT_EQ(a.bounding_box.hi[0], 5);
  EXPECT_EQ(a.bounding_box.lo[1], -1);
  EXPECT_EQ(a.bounding_box.hi[1], 2);
  EXPECT_EQ(a.bounding_box.lo[2], -1);
  EXPECT_EQ(a.bounding_box.hi[2], 3);
}

// A triangular prism on the right triangle (0,0), (1,0), (1, tan 10deg): the
// vertical edge at the origin has a 10-degree dihedral, the one at
// (1, tan 10deg) an 80-degree one, the one at (1,0) a right one.
TEST(Analysis, ThinWedge) {
  const double t = std::tan(10 * kPi / 180);
  const PLC plc = make_prism({{{0, 0}}, {{1, 0}}, {{1, t}}}, 0.25);
  const Analysis a = analyze(plc);
  check_invariants(plc, a);
  const auto& d10 = dihedral(plc, a, 0, 3);
  EXPECT_NEAR(d10.internal_degrees, 10, 1e-9);
  EXPECT_NEAR(d10.external_degrees, 350, 1e-9);
  EXPECT_TRUE(d10.sharp);
  EXPECT_NEAR(dihedral(plc, a, 2, 5).internal_degrees, 80, 1e-9);
  EXPECT_TRUE(dihedral(plc, a, 2, 5).sharp);
  EXPECT_NEAR(dihedral(plc, a, 1, 4).internal_degrees, 90, 1e-9);
  EXPECT_FALSE(dihedral(plc, a, 1, 4).sharp);
  EXPECT_NEAR(dihedral(plc, a, 0, 1).internal_degrees, 90, 1e-9);
  EXPECT_EQ(a.sharp_edges, (std::vector<int>{find_edge(plc, 0, 3), find_edge(plc, 2, 5)}));
  // The endpoints of the two sharp edges; (1,0,z) has only right angles.
  EXPECT_EQ(a.sharp_vertices, (std::vector<int>{0, 2, 3, 5}));
  EXPECT_NEAR(a.phi_m_degrees, 10, 1e-9);
  // The edge along x at the origin meets the hypotenuse facet at 10 degrees
  // (the projection of x on that facet's plane is its bottom edge direction).
  bool found = false;
  for (const auto& x : a.edge_facet)
    if (x.vertex == 0 && x.edge == find_edge(plc, 0, 1)) {
      found = true;
      EXPECT_EQ(x.facet, 4);  // side facet on the edge 2 -> 0
      EXPECT_NEAR(x.degrees, 10, 1e-9);
      EXPECT_TRUE(x.acute);
    }
  EXPECT_TRUE(found);
  // f(u) at the origin: vertex 3 right above it at 0.25 (the top facet and
  // the top edges through 3 are as near); everything else is at least 1
  // away and B at 0.5.
  ASSERT_EQ(a.lfs.size(), 4u);
  EXPECT_NEAR(a.lfs[0], 0.25, 1e-12);
}

// The corner tetrahedron and the regular one: internal dihedral at edge with
// facets of outward unit normals n1, n2 is 180 - angle(n1, n2).
TEST(Analysis, TetrahedronDihedrals) {
  {
    const PLC plc = make_tet({{{{0, 0, 0}}, {{1, 0, 0}}, {{0, 1, 0}}, {{0, 0, 1}}}});
    const Analysis a = analyze(plc);
    check_invariants(plc, a);
    const double slanted = deg(std::acos(1 / std::sqrt(3.0)));  // 54.7356...
    for (int e = 0; e < 6; ++e) {
      const bool axis = plc.edges[e].a == 0;
      EXPECT_NEAR(a.dihedral[e].internal_degrees, axis ? 90 : slanted, 1e-9) << e;
      EXPECT_EQ(a.dihedral[e].sharp, !axis) << e;
    }
    // The smallest angle: at vertex 1 the edge 1-0 meets the slanted facet
    // along its bisector, at arcsin(1/sqrt 3) (the facets' corners at 1, 2, 3
    // have 45 and 60 degrees).
    EXPECT_NEAR(a.phi_m_degrees, deg(std::asin(1 / std::sqrt(3.0))), 1e-9);
    // The origin has only right angles and no sharp edge.
    EXPECT_EQ(a.sharp_vertices, (std::vector<int>{1, 2, 3}));
  }
  {
    const double s = 1 / std::sqrt(2.0);
    // A regular tetrahedron, positively oriented.
    const PLC plc = make_tet({{{{1, 0, -s}}, {{-1, 0, -s}}, {{0, -1, s}}, {{0, 1, s}}}});
    const Analysis a = analyze(plc);
    check_invariants(plc, a);
    const double closed_form = deg(std::acos(1.0 / 3));  // 70.528779...
    for (const auto& d : a.dihedral) {
      EXPECT_NEAR(d.internal_degrees, closed_form, 1e-9);
      EXPECT_NEAR(d.external_degrees, 360 - closed_form, 1e-9);
      EXPECT_TRUE(d.sharp);
    }
    for (const auto& x : a.edge_edge) EXPECT_NEAR(x.degrees, 60, 1e-9);
    // Edge-facet: the edge from a vertex against the opposite-ish facet at
    // that vertex; the projection falls on the facet's bisector, and the
    // angle between an edge and a face of a regular tetrahedron is
    // arccos(1/sqrt 3).
    EXPECT_EQ(a.edge_facet.size(), 12u);
    for (const auto& x : a.edge_facet) {
      EXPECT_NEAR(x.degrees, deg(std::acos(1 / std::sqrt(3.0))), 1e-9);
      EXPECT_TRUE(x.acute);
    }
    EXPECT_NEAR(a.phi_m_degrees, 54.735610317245346, 1e-9);
  }
}

// An L-shaped block: the edge at the inner corner is reflex with 270 degrees
// inside, 90 outside: not sharp, and nothing else is sharp.
TEST(Analysis, LShapedBlockReflexEdge) {
  const PLC plc = make_prism({{{0, 0}}, {{2, 0}}, {{2, 1}}, {{1, 1}}, {{1, 2}}, {{0, 2}}}, 1);
  const Analysis a = analyze(plc);
  check_invariants(plc, a);
  const auto& d = dihedral(plc, a, 3, 9);
  EXPECT_NEAR(d.internal_degrees, 270, 1e-9);
  EXPECT_NEAR(d.external_degrees, 90, 1e-9);
  EXPECT_FALSE(d.sharp);
  EXPECT_TRUE(a.sharp_edges.empty());
  EXPECT_TRUE(a.sharp_vertices.empty());
  EXPECT_DOUBLE_EQ(a.phi_m_degrees, 90);
  for (const auto& x : a.edge_facet) EXPECT_NEAR(x.degrees, 90, 1e-9);
}

// A 4 x 4 x 1 box with a V notch of half-angle atan(1/8) cut from its top side
// to a depth of 2: the notch edge is reflex with internal 360 - 2 atan(1/8),
// so its external dihedral is acute.
TEST(Analysis, NotchedBoxAcuteExternalDihedral) {
  const double d = 0.25, k = 2;
  const PLC plc = make_prism({{{0, 0}}, {{4, 0}}, {{4, 4}}, {{2 + d, 4}}, {{2, 4 - k}}, {{2 - d, 4}}, {{0, 4}}}, 1);
  const Analysis a = analyze(plc);
  check_invariants(plc, a);
  const double notch = deg(2 * std::atan(d / k));  // 14.25 degrees
  const auto& tip = dihedral(plc, a, 4, 11);
  EXPECT_NEAR(tip.internal_degrees, 360 - notch, 1e-9);
  EXPECT_GT(tip.internal_degrees, 270);
  EXPECT_NEAR(tip.external_degrees, notch, 1e-9);
  EXPECT_TRUE(tip.sharp);
  EXPECT_EQ(a.sharp_edges, std::vector<int>{find_edge(plc, 4, 11)});
  EXPECT_EQ(a.sharp_vertices, (std::vector<int>{4, 11}));
  // The notch mouth: the polygon angle there is 180 - atan(k/d), obtuse.
  EXPECT_NEAR(dihedral(plc, a, 3, 10).internal_degrees, 180 - deg(std::atan(k / d)), 1e-9);
  EXPECT_FALSE(dihedral(plc, a, 3, 10).sharp);
  EXPECT_NEAR(a.phi_m_degrees, notch, 1e-9);
  // f at the tip (2, 2, 0): the vertex above it at distance 1 (also the top
  // facet and the top edges through that vertex), nearer than the mouth
  // vertices (sqrt(4 + 1/16)) and the box sides (2).
  ASSERT_EQ(a.lfs.size(), 2u);
  EXPECT_NEAR(a.lfs[0], 1, 1e-12);
  EXPECT_NEAR(a.lfs[1], 1, 1e-12);
}

// A square pyramid of height 3 on [-1,1]^2: the edge-edge angles at the apex
// are acute, arccos(9/11) between neighbouring lateral edges and arccos(7/11)
// between opposite ones.
TEST(Analysis, PyramidApexAcuteEdgeEdge) {
  const PLC plc = make_plc({{{-1, -1, 0}}, {{1, -1, 0}}, {{1, 1, 0}}, {{-1, 1, 0}}, {{0, 0, 3}}},
                           {{3, 2, 1, 0}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}});
  AnalysisOptions options;
  options.box_margin = 2;  // B far enough not to bound f at the apex
  const Analysis a = analyze(plc, options);
  check_invariants(plc, a);
  int apex_pairs = 0;
  for (const auto& x : a.edge_edge) {
    if (x.vertex != 4) continue;
    ++apex_pairs;
    const int p = plc.edges[x.edge1].a, q = plc.edges[x.edge2].a;  // base ends
    const bool opposite = (p + 2) % 4 == q || (q + 2) % 4 == p;
    EXPECT_NEAR(x.degrees, deg(std::acos((opposite ? 7.0 : 9.0) / 11)), 1e-9);
    EXPECT_TRUE(x.acute);
  }
  EXPECT_EQ(apex_pairs, 6);
  EXPECT_TRUE(std::binary_search(a.sharp_vertices.begin(), a.sharp_vertices.end(), 4));
  // Base edges: internal dihedral atan(3).
  EXPECT_NEAR(dihedral(plc, a, 0, 1).internal_degrees, deg(std::atan(3.0)), 1e-9);
  EXPECT_TRUE(dihedral(plc, a, 0, 1).sharp);
  // f at the apex: the base facet at distance 3 (projection at its centre),
  // nearer than the base edges (sqrt 10) and vertices (sqrt 11).
  const auto it = std::find(a.sharp_vertices.begin(), a.sharp_vertices.end(), 4);
  EXPECT_NEAR(a.lfs[it - a.sharp_vertices.begin()], 3, 1e-12);
}

// A tetrahedron with u at the origin, a = (1,0,0), b = (0,1,0) and v at
// elevation 30 degrees above the plane of u a b at azimuth 45 degrees (inside
// the sector of that facet at u): the edge-facet angle of uv with uab is 30.
// With v at azimuth -45 degrees (outside the sector) the angle is the one to
// the nearer sector side ua: arccos(cos 30 cos 45).
TEST(Analysis, EdgeFacetAngle) {
  const double c = std::cos(30 * kPi / 180), s = std::sin(30 * kPi / 180), r = std::sqrt(0.5);
  for (const double azimuth_sign : {1.0, -1.0}) {
    const Point3 v{{c * r, azimuth_sign * c * r, s}};
    // Positive orientation: det[a, b, v] = v_z > 0.
    const PLC plc = make_tet({{{{0, 0, 0}}, {{1, 0, 0}}, {{0, 1, 0}}, v}});
    const Analysis a = analyze(plc);
    check_invariants(plc, a);
    const int uv = find_edge(plc, 0, 3);
    bool found = false;
    for (const auto& x : a.edge_facet)
      if (x.vertex == 0 && x.edge == uv) {
        found = true;
        EXPECT_EQ(x.facet, 0);  // the facet 0 2 1 in the plane z = 0
        const double expected = azimuth_sign > 0 ? 30 : deg(std::acos(c * r));
        EXPECT_NEAR(x.degrees, expected, 1e-9);
        EXPECT_TRUE(x.acute);
      }
    EXPECT_TRUE(found);
  }
}

// An edge-facet pair that is not acute: the edge leaves u at more than 90
// degrees from every direction into the facet (exact test at the vertices).
TEST(Analysis, EdgeFacetObtuse) {
  // u = origin, facet u a b in z = 0 with a = (1,0,0), b = (0,1,0); v behind.
  const PLC plc = make_tet({{{{0, 0, 0}}, {{1, 0, 0}}, {{0, 1, 0}}, {{-1, -1, 1}}}});
  const Analysis a = analyze(plc);
  check_invariants(plc, a);
  int found = 0;
  for (const auto& x : a.edge_facet)
    if (x.vertex == 0 && x.edge == find_edge(plc, 0, 3)) {
      ++found;
      EXPECT_EQ(x.facet, 0);
      EXPECT_NEAR(x.degrees, deg(std::acos(-1 / std::sqrt(3.0))), 1e-9);
      EXPECT_FALSE(x.acute);
    }
  EXPECT_EQ(found, 1);
}

// A square frame (a 4 x 4 x 1 block with a 2 x 2 square hole through it:
// top and bottom facets have a hole) and, floating above the hole, a thin
// tetrahedron pointing down at (2, 2, 1.5). The hole's edges are reflex (270
// inside). At the tip, the projection on the top facet's plane (distance 0.5)
// falls in the hole, so f is the distance to the hole's upper edges,
// sqrt(1 + 0.25).
TEST(Analysis, FacetWithHole) {
  std::vector<Point3> v;
  const double outer[4][2] = {{0, 0}, {4, 0}, {4, 4}, {0, 4}};
  const double inner[4][2] = {{1, 1}, {3, 1}, {3, 3}, {1, 3}};
  for (double z : {0.0, 1.0})
    for (const auto& p : outer) v.push_back({{p[0], p[1], z}});  // 0-3, 4-7
  for (double z : {0.0, 1.0})
    for (const auto& p : inner) v.push_back({{p[0], p[1], z}});  // 8-11, 12-15
  std::vector<std::vector<std::vector<int>>> facets = {
      {{3, 2, 1, 0}, {8, 9, 10, 11}},     // bottom: outer CW from above, hole CCW
      {{4, 5, 6, 7}, {15, 14, 13, 12}}};  // top
  for (int i = 0; i < 4; ++i) {
    const int j = (i + 1) % 4;
    facets.push_back({{i, j, 4 + j, 4 + i}});            // outer wall
    facets.push_back({{8 + j, 8 + i, 12 + i, 12 + j}});  // hole wall, facing the hole
  }
  // The tetrahedron: tip 16 at (2, 2, 1.5), base 17-19 at z = 3.
  v.push_back({{2, 2, 1.5}});
  v.push_back({{1.8, 1.8, 3}});
  v.push_back({{2.2, 1.8, 3}});
  v.push_back({{2, 2.2, 3}});
  facets.push_back({{17, 18, 19}});  // top, facing +z
  facets.push_back({{16, 18, 17}});
  facets.push_back({{16, 19, 18}});
  facets.push_back({{16, 17, 19}});
  const PLC plc = make_plc_with_holes(v, facets);
  const Analysis a = analyze(plc);
  check_invariants(plc, a);
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(dihedral(plc, a, 8 + i, 12 + i).internal_degrees, 270, 1e-9);
    EXPECT_NEAR(dihedral(plc, a, i, 4 + i).internal_degrees, 90, 1e-9);
    EXPECT_NEAR(dihedral(plc, a, 12 + i, 12 + (i + 1) % 4).internal_degrees, 90, 1e-9);
  }
  // The frame has no sharp vertex; the tetrahedron's four are sharp.
  EXPECT_EQ(a.sharp_vertices, (std::vector<int>{16, 17, 18, 19}));
  EXPECT_NEAR(a.lfs[0], std::sqrt(1.25), 1e-12);
  // A frame vertex: the inner corner (1, 1, 0) is 1 away from the top facet
  // (projection on its boundary) and the walls x = 0, y = 0 (also on their
  // boundaries), and from the vertex (1, 1, 1).
  EXPECT_NEAR(local_feature_sizes(plc, {8}, a.bounding_box)[0], 1, 1e-12);
}

// f(u) on a flat tetrahedron over the base (0,0,0), (1,0,0), (0,1,0), with the
// apex u placed so that its nearest non-adjacent element is the base facet's
// interior, the interior of a base edge, or a base vertex.
TEST(Analysis, LocalFeatureSizeNearestElement) {
  struct Case {
    Point3 apex;
    double expected;
    const char* what;
  };
  const Case cases[] = {
      {{{0.2, 0.2, 0.1}}, 0.1, "facet interior"},
      {{{0.5, -0.1, 0.05}}, std::sqrt(0.01 + 0.0025), "edge interior"},
      {{{-0.1, -0.1, 0.05}}, std::sqrt(0.01 + 0.01 + 0.0025), "vertex"},
  };
  for (const auto& c : cases) {
    const PLC plc = make_tet({{{{0, 0, 0}}, {{1, 0, 0}}, {{0, 1, 0}}, c.apex}});
    const Analysis a = analyze(plc);
    check_invariants(plc, a);
    const auto f = local_feature_sizes(plc, {3}, a.bounding_box);
    ASSERT_EQ(f.size(), 1u);
    EXPECT_NEAR(f[0], c.expected, 1e-12) << c.what;
    // The same value where analyze computed it.
    const auto it = std::find(a.sharp_vertices.begin(), a.sharp_vertices.end(), 3);
    if (it != a.sharp_vertices.end()) EXPECT_NEAR(a.lfs[it - a.sharp_vertices.begin()], c.expected, 1e-12);
  }
  // The facet case, checked on the base vertex 0 too: the nearest element
  // not containing 0 is the edge 1-2 or the apex; here the apex (0.2,0.2,0.1)
  // at distance 0.3 is nearer than the edge x + y = 1 (sqrt(0.5)).
  const PLC plc = make_tet({{{{0, 0, 0}}, {{1, 0, 0}}, {{0, 1, 0}}, {{0.2, 0.2, 0.1}}}});
  const Box big{{{-100, -100, -100}}, {{100, 100, 100}}};
  EXPECT_NEAR(local_feature_sizes(plc, {0}, big)[0], 0.3, 1e-12);
}

// The boundary of B bounds f(u): at the tip of a needle, the far elements are
// 10 away but B (margin 0.5 x extent 10) is 5 away.
TEST(Analysis, LocalFeatureSizeBoundingBox) {
  const PLC plc = make_tet({{{{0, 0, 0}}, {{0.01, 0, 0}}, {{0, 0.01, 0}}, {{0, 0, 10}}}});
  const Analysis a = analyze(plc);
  check_invariants(plc, a);
  const auto f = local_feature_sizes(plc, {3}, a.bounding_box);
  EXPECT_NEAR(f[0], 5, 1e-12);
}

TEST(Analysis, Json) {
  const double t = std::tan(10 * kPi / 180);
  const PLC plc = make_prism({{{0, 0}}, {{1, 0}}, {{1, t}}}, 1);
  const Analysis a = analyze(plc);
  JsonWriter j(false);
  write_analysis_json(j, a);
  const std::string s = j.str();
  for (const char* key :
       {"\"counts\"", "\"phi_m_degrees\"", "\"sharp_vertices\":[0,2,3,5]", "\"sharp_edges\"", "\"lfs\"", "\"dihedral\"",
        "\"edge_edge\"", "\"edge_facet\"", "\"input_box\"", "\"bounding_box\"", "\"box_margin\":0.5", "\"internal\"",
        "\"external\"", "\"edge_edge\":[{\"vertex\":0,\"edge1\":", "\"edge_facet\":[{\"vertex\":0,\"edge\":",
        "\"input_box\":{\"lo\":[0,0,0],\"hi\":[1,", "\"dihedral_angles\":9", "\"sharp_edges\":2"})
    EXPECT_NE(s.find(key), std::string::npos) << key << " in " << s.substr(0, 400);
  EXPECT_EQ(s.front(), '{');
  EXPECT_EQ(s.back(), '}');
}

// ---- large polygons ------------------------------------------------------------

/// An oblique prism over a polygon of n vertices on the ellipse (cos t,
/// 0.6 sin t), every odd one pulled in to `odd` times its radius (1: convex,
/// less: a star), the top shifted by `shift` (sides are parallelograms).
PLC oblique_prism(int n, const Point3& shift, double odd = 1) {
  std::vector<std::array<double, 2>> xy;
  for (int i = 0; i < n; ++i) {
    const double t = 2 * kPi * i / n, r = i % 2 ? odd : 1;
    xy.push_back({{r * std::cos(t), r * 0.6 * std::sin(t)}});
  }
  PLC plc = make_prism(xy, 1);
  for (int i = n; i < 2 * n; ++i)
    for (int k = 0; k < 3; ++k) plc.vertices[i][k] = plc.vertices[i - n][k] + shift[k];
  return plc;
}

/// The literal edge-facet angle of the paper (min over p in F, p != u, of
/// the angle puv), independently of the library: the facet is fanned from u
/// into triangles (u, a_i, a_i+1), and the directions from u to F are those
/// to the segments a_i a_i+1 not at u, sampled at `samples` points each, and
/// along the two sides at u. The result is
/// at least the true angle and within the sampling step of it.
double sampled_edge_facet(const PLC& plc, int u, int v, int f, int samples) {
  const auto& loop = plc.facets[f].loops[0];
  const Point3& pu = plc.vertices[u];
  Point3 w;
  for (int k = 0; k < 3; ++k) w[k] = plc.vertices[v][k] - pu[k];
  auto angle = [&](const Point3& p) {
    Point3 d, c;
    for (int k = 0; k < 3; ++k) d[k] = p[k] - pu[k];
    c = {{d[1] * w[2] - d[2] * w[1], d[2] * w[0] - d[0] * w[2], d[0] * w[1] - d[1] * w[0]}};
    return deg(std::atan2(std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]), d[0] * w[0] + d[1] * w[1] + d[2] * w[2]));
  };
  double best = 180;
  const std::size_t m = loop.size();
  for (std::size_t i = 0; i < m; ++i) {
    const Point3 &a = plc.vertices[loop[i]], &b = plc.vertices[loop[(i + 1) % m]];
    if (loop[i] == u || loop[(i + 1) % m] == u) {  // one direction (rounded points near u have none)
      best = std::min(best, angle(loop[i] == u ? b : a));
      continue;
    }
    for (int s = 0; s <= samples; ++s) {
      const double t = static_cast<double>(s) / samples;
      const Point3 p{{a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])}};
      best = std::min(best, angle(p));
    }
  }
  return best;
}

// Convex facets and directions into a facet's sector take the O(1) paths of
// the analysis: on small oblique prisms over a convex polygon and over a star
// (acute and obtuse edge-facet angles, reflex corners, notches) every angle
// agrees with the sampled literal definition, and the invariants hold.
class AnalysisFastPaths : public ::testing::TestWithParam<double> {};
INSTANTIATE_TEST_SUITE_P(Analysis, AnalysisFastPaths, ::testing::Values(1.0, 0.6));
TEST_P(AnalysisFastPaths, MatchTheLiteralEdgeFacetAngle) {
  const PLC plc = oblique_prism(10, {{0.7, 0.4, 1.0}}, GetParam());
  const Analysis a = analyze(plc);
  check_invariants(plc, a);
  ASSERT_FALSE(a.edge_facet.empty());
  int acute = 0;
  for (const auto& x : a.edge_facet) {
    const auto& e = plc.edges[x.edge];
    const int v = e.a == x.vertex ? e.b : e.a;
    const double sampled = sampled_edge_facet(plc, x.vertex, v, x.facet, 4000);
    EXPECT_LE(x.degrees, sampled + 1e-9) << "u " << x.vertex << " v " << v << " f " << x.facet;
    EXPECT_GE(x.degrees, sampled - 0.2) << "u " << x.vertex << " e " << x.edge << " f " << x.facet;
    acute += x.acute;
  }
  EXPECT_GT(acute, 0);
  EXPECT_LT(acute, static_cast<int>(a.edge_facet.size()));
}

// A closed cylinder with two 30,000-gon caps (60,000 points, within every
// documented limit): the analysis is near-linear in the facet size, so this
// is a quick test; every entry keeps the invariants, and the angles are
// those of a right prism: 90 degrees between a vertical edge and a cap.
TEST(Analysis, CylinderWithHugeCaps) {
  const int n = 30000;
  std::vector<std::array<double, 2>> xy;
  for (int i = 0; i < n; ++i) xy.push_back({{std::cos(2 * kPi * i / n), std::sin(2 * kPi * i / n)}});
  const PLC plc = make_prism(xy, 1);
  const Analysis a = analyze(plc);
  check_invariants(plc, a, 1000);
  ASSERT_EQ(a.dihedral.size(), plc.edges.size());
  // Per vertex: its vertical edge against the other cap is not counted (the
  // cap does not hold u), against its own cap it is (90 degrees); each cap
  // edge against the side quad at u that does not hold it.
  EXPECT_EQ(a.edge_facet.size(), static_cast<std::size_t>(2 * n * 3));
  int vertical = 0;
  for (const auto& x : a.edge_facet) {
    const auto& e = plc.edges[x.edge];
    if (std::abs(e.a - e.b) == n) {
      ++vertical;
      EXPECT_LT(x.facet, 2);
      EXPECT_NEAR(x.degrees, 90, 1e-9);
      EXPECT_FALSE(x.acute);
    }
  }
  EXPECT_EQ(vertical, 2 * n);
}

// A pyramid over a 2,000-gon: its apex alone would make 6 million
// edge-edge and edge-facet angles, beyond the analysis' budget; it is refused
// at once with the budget's name and number, not run out of memory. A
// 500-gon (400,000 angles) is analysed.
TEST(Analysis, AngleBudgetRefusesHugeVertexDegree) {
  auto pyramid = [](int n) {
    std::vector<Point3> v;
    for (int i = 0; i < n; ++i) v.push_back({{std::cos(2 * kPi * i / n), std::sin(2 * kPi * i / n), 0}});
    v.push_back({{0, 0, 1}});
    std::vector<std::vector<int>> loops(1);
    for (int i = n - 1; i >= 0; --i) loops[0].push_back(i);
    for (int i = 0; i < n; ++i) loops.push_back({i, (i + 1) % n, n});
    return make_plc(v, loops);
  };
  try {
    analyze(pyramid(2000));
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.kind(), InputErrorKind::too_large);
    const std::string m = e.what();
    EXPECT_NE(m.find("beyond its budget of 4000000 angles"), std::string::npos) << m;
    EXPECT_NE(m.find("PLC vertex 2000 has 2000 edges and 2000 facets"), std::string::npos) << m;
  }
  const PLC ok = pyramid(500);
  const Analysis a = analyze(ok);
  check_invariants(ok, a, 100);
  EXPECT_GE(a.edge_edge.size(), static_cast<std::size_t>(500 * 499 / 2));
}

// The validation of a pyramid over a 100,000-gon (100,001 points, within the
// input limits): its apex is in 100,000 triangles, whose boxes all overlap;
// the self-intersection test counts those pairs first and refuses the input
// at once, naming its budget and the vertex (it used to test 2e8 pairs
// first, then say "too many pairs").
TEST(Analysis, SelfIntersectionBudgetIsNamed) {
  const int n = 100000;
  PolygonSoup soup;
  for (int i = 0; i < n; ++i) soup.points.push_back({{std::cos(2 * kPi * i / n), std::sin(2 * kPi * i / n), 0}});
  soup.points.push_back({{0, 0, 1}});
  soup.faces.emplace_back();
  for (int i = n - 1; i >= 0; --i) soup.faces[0].push_back(i);
  for (int i = 0; i < n; ++i) soup.faces.push_back({i, (i + 1) % n, n});
  soup.face_line.assign(soup.faces.size(), 0);
  soup.format = "OFF";
  Warnings warnings;
  try {
    build_plc(soup, warnings);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.kind(), InputErrorKind::too_large);
    const std::string m = e.what();
    EXPECT_NE(m.find("the vertex (0, 0, 1) is in 100000 triangles"), std::string::npos) << m;
    EXPECT_NE(m.find("the self-intersection test's budget of 200000000 pairs"), std::string::npos) << m;
  }
}

// The models of ../shared/models (skipped when absent): every one that reads
// and builds into a PLC must satisfy the invariants. Prints, per model, the
// sharp counts, phi_m and the time of the analysis.
TEST(Analysis, SharedModels) {
  namespace fs = std::filesystem;
  const fs::path dir = WQMESH_SHARED_MODELS;
  if (!fs::is_directory(dir)) GTEST_SKIP() << dir << " not found";
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string ext = entry.path().extension().string();
    if (ext == ".off" || ext == ".stl") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  int analysed = 0;
  for (const auto& file : files) {
    SCOPED_TRACE(file.filename().string());
    PLC plc;
    try {
      const PolygonSoup soup = read_polyhedron_file(file.string());
      Warnings warnings;
      plc = build_plc(soup, warnings);
    } catch (const InputError& e) {
      std::printf("  %-40s not a valid PLC: %s\n", file.filename().string().c_str(), e.what());
      continue;
    }
    const auto start = std::chrono::steady_clock::now();
    const Analysis a = analyze(plc);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    check_invariants(plc, a, std::max<std::size_t>(1, a.sharp_vertices.size() / 400));
    ++analysed;
    std::printf("  %-40s V %6zu E %6zu F %6zu  sharp V %6zu E %6zu  phi_m %9.4f  %8.1f ms\n",
                file.filename().string().c_str(), plc.vertices.size(), plc.edges.size(), plc.facets.size(),
                a.sharp_vertices.size(), a.sharp_edges.size(), a.phi_m_degrees, ms);
  }
  std::printf("  %d models analysed\n", analysed);
}

}  // namespace
}  // namespace wqmesh
