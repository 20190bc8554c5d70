// wqmesh: the classes of the output tets; see classify.h.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesher/classify.h"

#include "geometry.h"
#include "wqmesh/quality.h"

namespace wqmesh::mesher {

using namespace geometry;

bool classify_tets(MeshResult& r, const ProtectingBalls& balls, const MeshOptions& opt,
                   const std::function<bool()>& keep_going) {
  const TetMesh& mesh = r.mesh;
  r.slivers = r.skinny = r.near_small_angle = r.violations = 0;
  r.quality = mesh_quality(mesh, keep_going);
  if (r.quality.size() != mesh.tets.size()) return false;
  // Classes (see TetClass).
  r.tet_class.assign(mesh.tets.size(), TetClass::good);
  for (std::size_t i = 0; i < mesh.tets.size(); ++i) {
    if (keep_going && !keep_going()) return false;
    const TetQuality& q = r.quality[i];
    const bool skinny = q.radius_edge > opt.rho0;
    const bool sliver = !skinny && q.min_dihedral_deg < opt.theta_deg;
    if (!skinny && !sliver) continue;
    const auto& t = mesh.tets[i];
    double r2;
    const Point3 z =
        circumcenter(mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]], mesh.vertices[t[3]], r2);
    bool near = balls.contains(z);
    for (int k = 0; k < 4 && !near; ++k) {
      const double n = r.nearest_neighbour[t[k]];
      near = balls.expansion_encroached(mesh.vertices[t[k]], n * n / 9);
    }
    r.tet_class[i] = !near ? TetClass::violation : skinny ? TetClass::skinny_near : TetClass::sliver_near;
    r.slivers += sliver;
    r.skinny += skinny;
    r.near_small_angle += near;
    r.violations += !near;
  }
  return true;
}

}  // namespace wqmesh::mesher
