// wqmesh: the classes of the output tets; see classify.h for the definition.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesher/classify.h"

#include <algorithm>
#include <limits>

#include "geometry.h"
#include "wqmesh/quality.h"

namespace wqmesh::mesher {

using namespace geometry;

namespace {

/// The classes of every tet of `mesh` from its unweighted `quality`, by the
/// definition of classify.h; false when keep_going said stop.
bool classify(const TetMesh& mesh, const std::vector<TetQuality>& quality, const ProtectingBalls& balls, double rho0,
              double theta_deg, const std::function<bool()>& keep_going, MeshClasses& out) {
  out = MeshClasses{};
  // L_v: the shortest edge at v in the mesh.
  std::vector<double> shortest(mesh.vertices.size(), std::numeric_limits<double>::infinity());
  for (const auto& t : mesh.tets)
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) {
        const double l2 = dist2(mesh.vertices[t[i]], mesh.vertices[t[j]]);
        shortest[t[i]] = std::min(shortest[t[i]], l2);
        shortest[t[j]] = std::min(shortest[t[j]], l2);
      }
  out.tet_class.assign(mesh.tets.size(), TetClass::good);
  for (std::size_t i = 0; i < mesh.tets.size(); ++i) {
    if (keep_going && !keep_going()) return false;
    const TetQuality& q = quality[i];
    const bool skinny = q.radius_edge > rho0;
    const bool sliver = !skinny && q.min_dihedral_deg < theta_deg;
    if (!skinny && !sliver) continue;
    const auto& t = mesh.tets[i];
    double r2;
    const Point3 z =
        circumcenter(mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]], mesh.vertices[t[3]], r2);
    bool near = balls.contains(z);        // (a)
    for (int k = 0; k < 4 && !near; ++k)  // (b): shortest[] holds L_v^2
      near = balls.expansion_encroached(mesh.vertices[t[k]], shortest[t[k]] / 9);
    out.tet_class[i] = !near ? TetClass::violation : skinny ? TetClass::skinny_near : TetClass::sliver_near;
    out.slivers += sliver;
    out.skinny += skinny;
    out.near_small_angle += near;
    out.violations += !near;
  }
  return true;
}

/// A box holding every vertex of `mesh` and every ball: the anchor of the
/// balls' grid.
Box bounding_box(const TetMesh& mesh, const std::vector<ProtectingBall>& balls) {
  Box b;
  bool first = true;
  const auto grow = [&](const Point3& lo, const Point3& hi) {
    for (int k = 0; k < 3; ++k) {
      b.lo[k] = first ? lo[k] : std::min(b.lo[k], lo[k]);
      b.hi[k] = first ? hi[k] : std::max(b.hi[k], hi[k]);
    }
    first = false;
  };
  for (const Point3& p : mesh.vertices) grow(p, p);
  for (const ProtectingBall& s : balls) {
    const double r = 2 * s.radius;
    grow({{s.center[0] - r, s.center[1] - r, s.center[2] - r}}, {{s.center[0] + r, s.center[1] + r, s.center[2] + r}});
  }
  return b;
}

}  // namespace

bool classify_tets(MeshResult& r, const ProtectingBalls& balls, const MeshOptions& opt,
                   const std::function<bool()>& keep_going) {
  const TetMesh& mesh = r.mesh;
  r.slivers = r.skinny = r.near_small_angle = r.violations = r.orthoradius_skinny = 0;
  r.tet_class.clear();
  r.orthoradius_edge.clear();
  r.quality = mesh_quality(mesh, keep_going, false);
  if (r.quality.size() != mesh.tets.size()) return false;
  // The weighted view (the paper's rho with PUMP's weights): no class uses it.
  if (mesh.weights.empty()) {
    for (const TetQuality& q : r.quality) r.orthoradius_edge.push_back(q.radius_edge);
  } else {
    const std::vector<TetQuality> weighted = mesh_quality(mesh, keep_going, true);
    if (weighted.size() != mesh.tets.size()) return false;
    for (const TetQuality& q : weighted) r.orthoradius_edge.push_back(q.radius_edge);
  }
  for (double rho : r.orthoradius_edge) r.orthoradius_skinny += rho > opt.rho0;
  MeshClasses c;
  if (!classify(mesh, r.quality, balls, opt.rho0, opt.theta_deg, keep_going, c)) return false;
  r.tet_class = std::move(c.tet_class);
  r.skinny = c.skinny;
  r.slivers = c.slivers;
  r.near_small_angle = c.near_small_angle;
  r.violations = c.violations;
  return true;
}

}  // namespace wqmesh::mesher

namespace wqmesh {

MeshClasses classify_mesh(const TetMesh& mesh, const std::vector<ProtectingBall>& balls, double rho0,
                          double theta_deg) {
  mesher::ProtectingBalls index(mesher::bounding_box(mesh, balls));
  index.set(balls);
  MeshClasses c;
  mesher::classify(mesh, mesh_quality(mesh, {}, false), index, rho0, theta_deg, {}, c);
  return c;
}

}  // namespace wqmesh
