// SPDX-License-Identifier: GPL-3.0-or-later
// wqmesh: exact geometric checks for the PLC builder (see validation.h).
#include "validation.h"

#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cgal_types.h"

namespace wqmesh::validation {
namespace {

using cgal::K;
using P2 = K::Point_2;

std::string coords(const Point3& p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.17g, %.17g, %.17g)", p[0], p[1], p[2]);
  return buf;
}

/// Exact orientation of the projected points: > 0 for a left turn.
int orient2(const P2& a, const P2& b, const P2& c) {
  return static_cast<int>(CGAL::orientation(a, b, c));
}

}  // namespace

bool triangulate_polygon(const std::vector<Point3>& pts, const std::vector<int>& poly,
                         std::vector<std::array<int, 3>>& out) {
  const int n = static_cast<int>(poly.size());
  if (n < 3) return false;
  // Newell normal (rounded: it only chooses the projection and its sense).
  // Scaled by a power of two (exact) against overflow and underflow.
  double big = 0;
  for (int v : poly)
    for (double x : pts[v]) big = std::max(big, std::fabs(x));
  const double s = big > 0 ? std::ldexp(1.0, -std::ilogb(big)) : 1.0;
  double nx = 0, ny = 0, nz = 0;
  for (int i = 0; i < n; ++i) {
    const Point3& p = pts[poly[i]];
    const Point3& q = pts[poly[(i + 1) % n]];
    nx += (p[1] * s - q[1] * s) * (p[2] * s + q[2] * s);
    ny += (p[2] * s - q[2] * s) * (p[0] * s + q[0] * s);
    nz += (p[0] * s - q[0] * s) * (p[1] * s + q[1] * s);
  }
  int axis = 2;
  if (std::fabs(nx) >= std::fabs(ny) && std::fabs(nx) >= std::fabs(nz)) axis = 0;
  else if (std::fabs(ny) >= std::fabs(nz)) axis = 1;
  const double along = axis == 0 ? nx : axis == 1 ? ny : nz;
  // Drop `axis`; the two kept axes in cyclic order make the projection
  // counter-clockwise when the normal points along +axis, so mirror otherwise.
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  const bool mirror = !(along > 0);
  std::vector<P2> q(n);
  for (int i = 0; i < n; ++i) {
    const Point3& p = pts[poly[i]];
    q[i] = mirror ? P2(p[v], p[u]) : P2(p[u], p[v]);
  }
  std::vector<int> prev(n), next(n);
  for (int i = 0; i < n; ++i) {
    prev[i] = (i + n - 1) % n;
    next[i] = (i + 1) % n;
  }
  std::vector<char> removed(n, 0);
  auto convex = [&](int i) { return orient2(q[prev[i]], q[i], q[next[i]]) > 0; };
  // Only vertices that are not strictly convex can lie in an ear candidate.
  std::vector<int> reflex;
  std::vector<char> is_reflex(n, 0);
  for (int i = 0; i < n; ++i)
    if (!convex(i)) {
      reflex.push_back(i);
      is_reflex[i] = 1;
    }
  // Bounded work: a polygon that needs more orientation tests than this is
  // rejected rather than left to run for minutes.
  long long budget = 60'000'000;
  auto is_ear = [&](int i) {
    budget -= 1 + static_cast<long long>(reflex.size());
    if (budget < 0)
      throw InputError(InputErrorKind::too_large,
                       "a polygon of " + std::to_string(n) +
                           " vertices is too complex to triangulate");
    if (!convex(i)) return false;
    const int a = prev[i], c = next[i];
    for (int r : reflex) {
      if (removed[r] || !is_reflex[r] || r == a || r == c) continue;
      // Inside or on the closed triangle (a, i, c), counter-clockwise.
      if (orient2(q[a], q[i], q[r]) >= 0 && orient2(q[i], q[c], q[r]) >= 0 &&
          orient2(q[c], q[a], q[r]) >= 0)
        return false;
    }
    return true;
  };
  auto compact = [&] {
    std::size_t live = 0;
    for (int r : reflex)
      if (!removed[r] && is_reflex[r]) reflex[live++] = r;
    reflex.resize(live);
  };
  int remaining = n;
  int cur = 0;
  int since_last_ear = 0;
  while (remaining > 3) {
    if (is_ear(cur)) {
      const int a = prev[cur], c = next[cur];
      out.push_back({poly[a], poly[cur], poly[c]});
      removed[cur] = 1;
      next[a] = c;
      prev[c] = a;
      --remaining;
      for (int w : {a, c}) {
        const bool r = !convex(w);
        if (r && !is_reflex[w]) reflex.push_back(w);  // only if not simple
        is_reflex[w] = r;
      }
      since_last_ear = 0;
      if (remaining % 64 == 0) compact();
      // Skip a vertex: on a convex run this clips every other vertex per
      // round, so triangles grow geometrically instead of forming one fan of
      // long slivers (which would make many bounding boxes overlap).
      cur = next[c];
    } else {
      cur = next[cur];
      if (++since_last_ear > remaining) return false;
    }
  }
  if (orient2(q[prev[cur]], q[cur], q[next[cur]]) <= 0) return false;
  out.push_back({poly[prev[cur]], poly[cur], poly[next[cur]]});
  return true;
}

namespace {

using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, int>;

struct PairTester {
  const std::vector<Point3>& pts;
  const std::vector<std::array<int, 3>>& tris;
  const std::function<std::string(int)>& describe;

  cgal::Point P(int i) const { return cgal::to_cgal(pts[i]); }
  cgal::Triangle T(int t) const {
    return cgal::Triangle(P(tris[t][0]), P(tris[t][1]), P(tris[t][2]));
  }

  [[noreturn]] void report(int s, int t, const std::string& how) const {
    throw InputError(InputErrorKind::self_intersection,
                     describe(s) + " and " + describe(t) + " " + how);
  }

  /// Closed wedge at apex u spanned by rays ua, ub (coplanar, angle < 180)
  /// contains the ray up (p coplanar, p != u).
  bool ray_in_wedge(int u, int a, int b, int p) const {
    const auto s1 = CGAL::coplanar_orientation(P(u), P(a), P(b), P(p));
    const auto s2 = CGAL::coplanar_orientation(P(u), P(b), P(a), P(p));
    return s1 != CGAL::NEGATIVE && s2 != CGAL::NEGATIVE;
  }

  void test(int s, int t) const {
    const auto& A = tris[s];
    const auto& B = tris[t];
    int shared = 0, ia = -1, ib = -1;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (A[i] == B[j]) {
          ++shared;
          ia = i;
          ib = j;
        }
    if (shared == 0) {
      if (CGAL::do_intersect(T(s), T(t))) report(s, t, "intersect");
      return;
    }
    if (shared == 3) report(s, t, "are the same triangle");
    if (shared == 2) {
      // Common edge uv; they overlap iff coplanar with the opposite vertices
      // on the same side of uv (a triangle folded flat onto its neighbour).
      int wa = -1, wb = -1;
      for (int i = 0; i < 3; ++i) {
        if (A[i] != B[0] && A[i] != B[1] && A[i] != B[2]) wa = A[i];
        if (B[i] != A[0] && B[i] != A[1] && B[i] != A[2]) wb = B[i];
      }
      int u = -1, v = -1;
      for (int i = 0; i < 3; ++i)
        if (A[i] != wa) (u < 0 ? u : v) = A[i];
      if (CGAL::orientation(P(u), P(v), P(wa), P(wb)) == CGAL::COPLANAR &&
          CGAL::coplanar_orientation(P(u), P(v), P(wa), P(wb)) == CGAL::POSITIVE)
        report(s, t,
               "overlap: they are coplanar and folded onto each other across their common edge " +
                   coords(pts[u]) + " - " + coords(pts[v]));
      return;
    }
    // One common vertex u = A[ia] = B[ib]; the far edges are ab and cd.
    const int u = A[ia];
    const int a = A[(ia + 1) % 3], b = A[(ia + 2) % 3];
    const int c = B[(ib + 1) % 3], d = B[(ib + 2) % 3];
    auto where = [&] { return "meet away from their common vertex " + coords(pts[u]); };
    const bool coplanar = CGAL::orientation(P(u), P(a), P(b), P(c)) == CGAL::COPLANAR &&
                          CGAL::orientation(P(u), P(a), P(b), P(d)) == CGAL::COPLANAR;
    if (coplanar) {
      // Two convex wedges at u overlap beyond u iff a bounding ray of one lies
      // in the other.
      if (ray_in_wedge(u, a, b, c) || ray_in_wedge(u, a, b, d) || ray_in_wedge(u, c, d, a) ||
          ray_in_wedge(u, c, d, b))
        report(s, t, where() + " (coplanar overlap)");
      return;
    }
    // Not coplanar: the intersection is a segment from u along the line of the
    // two planes; it goes beyond u iff a far edge meets the other triangle.
    if (CGAL::do_intersect(cgal::Segment(P(a), P(b)), T(t)) ||
        CGAL::do_intersect(cgal::Segment(P(c), P(d)), T(s)))
      report(s, t, where());
  }
};

}  // namespace

void check_self_intersections(const std::vector<Point3>& pts,
                              const std::vector<std::array<int, 3>>& tris,
                              const std::function<std::string(int)>& describe) {
  std::vector<Box> boxes;
  boxes.reserve(tris.size());
  for (std::size_t t = 0; t < tris.size(); ++t) {
    double lo[3], hi[3];
    for (int k = 0; k < 3; ++k) {
      lo[k] = hi[k] = pts[tris[t][0]][k];
      for (int c = 1; c < 3; ++c) {
        lo[k] = std::min(lo[k], pts[tris[t][c]][k]);
        hi[k] = std::max(hi[k], pts[tris[t][c]][k]);
      }
    }
    boxes.emplace_back(lo, hi, static_cast<int>(t));
  }
  PairTester tester{pts, tris, describe};
  // Bounded work: so many overlapping boxes only come from pathological
  // inputs (e.g. huge fans of slivers); reject them rather than run for hours.
  long long budget = 200'000'000;
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& x, const Box& y) {
    if (--budget < 0)
      throw InputError(InputErrorKind::too_large,
                       "too many pairs of faces with overlapping bounding boxes to check for "
                       "self-intersections");
    tester.test(x.info(), y.info());
  });
}

}  // namespace wqmesh::validation
