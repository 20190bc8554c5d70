// wqmesh: the classes of the output tets (paper, section 6 and Table 2),
// computed on the mesh as written, so that anyone can recount them from the
// written mesh and the protecting balls of the statistics.
//
// The definition. Every measure is unweighted: the geometry of the written
// vertices, which is what a solver sees. For a tet t with circumradius R,
// shortest edge l and smallest dihedral angle theta_min:
//   skinny  R/l > rho0 (rule 6's rho0; 2.2 in Table 2);
//   sliver  not skinny and theta_min < theta_deg (section 6: "R/l no more
//           than 2.2, but a dihedral angle less than 3 degrees");
//   near a small input angle: skinny or sliver, and
//     (a) its circumcenter lies on or inside a protecting ball (c, r):
//         |z - c| <= r (rule 6 refuses such a circumcenter, so REFINE leaves
//         the tet), or
//     (b) a vertex v of t, weighted with L_v^2/9, encroaches the two-times
//         expansion of a protecting ball: |v - c|^2 <= (2r)^2 + L_v^2/9,
//         L_v the length of the shortest edge at v in the written mesh (rule
//         7 and PUMP ignore such a vertex, so a sliver at it is not pumped);
//   violation: skinny or sliver and not near.
// The protecting balls are those of section 4.3 (the vertex balls and the
// doubled diametric balls of the sharp subsegments at the end of CONFORM),
// listed in the statistics ("protecting_balls").
//
// Beyond the paper: the paper states its guarantee (Theorem 4.1) for the
// orthoradius-edge ratio of the pumped, weighted mesh, and "near" as the
// E-neighbourhood of the skinny tets at the end of REFINE or within O(f(x))
// of a sharp edge, which cannot be measured on the output. Rules 6 and 7
// give the measurable stand-ins (a) and (b) above; rule 7 takes L_v in the
// triangulation of the whole vertex set V at the time, here it is the
// written mesh's (the interior tets after PUMP, and after the improvement
// phase when it runs), which is at least the nearest-neighbour distance N(v)
// the extraction used before this (issue 14). The paper's weighted view,
// the orthoradius-edge ratio with PUMP's weights, is kept apart
// (MeshResult::orthoradius_edge, the "orthoradius_*" statistics); no class
// depends on it.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <functional>
#include <vector>

#include "mesher/protecting_balls.h"
#include "wqmesh/mesher.h"

namespace wqmesh::mesher {

/// The per-tet test of the definition above: the one code of classify_tets
/// (and classify_mesh) and of the improvement phase's guard (improve.h), so
/// that the guard predicts exactly the classes the statistics will count.
class TetClassifier {
 public:
  /// A tet's class apart from "near": skinny (R/l > rho0), sliver (not
  /// skinny, smallest dihedral angle < theta) or neither (good).
  enum class Shape : unsigned char { good, skinny, sliver };

  /// rho0 and theta_deg: rule 6's rho0 and section 6's sliver angle.
  TetClassifier(const ProtectingBalls& balls, double rho0, double theta_deg);

  /// The shape from tet_quality's unweighted radius_edge and
  /// min_dihedral_deg.
  Shape shape(double radius_edge, double min_dihedral_deg) const;
  /// The shape of tet abcd, the same as shape() of tet_quality(a, b, c, d)'s
  /// measures, bit for bit: tet_quality (or tet_min_dihedral_deg) is called
  /// only where a cheaper estimate lies within its rounding bound of a
  /// threshold. `min_sine`: the smallest sine of abcd's dihedral angles
  /// (improve.h's min_sine), which spares the angles when it is clearly
  /// above sin(theta).
  Shape shape(const Point3& a, const Point3& b, const Point3& c, const Point3& d, double min_sine) const {
    Point3 center;
    return shape(a, b, c, d, min_sine, center);
  }
  /// The same shape; `center` gets abcd's circumcenter (geometry::circumcenter)
  /// when the estimate computed it, else NaNs, for near() (the phase's time,
  /// issue 14: the class guard computed it twice).
  Shape shape(const Point3& a, const Point3& b, const Point3& c, const Point3& d, double min_sine,
              Point3& center) const;
  /// Near a small input angle: (a) or (b) of the definition above; L2[k] is
  /// L_v^2 of the k-th vertex (its squared shortest edge in the mesh).
  /// `center`, when given and not NaN, is abcd's circumcenter as
  /// geometry::circumcenter(a, b, c, d) gives it (shape()'s).
  bool near(const Point3& a, const Point3& b, const Point3& c, const Point3& d, const std::array<double, 4>& L2,
            const Point3* center = nullptr) const;
  /// The class of a tet of shape s: good, or near (skinny_near, sliver_near)
  /// or a violation.
  TetClass classify(Shape s, const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                    const std::array<double, 4>& L2, const Point3* center = nullptr) const {
    if (s == Shape::good) return TetClass::good;
    if (!near(a, b, c, d, L2, center)) return TetClass::violation;
    return s == Shape::skinny ? TetClass::skinny_near : TetClass::sliver_near;
  }

 private:
  const ProtectingBalls& balls_;
  double rho0_, theta_deg_, sin_theta_;
};

/// L_v^2 for every vertex v of `mesh`: the squared length of its shortest
/// edge in mesh.tets (+infinity for a vertex of no tet).
std::vector<double> shortest_edges2(const TetMesh& mesh);

/// Fills r.quality (unweighted: the geometry of r.mesh as written),
/// r.orthoradius_edge (with r.mesh.weights; R/l when there are none),
/// r.tet_class and the class counts of r (skinny, slivers, near_small_angle,
/// violations, orthoradius_skinny) for every tet of r.mesh, from r.mesh, the
/// protecting balls and opt's thresholds (rho0, theta_deg) only, by the
/// definition above. The counts are reset first, so it may be called again
/// on a changed mesh. `keep_going` (optional) is polled once per tet for the
/// measures and once per tet for the class; when it returns false the
/// function returns false and r's classes are unusable.
bool classify_tets(MeshResult& r, const ProtectingBalls& balls, const MeshOptions& opt,
                   const std::function<bool()>& keep_going = {});

}  // namespace wqmesh::mesher
