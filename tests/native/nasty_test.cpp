// Tests of the whole path (check_polyhedron, then mesh_polyhedron) on nasty
// inputs generated at test time: cospherical points, nearly coplanar facets,
// input angles under 0.1 degree, nearly parallel edges almost touching, far
// offsets and tiny scales, duplicate vertices and faces, zero-area faces and
// sliver triangles. Each input must either mesh (and then the mesh must meet
// the invariants: positive tets, the input volume, input vertices kept, facets
// covered exactly by boundary triangles in their planes, input edges as chains
// of mesh edges) or stop cleanly: an InputError of the expected kind, or a run
// stopped at its vertex limit. Every run must return: a vertex limit bounds the
// work, and a deadline cancels (and fails) a run that would not end.
//
// Each input is written as an OFF file to a temporary folder and read back
// from it; a failure names the file and the command line that reproduces it
// (the file is then kept). WQMESH_NASTY_DIR=folder keeps every file there.
// Far offsets: the volume and the facet areas are compared within 1e-9
// relative plus the rounding of the inserted points (see expect_meshed).
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "decimated_surface.h"
#include "geometry.h"
#include "mesh_invariants.h"
#include "wqmesh/mesher.h"
#include "wqmesh/report.h"

namespace wqmesh {
namespace {

namespace fs = std::filesystem;

using geometry::kPi;
/// A run that takes longer is cancelled and fails: it would not end in a test
/// (the runs take seconds; the margin is for sanitizer builds and busy machines).
constexpr double kDeadlineSeconds = 300;

// ---- Generators ----------------------------------------------------------------

struct Soup {
  std::vector<Point3> points;
  std::vector<std::vector<int>> faces;
};

std::string to_off(const Soup& s) { return testing::to_off(s.points, s.faces); }

// x -> x * scale + offset, for every point.
Soup transformed(Soup s, double scale, const Point3& offset) {
  for (Point3& p : s.points)
    for (int i = 0; i < 3; ++i) p[i] = p[i] * scale + offset[i];
  return s;
}

// The unit cube, faces oriented outwards.
Soup unit_box() {
  return {{{{0, 0, 0}}, {{1, 0, 0}}, {{1, 1, 0}}, {{0, 1, 0}}, {{0, 0, 1}}, {{1, 0, 1}}, {{1, 1, 1}}, {{0, 1, 1}}},
          {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}}};
}

// A triangular prism whose edge along z has the dihedral angle `degrees`.
Soup wedge(double degrees) {
  const double t = std::tan(degrees * kPi / 180);
  return {{{{0, 0, 0}}, {{1, 0, 0}}, {{1, t, 0}}, {{0, 0, 1}}, {{1, 0, 1}}, {{1, t, 1}}},
          {{0, 2, 1}, {3, 4, 5}, {0, 1, 4, 3}, {1, 2, 5, 4}, {2, 0, 3, 5}}};
}

// The unit cube with a square pyramid on its top whose faces meet at the apex
// at about `degrees` (twice the half-angle of the apex's cone).
Soup spike(double degrees) {
  const double w = 0.05, h = w / std::tan(degrees * kPi / 360);
  Soup s = unit_box();
  s.faces.erase(s.faces.begin() + 1);  // the top becomes a square ring
  for (const auto& xy : std::vector<std::array<double, 2>>{{-w, -w}, {w, -w}, {w, w}, {-w, w}})
    s.points.push_back({{0.5 + xy[0], 0.5 + xy[1], 1}});
  s.points.push_back({{0.5, 0.5, 1 + h}});
  s.faces.insert(
      s.faces.end(),
      {{4, 5, 9, 8}, {5, 6, 10, 9}, {6, 7, 11, 10}, {7, 4, 8, 11}, {8, 9, 12}, {9, 10, 12}, {10, 11, 12}, {11, 8, 12}});
  return s;
}

// The unit cube whose top is folded along x = 0.5 by `radians`: two facets
// meeting at an angle of 180 degrees minus a hair.
Soup folded_box(double radians) {
  const double d = 0.5 * std::tan(radians);
  Soup s = unit_box();
  s.points.push_back({{0.5, 0, 1 + d}});
  s.points.push_back({{0.5, 1, 1 + d}});
  s.faces = {{0, 3, 2, 1}, {4, 8, 9, 7}, {8, 5, 6, 9}, {0, 1, 5, 8, 4}, {1, 2, 6, 5}, {2, 3, 7, 9, 6}, {3, 0, 4, 7}};
  return s;
}

// A U-shaped block extruded along y whose two inner walls carry teeth; the
// tips of the teeth are edges along y that nearly touch: `gap` apart at y = 0
// and gap + skew at y = 1 (so nearly parallel, not parallel). The side faces
// are given as triangles (the skewed tip makes some of them non-planar quads).
Soup teeth(double gap, double skew) {
  const std::vector<std::array<double, 2>> profile = {// (x, z), counter-clockwise
                                                      {0, 0},
                                                      {3, 0},
                                                      {3, 3},
                                                      {2, 3},
                                                      {2, 2},
                                                      {1.5 + gap / 2, 1.5},
                                                      {2, 1},
                                                      {2, 0.5},
                                                      {1, 0.5},
                                                      {1, 1},
                                                      {1.5 - gap / 2, 1.5},
                                                      {1, 2},
                                                      {1, 3},
                                                      {0, 3}};
  const int n = static_cast<int>(profile.size()), tip = 5;
  Soup s;
  for (int y = 0; y < 2; ++y)
    for (int i = 0; i < n; ++i)
      s.points.push_back({{profile[i][0] + (y == 1 && i == tip ? skew : 0), double(y), profile[i][1]}});
  std::vector<int> front, back;
  for (int i = 0; i < n; ++i) front.push_back(i);
  for (int i = n - 1; i >= 0; --i) back.push_back(n + i);
  s.faces = {front, back};
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    s.faces.push_back({i, n + i, n + j});
    s.faces.push_back({i, n + j, j});
  }
  return s;
}

// A tetrahedron of height `h` over a unit right triangle.
Soup flat_tet(double h) {
  return {{{{0, 0, 0}}, {{1, 0, 0}}, {{0, 1, 0}}, {{0.3, 0.3, h}}}, {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}}};
}

// An icosahedron subdivided `levels` times, its points projected on the unit
// sphere (cospherical up to rounding): decimated_surface.h's.
Soup icosphere(int levels) {
  const testing::TriSurface t = testing::icosphere(levels);
  Soup s;
  s.points = t.points;
  for (const auto& f : t.faces) s.faces.push_back({f[0], f[1], f[2]});
  return s;
}

// The convex hull of every integer point on the sphere x^2 + y^2 + z^2 = r2:
// exactly cospherical points (and many exactly cocircular on hull faces).
Soup lattice_sphere(int r2) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  std::vector<K::Point_3> points;
  const int r = static_cast<int>(std::ceil(std::sqrt(double(r2))));
  for (int x = -r; x <= r; ++x)
    for (int y = -r; y <= r; ++y)
      for (int z = -r; z <= r; ++z)
        if (x * x + y * y + z * z == r2) points.emplace_back(x, y, z);
  CGAL::Surface_mesh<K::Point_3> hull;
  CGAL::convex_hull_3(points.begin(), points.end(), hull);
  Soup s;
  std::map<CGAL::Surface_mesh<K::Point_3>::Vertex_index, int> index;
  for (const auto v : hull.vertices()) {
    const K::Point_3& p = hull.point(v);
    index[v] = static_cast<int>(s.points.size());
    s.points.push_back({{p.x(), p.y(), p.z()}});
  }
  for (const auto f : hull.faces()) {
    std::vector<int> face;
    for (const auto v : CGAL::vertices_around_face(hull.halfedge(f), hull)) face.push_back(index[v]);
    s.faces.push_back(face);
  }
  return s;
}

// ---- Invariants of a finished mesh ------------------------------------------------

/// The shared invariants (mesh_invariants.h), whose tolerances allow for the
/// rounding of inserted points at large coordinates.
void expect_meshed(const std::string& name, const CheckResult& in, const MeshResult& r) {
  invariants::expect_invariants(name, {in.plc, in.analysis}, r);
}

// ---- Running a case --------------------------------------------------------------

enum class Expect {
  mesh,           ///< meshes under its vertex limit
  mesh_or_limit,  ///< meshes, or stops at its vertex limit
  error,          ///< rejected with InputError `kind`
};

struct Case {
  std::string name;
  Soup soup;
  Expect expect = Expect::mesh;
  std::size_t max_vertices = 200000;
  std::string kind;  ///< for Expect::error
};

// The folder for the generated files: WQMESH_NASTY_DIR, or one of this
// process under the system's temporary folder (removed once empty).
fs::path nasty_dir() {
  const char* env = std::getenv("WQMESH_NASTY_DIR");
  return env && *env ? fs::path(env) : fs::temp_directory_path() / ("wqmesh-nasty-" + std::to_string(::getpid()));
}

void run(const Case& c) {
  const bool keep = std::getenv("WQMESH_NASTY_DIR") != nullptr;
  const fs::path file = nasty_dir() / (c.name + ".off");
  fs::create_directories(nasty_dir());
  {
    std::ofstream out(file, std::ios::binary);
    out << to_off(c.soup);
    ASSERT_TRUE(out.good()) << "cannot write " << file;
  }
  SCOPED_TRACE("reproduce: wqmesh mesh " + file.string() + " -o out.mesh --max-vertices " +
               std::to_string(c.max_vertices));
  std::string bytes;
  {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    bytes = s.str();
  }
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  const auto seconds = [&] { return std::chrono::duration<double>(clock::now() - t0).count(); };
  const CheckResult in = check_polyhedron(bytes.data(), bytes.size());
  if (c.expect == Expect::error) {
    EXPECT_FALSE(in.valid) << c.name << " was accepted";
    EXPECT_EQ(in.error_kind, c.kind) << in.error;
    EXPECT_FALSE(in.error.empty());
    std::printf("[ nasty    ] %-22s %s: %s\n", c.name.c_str(), in.error_kind.c_str(), in.error.c_str());
  } else {
    ASSERT_TRUE(in.valid) << in.error_kind << ": " << in.error;
    MeshOptions o;
    o.max_vertices = c.max_vertices;
    bool late = false;
    const MeshResult r = mesh_polyhedron(in.plc, in.analysis, o, [&](const Progress&) {
      late = late || seconds() > kDeadlineSeconds;
      return !late;
    });
    const double t = seconds();
    std::printf("[ nasty    ] %-22s %s: %zu vertices (%zu in all), %zu tets, %zu violations, %.2f s%s%s\n",
                c.name.c_str(), r.stopped.empty() ? "meshed" : ("stopped: " + r.stopped).c_str(),
                r.mesh.vertices.size(), r.all_vertices, r.mesh.tets.size(), r.violations, t,
                r.stop_message.empty() ? "" : " - ", r.stop_message.c_str());
    ASSERT_FALSE(late) << c.name << " did not return within " << kDeadlineSeconds << " s";
    if (r.stopped.empty()) {
      expect_meshed(c.name, in, r);
    } else {
      EXPECT_EQ(c.expect, Expect::mesh_or_limit) << c.name << " should mesh, but stopped: " << r.stopped;
      EXPECT_EQ(r.stopped, "limit");
      EXPECT_FALSE(r.stop_message.empty());
      EXPECT_LE(r.all_vertices, c.max_vertices + 64) << "the run went past its vertex limit";
      EXPECT_LE(r.mesh.vertices.size(), r.all_vertices);
    }
  }
  if (!keep && !::testing::Test::HasFailure()) {
    std::error_code ec;
    fs::remove(file, ec);
    fs::remove(nasty_dir(), ec);  // only once empty
  }
}

// ---- The inputs -------------------------------------------------------------------

TEST(Nasty, CosphericalLatticePointsMesh) {
  // 168 integer points on the sphere of radius sqrt(101), exactly cospherical.
  const Soup s = lattice_sphere(101);
  ASSERT_EQ(s.points.size(), 168u);
  run({"lattice_sphere_101", s});
}

// Symmetric Steiner points on the icosphere's facets are cocircular: Del V
// then holds flat tets in a facet, and the wall triangles an inside cell meets
// may be the other diagonal than the facet's planar triangulation took. They
// must still carry their input facet and cover it (this failed once: 8 wall
// triangles in facets 47 and 207 were unlabelled).
TEST(Nasty, CosphericalIcosphereMeshes) {
  // 162 points on the unit sphere (up to rounding), 320 triangles.
  run({"icosphere_2", icosphere(2)});
}

TEST(Nasty, NearlyCoplanarFacetsMesh) {
  for (const double radians : {1e-9, 1e-13}) {
    char name[32];
    std::snprintf(name, sizeof name, "folded_box_%g", radians);
    run({name, folded_box(radians)});
  }
}

TEST(Nasty, DihedralAnglesUnderATenthOfADegreeReturn) {
  // The protection of a 0.05 or 0.005 degree edge needs more vertices than a
  // test affords: the runs must stop at the limit or mesh.
  run({"wedge_0.05deg", wedge(0.05), Expect::mesh_or_limit, 3000});
  run({"wedge_0.005deg", wedge(0.005), Expect::mesh_or_limit, 3000});
}

TEST(Nasty, SpikesUnderATenthOfADegreeReturn) {
  // Unlimited, 0.05 degrees meshes with 19211 vertices (7 s; 30 s or more
  // under the sanitizers) and 0.005 degrees with 146177 (60 s).
  run({"spike_0.05deg", spike(0.05), Expect::mesh_or_limit, 8000});
  run({"spike_0.005deg", spike(0.005), Expect::mesh_or_limit, 3000});
}

TEST(Nasty, NearlyParallelEdgesAlmostTouchingReturn) {
  // Tips 1e-3 apart, skewed by 1e-3 over their length: meshes.
  run({"teeth_1e-3", teeth(1e-3, 1e-3)});
  // Tips 1e-6 apart, skewed by 1e-6: the gap needs about a million vertices.
  // The subfacets of the walls fan out from the tooth tips, with thousands of
  // triangles around one vertex; 20000 vertices take 0.7 s natively since the
  // fan walks stopped being quadratic (they took 3.9 s before).
  run({"teeth_1e-6", teeth(1e-6, 1e-6), Expect::mesh_or_limit, 20000});
}

TEST(Nasty, FarOffsetMeshes) {
  const Point3 far{{1e8, 1e8, 1e8}};
  run({"box_at_1e8", transformed(unit_box(), 1, far)});
  run({"wedge_10deg_at_1e8", transformed(wedge(10), 1, far)});
  run({"spike_20deg_at_1e8", transformed(spike(20), 1, far)});
}

TEST(Nasty, TinyScaleMeshes) {
  run({"wedge_10deg_1e-8", transformed(wedge(10), 1e-8, {{0, 0, 0}})});
  run({"spike_20deg_1e-8", transformed(spike(20), 1e-8, {{0, 0, 0}})});
}

TEST(Nasty, DuplicateVerticesAreMerged) {
  // Every point listed twice; faces use either copy.
  Soup s = unit_box();
  const std::size_t n = s.points.size();
  for (std::size_t i = 0; i < n; ++i) s.points.push_back(s.points[i]);
  for (std::size_t f = 0; f < s.faces.size(); ++f)
    for (std::size_t k = 0; k < s.faces[f].size(); ++k)
      if ((f + k) % 2) s.faces[f][k] += static_cast<int>(n);
  run({"duplicate_vertices", s});
}

TEST(Nasty, DuplicateFaceIsAnInputError) {
  Soup s = unit_box();
  s.faces.push_back(s.faces[1]);
  run({"duplicate_face", s, Expect::error, 0, "duplicate_face"});
}

TEST(Nasty, ZeroAreaFacesAreInputErrors) {
  // The top split by a point on one of its edges, with the zero-area
  // triangle along that edge.
  Soup collinear = unit_box();
  collinear.points.push_back({{0.5, 0, 1}});
  collinear.faces = {{0, 3, 2, 1}, {4, 8, 5}, {4, 5, 6, 7}, {0, 1, 5, 8, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  run({"zero_area_collinear", collinear, Expect::error, 0, "degenerate_face"});
  // A triangle with a repeated vertex.
  Soup repeated = unit_box();
  repeated.faces.push_back({4, 4, 5});
  run({"zero_area_repeated_vertex", repeated, Expect::error, 0, "degenerate_face"});
}

TEST(Nasty, SliverTrianglesMeshOrReturn) {
  // A fan on the top around a point 1e-9 from an edge: sliver triangles, all
  // coplanar, merged back into one facet.
  Soup fan = unit_box();
  fan.points.push_back({{0.5, 1e-9, 1}});
  fan.faces = {{0, 3, 2, 1}, {4, 5, 8},    {5, 6, 8},    {6, 7, 8},   {7, 4, 8},
               {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  run({"coplanar_slivers", fan});
  // A point 1e-10 outside the middle of a top edge: a sliver triangle on the
  // top and a non-planar side split into slivers.
  Soup bulge = unit_box();
  bulge.points.push_back({{0.5, -1e-10, 1}});
  bulge.faces = {{0, 3, 2, 1}, {4, 8, 5, 6, 7}, {0, 1, 5, 8, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  run({"sliver_bulge", bulge});
  // A tetrahedron 1e-9 high: every face a sliver, dihedral angles near 0.
  run({"flat_tetrahedron", flat_tet(1e-9), Expect::mesh_or_limit, 3000});
}

}  // namespace
}  // namespace wqmesh
