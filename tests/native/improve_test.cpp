// Tests of the improvement phase after PUMP (core/src/mesher/improve.h,
// beyond the paper): each operation on a tiny hand-made configuration whose
// answer is known, then the whole phase on the example models and a few
// shared ones (the mesh invariants hold after it, the worst tet is never
// worse, and with improve = false the mesh is the one the phase starts from).
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

#include "mesh_invariants.h"
#include "mesher/improve.h"
#include "wqmesh/quality.h"

namespace wqmesh {
namespace {

namespace fs = std::filesystem;
using mesher::Improver;
using mesher::min_sine;

// A hand-made mesh: the tets made positive, the convex hull's faces as
// boundary triangles (outward), each in its own facet unless `facet` says.
struct Config {
  MeshResult r;
  void add_tet(int a, int b, int c, int d) {
    std::array<int, 4> t{{a, b, c, d}};
    if (tet_orientation(r.mesh.vertices[a], r.mesh.vertices[b], r.mesh.vertices[c], r.mesh.vertices[d]) < 0)
      std::swap(t[0], t[1]);
    r.mesh.tets.push_back(t);
  }
  // The faces used by one tet only become boundary triangles (outward).
  void close(const std::map<std::set<int>, int>& facet = {}) {
    std::map<std::set<int>, std::pair<std::array<int, 3>, int>> seen;
    static const int kOut[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
    for (const auto& t : r.mesh.tets)
      for (const auto& f : kOut) {
        const std::array<int, 3> tri{{t[f[0]], t[f[1]], t[f[2]]}};
        const std::set<int> key(tri.begin(), tri.end());
        if (seen.count(key))
          seen.erase(key);
        else
          seen[key] = {tri, 0};
      }
    int next = 100;
    for (const auto& [key, v] : seen) {
      r.mesh.boundary.push_back(v.first);
      const auto it = facet.find(key);
      r.mesh.boundary_facet.push_back(it == facet.end() ? next++ : it->second);
    }
    r.input_vertex.assign(r.mesh.vertices.size(), -1);
    r.nearest_neighbour.assign(r.mesh.vertices.size(), 1);
  }
  double worst() const {
    double w = HUGE_VAL;
    for (const auto& t : r.mesh.tets)
      w = std::min(
          w, min_sine(r.mesh.vertices[t[0]], r.mesh.vertices[t[1]], r.mesh.vertices[t[2]], r.mesh.vertices[t[3]]));
    return w;
  }
  double volume() const {
    double v = 0;
    for (const auto& t : r.mesh.tets)
      v += tet_volume(r.mesh.vertices[t[0]], r.mesh.vertices[t[1]], r.mesh.vertices[t[2]], r.mesh.vertices[t[3]]);
    return v;
  }
};

int slot(const std::array<int, 4>& t, int v) { return int(std::find(t.begin(), t.end(), v) - t.begin()); }

void expect_positive(const MeshResult& r) {
  for (const auto& t : r.mesh.tets)
    EXPECT_GT(
        tet_orientation(r.mesh.vertices[t[0]], r.mesh.vertices[t[1]], r.mesh.vertices[t[2]], r.mesh.vertices[t[3]]), 0);
}

TEST(Improve, MinSineOfARegularTetAndOfAnInvertedOne) {
  const Point3 a{{1, 1, 1}}, b{{1, -1, -1}}, c{{-1, 1, -1}}, d{{-1, -1, 1}};
  const double s = min_sine(a, b, c, d);
  EXPECT_NEAR(std::fabs(s), std::sin(std::acos(1.0 / 3)), 1e-12);
  // The sign follows the orientation of tet_orientation (and CGAL's).
  EXPECT_EQ(s > 0, tet_orientation(a, b, c, d) > 0);
  EXPECT_NEAR(min_sine(b, a, c, d), -s, 1e-12);
  EXPECT_EQ(min_sine(a, b, c, mesher::midpoint(a, b)), 0);
}

// The classic sliver abcd (its edges ab and cd nearly cross) between an apex
// above and one below, all six points on the convex hull.
Config sliver_octahedron() {
  Config c;
  const double h = 0.02;
  c.r.mesh.vertices = {{{1, 0, h}}, {{-1, 0, h}}, {{0, 1, -h}}, {{0, -1, -h}}, {{0, 0, 2}}, {{0, 0, -2}}};
  c.add_tet(0, 1, 2, 3);  // the sliver
  c.add_tet(4, 0, 1, 2);
  c.add_tet(4, 0, 1, 3);
  c.add_tet(5, 2, 3, 0);
  c.add_tet(5, 2, 3, 1);
  c.close();
  return c;
}

TEST(Improve, ThreeTwoFlipRemovesASliverAmongThreeTets) {
  Config c = sliver_octahedron();
  const double before = c.worst(), volume = c.volume();
  Improver im(c.r, 2.2, 0);
  const auto& t = im.tets()[0];
  ASSERT_TRUE(im.remove_edge(0, slot(t, 0), slot(t, 1)));  // edge ab: a ring of 3 tets
  EXPECT_EQ(im.stats().flips32, 1u);
  im.finish();
  EXPECT_EQ(c.r.mesh.tets.size(), 4u);
  EXPECT_GT(c.worst(), before);
  EXPECT_NEAR(c.volume(), volume, 1e-12);
  expect_positive(c.r);
  for (const auto& T : c.r.mesh.tets) EXPECT_FALSE(slot(T, 0) < 4 && slot(T, 1) < 4) << "edge ab is gone";
}

TEST(Improve, TheWholePhaseDoesAtLeastAsWellAsTheFirstFlip) {
  // The phase starts with the sliver's edge ab or cd (congruent by the
  // configuration's symmetry), so it ends at least as well as that flip.
  Config one = sliver_octahedron();
  {
    Improver im(one.r, 2.2, 0);
    const auto& t = im.tets()[0];
    ASSERT_TRUE(im.remove_edge(0, slot(t, 0), slot(t, 1)));
    im.finish();
  }
  Config c = sliver_octahedron();
  const double before = c.worst(), volume = c.volume();
  Improver im(c.r, 2.2, 0);
  ASSERT_TRUE(im.run());
  im.finish();
  EXPECT_GT(c.worst(), before);
  EXPECT_GE(c.worst(), one.worst());
  EXPECT_NEAR(c.volume(), volume, 1e-12);
  expect_positive(c.r);
  EXPECT_GE(c.r.improve.passes, 1);
  EXPECT_GE(c.r.improve.changes(), 1u);
}

TEST(Improve, TwoThreeFlipThroughAFlatFace) {
  // Two flat tets on the triangle xyz, apexes d above and e below.
  Config c;
  c.r.mesh.vertices = {{{1, 0, 0}}, {{-0.5, 0.8660254, 0}}, {{-0.5, -0.8660254, 0}}, {{0, 0, 0.3}}, {{0, 0, -0.3}}};
  c.add_tet(0, 1, 2, 3);
  c.add_tet(0, 1, 2, 4);
  c.close();
  const double before = c.worst();
  Improver im(c.r, 2.2, 0);
  const auto& t = im.tets()[0];
  ASSERT_TRUE(im.flip23(0, slot(t, 3)));
  EXPECT_EQ(im.stats().flips23, 1u);
  im.finish();
  EXPECT_EQ(c.r.mesh.tets.size(), 3u);
  EXPECT_GT(c.worst(), before);
  expect_positive(c.r);
  for (const auto& T : c.r.mesh.tets) EXPECT_TRUE(slot(T, 3) < 4 && slot(T, 4) < 4);
}

TEST(Improve, FourFourFlipTakesTheShorterDiagonal) {
  // An octahedron around its long diagonal ab (length 5); the flip takes a
  // diagonal of the ring (length 2).
  Config c;
  c.r.mesh.vertices = {{{0, 0, 2.5}}, {{0, 0, -2.5}}, {{1, 0, 0}}, {{0, 1, 0}}, {{-1, 0, 0}}, {{0, -1, 0}}};
  for (int i = 0; i < 4; ++i) c.add_tet(0, 1, 2 + i, 2 + (i + 1) % 4);
  c.close();
  const double before = c.worst();
  Improver im(c.r, 2.2, 0);
  const auto& t = im.tets()[0];
  ASSERT_TRUE(im.remove_edge(0, slot(t, 0), slot(t, 1)));
  EXPECT_EQ(im.stats().flips44, 1u);
  im.finish();
  EXPECT_EQ(c.r.mesh.tets.size(), 4u);
  EXPECT_GT(c.worst(), before);
  expect_positive(c.r);
  for (const auto& T : c.r.mesh.tets) EXPECT_FALSE(slot(T, 0) < 4 && slot(T, 1) < 4);
}

// Two tets over the quadrilateral a d b e of the plane z = 0, cut along its
// long diagonal ab, with the apex c above; `same_facet`: both triangles on
// z = 0 in facet 0, else in facets 0 and 1.
Config flat_quad(bool same_facet) {
  Config c;
  c.r.mesh.vertices = {{{-1, 0, 0}}, {{1, 0, 0}}, {{0.1, 0, 1}}, {{0, -0.45, 0}}, {{0, 0.45, 0}}};
  c.add_tet(0, 1, 2, 3);
  c.add_tet(0, 1, 2, 4);
  c.close({{{0, 1, 3}, 0}, {{0, 1, 4}, same_facet ? 0 : 1}});
  return c;
}

TEST(Improve, TwoTwoFlipInsideOneFacetKeepsItCovered) {
  Config c = flat_quad(true);
  const double before = c.worst();
  Improver im(c.r, 2.2, 0);
  // The edge ab is on the boundary: t's boundary face abd and interior abc.
  const auto& t = im.tets()[0];
  ASSERT_TRUE(im.flip22(0, slot(t, 0), slot(t, 1)));
  EXPECT_EQ(im.stats().flips22, 1u);
  im.finish();
  EXPECT_GT(c.worst(), before);
  expect_positive(c.r);
  // The triangles of facet 0 now use the diagonal de, lie on z = 0, face
  // down (outward) and cover the quadrilateral's area 0.9.
  double area = 0;
  int in_facet = 0;
  for (std::size_t i = 0; i < c.r.mesh.boundary.size(); ++i) {
    if (c.r.mesh.boundary_facet[i] != 0) continue;
    ++in_facet;
    const auto& b = c.r.mesh.boundary[i];
    const Point3 n = mesher::cross(mesher::sub(c.r.mesh.vertices[b[1]], c.r.mesh.vertices[b[0]]),
                                   mesher::sub(c.r.mesh.vertices[b[2]], c.r.mesh.vertices[b[0]]));
    EXPECT_LT(n[2], 0);
    area += 0.5 * std::fabs(n[2]);
    for (int v : b) EXPECT_EQ(c.r.mesh.vertices[v][2], 0);
    const std::set<int> s(b.begin(), b.end());
    EXPECT_TRUE(s.count(3) && s.count(4)) << "facet 0 triangle without the new diagonal";
  }
  EXPECT_EQ(in_facet, 2);
  EXPECT_DOUBLE_EQ(area, 0.9);
}

TEST(Improve, BoundaryEdgeBetweenTwoFacetsNeverFlips) {
  Config c = flat_quad(false);
  const MeshResult before = c.r;
  Improver im(c.r, 2.2, 0);
  const auto& t = im.tets()[0];
  EXPECT_FALSE(im.flip22(0, slot(t, 0), slot(t, 1)));
  ASSERT_TRUE(im.run());
  im.finish();
  EXPECT_EQ(c.r.mesh.tets, before.mesh.tets);
  EXPECT_EQ(c.r.mesh.boundary, before.mesh.boundary);
  EXPECT_EQ(c.r.improve.changes(), 0u);
}

TEST(Improve, SmoothingMovesAnInteriorVertexAndNeverAFacetVertex) {
  // An octahedron with an interior vertex off its centre: smoothing moves it
  // and raises the worst tet.
  Config c;
  c.r.mesh.vertices = {{{1, 0, 0}}, {{-1, 0, 0}}, {{0, 1, 0}},       {{0, -1, 0}},
                       {{0, 0, 1}}, {{0, 0, -1}}, {{0.45, 0.3, 0.2}}};
  const int faces[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (const auto& f : faces) c.add_tet(f[0], f[1], f[2], 6);
  c.close();
  const double before = c.worst();
  {
    MeshResult copy = c.r;
    Improver im(copy, 2.2, 0);
    EXPECT_TRUE(im.movable(6));
    ASSERT_TRUE(im.smooth(6));
    im.finish();
    EXPECT_NE(copy.mesh.vertices[6], c.r.mesh.vertices[6]);
    Config after;
    after.r = copy;
    EXPECT_GT(after.worst(), before);
    expect_positive(copy);
  }
  // A square pyramid whose base (a facet) holds the vertex v off its centre:
  // moving v would help, but v lies on boundary triangles.
  Config p;
  p.r.mesh.vertices = {{{-1, -1, 0}}, {{1, -1, 0}}, {{1, 1, 0}}, {{-1, 1, 0}}, {{0, 0, 1}}, {{0.6, 0.5, 0}}};
  for (int i = 0; i < 4; ++i) p.add_tet(i, (i + 1) % 4, 5, 4);
  std::map<std::set<int>, int> base;
  for (int i = 0; i < 4; ++i) base[{i, (i + 1) % 4, 5}] = 0;
  p.close(base);
  const Point3 v = p.r.mesh.vertices[5];
  Improver im(p.r, 2.2, 0);
  EXPECT_FALSE(im.movable(5));
  EXPECT_FALSE(im.smooth(5));
  ASSERT_TRUE(im.run());
  im.finish();
  EXPECT_EQ(p.r.mesh.vertices[5], v);
  EXPECT_EQ(p.r.improve.smoothed, 0u);
  // Input vertices never move either.
  Config q;
  q.r = c.r;
  q.r.input_vertex[6] = 0;
  Improver iq(q.r, 2.2, 0);
  EXPECT_FALSE(iq.smooth(6));
}

TEST(Improve, InsertionRemovesASliver) {
  // The sliver octahedron again, every vertex on the hull: a point inside
  // (the sliver's circumcentre or centroid) re-triangulates a cavity around it.
  Config c = sliver_octahedron();
  const double before = c.worst(), volume = c.volume();
  const std::size_t n = c.r.mesh.vertices.size();
  Improver im(c.r, 2.2, 0);
  ASSERT_TRUE(im.insert(0));
  EXPECT_EQ(im.stats().inserted, 1u);
  im.finish();
  ASSERT_EQ(c.r.mesh.vertices.size(), n + 1);
  EXPECT_EQ(c.r.input_vertex[n], -1);
  EXPECT_GT(c.r.nearest_neighbour[n], 0);
  EXPECT_GT(c.worst(), before);
  EXPECT_NEAR(c.volume(), volume, 1e-12);
  expect_positive(c.r);
  for (const auto& T : c.r.mesh.tets)
    EXPECT_FALSE(slot(T, 0) < 4 && slot(T, 1) < 4 && slot(T, 2) < 4 && slot(T, 3) < 4);
}

// The worst min-sine over a mesh's tets.
double worst(const TetMesh& m) {
  double w = HUGE_VAL;
  for (const auto& t : m.tets)
    w = std::min(w, min_sine(m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]], m.vertices[t[3]]));
  return w;
}

std::vector<std::string> models() {
  std::vector<std::string> out;
  for (const char* n : {"box.off", "bracket.off", "edge_facet.off", "slit.off", "spike.off", "thin_wedge.off"})
    if (fs::exists(std::string(WQMESH_EXAMPLE_MODELS) + "/" + n))
      out.push_back(std::string(WQMESH_EXAMPLE_MODELS) + "/" + n);
  for (const char* n : {"schonhardt.off", "extrusion.off", "wedge.off", "example012.stl"})
    if (fs::exists(std::string(WQMESH_SHARED_MODELS) + "/" + n))
      out.push_back(std::string(WQMESH_SHARED_MODELS) + "/" + n);
  return out;
}

TEST(Improve, ModelsKeepEveryInvariantAndNeverGetWorse) {
  const auto files = models();
  ASSERT_FALSE(files.empty());
  for (const std::string& f : files) {
    SCOPED_TRACE(f);
    const invariants::Input in = invariants::load(f);
    MeshOptions off;
    off.improve = false;
    const MeshResult plain = mesh_polyhedron(in.plc, in.analysis, off);
    const MeshResult r = mesh_polyhedron(in.plc, in.analysis);
    EXPECT_FALSE(plain.improve.ran);
    EXPECT_TRUE(r.improve.ran);
    invariants::expect_invariants(f, in, r);
    EXPECT_GE(worst(r.mesh), worst(plain.mesh));
    EXPECT_EQ(r.phases.back().name, "improve");
    // The phase starts from the mesh improve = false returns: the same
    // vertices first (Steiner points are appended), moved only if free.
    ASSERT_GE(r.mesh.vertices.size(), plain.mesh.vertices.size());
    std::set<int> on_boundary;
    for (const auto& b : plain.mesh.boundary) on_boundary.insert(b.begin(), b.end());
    for (int v : on_boundary) EXPECT_EQ(r.mesh.vertices[v], plain.mesh.vertices[v]);
    EXPECT_EQ(r.mesh.boundary.size(), plain.mesh.boundary.size());
    EXPECT_EQ(r.mesh.boundary_facet, plain.mesh.boundary_facet);
    std::printf(
        "[ improve  ] %s: min dihedral %.3g -> %.3g deg, tets %zu -> %zu; 2-3 %zu, 3-2 %zu, 4-4 %zu, "
        "2-2 %zu, edge removals %zu, smoothed %zu, inserted %zu, passes %d\n",
        fs::path(f).filename().c_str(), r.improve.min_dihedral_before, r.improve.min_dihedral_after,
        plain.mesh.tets.size(), r.mesh.tets.size(), r.improve.flips23, r.improve.flips32, r.improve.flips44,
        r.improve.flips22, r.improve.edge_removals, r.improve.smoothed, r.improve.inserted, r.improve.passes);
  }
}

TEST(Improve, CancelDuringThePhaseReturnsNoMesh) {
  const auto files = models();
  ASSERT_FALSE(files.empty());
  const invariants::Input in = invariants::load(files.back());
  bool seen = false;
  const MeshResult r = mesh_polyhedron(in.plc, in.analysis, {}, [&](const Progress& p) {
    if (p.phase == "improve") seen = true;
    return p.phase != "improve";
  });
  EXPECT_TRUE(seen);
  EXPECT_EQ(r.stopped, "cancelled");
  EXPECT_TRUE(r.mesh.tets.empty());
}

}  // namespace
}  // namespace wqmesh
