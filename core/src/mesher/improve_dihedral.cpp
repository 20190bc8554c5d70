// wqmesh: the polish's smoothing on the smallest dihedral angle (beyond the
// paper and beyond Stellar, whose smoothing raises the worst min-sine): a
// vertex moves to lower the largest cosine of its star's dihedral angles.
// See improve.h, Improver::ascend_dihedral, for the contract.
//
// Why (issue 14, slit.off): the polish's rounds work on the tets of the
// smallest dihedral angles, but the min-sine ascent (ascend()) raises the
// smallest sine, which a dihedral angle near 180 degrees can hold: a step that
// raises a star's min-sine may leave its smallest angle where it was, and the
// polish then needs many small steps.
//
// The gradients: the dihedral angle at edge ij of tet ijkl is the angle
// between u = e x (p_k - p_i) and w = e x (p_l - p_i), e = p_j - p_i
// (largest_cosine()); with c = u.w / (|u| |w|), A = (w/|w| - c u/|u|) / |u|
// and B = (u/|u| - c w/|w|) / |w|, dc = du.A + dw.B, so grad_k c = A x e,
// grad_l c = B x e, grad_j c = (p_k - p_i) x A + (p_l - p_i) x B and grad_i c
// = -(the three others) (c does not change when the tet moves as a whole).
// SPDX-License-Identifier: GPL-3.0-or-later
#include <algorithm>
#include <cmath>

#include "geometry.h"
#include "mesher/improve.h"

namespace wqmesh::mesher {

namespace {

using geometry::add;
using geometry::cross;
using geometry::dot;
using geometry::mul;
using geometry::sub;

/// The cosine c of the dihedral angle of tet p at edge ij (ijkl one row of
/// kEdgeAndOthers) and, when c is at least `low`, its gradient g over the
/// point p[s]; false when a face at the edge is degenerate or c is below
/// `low` (g then not computed: the descent needs only the gradients of the
/// nearly largest cosines). c is largest_cosine()'s value for the edge, bit
/// for bit.
bool cosine_and_gradient(const Point3* const p[4], const int ijkl[4], int s, double low, double& c, Point3& g) {
  const Point3 &pi = *p[ijkl[0]], e = sub(*p[ijkl[1]], pi), a = sub(*p[ijkl[2]], pi), b = sub(*p[ijkl[3]], pi);
  const Point3 u = cross(e, a), w = cross(e, b);
  const double uu = dot(u, u), ww = dot(w, w);
  if (!(uu > 0 && ww > 0)) return false;
  c = dot(u, w) / std::sqrt(uu * ww);
  if (c < low) return false;
  const double nu = std::sqrt(uu), nw = std::sqrt(ww);
  const Point3 uh = mul(u, 1 / nu), wh = mul(w, 1 / nw);
  const Point3 A = mul(sub(wh, mul(uh, c)), 1 / nu), B = mul(sub(uh, mul(wh, c)), 1 / nw);
  const Point3 gk = cross(A, e), gl = cross(B, e), gj = add(cross(a, A), cross(b, B));
  if (s == ijkl[2])
    g = gk;
  else if (s == ijkl[3])
    g = gl;
  else if (s == ijkl[1])
    g = gj;
  else
    g = mul(add(add(gj, gk), gl), -1);
  return true;
}

/// largest_at()'s prefilter margin (relative, in cosine).
constexpr double kSureMargin = 1e-9;

/// The slot of v in T (v is one of its vertices).
int slot_of(const std::array<int, 4>& T, int v) { return T[0] == v ? 0 : T[1] == v ? 1 : T[2] == v ? 2 : 3; }

/// The point of least norm of the convex hull of the m-vectors gs[0 .. n-1]
/// (Gilbert's iteration; m <= 3, the unused coordinates 0).
Point3 least_norm(const std::vector<Point3>& gs) {
  Point3 x = gs[0];
  for (int it = 0; it < 64; ++it) {
    std::size_t best = 0;
    double low = HUGE_VAL;
    for (std::size_t k = 0; k < gs.size(); ++k)
      if (dot(x, gs[k]) < low) low = dot(x, gs[k]), best = k;
    const double xx = dot(x, x);
    if (xx - low <= 1e-12 * xx) break;  // x is the nearest point (to rounding)
    const Point3 diff = sub(x, gs[best]);
    const double dd = dot(diff, diff);
    if (!(dd > 0)) break;
    const double lambda = std::min(1.0, std::max(0.0, dot(x, diff) / dd));
    x = sub(x, mul(diff, lambda));
  }
  return x;
}

}  // namespace

bool Improver::ascend_dihedral(int v, const std::vector<Tet>& tets, double lmin, const std::function<bool()>& valid,
                               int axes) {
  if (!(lmin > 0) || tets.empty()) return false;
  // The movable coordinates: the unit axes of `axes`, and the unit in-plane
  // direction (kPlaneSlide), which has a 0 at each axis a vertex with it may
  // use (improve_boundary.cpp), so the basis is orthonormal.
  Point3 basis[4];
  int m = 0, plane = -1;
  for (int c = 0; c < 3; ++c)
    if (axes >> c & 1) {
      basis[m] = Point3{{0, 0, 0}};
      basis[m++][c] = 1;
    }
  if (axes & kPlaneSlide) {
    const Point3 d = plane_direction(v);
    const double dn = std::sqrt(dot(d, d));
    if (dn > 0) plane = m, basis[m++] = mul(d, 1 / dn);
  }
  if (m == 0 || m > 3) return false;
  // The largest cosine of `tets` with v at x if it is below `bound` and
  // every tet's min-sine is at least polish_sine_floor_; else some value at
  // least `bound`.
  // The tet that failed the last call is tried first (most points of the
  // line searches fail, and mostly at the same tet): the answer does not
  // depend on the order (a maximum, or a failure), as in smooth()'s valid().
  std::size_t hard = 0;
  // Every |cosine| of a tet below sure_cos = cos(asin(floor)) (1 - 1e-9)
  // puts each sine, sqrt(1 - cos^2), above the floor by a relative margin of
  // at least about 1e-9 cot^2(floor) (above 1e-10 for any tet's min-sine),
  // far above the roundings of both measures, so min_sine() is computed only
  // for the other tets: the same answer.
  const double sure_cos = std::sqrt(std::max(0.0, 1 - polish_sine_floor_ * polish_sine_floor_)) * (1 - kSureMargin);
  auto largest_at = [&](const Point3& x, double bound) {
    const Point3 keep = P_[v];
    P_[v] = x;
    double c = -1;
    for (std::size_t n = 0; n < tets.size(); ++n) {
      const std::size_t i = n == 0 ? hard : n <= hard ? n - 1 : n;
      const Tet& T = tets[i];
      double largest_abs;
      c = std::max(c, largest_cosine_within(T, bound, largest_abs));
      if (!(c < bound) ||
          (!(largest_abs < sure_cos) && !(min_sine(P_[T[0]], P_[T[1]], P_[T[2]], P_[T[3]]) >= polish_sine_floor_))) {
        c = std::max(c, bound);
        hard = i;
        break;
      }
    }
    P_[v] = keep;
    return c;
  };
  double current = largest_at(P_[v], HUGE_VAL);
  if (!(current < 1)) return false;
  bool moved = false;
  std::vector<Point3>& gs = dihedral_gradients_;
  // One descent step with the cosines within `margin` radians of the
  // smallest angle (to first order) counted as nearly the largest; false
  // when it found no point.
  const auto descend = [&](double margin) {
    const double sine = std::sqrt(std::max(0.0, 1 - current * current));
    gs.clear();
    double gmax = 0;  // the largest squared norm of those gradients
    const double low = current - margin * sine;
    for (const Tet& T : tets) {
      const Point3* p[4] = {&P_[T[0]], &P_[T[1]], &P_[T[2]], &P_[T[3]]};
      const int s = slot_of(T, v);
      for (const auto& ijkl : kEdgeAndOthers) {
        double c;
        Point3 g;
        if (!cosine_and_gradient(p, ijkl, s, low, c, g)) continue;
        Point3 q{{0, 0, 0}};
        for (int k = 0; k < m; ++k) q[k] = dot(g, basis[k]);
        gmax = std::max(gmax, dot(q, q));
        gs.push_back(q);
      }
    }
    if (gs.empty()) return false;
    const Point3 x = least_norm(gs);
    const double xn = std::sqrt(dot(x, x));
    if (!(xn > 1e-9 * std::sqrt(gmax))) return false;  // stationary for this margin
    Point3 dir{{0, 0, 0}};                             // in space, unit
    for (int k = 0; k < m; ++k)
      if (k != plane) dir = add(dir, mul(basis[k], -x[k] / xn));
    for (double alpha = 0.2 * lmin; alpha > 1e-4 * lmin; alpha *= 0.5) {
      Point3 y = add(P_[v], mul(dir, alpha));
      if (plane >= 0 && x[plane] != 0) {
        // The in-plane part: snapped so that v stays on its facets exactly
        // (the point before snapping first: the exact check is the costly
        // part).
        const double s = -x[plane] / xn * alpha;
        if (!(largest_at(add(y, mul(basis[plane], s)), current) < current - kPolishTieCos)) continue;
        Point3 snapped;
        if (!snap_in_plane(v, y, s, snapped)) continue;
        y = snapped;
      }
      if (y == P_[v]) continue;
      const double c = largest_at(y, current);
      if (!(c < current - kPolishTieCos) || !move_if_valid(v, y, valid)) continue;
      current = c;
      return true;
    }
    return false;
  };
  // Where the margin's angles pull against each other (the origin in their
  // gradients' hull, or no step found), a narrower margin, down to
  // kDihedralActive / 100: near the optimum many angles are within the
  // margin of the smallest.
  for (int step = 0; step < kDihedralSteps; ++step) {
    bool better = false;
    for (double margin = kDihedralActive; !better && margin >= kDihedralActive * 0.01 * (1 - 1e-9); margin *= 0.1)
      better = descend(margin);
    if (!better) break;
    moved = true;
  }
  return moved;
}

}  // namespace wqmesh::mesher
