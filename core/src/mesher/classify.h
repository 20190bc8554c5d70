// wqmesh: the classes of the output tets (paper, section 6 and Table 2):
// skinny or sliver, near a small angle or a violation of the guarantees.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <functional>

#include "mesher/protecting_balls.h"
#include "wqmesh/mesher.h"

namespace wqmesh::mesher {

/// Fills r.quality (mesh_quality of r.mesh, with r.mesh.weights when set),
/// r.tet_class and the class counts of r (skinny, slivers, near_small_angle,
/// violations) for every tet of r.mesh, from r.mesh, r.nearest_neighbour, the
/// protecting balls and opt's thresholds (rho0, theta_deg) only. A tet is
/// skinny when R/l > rho0, a sliver when not skinny and its smallest dihedral
/// is below theta_deg; a skinny tet or sliver is near a small angle (see
/// TetClass) when its circumcenter lies on or inside a protecting ball or one
/// of its vertices v, weighted with N(v)^2/9, encroaches the two-times
/// expansion of one; else it is a violation. The counts are reset first, so
/// the function may be called again on a changed mesh. `keep_going`
/// (optional) is polled once per tet for the quality and once per tet for
/// the class; when it returns false the function returns false and r's
/// classes are unusable.
bool classify_tets(MeshResult& r, const ProtectingBalls& balls, const MeshOptions& opt,
                   const std::function<bool()>& keep_going = {});

}  // namespace wqmesh::mesher
