// SPDX-License-Identifier: GPL-3.0-or-later
// wqmesh: libFuzzer target of the mesher itself (issue 10): bytes -> a small
// star-shaped polyhedron -> check_polyhedron -> mesh_polyhedron under a
// vertex limit. The bytes choose a subdivided octahedron (6, 18 or 66
// vertices, tests/native/decimated_surface.h's subdivision), a power-of-two scale and an offset, and per vertex a radius
// (quantised to 1/64, so that neighbouring triangles are often exactly
// coplanar and merge into larger facets, with small angles and nearly
// coplanar facets between them) and a small angular jitter; then the mesh
// options (rho, PUMP, a size bound). A radial graph over a spherical
// triangulation with positive radii is always a closed embedded surface, so
// every input is a valid polyhedron: a rejection by check_polyhedron is a
// finding too.
//
// Contract under test: the run returns (libFuzzer's -timeout catches a hang)
// with stopped == "" and a conforming mesh of positive tets whose volume is
// the input's, or with stopped == "limit" holding at most the limit plus one
// step's points. An exception (an internal error), a crash, a sanitizer
// report or a broken contract is a finding.
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include "decimated_surface.h"
#include "fuzz_check.h"
#include "geometry.h"
#include "wqmesh/mesher.h"
#include "wqmesh/report.h"

namespace {

using wqmesh::Point3;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;

class Bytes {
 public:
  Bytes(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  /// The next byte, 0 past the end.
  unsigned next() { return pos_ < size_ ? data_[pos_++] : 0u; }

 private:
  const std::uint8_t* data_;
  std::size_t size_, pos_ = 0;
};

/// The octahedron subdivided `levels` times, its points on the unit sphere;
/// faces counter-clockwise seen from outside.
wqmesh::testing::TriSurface octasphere(int levels) {
  wqmesh::testing::TriSurface s;
  s.points = {{{1, 0, 0}}, {{-1, 0, 0}}, {{0, 1, 0}}, {{0, -1, 0}}, {{0, 0, 1}}, {{0, 0, -1}}};
  s.faces = {{{0, 2, 4}}, {{2, 1, 4}}, {{1, 3, 4}}, {{3, 0, 4}}, {{2, 0, 5}}, {{1, 2, 5}}, {{3, 1, 5}}, {{0, 3, 5}}};
  return wqmesh::testing::subdivided_on_unit_sphere(s, levels);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using wqmesh::fuzz::require;
  Bytes in(data, size);
  const int levels = static_cast<int>(in.next() % 3);
  const int exponent = static_cast<int>(in.next() % 81) - 40;  // scale 2^-40 .. 2^40
  const double scale = std::ldexp(1.0, exponent);
  const double offset = scale * (static_cast<int>(in.next()) - 128) / 64.0;
  using wqmesh::testing::on_unit_sphere;
  wqmesh::testing::TriSurface sphere = octasphere(levels);
  std::vector<Point3>& points = sphere.points;
  // Jitter below a tenth of the smallest edge's angle (0.39 rad at level 2):
  // the spherical triangulation stays valid.
  for (Point3& p : points) {
    const double r = (1 + in.next()) / 64.0;
    const double j1 = (static_cast<int>(in.next()) - 128) / 128.0 * 0.03;
    const double j2 = (static_cast<int>(in.next()) - 128) / 128.0 * 0.03;
    // Two directions orthogonal to p.
    const Point3 a = on_unit_sphere(std::fabs(p[0]) < 0.9 ? Point3{{0, p[2], -p[1]}} : Point3{{-p[2], 0, p[0]}});
    const Point3 b = wqmesh::geometry::cross(p, a);
    const Point3 d =
        on_unit_sphere({{p[0] + j1 * a[0] + j2 * b[0], p[1] + j1 * a[1] + j2 * b[1], p[2] + j1 * a[2] + j2 * b[2]}});
    for (int k = 0; k < 3; ++k) p[k] = r * d[k] * scale + offset;
  }
  const unsigned opts = in.next();
  wqmesh::MeshOptions o;
  o.max_vertices = 800;
  o.rho0 = (opts & 3) == 0 ? 1.6 : (opts & 3) == 1 ? 3.5 : 2.2;
  o.pump = (opts & 4) == 0;
  if (opts & 8) o.max_size = 0.3 * scale;

  const std::string off = wqmesh::testing::to_off(sphere);
  const wqmesh::CheckResult c = wqmesh::check_polyhedron(off.data(), off.size());
  if (!c.valid) {
    std::fprintf(stderr, "wqmesh fuzz: a star-shaped polyhedron was rejected: %s: %s\n%s", c.error_kind.c_str(),
                 c.error.c_str(), off.c_str());
    require(false, "a valid star-shaped polyhedron passes check_polyhedron");
  }
  const wqmesh::MeshResult r = wqmesh::mesh_polyhedron(c.plc, c.analysis, o);
  if (!r.stopped.empty()) {
    require(r.stopped == "limit", "a run without callback stops only at the vertex limit");
    require(r.all_vertices <= o.max_vertices + 64, "a stopped run holds at most the limit plus one step");
    return 0;
  }
  require(r.conforming, "a finished run conforms");
  require(!r.mesh.tets.empty(), "a finished run has tets");
  double volume = 0;
  for (const auto& t : r.mesh.tets) {
    const Point3 &a = r.mesh.vertices[t[0]], &b = r.mesh.vertices[t[1]], &cc = r.mesh.vertices[t[2]],
                 &d = r.mesh.vertices[t[3]];
    const Point3 u{{b[0] - a[0], b[1] - a[1], b[2] - a[2]}}, v{{cc[0] - a[0], cc[1] - a[1], cc[2] - a[2]}},
        w{{d[0] - a[0], d[1] - a[1], d[2] - a[2]}};
    const double o6 =
        u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0]);
    require(CGAL::orientation(K::Point_3(a[0], a[1], a[2]), K::Point_3(b[0], b[1], b[2]),
                              K::Point_3(cc[0], cc[1], cc[2]), K::Point_3(d[0], d[1], d[2])) == CGAL::POSITIVE,
            "every tet is positively oriented (exact)");
    volume += o6 / 6;
  }
  const double expected = wqmesh::plc_volume(c.plc);
  require(std::fabs(volume - expected) <= 1e-9 * std::fabs(expected), "the tets fill the input's volume");
  return 0;
}
