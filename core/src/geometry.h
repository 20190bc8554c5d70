// wqmesh: the double-precision geometry every part of the core shares
// (private): vectors, pi, circumcenters, the orthosphere of four weighted
// points (paper, section 3), Newell's normal. One copy of each: the mesher's
// decisions depend on the exact order of these operations, so a helper is
// changed only together with a check that every model meshes bit for bit as
// before (see CONTRIBUTING.md).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cmath>
#include <utility>
#include <vector>

#include "wqmesh/types.h"

namespace wqmesh::geometry {

constexpr double kPi = 3.14159265358979323846;

inline Point3 sub(const Point3& a, const Point3& b) { return {{a[0] - b[0], a[1] - b[1], a[2] - b[2]}}; }
inline Point3 add(const Point3& a, const Point3& b) { return {{a[0] + b[0], a[1] + b[1], a[2] + b[2]}}; }
inline Point3 mul(const Point3& a, double s) { return {{a[0] * s, a[1] * s, a[2] * s}}; }
inline double dot(const Point3& a, const Point3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Point3 cross(const Point3& a, const Point3& b) {
  return {{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}};
}
inline double norm(const Point3& a) { return std::sqrt(dot(a, a)); }
inline double dist2(const Point3& a, const Point3& b) { return dot(sub(a, b), sub(a, b)); }
inline Point3 midpoint(const Point3& a, const Point3& b) {
  return {{0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.5 * (a[2] + b[2])}};
}
/// v / |v|, or v itself when it is the zero vector.
inline Point3 unit(const Point3& v) {
  const double n = std::sqrt(dot(v, v));
  return n > 0 ? mul(v, 1 / n) : v;
}

/// Circumcenter of triangle abc (in its plane) and the squared circumradius
/// r2 (HUGE_VAL, and a returned, when abc is degenerate):
/// a + ((|ab|^2 ac - |ac|^2 ab) x n) / (2 |n|^2), n = ab x ac.
inline Point3 circumcenter(const Point3& a, const Point3& b, const Point3& c, double& r2) {
  const Point3 ab = sub(b, a), ac = sub(c, a);
  const Point3 n = cross(ab, ac);
  const double d = 2 * dot(n, n);
  if (d == 0) {
    r2 = HUGE_VAL;
    return a;
  }
  const Point3 t = sub(mul(ac, dot(ab, ab)), mul(ab, dot(ac, ac)));
  const Point3 off = mul(cross(t, n), 1 / d);
  r2 = dot(off, off);
  return add(a, off);
}

/// Circumcenter of tet abcd and the squared circumradius r2 (HUGE_VAL, and a
/// returned, when abcd is flat).
inline Point3 circumcenter(const Point3& a, const Point3& b, const Point3& c, const Point3& d, double& r2) {
  const Point3 ab = sub(b, a), ac = sub(c, a), ad = sub(d, a);
  const double det = 2 * dot(ab, cross(ac, ad));
  if (det == 0) {
    r2 = HUGE_VAL;
    return a;
  }
  const Point3 t =
      add(add(mul(cross(ac, ad), dot(ab, ab)), mul(cross(ad, ab), dot(ac, ac))), mul(cross(ab, ac), dot(ad, ad)));
  const Point3 off = mul(t, 1 / det);
  r2 = dot(off, off);
  return add(a, off);
}

/// The orthosphere (paper, section 3) of four weighted points p[i] with
/// weights w[i] (squared radii): its center z and z2 = Z^2, the squared
/// orthoradius (negative when the weights are large), such that
/// |z - p_i|^2 - w_i = z2 for every i. Solves 2 (p_i - p_0) . z = |p_i|^2 - w_i
/// - |p_0|^2 + w_0 (i = 1..3) by Gauss-Jordan elimination with partial
/// pivoting; false when a pivot is 0 (the points are coplanar).
inline bool orthosphere(const Point3 (&p)[4], const double (&w)[4], Point3& z, double& z2) {
  const Point3& p0 = p[0];
  double m[3][4];
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) m[r][k] = 2 * (p[r + 1][k] - p0[k]);
    m[r][3] = dot(p[r + 1], p[r + 1]) - w[r + 1] - dot(p0, p0) + w[0];
  }
  for (int col = 0; col < 3; ++col) {
    int piv = col;
    for (int r = col + 1; r < 3; ++r)
      if (std::fabs(m[r][col]) > std::fabs(m[piv][col])) piv = r;
    if (m[piv][col] == 0) return false;
    if (piv != col)
      for (int k = 0; k < 4; ++k) std::swap(m[col][k], m[piv][k]);
    for (int r = 0; r < 3; ++r)
      if (r != col) {
        const double f = m[r][col] / m[col][col];
        for (int k = col; k < 4; ++k) m[r][k] -= f * m[col][k];
      }
  }
  z = {{m[0][3] / m[0][0], m[1][3] / m[1][1], m[2][3] / m[2][2]}};
  z2 = dist2(p0, z) - w[0];
  return true;
}

/// Newell's normal of the closed polygon vertices[loop[0]], vertices[loop[1]],
/// ...: twice its vector area (robust for non-convex loops), pointing to the
/// side from which the loop turns counter-clockwise; not normalised. With
/// `scale` (a power of two, so exact: validation scales against overflow and
/// underflow) it is the normal of the polygon scaled by it; scale 1 changes no
/// bit.
inline Point3 newell_normal(const std::vector<Point3>& vertices, const std::vector<int>& loop, double scale = 1) {
  const double s = scale;
  Point3 nw{{0, 0, 0}};
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const Point3& a = vertices[loop[i]];
    const Point3& b = vertices[loop[(i + 1) % loop.size()]];
    nw[0] += (a[1] * s - b[1] * s) * (a[2] * s + b[2] * s);
    nw[1] += (a[2] * s - b[2] * s) * (a[0] * s + b[0] * s);
    nw[2] += (a[0] * s - b[0] * s) * (a[1] * s + b[1] * s);
  }
  return nw;
}

/// Twice the vector area of the closed polygon vertices[loop[0]], ...,
/// summed as the fan of cross products (p_m - p_0) x (p_{m+1} - p_0) about
/// its first vertex: the same vector as newell_normal up to rounding, but
/// rounded on differences from p_0 (so independent of where the polygon
/// lies); not normalised.
inline Point3 fan_area_vector(const std::vector<Point3>& vertices, const std::vector<int>& loop) {
  Point3 n{{0, 0, 0}};
  if (loop.empty()) return n;
  const Point3& o = vertices[loop[0]];
  for (std::size_t m = 1; m + 1 < loop.size(); ++m) {
    const Point3 c = cross(sub(vertices[loop[m]], o), sub(vertices[loop[m + 1]], o));
    for (int q = 0; q < 3; ++q) n[q] += c[q];
  }
  return n;
}

}  // namespace wqmesh::geometry
