// wqmesh: the improvement phase's operations at the boundary (beyond the
// paper, and beyond Stellar, which moves boundary vertices freely): Steiner
// vertices of the boundary slide along the coordinate axes that leave their
// facets' planes exactly where they were (see improve.h, "Boundary
// operations").
// SPDX-License-Identifier: GPL-3.0-or-later
#include <algorithm>

#include "cgal_types.h"
#include "mesher/improve.h"

namespace wqmesh::mesher {

namespace {

using Point2 = cgal::K::Point_2;

/// p without its coordinate `axis`.
Point2 drop(const Point3& p, int axis) {
  const int i = axis == 0 ? 1 : 0, j = axis == 2 ? 1 : 2;
  return Point2(p[i], p[j]);
}

/// The coordinate axes along which the plane of `pts` (input vertices of one
/// facet, at least three not on a line) runs, as bits: axis i when every
/// point of pts dropped to the other two coordinates lies on one line, by
/// CGAL's exact orientation. Then the plane's normal has an exact 0 in
/// coordinate i, so its equation does not read that coordinate. 0 when the
/// points are fewer than three or all on a line (no plane to trust).
int plane_axes(const std::vector<Point3>& pts) {
  if (pts.size() < 3) return 0;
  // A triangle of pts that is not flat: the plane is the one through it.
  std::size_t b = 1, c = 0;
  while (b < pts.size() && pts[b] == pts[0]) ++b;
  for (std::size_t k = b + 1; k < pts.size() && c == 0; ++k)
    if (!CGAL::collinear(cgal::to_cgal(pts[0]), cgal::to_cgal(pts[b]), cgal::to_cgal(pts[k]))) c = k;
  if (b >= pts.size() || c == 0) return 0;
  int axes = 0;
  for (int axis = 0; axis < 3; ++axis) {
    const Point2 p = drop(pts[0], axis), q = drop(pts[b], axis), r = drop(pts[c], axis);
    // The triangle seen along the axis is a segment (it cannot be a point:
    // pts[0], pts[b], pts[c] are not on a line); every point must lie on it.
    const Point2& far = p != q ? q : r;
    bool on_line = true;
    for (const Point3& x : pts)
      if (CGAL::orientation(p, far, drop(x, axis)) != CGAL::COLLINEAR) on_line = false;
    if (on_line) axes |= 1 << axis;
  }
  return axes;
}

}  // namespace

void Improver::init_slides() {
  slide_.assign(P_.size(), 0);
  if (r_.mesh.boundary_facet.size() != bnd_.size()) return;  // no facets known: nothing slides
  // The input vertices of each facet (the corners of its boundary triangles
  // that are input vertices: every corner of a facet's loops is one).
  int facets = 0;
  for (int f : r_.mesh.boundary_facet) facets = std::max(facets, f + 1);
  std::vector<std::vector<int>> corners(facets);
  for (std::size_t b = 0; b < bnd_.size(); ++b) {
    const int f = r_.mesh.boundary_facet[b];
    if (f < 0) continue;
    for (int v : bnd_[b])
      if (v < int(r_.input_vertex.size()) && r_.input_vertex[v] >= 0) corners[f].push_back(v);
  }
  std::vector<int> facet_axes(facets, 0);
  for (int f = 0; f < facets; ++f) {
    std::sort(corners[f].begin(), corners[f].end());
    corners[f].erase(std::unique(corners[f].begin(), corners[f].end()), corners[f].end());
    std::vector<Point3> pts;
    for (int v : corners[f]) pts.push_back(P_[v]);
    facet_axes[f] = plane_axes(pts);
  }
  // A Steiner vertex of the boundary slides along the axes that every facet
  // of its boundary triangles runs along (one facet: within the facet; two:
  // along their common input edge). 7 marks "not yet seen".
  std::vector<std::uint8_t> axes(P_.size(), 7);
  for (std::size_t b = 0; b < bnd_.size(); ++b) {
    const int f = r_.mesh.boundary_facet[b];
    for (int v : bnd_[b]) axes[v] &= f < 0 ? 0 : facet_axes[f];
  }
  const int open = -1 - int(bnd_.size());
  for (std::size_t t = 0; t < tets_.size(); ++t)
    for (int k = 0; k < 4; ++k)
      if (nb_[t][k] <= open)
        for (int v : tets_[t]) axes[v] = 0;  // a mesh that is not closed: its open faces' tets stay
  for (std::size_t v = 0; v < P_.size(); ++v) {
    const bool input = v < r_.input_vertex.size() && r_.input_vertex[v] >= 0;
    if (fixed_[v] && !input && axes[v] != 7) slide_[v] = axes[v];
  }
}

int Improver::slide_axes(int v) const { return v >= 0 && v < int(slide_.size()) ? slide_[v] : 0; }

int Improver::movable_axes(int v) const {
  if (v < 0 || v >= int(fixed_.size())) return 0;
  return fixed_[v] ? slide_axes(v) : 7;
}

}  // namespace wqmesh::mesher
