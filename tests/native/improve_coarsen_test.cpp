// Tests of the improvement phase's coarsening (core/src/mesher/improve_coarsen.cpp,
// Improver::coarsen(); beyond the paper, issue 14): on slit.off's mesh as
// the passes leave it and on hand-made meshes, the step never lowers the
// smallest dihedral angle or the worst min-sine, makes no tet under 5
// degrees, never adds tets, keeps the region (volume, orientation) and the
// boundary on its facets, and does nothing when the passes leave the mesh's
// smallest dihedral angle below kImproveTargetDeg.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <vector>

#include "geometry.h"
#include "mesh_invariants.h"
#include "mesher/improve.h"
#include "wqmesh/quality.h"

namespace wqmesh {
namespace {

using mesher::Improver;

/// The measures the step promises to keep, of the Improver's live tets.
struct Measures {
  double smallest = 180;  ///< smallest dihedral angle (degrees)
  std::size_t under5 = 0, tets = 0;
  double worst = HUGE_VAL;  ///< worst min-sine
};

Measures measure(const Improver& im) {
  Measures m;
  const auto& P = im.points();
  for (std::size_t t = 0; t < im.tets().size(); ++t) {
    if (!im.alive(int(t))) continue;
    const auto& T = im.tets()[t];
    const double a = tet_min_dihedral_deg(P[T[0]], P[T[1]], P[T[2]], P[T[3]]);
    m.smallest = std::min(m.smallest, a);
    m.under5 += a < 5;
    ++m.tets;
  }
  m.worst = im.worst();
  return m;
}

void expect_kept(const Measures& before, const Measures& after) {
  EXPECT_GE(after.smallest, before.smallest) << "the smallest dihedral angle dropped";
  EXPECT_LE(after.under5, before.under5) << "a tet under 5 degrees was made";
  EXPECT_LE(after.tets, before.tets) << "tets were added";
  EXPECT_GE(after.worst, before.worst) << "the worst min-sine dropped";
}

double mesh_volume(const TetMesh& m) {
  double v = 0;
  for (const auto& t : m.tets) v += tet_volume(m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]], m.vertices[t[3]]);
  return v;
}

/// Every tet positive and not flat; the boundary triangles of each facet
/// cover its area and lie on its plane (within rounding).
void expect_region_and_boundary(const invariants::Input& in, const TetMesh& m) {
  invariants::expect_no_flat_tets(m);
  for (const auto& t : m.tets)
    EXPECT_GT(tet_orientation(m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]], m.vertices[t[3]]), 0);
  const PLC& plc = in.plc;
  const double d = invariants::diag(plc);
  std::vector<double> covered(plc.facets.size(), 0);
  ASSERT_EQ(m.boundary.size(), m.boundary_facet.size());
  for (std::size_t i = 0; i < m.boundary.size(); ++i) {
    const int f = m.boundary_facet[i];
    ASSERT_GE(f, 0);
    ASSERT_LT(f, int(plc.facets.size()));
    const auto& tri = m.boundary[i];
    const Point3 &a = m.vertices[tri[0]], &b = m.vertices[tri[1]], &c = m.vertices[tri[2]];
    const Point3 n = invariants::cross(invariants::sub(b, a), invariants::sub(c, a));
    covered[f] += 0.5 * std::sqrt(invariants::dot(n, n));
    // On the facet's plane: the plane of its first loop's first three
    // corners that are not on a line.
    const auto& loop = plc.facets[f].loops[0];
    const Point3& p0 = plc.vertices[loop[0]];
    Point3 normal{{0, 0, 0}};
    for (std::size_t k = 2; k < loop.size() && invariants::dot(normal, normal) == 0; ++k)
      normal =
          invariants::cross(invariants::sub(plc.vertices[loop[1]], p0), invariants::sub(plc.vertices[loop[k]], p0));
    const double len = std::sqrt(invariants::dot(normal, normal));
    ASSERT_GT(len, 0);
    for (int x : tri)
      EXPECT_LE(std::fabs(invariants::dot(normal, invariants::sub(m.vertices[x], p0))) / len, 1e-12 * d)
          << "boundary vertex " << x << " off the plane of facet " << f;
  }
  for (std::size_t f = 0; f < plc.facets.size(); ++f) {
    const double area = invariants::facet_area(plc, plc.facets[f]);
    EXPECT_NEAR(covered[f], area, 1e-9 * area) << "facet " << f << " not covered exactly";
  }
}

// slit.off (a block with a thin V slit): the passes leave it above
// kImproveTargetDeg, so the step runs; it contracts vertices and polishes
// under the floors, and every measure and invariant is kept.
TEST(ImproveCoarsen, OnSlitKeepsTheSmallestAngleTheTetsAndTheRegion) {
  const std::string f = std::string(WQMESH_EXAMPLE_MODELS) + "/slit.off";
  const invariants::Input in = invariants::load(f);
  MeshOptions off;
  off.improve = false;
  MeshResult r = mesh_polyhedron(in.plc, in.analysis, off);
  const double volume = mesh_volume(r.mesh);
  Improver im(r, 2.2, 0);
  im.set_coarsen(false);
  ASSERT_TRUE(im.run());
  const Measures before = measure(im);
  ASSERT_GE(before.smallest, mesher::kImproveTargetDeg) << "the passes no longer reach their target on slit";
  EXPECT_GT(im.coarsen(), 0u);
  const Measures after = measure(im);
  expect_kept(before, after);
  EXPECT_LT(after.tets, before.tets) << "slit's boundary Steiner vertices are contracted";
  im.finish();
  EXPECT_EQ(r.mesh.tets.size(), after.tets);
  EXPECT_NEAR(mesh_volume(r.mesh), volume, 1e-12 * volume);
  EXPECT_NEAR(mesh_volume(r.mesh), plc_volume(in.plc), 1e-9 * volume);
  for (std::size_t i = 0; i < in.plc.vertices.size(); ++i) EXPECT_EQ(r.mesh.vertices[i], in.plc.vertices[i]);
  expect_region_and_boundary(in, r.mesh);
  std::printf("[ coarsen  ] slit.off: smallest dihedral %.4g -> %.4g deg, tets %zu -> %zu\n", before.smallest,
              after.smallest, before.tets, after.tets);
}

// The whole default run on slit.off (the step at the end of Improver::run):
// the phase's output meets every invariant of the mesher, with no more tets,
// tets under 5 degrees or violations than the passes alone leave.
TEST(ImproveCoarsen, TheDefaultRunOnSlitMeetsEveryInvariant) {
  const std::string f = std::string(WQMESH_EXAMPLE_MODELS) + "/slit.off";
  const invariants::Input in = invariants::load(f);
  const MeshResult r = mesh_polyhedron(in.plc, in.analysis);
  invariants::expect_invariants(f, in, r);
  EXPECT_GE(r.improve.min_dihedral_after, mesher::kImproveTargetDeg);
  EXPECT_EQ(r.violations, 0u);
  std::size_t under5 = 0;
  for (const auto& t : r.mesh.tets)
    under5 += tet_min_dihedral_deg(r.mesh.vertices[t[0]], r.mesh.vertices[t[1]], r.mesh.vertices[t[2]],
                                   r.mesh.vertices[t[3]]) < 5;
  EXPECT_EQ(under5, 0u);
  std::printf("[ coarsen  ] slit.off by default: smallest dihedral %.4g deg, %zu tets\n", r.improve.min_dihedral_after,
              r.mesh.tets.size());
}

// A hand-made mesh: a regular tet abcd (input vertices, each face a facet of
// its own) cut into four by the Steiner vertex v at `inner`.
struct Split {
  MeshResult r;
  invariants::Input in;
  explicit Split(const Point3& inner) {
    const double s = std::sqrt(3.0), h = 1 / std::sqrt(2.0);
    r.mesh.vertices = {{{1, 0, -h}}, {{-0.5, s / 2, -h}}, {{-0.5, -s / 2, -h}}, {{0, 0, h}}, inner};
    // The tet's faces, outward (abcd is positive).
    const int faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
    for (int k = 0; k < 4; ++k) {
      std::array<int, 4> t{{faces[k][0], faces[k][1], faces[k][2], 4}};
      if (tet_orientation(r.mesh.vertices[t[0]], r.mesh.vertices[t[1]], r.mesh.vertices[t[2]], r.mesh.vertices[t[3]]) <
          0)
        std::swap(t[0], t[1]);
      r.mesh.tets.push_back(t);
      r.mesh.boundary.push_back({{faces[k][0], faces[k][1], faces[k][2]}});
      r.mesh.boundary_facet.push_back(k);
    }
    r.input_vertex = {0, 1, 2, 3, -1};
    r.nearest_neighbour.assign(5, 1);
    // The same tet as a PLC, for the boundary checks.
    in.plc.vertices.assign(r.mesh.vertices.begin(), r.mesh.vertices.begin() + 4);
    for (const auto& f : faces) {
      PlcFacet facet;
      facet.loops = {{f[0], f[1], f[2]}};
      in.plc.facets.push_back(facet);
    }
  }
};

// v at the centroid: four tets of smallest dihedral angle 35.26 degrees
// (above kImproveTargetDeg, none under kContractBelowDeg, so the passes'
// contraction never tries v); the step contracts v and gives back abcd.
TEST(ImproveCoarsen, ContractsAVertexThePassesNeverTry) {
  Split c(Point3{{0, 0, -0.5 / std::sqrt(2.0)}});
  const double volume = mesh_volume(c.r.mesh);
  Improver im(c.r, 2.2, 0);
  const Measures before = measure(im);
  ASSERT_NEAR(before.smallest, 35.26, 0.01);
  EXPECT_EQ(im.contract_pass(), 0u) << "no tet under kContractBelowDeg";
  EXPECT_GT(im.coarsen(), 0u);
  const Measures after = measure(im);
  expect_kept(before, after);
  EXPECT_EQ(after.tets, 1u);
  EXPECT_NEAR(after.smallest, 70.53, 0.01);
  EXPECT_TRUE(im.removed(4));
  im.finish();
  EXPECT_NEAR(mesh_volume(c.r.mesh), volume, 1e-12);
  expect_region_and_boundary(c.in, c.r.mesh);
}

// v just inside face abc: the tet vabc is nearly flat, so the mesh's
// smallest angle is under kImproveTargetDeg and the step does nothing,
// though a contraction (by the phase's strict rule) would remove the sliver.
TEST(ImproveCoarsen, DoesNothingBelowThePassesTarget) {
  Split c(Point3{{0.01, 0.02, -1 / std::sqrt(2.0) + 0.01}});
  Improver im(c.r, 2.2, 0);
  const Measures before = measure(im);
  ASSERT_LT(before.smallest, mesher::kImproveTargetDeg);
  const std::vector<std::array<int, 4>> tets = im.tets();
  const std::vector<Point3> points = im.points();
  EXPECT_EQ(im.coarsen(), 0u);
  EXPECT_EQ(im.tets(), tets);
  EXPECT_EQ(im.points(), points);
  EXPECT_EQ(im.stats().changes(), 0u);
  EXPECT_TRUE(im.contract_vertex(4)) << "a contraction was possible";
}

}  // namespace
}  // namespace wqmesh
