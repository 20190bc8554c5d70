// SPDX-License-Identifier: GPL-3.0-or-later
// wqmesh: tests of build_plc (input.h): the PLC of the paper, section 2, built
// from polygon soups, and the invariants of its contract (types.h).
#include <gtest/gtest.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "expect_input_error.h"
#include "geometry.h"
#include "validation.h"
#include "wqmesh/input.h"

namespace wqmesh {

namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
K::Point_3 P(const Point3& p) { return K::Point_3(p[0], p[1], p[2]); }

/// Newell area vector (twice the vector area) of a closed polygon: the library's.
std::array<double, 3> newell(const PLC& plc, const std::vector<int>& loop) {
  return geometry::newell_normal(plc.vertices, loop);
}
using geometry::dot;
}  // namespace

/// Checks the contract of a PLC (types.h; paper, section 2). Also used by
/// models_test.cpp. Returns the number of connected components.
int expect_valid_plc(const PLC& plc) {
  const int nv = static_cast<int>(plc.vertices.size());
  const int nf = static_cast<int>(plc.facets.size());
  EXPECT_GE(nv, 4);
  EXPECT_GE(nf, 4);
  EXPECT_GE(plc.edges.size(), 6u);
  for (const auto& p : plc.vertices)
    for (double x : p) EXPECT_TRUE(std::isfinite(x));
  // Edges: a < b, distinct, each in two distinct facets.
  std::map<std::pair<int, int>, int> edge_of;
  for (std::size_t e = 0; e < plc.edges.size(); ++e) {
    const PlcEdge& E = plc.edges[e];
    EXPECT_TRUE(0 <= E.a && E.a < E.b && E.b < nv) << "edge " << e;
    EXPECT_TRUE(edge_of.emplace(std::make_pair(E.a, E.b), static_cast<int>(e)).second) << "edge " << e << " repeated";
    EXPECT_TRUE(E.facets[0] >= 0 && E.facets[0] < nf && E.facets[1] >= 0 && E.facets[1] < nf &&
                E.facets[0] != E.facets[1])
        << "edge " << e;
  }
  // Loops: every side is an input edge, traversed once each way over all
  // facets (closed, consistently oriented 2-manifold); every vertex is used.
  std::map<std::pair<int, int>, int> directed;
  std::vector<int> used(nv, 0);
  std::vector<std::set<int>> edge_facets(plc.edges.size());
  for (int f = 0; f < nf; ++f) {
    const PlcFacet& F = plc.facets[f];
    EXPECT_FALSE(F.loops.empty()) << "facet " << f;
    EXPECT_FALSE(F.source_faces.empty()) << "facet " << f;
    for (const auto& loop : F.loops) {
      EXPECT_GE(loop.size(), 3u) << "facet " << f;
      for (std::size_t i = 0; i < loop.size(); ++i) {
        const int a = loop[i], b = loop[(i + 1) % loop.size()];
        if (!(a >= 0 && a < nv && b >= 0 && b < nv)) {
          ADD_FAILURE() << "facet " << f << " has a vertex index out of range";
          return 0;
        }
        used[a] = 1;
        auto it = edge_of.find({std::min(a, b), std::max(a, b)});
        EXPECT_TRUE(it != edge_of.end()) << "facet " << f << " side " << a << "-" << b << " is not an input edge";
        if (it != edge_of.end()) edge_facets[it->second].insert(f);
        ++directed[{a, b}];
      }
    }
  }
  for (int v = 0; v < nv; ++v) EXPECT_TRUE(used[v]) << "vertex " << v << " in no loop";
  for (const auto& [ab, count] : directed) {
    EXPECT_EQ(count, 1) << ab.first << "->" << ab.second;
    EXPECT_EQ(directed.count({ab.second, ab.first}), 1u) << ab.first << "->" << ab.second;
  }
  for (std::size_t e = 0; e < plc.edges.size(); ++e) {
    const PlcEdge& E = plc.edges[e];
    EXPECT_EQ(edge_facets[e], (std::set<int>{E.facets[0], E.facets[1]})) << "edge " << e;
  }
  // Facets are planar (exactly), with outer loop counter-clockwise from
  // outside (along the normal) and holes clockwise.
  for (int f = 0; f < nf; ++f) {
    const PlcFacet& F = plc.facets[f];
    const auto& L = F.loops[0];
    int c = -1;
    for (std::size_t i = 2; i < L.size() && c < 0; ++i)
      if (!CGAL::collinear(P(plc.vertices[L[0]]), P(plc.vertices[L[1]]), P(plc.vertices[L[i]])))
        c = static_cast<int>(i);
    if (c < 0) {
      ADD_FAILURE() << "facet " << f << " outer loop is collinear";
      continue;
    }
    for (const auto& loop : F.loops)
      for (int v : loop)
        EXPECT_EQ(
            CGAL::orientation(P(plc.vertices[L[0]]), P(plc.vertices[L[1]]), P(plc.vertices[L[c]]), P(plc.vertices[v])),
            CGAL::COPLANAR)
            << "facet " << f << " is not planar";
    EXPECT_NEAR(std::sqrt(dot(F.normal, F.normal)), 1.0, 1e-9) << "facet " << f;
    EXPECT_GT(dot(newell(plc, L), F.normal), 0) << "facet " << f << " outer loop";
    for (std::size_t l = 1; l < F.loops.size(); ++l)
      EXPECT_LT(dot(newell(plc, F.loops[l]), F.normal), 0) << "facet " << f << " hole " << l;
  }
  // Facets sharing an edge are not coplanar.
  for (const PlcEdge& E : plc.edges) {
    const auto& L = plc.facets[E.facets[0]].loops[0];
    int c = -1;
    for (std::size_t i = 2; i < L.size() && c < 0; ++i)
      if (!CGAL::collinear(P(plc.vertices[L[0]]), P(plc.vertices[L[1]]), P(plc.vertices[L[i]])))
        c = static_cast<int>(i);
    if (c < 0) continue;
    bool off_plane = false;
    for (int v : plc.facets[E.facets[1]].loops[0])
      off_plane |= CGAL::orientation(P(plc.vertices[L[0]]), P(plc.vertices[L[1]]), P(plc.vertices[L[c]]),
                                     P(plc.vertices[v])) != CGAL::COPLANAR;
    EXPECT_TRUE(off_plane) << "facets " << E.facets[0] << " and " << E.facets[1] << " coplanar";
  }
  // No vertex inside an edge: a vertex of two edges is a real corner.
  std::vector<std::vector<int>> nbrs(nv);
  for (const PlcEdge& E : plc.edges) {
    nbrs[E.a].push_back(E.b);
    nbrs[E.b].push_back(E.a);
  }
  for (int v = 0; v < nv; ++v) {
    EXPECT_GE(nbrs[v].size(), 2u) << "vertex " << v;
    if (nbrs[v].size() == 2)
      EXPECT_FALSE(CGAL::collinear(P(plc.vertices[nbrs[v][0]]), P(plc.vertices[v]), P(plc.vertices[nbrs[v][1]])))
          << "vertex " << v << " lies inside an edge";
  }
  // Outward: the enclosed volume (sum over loops of Newell . p / 6) is
  // positive.
  double volume = 0;
  for (const PlcFacet& F : plc.facets)
    for (const auto& loop : F.loops) volume += dot(newell(plc, loop), plc.vertices[loop[0]]) / 6;
  EXPECT_GT(volume, 0) << "the surface is not oriented outwards";
  // Euler: V - E + sum(1 - holes) = 2 - 2g per component.
  std::vector<int> comp(nf);
  std::iota(comp.begin(), comp.end(), 0);
  std::function<int(int)> find = [&](int x) { return comp[x] == x ? x : comp[x] = find(comp[x]); };
  for (const PlcEdge& E : plc.edges) comp[find(E.facets[0])] = find(E.facets[1]);
  int components = 0;
  for (int f = 0; f < nf; ++f) components += find(f) == f;
  long chi = nv - static_cast<long>(plc.edges.size());
  for (const PlcFacet& F : plc.facets) chi += 2 - static_cast<long>(F.loops.size());
  EXPECT_EQ(chi % 2, 0) << "Euler characteristic " << chi;
  EXPECT_LE(chi, 2 * components) << "Euler characteristic " << chi;
  return components;
}

namespace {

/// A soup from points and polygons (OFF-like lines: face i on line 100 + i).
PolygonSoup soup_of(std::vector<Point3> pts, std::vector<std::vector<int>> faces) {
  PolygonSoup s;
  s.points = std::move(pts);
  s.faces = std::move(faces);
  for (std::size_t i = 0; i < s.faces.size(); ++i) s.face_line.push_back(100 + static_cast<long>(i));
  s.format = "OFF";
  return s;
}

std::vector<Point3> box_points(double x, double y, double z) {
  return {{0, 0, 0}, {x, 0, 0}, {x, y, 0}, {0, y, 0}, {0, 0, z}, {x, 0, z}, {x, y, z}, {0, y, z}};
}
/// Outward quads of the box above.
std::vector<std::vector<int>> box_quads() {
  return {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
}
/// The quads split into 12 triangles, as an STL would have them.
std::vector<std::vector<int>> box_triangles() {
  std::vector<std::vector<int>> t;
  for (const auto& q : box_quads()) {
    t.push_back({q[0], q[1], q[2]});
    t.push_back({q[0], q[2], q[3]});
  }
  return t;
}

/// build_plc's error of `kind` on `soup`, and its message.
std::string build_error(const PolygonSoup& soup, InputErrorKind kind) {
  return testing::expect_input_error(
      [&] {
        Warnings w;
        build_plc(soup, w);
      },
      kind);
}

bool has_warning(const Warnings& w, const std::string& needle) {
  for (const auto& s : w)
    if (s.find(needle) != std::string::npos) return true;
  return false;
}

TEST(Plc, StlCubeBecomesSixFacets) {
  Warnings w;
  MergeReport r;
  const PLC plc = build_plc(soup_of(box_points(1, 2, 3), box_triangles()), w, &r);
  expect_valid_plc(plc);
  EXPECT_EQ(plc.vertices.size(), 8u);
  EXPECT_EQ(plc.edges.size(), 12u);
  EXPECT_EQ(plc.facets.size(), 6u);
  for (const auto& F : plc.facets) {
    EXPECT_EQ(F.loops.size(), 1u);
    EXPECT_EQ(F.loops[0].size(), 4u);
    EXPECT_EQ(F.source_faces.size(), 2u);
    // Axis-aligned unit normals.
    EXPECT_NEAR(std::fabs(F.normal[0]) + std::fabs(F.normal[1]) + std::fabs(F.normal[2]), 1.0, 1e-12);
  }
  EXPECT_EQ(r.faces_read, 12u);
  EXPECT_EQ(r.facets, 6u);
  EXPECT_EQ(r.edges, 12u);
  EXPECT_EQ(r.edges_before, 18u);
  EXPECT_EQ(r.faces_flipped, 0u);
  EXPECT_TRUE(w.empty());
}

TEST(Plc, IdenticalPointsMergedUnusedDropped) {
  // Every triangle with its own copies of the corners, as STL stores them,
  // plus an unused point.
  std::vector<Point3> pts;
  std::vector<std::vector<int>> faces;
  const auto bp = box_points(1, 1, 1);
  for (const auto& t : box_triangles()) {
    faces.push_back({});
    for (int v : t) {
      faces.back().push_back(static_cast<int>(pts.size()));
      pts.push_back(bp[v]);
    }
  }
  pts.push_back({5, 5, 5});
  Warnings w;
  MergeReport r;
  const PLC plc = build_plc(soup_of(pts, faces), w, &r);
  expect_valid_plc(plc);
  EXPECT_EQ(r.points_read, 37u);
  EXPECT_EQ(r.vertices, 8u);
  EXPECT_EQ(plc.vertices.size(), 8u);
  EXPECT_TRUE(has_warning(w, "used by no face"));
}

TEST(Plc, SubdividedFaceLosesInteriorVertex) {
  // The top quad of the box is a fan of 4 triangles around its centre.
  auto pts = box_points(2, 2, 2);
  pts.push_back({1, 1, 2});  // 8: centre of the top
  auto faces = box_quads();
  faces.erase(faces.begin() + 1);
  for (auto [a, b] : {std::pair{4, 5}, {5, 6}, {6, 7}, {7, 4}}) faces.push_back({a, b, 8});
  Warnings w;
  MergeReport r;
  const PLC plc = build_plc(soup_of(pts, faces), w, &r);
  expect_valid_plc(plc);
  EXPECT_EQ(plc.vertices.size(), 8u);
  EXPECT_EQ(plc.facets.size(), 6u);
  EXPECT_EQ(plc.edges.size(), 12u);
  EXPECT_EQ(r.vertices_removed, 1u);
  for (const auto& v : plc.vertices) EXPECT_FALSE(v == (Point3{1, 1, 2}));
}

TEST(Plc, CollinearChainJoined) {
  // The edge from (0,0,2) to (2,0,2) carries a midpoint shared by a split top
  // face and a split front face: the midpoint goes and one edge remains.
  auto pts = box_points(2, 2, 2);
  pts.push_back({1, 0, 2});  // 8
  std::vector<std::vector<int>> faces = {{0, 3, 2, 1},
                                         {1, 2, 6, 5},
                                         {2, 3, 7, 6},
                                         {3, 0, 4, 7},
                                         // top (z = 2) split at 8
                                         {4, 8, 7},
                                         {8, 6, 7},
                                         {8, 5, 6},
                                         // front (y = 0) as a pentagon through 8
                                         {0, 1, 5, 8, 4}};
  Warnings w;
  MergeReport r;
  const PLC plc = build_plc(soup_of(pts, faces), w, &r);
  expect_valid_plc(plc);
  EXPECT_EQ(plc.vertices.size(), 8u);
  EXPECT_EQ(plc.edges.size(), 12u);
  EXPECT_EQ(plc.facets.size(), 6u);
  EXPECT_EQ(r.vertices_removed, 1u);
}

TEST(Plc, BoxWithThroughHoleHasHoleLoops) {
  // A 4x4x1 slab with a 2x2 square hole through it, as triangles.
  std::vector<Point3> pts;
  auto add = [&](double x, double y, double z) {
    pts.push_back({x, y, z});
    return static_cast<int>(pts.size() - 1);
  };
  int o[2][4], h[2][4];
  const double ox[4] = {0, 4, 4, 0}, oy[4] = {0, 0, 4, 4};
  const double hx[4] = {1, 3, 3, 1}, hy[4] = {1, 1, 3, 3};
  for (int z = 0; z < 2; ++z)
    for (int i = 0; i < 4; ++i) {
      o[z][i] = add(ox[i], oy[i], z);
      h[z][i] = add(hx[i], hy[i], z);
    }
  std::vector<std::vector<int>> faces;
  for (int i = 0; i < 4; ++i) {
    const int j = (i + 1) % 4;
    // Top ring (z = 1, facing +z) and bottom ring (z = 0, facing -z).
    faces.push_back({o[1][i], o[1][j], h[1][j]});
    faces.push_back({o[1][i], h[1][j], h[1][i]});
    faces.push_back({o[0][i], h[0][j], o[0][j]});
    faces.push_back({o[0][i], h[0][i], h[0][j]});
    // Outer walls facing out, hole walls facing the hole.
    faces.push_back({o[0][i], o[0][j], o[1][j], o[1][i]});
    faces.push_back({h[0][i], h[1][i], h[1][j], h[0][j]});
  }
  Warnings w;
  const PLC plc = build_plc(soup_of(pts, faces), w);
  expect_valid_plc(plc);
  EXPECT_EQ(plc.vertices.size(), 16u);
  EXPECT_EQ(plc.facets.size(), 10u);
  EXPECT_EQ(plc.edges.size(), 24u);
  int with_hole = 0;
  for (const auto& F : plc.facets) {
    if (F.loops.size() == 2) {
      ++with_hole;
      EXPECT_EQ(F.loops[0].size(), 4u);
      EXPECT_EQ(F.loops[1].size(), 4u);
      // The outer loop has the outer corners.
      for (int v : F.loops[0]) EXPECT_TRUE(plc.vertices[v][0] == 0 || plc.vertices[v][0] == 4);
    }
  }
  EXPECT_EQ(with_hole, 2);
}

TEST(Plc, OrientationRepairedWithWarning) {
  auto faces = box_triangles();
  std::reverse(faces[3].begin(), faces[3].end());
  std::reverse(faces[7].begin(), faces[7].end());
  Warnings w;
  MergeReport r;
  const PLC plc = build_plc(soup_of(box_points(1, 1, 1), faces), w, &r);
  expect_valid_plc(plc);
  EXPECT_EQ(r.faces_flipped, 2u);
  EXPECT_TRUE(has_warning(w, "reversed"));
  EXPECT_EQ(plc.facets.size(), 6u);
}

TEST(Plc, InwardSurfaceFlipped) {
  auto faces = box_quads();
  for (auto& f : faces) std::reverse(f.begin(), f.end());
  Warnings w;
  MergeReport r;
  const PLC plc = build_plc(soup_of(box_points(1, 1, 1), faces), w, &r);
  expect_valid_plc(plc);
  EXPECT_TRUE(has_warning(w, "inwards"));
  EXPECT_EQ(r.faces_flipped, 6u);
}

TEST(Plc, CavityShellFacesTheCavity) {
  // A 3x3x3 box with a 1x1x1 cavity; the cavity's shell is given facing out
  // of itself (wrong) and must be turned to face the cavity.
  auto pts = box_points(3, 3, 3);
  for (const auto& q : box_points(1, 1, 1)) pts.push_back({q[0] + 1, q[1] + 1, q[2] + 1});
  auto faces = box_quads();
  for (auto f : box_quads()) {
    for (int& v : f) v += 8;
    faces.push_back(f);
  }
  Warnings w;
  const PLC plc = build_plc(soup_of(pts, faces), w);
  EXPECT_EQ(expect_valid_plc(plc), 2);
  EXPECT_TRUE(has_warning(w, "cavity"));
  int inner = 0;
  for (const auto& F : plc.facets) {
    Point3 c{0, 0, 0};
    for (int v : F.loops[0])
      for (int i = 0; i < 3; ++i) c[i] += plc.vertices[v][i] / F.loops[0].size();
    const bool is_inner = c[0] > 0.5 && c[0] < 2.5 && c[1] > 0.5 && c[1] < 2.5 && c[2] > 0.5 && c[2] < 2.5;
    const double towards_centre = (1.5 - c[0]) * F.normal[0] + (1.5 - c[1]) * F.normal[1] + (1.5 - c[2]) * F.normal[2];
    if (is_inner) {
      ++inner;
      EXPECT_GT(towards_centre, 0) << "a cavity facet faces away from the cavity";
    } else {
      EXPECT_LT(towards_centre, 0) << "an outer facet faces inwards";
    }
  }
  EXPECT_EQ(inner, 6);
  // Given the right way, nothing is reversed.
  for (std::size_t f = 6; f < faces.size(); ++f) std::reverse(faces[f].begin(), faces[f].end());
  Warnings w2;
  MergeReport r2;
  expect_valid_plc(build_plc(soup_of(pts, faces), w2, &r2));
  EXPECT_EQ(r2.faces_flipped, 0u);
}

TEST(Plc, NonPlanarQuadSplit) {
  auto pts = box_points(1, 1, 1);
  pts[6] = {1.25, 1.25, 1.25};  // moves one corner: top and two sides are not planar
  Warnings w;
  MergeReport r;
  const PLC plc = build_plc(soup_of(pts, box_quads()), w, &r);
  expect_valid_plc(plc);
  EXPECT_EQ(r.faces_split, 3u);
  EXPECT_TRUE(has_warning(w, "non-planar"));
  EXPECT_EQ(plc.facets.size(), 3u + 2u * 3u);
  // A planar non-convex (L-shaped) polygon stays one facet.
  std::vector<Point3> L = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}};
  const std::size_t n = L.size();
  for (std::size_t i = 0; i < n; ++i) L.push_back({L[i][0], L[i][1], 1});
  std::vector<std::vector<int>> faces = {{5, 4, 3, 2, 1, 0}, {6, 7, 8, 9, 10, 11}};
  for (int i = 0; i < 6; ++i) faces.push_back({i, (i + 1) % 6, (i + 1) % 6 + 6, i + 6});
  Warnings w2;
  MergeReport r2;
  const PLC lp = build_plc(soup_of(L, faces), w2, &r2);
  expect_valid_plc(lp);
  EXPECT_EQ(lp.facets.size(), 8u);
  EXPECT_EQ(r2.faces_split, 0u);
}

/// Cubes whose faces are n x n grids of triangles, with random diagonals,
/// some vertices moved by multiples of a quarter unit (so exact coplanar,
/// collinear, degenerate and crossing configurations are frequent) and some triangles reversed:
/// build_plc either throws InputError or gives a PLC meeting its contract.
TEST(Plc, RandomGridCubesAreValidOrRejected) {
  std::mt19937 rng(2005);
  const int n = 3;
  int accepted = 0, rejected = 0;
  for (int trial = 0; trial < 300; ++trial) {
    std::map<std::array<int, 3>, int> index;
    std::vector<Point3> pts;
    auto vertex = [&](std::array<int, 3> c) {
      auto [it, fresh] = index.emplace(c, static_cast<int>(pts.size()));
      if (fresh) pts.push_back({double(c[0]), double(c[1]), double(c[2])});
      return it->second;
    };
    std::vector<std::vector<int>> faces;
    for (int a = 0; a < 3; ++a)
      for (int side : {0, n}) {
        const int u = (a + 1) % 3, v = (a + 2) % 3;
        for (int i = 0; i < n; ++i)
          for (int j = 0; j < n; ++j) {
            auto at = [&](int x, int y) {
              std::array<int, 3> c{};
              c[a] = side;
              c[u] = x;
              c[v] = y;
              return vertex(c);
            };
            std::vector<int> q = {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)};
            if (side == 0) std::reverse(q.begin(), q.end());
            const int d = static_cast<int>(rng() % 2);
            faces.push_back({q[d], q[d + 1], q[(d + 2) % 4]});
            faces.push_back({q[d], q[(d + 2) % 4], q[(d + 3) % 4]});
          }
      }
    const auto outward = faces;  // before some are reversed
    if (trial > 0) {
      for (auto& p : pts)
        if (rng() % 100 < 15) p[rng() % 3] += 0.25 * (static_cast<int>(rng() % 7) - 3);
      for (auto& f : faces)
        if (rng() % 100 < 5) std::reverse(f.begin(), f.end());
    }
    try {
      Warnings w;
      MergeReport r;
      const PLC plc = build_plc(soup_of(pts, faces), w, &r);
      ++accepted;
      SCOPED_TRACE("trial " + std::to_string(trial));
      expect_valid_plc(plc);
      EXPECT_EQ(r.facets, plc.facets.size());
      // Merging faces into facets keeps the enclosed volume.
      double soup_volume = 0, plc_volume = 0;
      for (const auto& f : outward) {
        const Point3 &a = pts[f[0]], &b = pts[f[1]], &c = pts[f[2]];
        soup_volume += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                        a[2] * (b[0] * c[1] - b[1] * c[0])) /
                       6;
      }
      for (const auto& F : plc.facets)
        for (const auto& loop : F.loops) plc_volume += dot(newell(plc, loop), plc.vertices[loop[0]]) / 6;
      EXPECT_NEAR(soup_volume, plc_volume, 1e-9);
      if (trial == 0) {
        EXPECT_EQ(plc.facets.size(), 6u);
        EXPECT_EQ(plc.vertices.size(), 8u);
        EXPECT_EQ(plc.edges.size(), 12u);
      }
    } catch (const InputError&) {
      ++rejected;
    }
  }
  EXPECT_GT(accepted, 10);
  std::cout << "[ random   ] " << accepted << " accepted, " << rejected << " rejected\n";
}

TEST(Plc, Errors) {
  const auto pts = box_points(1, 1, 1);
  std::string m;
  build_error(PolygonSoup{}, InputErrorKind::empty);
  {
    auto p = pts;
    p[2][1] = std::nan("");
    m = build_error(soup_of(p, box_quads()), InputErrorKind::non_finite);
    EXPECT_NE(m.find("point 2"), std::string::npos) << m;
  }
  {
    auto f = box_quads();
    f[4][1] = 8;
    m = build_error(soup_of(pts, f), InputErrorKind::bad_index);
    EXPECT_NE(m.find("face 4 (line 104)"), std::string::npos) << m;
  }
  {
    // Three faces closing up combinatorially.
    m = build_error(soup_of(pts, {{0, 1, 2, 3}, {0, 3, 2}, {0, 2, 1}}), InputErrorKind::too_few_faces);
  }
  {
    auto p = pts;
    p.push_back({0.5, 0, 0});  // 8, on the edge 0-1
    auto f = box_triangles();
    f.push_back({0, 8, 1});
    m = build_error(soup_of(p, f), InputErrorKind::degenerate_face);
    EXPECT_NE(m.find("face 12 (line 112)"), std::string::npos) << m;
    auto g = box_triangles();
    g[5] = {0, 0, 1};
    m = build_error(soup_of(pts, g), InputErrorKind::degenerate_face);
    EXPECT_NE(m.find("face 5"), std::string::npos) << m;
  }
  {
    auto f = box_triangles();
    f.push_back({2, 1, 0});
    m = build_error(soup_of(pts, f), InputErrorKind::duplicate_face);
    EXPECT_NE(m.find("face 1 (line 101)"), std::string::npos) << m;  // {0, 2, 1}
    EXPECT_NE(m.find("face 12 (line 112)"), std::string::npos) << m;
  }
  {
    auto f = box_triangles();
    f.pop_back();
    m = build_error(soup_of(pts, f), InputErrorKind::open_boundary);
    EXPECT_NE(m.find("vertex"), std::string::npos) << m;
  }
  {
    // Two boxes sharing an edge.
    auto p = pts;
    for (const auto& q : box_points(1, 1, 1)) p.push_back({q[0] + 1, q[1] + 1, q[2]});
    // Identify the shared edge: second box's corners (0,0,z) are (1,1,z) = 2, 6.
    auto f = box_triangles();
    for (auto t : box_triangles()) {
      for (int& v : t) v = v == 0 ? 2 : v == 4 ? 6 : v + 8;
      f.push_back(t);
    }
    m = build_error(soup_of(p, f), InputErrorKind::non_manifold_edge);
    EXPECT_NE(m.find("4 faces"), std::string::npos) << m;
  }
  {
    // Two boxes sharing a corner only.
    auto p = pts;
    for (const auto& q : box_points(1, 1, 1)) p.push_back({q[0] + 1, q[1] + 1, q[2] + 1});
    auto f = box_triangles();
    for (auto t : box_triangles()) {
      for (int& v : t) v = v == 0 ? 6 : v + 8;
      f.push_back(t);
    }
    m = build_error(soup_of(p, f), InputErrorKind::non_manifold_vertex);
    EXPECT_NE(m.find("(1, 1, 1)"), std::string::npos) << m;
  }
  {
    // A Moebius-like closed surface cannot be built from a manifold soup of
    // few triangles easily; a Klein-bottle-like torus: a 3x3 grid torus with
    // one twisted identification.
    std::vector<Point3> p;
    const int n = 3, m2 = 4;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < m2; ++j) p.push_back({double(i), double(j), double(i * j % 5)});
    auto id = [&](int i, int j) {
      // Going around i once mirrors j (Klein bottle).
      if (i >= n) {
        i -= n;
        j = (m2 - j) % m2;
      }
      return i * m2 + ((j % m2) + m2) % m2;
    };
    std::vector<std::vector<int>> f;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < m2; ++j) {
        f.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
        f.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      }
    build_error(soup_of(p, f), InputErrorKind::not_orientable);
  }
  {
    // A closed box with a spike poking through its top: a tetrahedron-like
    // tent whose apex is above the box, built as a second closed shell that
    // crosses the first.
    auto p = pts;
    p.push_back({0.5, 0.5, 0.5});  // 8
    p.push_back({0.2, 0.2, 1.5});  // 9
    p.push_back({0.8, 0.2, 1.5});  // 10
    p.push_back({0.5, 0.8, 1.5});  // 11
    auto f = box_triangles();
    f.push_back({8, 10, 9});
    f.push_back({8, 11, 10});
    f.push_back({8, 9, 11});
    f.push_back({9, 10, 11});
    m = build_error(soup_of(p, f), InputErrorKind::self_intersection);
    EXPECT_NE(m.find("face"), std::string::npos) << m;
  }
}

/// Found by the fuzz target build_plc's contract check: a box whose
/// coordinates are all subnormal was rejected as a self-crossing polygon and
/// its facets got no unit normal, because the power of two that scales the
/// coordinates before the rounded normal overflowed to infinity. Every scale
/// from subnormal to near DBL_MAX now gives the box's six outward unit normals.
TEST(Plc, SubnormalAndHugeCoordinatesGiveUnitNormals) {
  for (const double scale : {1e-310, 4.9e-324 * 4, 1e-300, 1.0, 1e300, 4e307}) {
    SCOPED_TRACE("scale " + std::to_string(scale));
    EXPECT_GE(validation::power_of_two_scale(scale) * scale, 0x1p-52);
    EXPECT_TRUE(std::isfinite(validation::power_of_two_scale(scale)));
    auto pts = box_points(2, 1, 1);
    for (auto& p : pts)
      for (double& x : p) x *= scale;
    for (const auto& faces : {box_quads(), box_triangles()}) {
      Warnings w;
      PLC plc;
      ASSERT_NO_THROW(plc = build_plc(soup_of(pts, faces), w));
      ASSERT_EQ(plc.facets.size(), 6u);
      EXPECT_EQ(plc.edges.size(), 12u);
      for (const PlcFacet& F : plc.facets) {
        // The axis of the facet is the one coordinate all its vertices share.
        int axis = -1;
        for (int k = 0; k < 3; ++k) {
          bool same = true;
          for (int v : F.loops[0]) same &= plc.vertices[v][k] == plc.vertices[F.loops[0][0]][k];
          if (same) axis = k;
        }
        ASSERT_GE(axis, 0);
        Point3 want{0, 0, 0};
        want[axis] = plc.vertices[F.loops[0][0]][axis] > 0 ? 1 : -1;
        EXPECT_EQ(F.normal, want);
      }
    }
  }
}

/// Found by the fuzz target build_plc's contract check (inputs also in
/// tests/fuzz/corpus/): facets with sides of very different magnitudes got a
/// zero normal (a side of 2e-320 beside sides of 4: the rounded cross products
/// underflowed) or one of length 0.99999 (a needle to a vertex at 4.4e159: its
/// squared components underflowed). Every facet normal is now a unit vector
/// within 1e-7 of the exact direction.
TEST(Plc, FacetsWithSidesOfVeryDifferentMagnitudesGetUnitNormals) {
  const std::vector<std::vector<int>> faces = {{4, 2, 0}, {1, 3, 5}, {0, 2, 3, 1}, {2, 4, 5, 3}, {4, 0, 1, 5}};
  const std::vector<std::vector<Point3>> inputs = {
      {{0, 0, 0}, {0, 0, 2e-320}, {4, 0, 0}, {4, 0, 2}, {4, 3, 5}, {4, 5, 8}},
      {{0, 0, 0},
       {0, 0, 4.4444444444444442e+159},
       {4, 0, 0},
       {4, 0, 2},
       {4, 0.703125, 0},
       {4, 0.69999999999999996, 125}}};
  for (const auto& pts : inputs) {
    Warnings w;
    PLC plc;
    ASSERT_NO_THROW(plc = build_plc(soup_of(pts, faces), w));
    ASSERT_EQ(plc.facets.size(), 6u);
    for (std::size_t f = 0; f < plc.facets.size(); ++f) {
      const PlcFacet& F = plc.facets[f];
      EXPECT_NEAR(std::sqrt(dot(F.normal, F.normal)), 1.0, 1e-12) << "facet " << f;
      std::vector<std::array<int, 3>> fan;
      for (std::size_t i = 1; i + 1 < F.loops[0].size(); ++i)
        fan.push_back({F.loops[0][0], F.loops[0][i], F.loops[0][i + 1]});
      const Point3 exact = validation::exact_unit_area_vector(plc.vertices, fan);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(F.normal[k], exact[k], 1e-7) << "facet " << f;
    }
  }
  // The exact fallback on its own: a needle whose rounded cross product is
  // below its error bound, and a triangle whose cross product underflows.
  const std::vector<Point3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1e-320, 0}, {1e-200, 0, 0}, {0, 1e-200, 0}};
  EXPECT_EQ(validation::unit_area_vector(p, {{{0, 1, 2}}}), (Point3{0, 0, 1}));
  EXPECT_EQ(validation::exact_unit_area_vector(p, {{{0, 3, 4}}}), (Point3{0, 0, 1}));
  EXPECT_EQ(validation::exact_unit_area_vector(p, {{{0, 4, 3}}}), (Point3{0, 0, -1}));
  EXPECT_EQ(validation::exact_unit_area_vector(p, {{{0, 1, 1}}}), (Point3{0, 0, 0}));
}

/// Pairs of triangles through the exact self-intersection test (validation.h):
/// sharing an edge, a vertex or nothing; touching or not.
TEST(Plc, SelfIntersectionPairs) {
  const std::vector<Point3> p = {{0, 0, 0},
                                 {2, 0, 0},
                                 {0, 2, 0},
                                 {1, 1, 0} /*3*/,
                                 {1, -1, 0} /*4*/,
                                 {0.5, 0.5, 0} /*5*/,
                                 {0, 0, 1} /*6*/,
                                 {3, 3, -1} /*7*/,
                                 {3, 3, 1} /*8*/,
                                 {0.2, 0.2, -1} /*9*/,
                                 {0.2, 0.2, 1} /*10*/,
                                 {-1, -1, 0} /*11*/,
                                 {-2, 0, 0} /*12*/,
                                 {5, 0, 0} /*13*/};
  auto run = [&](std::vector<std::array<int, 3>> t) {
    validation::check_self_intersections(p, t, [](int i) { return "triangle " + std::to_string(i); });
  };
  auto bad = [&](std::vector<std::array<int, 3>> t, const std::string& needle) {
    try {
      run(t);
      ADD_FAILURE() << "no self-intersection found; expected " << needle;
    } catch (const InputError& e) {
      EXPECT_EQ(e.kind(), InputErrorKind::self_intersection);
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  // Common edge 0-1: coplanar on opposite sides is fine, on the same side
  // (folded flat) overlaps; not coplanar is fine.
  EXPECT_NO_THROW(run({{0, 1, 2}, {1, 0, 4}}));
  bad({{0, 1, 2}, {1, 0, 5}}, "folded");
  EXPECT_NO_THROW(run({{0, 1, 2}, {1, 0, 6}}));
  // Common vertex 0: coplanar wedges apart are fine, overlapping wedges not;
  // a far edge through the other triangle is a crossing.
  EXPECT_NO_THROW(run({{0, 1, 2}, {0, 11, 12}}));
  bad({{0, 1, 2}, {0, 3, 12}}, "coplanar overlap");
  bad({{0, 1, 2}, {0, 9, 10}}, "common vertex");
  EXPECT_NO_THROW(run({{0, 1, 6}, {0, 12, 11}}));
  // Nothing in common: crossing or disjoint.
  bad({{0, 1, 2}, {7, 8, 5}}, "intersect");
  EXPECT_NO_THROW(run({{0, 1, 2}, {7, 8, 13}}));
}

// Large non-convex polygons: a star of 30,000 vertices (15,000 reflex) is
// triangulated, its reflex vertices found through the grid of the ear test
// (it used to exceed the ear-clipping budget after 6e7 tests and be refused
// as too_large): n - 2 triangles turning the polygon's way whose areas add
// up to the polygon's; a prism over a star is a valid PLC with the two stars
// as facets.
TEST(Plc, LargeStarPolygonsTriangulate) {
  const int n = 30000;
  std::vector<Point3> pts;
  for (int i = 0; i < n; ++i) {
    const double t = 2 * geometry::kPi * i / n, r = i % 2 ? 0.8 : 1;
    pts.push_back({{r * std::cos(t), r * std::sin(t), 0}});
  }
  std::vector<int> poly(n);
  std::iota(poly.begin(), poly.end(), 0);
  std::vector<std::array<int, 3>> tris;
  ASSERT_TRUE(validation::triangulate_polygon(pts, poly, tris));
  ASSERT_EQ(tris.size(), static_cast<std::size_t>(n - 2));
  auto area2 = [&](int a, int b, int c) {
    return (pts[b][0] - pts[a][0]) * (pts[c][1] - pts[a][1]) - (pts[b][1] - pts[a][1]) * (pts[c][0] - pts[a][0]);
  };
  double polygon = 0, sum = 0;
  for (int i = 0; i < n; ++i) polygon += pts[i][0] * pts[(i + 1) % n][1] - pts[(i + 1) % n][0] * pts[i][1];
  std::set<int> used;
  for (const auto& t : tris) {
    EXPECT_GT(area2(t[0], t[1], t[2]), 0);
    sum += area2(t[0], t[1], t[2]);
    used.insert(t.begin(), t.end());
  }
  EXPECT_NEAR(sum, polygon, 1e-9 * polygon);
  EXPECT_EQ(used.size(), static_cast<std::size_t>(n));

  // The prism over a smaller star (the self-intersection test of its radial
  // slivers is not near-linear: their boxes overlap in about n^2 / 40 pairs).
  const int m = 4000;
  std::vector<Point3> prism;
  for (int i = 0; i < m; ++i) {
    const double t = 2 * geometry::kPi * i / m, r = i % 2 ? 0.8 : 1;
    prism.push_back({{r * std::cos(t), r * std::sin(t), 0}});
  }
  for (int i = 0; i < m; ++i) prism.push_back({{prism[i][0], prism[i][1], 1}});
  std::vector<std::vector<int>> faces(2);
  for (int i = m - 1; i >= 0; --i) faces[0].push_back(i);
  for (int i = 0; i < m; ++i) faces[1].push_back(m + i);
  for (int i = 0; i < m; ++i) faces.push_back({i, (i + 1) % m, m + (i + 1) % m, m + i});
  Warnings warnings;
  const PLC plc = build_plc(soup_of(prism, faces), warnings);
  expect_valid_plc(plc);
  EXPECT_EQ(plc.facets.size(), static_cast<std::size_t>(m + 2));
}

}  // namespace
}  // namespace wqmesh
