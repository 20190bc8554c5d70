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

/// Work budgets (README, Limits): beyond them the input is refused with
/// InputError(too_large) naming the budget. Ear clipping of one polygon: at
/// most this many steps (1 per ear candidate, 1 per grid cell it visits and 1
/// per reflex vertex listed there); the self-intersection test: at most this many candidate pairs
/// of triangles with overlapping bounding boxes.
constexpr long long kMaxEarTests = 60'000'000;
constexpr long long kMaxOverlappingPairs = 200'000'000;

/// A power of two s by which coordinates of magnitude at most `big` are
/// scaled exactly before rounded products (normals), so that they neither
/// overflow nor underflow: 2^-ilogb(big), i.e. big * s in [1, 2), but at most
/// 2^1022 so that s stays finite when `big` is subnormal (then big * s is in
/// [2^-52, 1)); 1 when big is 0 or not finite.
double power_of_two_scale(double big);

/// The unit vector along the exact sum over `tris` (indices into `pts`) of
/// (b - a) x (c - a), i.e. twice their vector area, with rounded components;
/// (0, 0, 0) when the sum is exactly zero. Right whatever the magnitudes, also
/// where rounded cross products underflow or overflow (slower than those).
Point3 exact_unit_area_vector(const std::vector<Point3>& pts, const std::vector<std::array<int, 3>>& tris);

/// The same vector, each component within about 1e-7 of the exact unit
/// vector's: from rounded arithmetic on the coordinates scaled by
/// power_of_two_scale (the same bits on every platform) when an error bound
/// shows it that close, else from exact_unit_area_vector (thin triangles of
/// huge coordinates, products that underflow). For a facet (coplanar
/// triangles turning the same way) this is its unit normal.
Point3 unit_area_vector(const std::vector<Point3>& pts, const std::vector<std::array<int, 3>>& tris);

/// Triangulates the polygon `poly` (indices into `pts`, at least 3 distinct
/// points, not all collinear) by ear clipping in a coordinate plane, the one
/// most parallel to it (by the rounded Newell normal) among those along whose
/// normal axis the exact Newell normal is not zero, keeping its orientation:
/// every triangle (a, b, c) is counter-clockwise in the projection exactly when
/// the polygon is (seen from the side its exact Newell normal points to).
/// Handles non-convex polygons and vertices on straight sides; every triangle
/// has non-zero area (its projection is strictly convex, decided exactly).
/// Returns false when no ear can be found, i.e. the projection of the polygon
/// is not simple, or when the exact Newell normal is zero. Throws InputError
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
/// Throws InputError(too_large) beyond kMaxOverlappingPairs candidate pairs,
/// at once (before any box is built) when the pairs of triangles at common
/// vertices, which always overlap, are already more.
void check_self_intersections(const std::vector<Point3>& pts, const std::vector<std::array<int, 3>>& tris,
                              const std::function<std::string(int)>& describe);

/// "(x, y, z)" with 17 significant digits: a point as error messages name it.
std::string coords(const Point3& p);

}  // namespace wqmesh::validation
