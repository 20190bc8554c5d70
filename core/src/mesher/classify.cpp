// wqmesh: the classes of the output tets; see classify.h for the definition.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesher/classify.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "geometry.h"
#include "mesher/mesher.h"
#include "wqmesh/quality.h"

namespace wqmesh::mesher {

using namespace geometry;

namespace {

/// The relative rounding bound of the double circumcenter and min-sine of a
/// tet whose longest edge cubed is kappa times |6V| (with a safety factor
/// of about 20 over the operations' count): kappa grows as the tet flattens.
double rounding_bound(double kappa) { return 1e-12 + 2e-13 * kappa; }

/// The classes of every tet of `mesh` from its unweighted `quality`, by the
/// definition of classify.h; false when keep_going said stop.
bool classify(const TetMesh& mesh, const std::vector<TetQuality>& quality, const ProtectingBalls& balls, double rho0,
              double theta_deg, const std::function<bool()>& keep_going, MeshClasses& out) {
  out = MeshClasses{};
  const TetClassifier classifier(balls, rho0, theta_deg);
  const std::vector<double> shortest = shortest_edges2(mesh);  // L_v^2
  out.tet_class.assign(mesh.tets.size(), TetClass::good);
  for (std::size_t i = 0; i < mesh.tets.size(); ++i) {
    if (keep_going && !keep_going()) return false;
    const TetQuality& q = quality[i];
    const TetClassifier::Shape shape = classifier.shape(q.radius_edge, q.min_dihedral_deg);
    if (shape == TetClassifier::Shape::good) continue;
    const auto& t = mesh.tets[i];
    const TetClass c =
        classifier.classify(shape, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]], mesh.vertices[t[3]],
                            {{shortest[t[0]], shortest[t[1]], shortest[t[2]], shortest[t[3]]}});
    out.tet_class[i] = c;
    out.slivers += shape == TetClassifier::Shape::sliver;
    out.skinny += shape == TetClassifier::Shape::skinny;
    out.near_small_angle += c != TetClass::violation;
    out.violations += c == TetClass::violation;
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

TetClassifier::TetClassifier(const ProtectingBalls& balls, double rho0, double theta_deg)
    : balls_(balls), rho0_(rho0), theta_deg_(theta_deg), sin_theta_(std::sin(theta_deg * kPi / 180)) {}

TetClassifier::Shape TetClassifier::shape(double radius_edge, double min_dihedral_deg) const {
  if (radius_edge > rho0_) return Shape::skinny;
  return min_dihedral_deg < theta_deg_ ? Shape::sliver : Shape::good;
}

TetClassifier::Shape TetClassifier::shape(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                                          double min_sine, Point3& center) const {
  center = {{NAN, NAN, NAN}};
  // Estimates first (R^2 / l^2 from geometry::circumcenter, the min-sine),
  // trusted when they are farther from their threshold than their rounding
  // bound; tet_quality's own measures otherwise.
  const double l2 = std::min({dist2(a, b), dist2(a, c), dist2(a, d), dist2(b, c), dist2(b, d), dist2(c, d)});
  const double L2 = std::max({dist2(a, b), dist2(a, c), dist2(a, d), dist2(b, c), dist2(b, d), dist2(c, d)});
  const double det = std::fabs(dot(sub(b, a), cross(sub(c, a), sub(d, a))));
  const double kappa = det > 0 ? L2 * std::sqrt(L2) / det : HUGE_VAL;
  const double m = rounding_bound(kappa);
  bool skinny = false, decided = false;
  if (std::isfinite(m) && l2 > 0) {
    double r2;
    center = circumcenter(a, b, c, d, r2);
    const double level = rho0_ * rho0_ * l2;
    if (std::isfinite(r2) && r2 > level * (1 + 4 * m)) skinny = decided = true;
    if (std::isfinite(r2) && r2 < level * (1 - 4 * m)) decided = true;
  }
  if (!decided) skinny = tet_quality(a, b, c, d).radius_edge > rho0_;
  if (skinny) return Shape::skinny;
  if (std::isfinite(m) && min_sine > sin_theta_ * (1 + 1e-6 + m)) return Shape::good;
  return tet_min_dihedral_deg(a, b, c, d) < theta_deg_ ? Shape::sliver : Shape::good;
}

bool TetClassifier::near(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                         const std::array<double, 4>& L2, const Point3* center) const {
  double r2;
  const bool known = center != nullptr && !std::isnan((*center)[0]);
  if (balls_.contains(known ? *center : circumcenter(a, b, c, d, r2))) return true;  // (a)
  const Point3* p[4] = {&a, &b, &c, &d};
  for (int k = 0; k < 4; ++k)  // (b)
    if (balls_.expansion_encroached(*p[k], L2[k] / 9)) return true;
  return false;
}

std::vector<double> shortest_edges2(const TetMesh& mesh) {
  std::vector<double> shortest(mesh.vertices.size(), std::numeric_limits<double>::infinity());
  for (const auto& t : mesh.tets)
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) {
        const double l2 = dist2(mesh.vertices[t[i]], mesh.vertices[t[j]]);
        shortest[t[i]] = std::min(shortest[t[i]], l2);
        shortest[t[j]] = std::min(shortest[t[j]], l2);
      }
  return shortest;
}

bool classify_tets(MeshResult& r, const ProtectingBalls& balls, const MeshOptions& opt,
                   const std::function<bool()>& keep_going) {
  const TetMesh& mesh = r.mesh;
  r.slivers = r.skinny = r.near_small_angle = r.violations = r.orthoradius_skinny = 0;
  // The old measures and classes go first (freed: clear() would keep their
  // blocks, sized for the mesh before the improvement phase), so that they
  // and the new ones are never held together (issue 15, the peak memory),
  // and the memory freed before (the improvement phase's arrays) goes back
  // to the system (trim_heap), so that the new measures do not come on top
  // of it in the resident memory.
  std::vector<TetClass>().swap(r.tet_class);
  std::vector<double>().swap(r.orthoradius_edge);
  std::vector<TetQuality>().swap(r.quality);
  trim_heap();
  r.quality = mesh_quality(mesh, keep_going, false);
  if (r.quality.size() != mesh.tets.size()) return false;
  // The weighted view (the paper's rho with PUMP's weights): no class uses it.
  r.orthoradius_edge.reserve(mesh.tets.size());
  if (mesh.weights.empty()) {
    for (const TetQuality& q : r.quality) r.orthoradius_edge.push_back(q.radius_edge);
  } else {
    // mesh_quality(mesh, keep_going, true)'s radius_edge, one tet at a time
    // (not a second whole-mesh TetQuality vector), by tet_radius_edge (the
    // same value without the angles; the phase's time, issue 14).
    for (const auto& t : mesh.tets) {
      if (keep_going && !keep_going()) return false;
      const std::array<double, 4> w{{mesh.weights[t[0]], mesh.weights[t[1]], mesh.weights[t[2]], mesh.weights[t[3]]}};
      r.orthoradius_edge.push_back(
          tet_radius_edge(mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]], mesh.vertices[t[3]], &w));
    }
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
