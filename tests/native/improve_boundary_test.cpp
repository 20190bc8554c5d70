// Tests of the improvement phase's insertion on a facet (Improver::insert_boundary,
// core/src/mesher/improve_boundary.cpp; beyond the paper): on models with a
// small input angle, every point it inserts keeps the mesh conforming, every
// tet positive and the worst tet of the mesh no worse.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "geometry.h"
#include "mesh_invariants.h"
#include "mesher/classify.h"
#include "mesher/improve.h"
#include "mesher/protecting_balls.h"
#include "wqmesh/quality.h"

namespace wqmesh {
namespace {

using mesher::Improver;

// insert_boundary on every tet under kInsertBelowDeg of the mesh PUMP left
// (the phase off), one after the other as run() tries them: each accepted
// point adds one vertex, leaves the new vertex's tets positive (exact sign)
// and the mesh's worst min-sine no lower (the phase's contract); at the end
// the mesh written back keeps every invariant of the issue (conformity: each
// facet's area, each input edge's length, the volume).
TEST(ImproveBoundary, PointsInsertedOnFacetsKeepTheMeshConformingAndTheWorstTetNoWorse) {
  const std::vector<std::string> files = {std::string(WQMESH_EXAMPLE_MODELS) + "/thin_wedge.off",
                                          std::string(WQMESH_SHARED_MODELS) + "/wedge-1.off"};
  const double below = std::sin(mesher::kInsertBelowDeg * geometry::kPi / 180);
  std::size_t inserted_all = 0;
  for (const std::string& f : files) {
    if (!std::filesystem::exists(f)) continue;
    SCOPED_TRACE(f);
    const invariants::Input in = invariants::load(f);
    MeshOptions opt;
    opt.improve = false;
    MeshResult r = mesh_polyhedron(in.plc, in.analysis, opt);
    ASSERT_TRUE(r.conforming);
    Improver im(r, opt.rho0, opt.max_size);
    double worst = im.worst();
    std::size_t inserted = 0;
    const std::size_t tets = im.tets().size();
    for (std::size_t t = 0; t < tets; ++t) {
      if (!im.alive(int(t)) || !(im.quality(int(t)) < below)) continue;
      const std::size_t n = im.points().size();
      if (!im.insert_boundary(int(t))) {
        ASSERT_EQ(im.points().size(), n) << "a refused insertion adds no point";
        continue;
      }
      ++inserted;
      ASSERT_EQ(im.points().size(), n + 1);
      EXPECT_GE(im.worst(), worst);
      worst = im.worst();
      const int p = int(n);
      EXPECT_FALSE(im.movable(p)) << "the new point is on the boundary";
      int star = 0;
      for (std::size_t s = 0; s < im.tets().size(); ++s) {
        if (!im.alive(int(s))) continue;
        const auto& T = im.tets()[s];
        if (T[0] != p && T[1] != p && T[2] != p && T[3] != p) continue;
        ++star;
        const auto& P = im.points();
        EXPECT_GT(tet_orientation(P[T[0]], P[T[1]], P[T[2]], P[T[3]]), 0);
      }
      EXPECT_GE(star, 2);
    }
    im.finish();
    // The statistics' classes are those of the mesh before the insertions:
    // classify the mesh written back again (classify_tets, as the phase's
    // caller does) before its invariants, which count its violations.
    mesher::ProtectingBalls balls(in.analysis.bounding_box);
    balls.set(r.protecting_balls);
    ASSERT_TRUE(mesher::classify_tets(r, balls, opt));
    ASSERT_EQ(r.tet_class.size(), r.mesh.tets.size());
    invariants::expect_invariants(f, in, r);
    inserted_all += inserted;
  }
  EXPECT_GT(inserted_all, 0u) << "no point inserted: the test checks nothing";
}

}  // namespace
}  // namespace wqmesh
