// SPDX-License-Identifier: GPL-3.0-or-later
// wqmesh: exact geometric checks for the PLC builder (see validation.h).
#include "validation.h"

#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cgal_types.h"
#include "exact.h"
#include "geometry.h"

namespace wqmesh::validation {

std::string coords(const Point3& p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.17g, %.17g, %.17g)", p[0], p[1], p[2]);
  return buf;
}

namespace {

using cgal::K;
using P2 = K::Point_2;

/// v / |v| for a finite v with a component other than 0; divided by its
/// largest component first so that squaring neither overflows nor underflows.
Point3 normalized(Point3 v) {
  const double m = std::max({std::fabs(v[0]), std::fabs(v[1]), std::fabs(v[2])});
  for (double& x : v) x /= m;
  const double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  for (double& x : v) x /= len;
  return v;
}

/// Exact orientation of the projected points: > 0 for a left turn.
int orient2(const P2& a, const P2& b, const P2& c) { return static_cast<int>(CGAL::orientation(a, b, c)); }

}  // namespace

double power_of_two_scale(double big) {
  if (!(big > 0) || !std::isfinite(big)) return 1.0;
  return std::ldexp(1.0, std::min(-std::ilogb(big), 1022));
}

Point3 exact_unit_area_vector(const std::vector<Point3>& pts, const std::vector<std::array<int, 3>>& tris) {
  using MP = CGAL::MP_Float;  // exact for +, - and * on doubles
  std::array<MP, 3> sum{{MP(0), MP(0), MP(0)}};
  for (const auto& t : tris) {
    std::array<MP, 3> u, v;
    for (int i = 0; i < 3; ++i) {
      u[i] = MP(pts[t[1]][i]) - MP(pts[t[0]][i]);
      v[i] = MP(pts[t[2]][i]) - MP(pts[t[0]][i]);
    }
    for (int a = 0; a < 3; ++a) {
      const int b = (a + 1) % 3, c = (a + 2) % 3;
      sum[a] = sum[a] + (u[b] * v[c] - u[c] * v[b]);
    }
  }
  // Each component as m * 2^e (|m| < 1); all are brought to the exponent of
  // the largest one, so that none overflows and only negligible ones vanish.
  std::array<std::pair<double, int>, 3> me;
  bool any = false;
  int top = 0;
  for (int a = 0; a < 3; ++a) {
    me[a] = CGAL::to_double_exp(sum[a]);
    if (me[a].first == 0) continue;
    top = any ? std::max(top, me[a].second) : me[a].second;
    any = true;
  }
  if (!any) return {{0, 0, 0}};
  Point3 r{{0, 0, 0}};
  for (int a = 0; a < 3; ++a)
    if (me[a].first != 0) r[a] = std::ldexp(me[a].first, me[a].second - top);
  return normalized(r);
}

Point3 unit_area_vector(const std::vector<Point3>& pts, const std::vector<std::array<int, 3>>& tris) {
  double big = 0;
  for (const auto& t : tris)
    for (int v : t)
      for (double x : pts[v]) big = std::max(big, std::fabs(x));
  const double s = power_of_two_scale(big);
  // Rounded sum of the cross products on the scaled coordinates, and the sum
  // of the magnitudes of its products, which bounds its rounding error.
  std::array<double, 3> n{{0, 0, 0}};
  double mass = 0;
  for (const auto& t : tris) {
    const Point3 &a = pts[t[0]], &b = pts[t[1]], &c = pts[t[2]];
    double u[3], v[3];
    for (int i = 0; i < 3; ++i) {
      u[i] = b[i] * s - a[i] * s;
      v[i] = c[i] * s - a[i] * s;
    }
    for (int k = 0; k < 3; ++k) {
      const int i = (k + 1) % 3, j = (k + 2) % 3;
      n[k] += u[i] * v[j] - u[j] * v[i];
      mass += std::fabs(u[i] * v[j]) + std::fabs(u[j] * v[i]);
    }
  }
  // Error of each component: a few roundings of every product and of the
  // running sum (relative to `mass`), plus what underflow loses (absolute;
  // scaled coordinates are below 2, so their differences below 4).
  const double count = static_cast<double>(tris.size());
  const double error = 2 * ((count + 8) * 0x1p-52 * mass + 64 * (count + 1) * 0x1p-1074);
  const double m = std::max({std::fabs(n[0]), std::fabs(n[1]), std::fabs(n[2])});
  if (!(std::isfinite(m) && std::isfinite(mass) && m > 0x1p24 * error))
    return exact_unit_area_vector(pts, tris);  // too close to call: exactly
  if (m >= 1e-150) {
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    return {{n[0] / len, n[1] / len, n[2] / len}};
  }
  return normalized(n);
}

bool triangulate_polygon(const std::vector<Point3>& pts, const std::vector<int>& poly,
                         std::vector<std::array<int, 3>>& out) {
  const int n = static_cast<int>(poly.size());
  if (n < 3) return false;
  // Newell normal, rounded, to rank the axes (largest component first); it
  // is scaled by a power of two (exact) against overflow and underflow.
  double big = 0;
  for (int v : poly)
    for (double x : pts[v]) big = std::max(big, std::fabs(x));
  const Point3 nrm = geometry::newell_normal(pts, poly, power_of_two_scale(big));
  std::array<int, 3> rank{{0, 1, 2}};
  auto size = [&](int a) { return std::isfinite(nrm[a]) ? std::fabs(nrm[a]) : 0.0; };
  std::stable_sort(rank.begin(), rank.end(), [&](int a, int b) { return size(a) > size(b); });
  // The projection drops the first axis, in that order, along which the exact
  // Newell normal is not zero (rounding may cancel it or give it the wrong
  // sign): the projection of a planar polygon is then an affine image of it,
  // simple exactly when the polygon is, and its sense is the sign of that
  // exact component.
  int axis = -1, along = 0;
  for (int a : rank) {
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    along = exact::sign([&](auto z) {
      using NT = decltype(z);
      NT sum = z;
      for (int i = 0; i < n; ++i) {
        const Point3& p = pts[poly[i]];
        const Point3& q = pts[poly[(i + 1) % n]];
        sum = sum + (NT(p[b]) - NT(q[b])) * (NT(p[c]) + NT(q[c]));
      }
      return sum;
    });
    if (along != 0) {
      axis = a;
      break;
    }
  }
  if (axis < 0) return false;  // a non-planar polygon with no area vector
  // Drop `axis`; the two kept axes in cyclic order make the projection
  // counter-clockwise when the normal points along +axis, so mirror otherwise.
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  const bool mirror = along < 0;
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
  // The reflex vertices in a uniform grid over the projection (beyond the
  // paper, for large polygons): an ear candidate is tested against the ones
  // in the cells its bounding box meets, not against all. Cells come from a
  // monotone rounded map of the coordinates, so every point inside the box
  // is in a visited cell; the test itself stays exact. Dead entries (clipped
  // or no longer reflex) are skipped, and the grid is rebuilt, about as many
  // cells as live reflex vertices, whenever their number has halved.
  double lo[2] = {0, 0}, cell_scale[2] = {0, 0};
  int cells = 1;
  std::vector<std::vector<int>> grid(1);
  std::size_t grid_built_for = 0;
  auto cell_of = [&](const P2& p, int k) {
    const double x = ((k == 0 ? p.x() : p.y()) - lo[k]) * cell_scale[k];
    return x >= cells ? cells - 1 : x >= 0 ? static_cast<int>(x) : 0;  // (a NaN: column 0)
  };
  auto insert = [&](int r) { grid[cell_of(q[r], 0) * cells + cell_of(q[r], 1)].push_back(r); };
  auto build_grid = [&] {
    cells = 1;
    while (static_cast<std::size_t>(cells) * cells < reflex.size() && cells < 1024) cells *= 2;
    double hi[2] = {q[0].x(), q[0].y()};
    lo[0] = hi[0], lo[1] = hi[1];
    for (const P2& p : q) {
      lo[0] = std::min(lo[0], p.x()), hi[0] = std::max(hi[0], p.x());
      lo[1] = std::min(lo[1], p.y()), hi[1] = std::max(hi[1], p.y());
    }
    for (int k = 0; k < 2; ++k) {
      const double extent = hi[k] - lo[k];
      // An extent that is 0 or overflows: one column (sound, only slower).
      cell_scale[k] = extent > 0 && std::isfinite(extent) && std::isfinite(cells / extent) ? cells / extent : 0;
    }
    grid.assign(static_cast<std::size_t>(cells) * cells, {});
    for (int r : reflex) insert(r);
    grid_built_for = reflex.size();
  };
  build_grid();
  // Bounded work: a polygon that needs more ear-test steps than this is
  // rejected rather than left to run for minutes (README, Limits).
  long long budget = kMaxEarTests;
  auto is_ear = [&](int i) {
    --budget;
    if (budget < 0)
      throw InputError(InputErrorKind::too_large, "a polygon of " + std::to_string(n) + " vertices (" +
                                                      std::to_string(reflex.size()) +
                                                      " of them reflex) is too complex to triangulate: beyond the ear "
                                                      "clipping's budget of " +
                                                      std::to_string(kMaxEarTests) + " ear-test steps per polygon");
    if (!convex(i)) return false;
    if (reflex.empty()) return true;
    const int a = prev[i], c = next[i];
    int from[2], to[2];
    for (int k = 0; k < 2; ++k) {
      const int ca = cell_of(q[a], k), ci = cell_of(q[i], k), cc = cell_of(q[c], k);
      from[k] = std::min({ca, ci, cc}), to[k] = std::max({ca, ci, cc});
    }
    for (int x = from[0]; x <= to[0]; ++x)
      for (int y = from[1]; y <= to[1]; ++y) {
        const auto& here = grid[static_cast<std::size_t>(x) * cells + y];
        budget -= 1 + static_cast<long long>(here.size());
        for (int r : here) {
          if (removed[r] || !is_reflex[r] || r == a || r == c) continue;
          // Inside or on the closed triangle (a, i, c), counter-clockwise.
          if (orient2(q[a], q[i], q[r]) >= 0 && orient2(q[i], q[c], q[r]) >= 0 && orient2(q[c], q[a], q[r]) >= 0)
            return false;
        }
      }
    return true;
  };
  auto compact = [&] {
    std::size_t live = 0;
    for (int r : reflex)
      if (!removed[r] && is_reflex[r]) reflex[live++] = r;
    reflex.resize(live);
    if (2 * reflex.size() < grid_built_for) build_grid();
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
        if (r && !is_reflex[w]) reflex.push_back(w), insert(w);  // only if not simple
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
  cgal::Triangle T(int t) const { return cgal::Triangle(P(tris[t][0]), P(tris[t][1]), P(tris[t][2])); }

  [[noreturn]] void report(int s, int t, const std::string& how) const {
    throw InputError(InputErrorKind::self_intersection, describe(s) + " and " + describe(t) + " " + how);
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
               "overlap: they are coplanar and folded onto each other across their common edge " + coords(pts[u]) +
                   " - " + coords(pts[v]));
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
      if (ray_in_wedge(u, a, b, c) || ray_in_wedge(u, a, b, d) || ray_in_wedge(u, c, d, a) || ray_in_wedge(u, c, d, b))
        report(s, t, where() + " (coplanar overlap)");
      return;
    }
    // Not coplanar: the intersection is a segment from u along the line of the
    // two planes; it goes beyond u iff a far edge meets the other triangle.
    if (CGAL::do_intersect(cgal::Segment(P(a), P(b)), T(t)) || CGAL::do_intersect(cgal::Segment(P(c), P(d)), T(s)))
      report(s, t, where());
  }
};

}  // namespace

void check_self_intersections(const std::vector<Point3>& pts, const std::vector<std::array<int, 3>>& tris,
                              const std::function<std::string(int)>& describe) {
  // Bounded work: so many overlapping boxes only come from pathological
  // inputs (huge fans of slivers, a vertex of very high degree); reject them
  // rather than run for hours (README, Limits).
  const long long kBudget = kMaxOverlappingPairs;
  const std::string budget_name = "the self-intersection test's budget of " + std::to_string(kBudget) +
                                  " pairs of triangles with overlapping bounding boxes";
  // Triangles at a common vertex always have overlapping boxes: count those
  // pairs first, so that a vertex of huge degree is refused at once.
  {
    std::vector<long long> degree(pts.size(), 0);
    for (const auto& t : tris)
      for (int v : t) ++degree[v];
    long long pairs = 0, worst = 0;
    std::size_t worst_vertex = 0;
    for (std::size_t v = 0; v < degree.size(); ++v) {
      pairs += degree[v] * (degree[v] - 1) / 2;
      if (degree[v] > worst) worst = degree[v], worst_vertex = v;
    }
    if (pairs > kBudget)
      throw InputError(InputErrorKind::too_large, "the triangles at common vertices alone make " +
                                                      std::to_string(pairs) + " pairs (the vertex " +
                                                      coords(pts[worst_vertex]) + " is in " + std::to_string(worst) +
                                                      " triangles), beyond " + budget_name);
  }
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
  long long budget = kBudget;
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& x, const Box& y) {
    if (--budget < 0)
      throw InputError(InputErrorKind::too_large,
                       "more pairs of triangles to check for "
                       "self-intersections than " +
                           budget_name);
    tester.test(x.info(), y.info());
  });
}

}  // namespace wqmesh::validation
