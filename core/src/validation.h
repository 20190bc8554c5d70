// SPDX-License-Identifier: GPL-3.0-or-later
// wqmesh: geometric checks used while building the PLC (private header).
// Every decision is exact: CGAL's Epick predicates on the input doubles.
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "wqmesh/error.h"
#include "wqmesh/types.h"

namespace wqmesh::validation {

/// Triangulates the polygon `poly` (indices into `pts`, at least 3 distinct
/// points, not all collinear) by ear clipping in the coordinate plane most
/// parallel to it, keeping its orientation: every triangle (a, b, c) is
/// counter-clockwise in the projection exactly when the polygon is (seen from
/// the side its Newell normal points to). Handles non-convex polygons and
/// vertices on straight sides; every triangle has non-zero area (its projection
/// is strictly convex, decided exactly). Returns false when no ear can be found,
/// i.e. the projection of the polygon is not simple. Throws InputError
/// (too_large) when a huge polygon would take too long.
bool triangulate_polygon(const std::vector<Point3>& pts, const std::vector<int>& poly,
                         std::vector<std::array<int, 3>>& out);

/// Throws InputError(self_intersection) when two triangles of the surface meet
/// anywhere but in their common vertices and edges (paper, section 2: the
/// elements of the PLC intersect properly). Triangles sharing an edge must not
/// overlap (a triangle folded flat onto its coplanar neighbour is reported);
/// triangles sharing one vertex must not meet anywhere else; others must be
/// disjoint. Candidate pairs come from CGAL::box_intersection_self_d on the
/// bounding boxes. `describe(t)` names triangle t in messages (its face, line).
/// Throws InputError(too_large) beyond 2e8 candidate pairs.
void check_self_intersections(const std::vector<Point3>& pts,
                              const std::vector<std::array<int, 3>>& tris,
                              const std::function<std::string(int)>& describe);

}  // namespace wqmesh::validation
