// SPDX-License-Identifier: GPL-3.0-or-later
// wqmesh: the input analysis of the paper, section 2: edge-edge, edge-facet
// and dihedral angles, sharp edges and vertices, phi_m, the boxes, and (via
// local_feature_size.cpp) f(u) at the sharp vertices (section 4.1). The JSON
// form is written by analysis_json.cpp.
//
// Every yes/no decision (acute or not, convex or reflex, coplanar or not) is
// the sign of a polynomial in the input doubles, evaluated by exact::sign, so
// it is the same on every platform. Angle values are computed in double
// precision with atan2 (accurate also near 0 and 180 degrees). phi_m is the
// smallest of the input's edge-edge, edge-facet, internal and external
// dihedral angles (the right angles of the box B are not counted).
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <utility>

#include "exact.h"
#include "geometry.h"
#include "plc_index.h"
#include "scaling.h"
#include "wqmesh/analysis.h"
#include "wqmesh/error.h"

namespace wqmesh {
namespace {

using geometry::kPi;
/// The analysis' budget of edge-edge plus edge-facet angles (README, Limits):
/// 4e6 entries make a JSON report of about 330 MB, under what a JavaScript
/// string holds (2^29 characters in V8).
constexpr unsigned long long kMaxAngles = 4'000'000;

// ---- double-precision vectors ------------------------------------------------
using V = Point3;
using geometry::cross;
using geometry::dot;
using geometry::norm;
using geometry::sub;
/// The angle between two vectors, in degrees, in [0, 180].
double angle_degrees(const V& a, const V& b) { return std::atan2(norm(cross(a, b)), dot(a, b)) * (180 / kPi); }

// ---- exact polynomials over a number type NT ----------------------------------
template <class NT>
struct V3 {
  NT x, y, z;
};
template <class NT>
V3<NT> lift(const Point3& p) {
  return {NT(p[0]), NT(p[1]), NT(p[2])};
}
template <class NT>
V3<NT> operator-(const V3<NT>& a, const V3<NT>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class NT>
V3<NT> operator-(const V3<NT>& a) {
  return {NT(0) - a.x, NT(0) - a.y, NT(0) - a.z};
}
template <class NT>
NT dotn(const V3<NT>& a, const V3<NT>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class NT>
V3<NT> crossn(const V3<NT>& a, const V3<NT>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

/// A facet's exact outward normal: (p[j] - p[i]) x (p[k] - p[i]) for three
/// vertices i, j, k of the facet, chosen not collinear and ordered so that the
/// cross product points outwards (the side from which the outer loop is
/// counter-clockwise). `unit` is the same direction in double precision,
/// for angle values: the index's fan area vector (PlcIndex::Frame::area)
/// normalised.
struct ExactNormal {
  int i = -1, j = -1, k = -1;
  V unit{{0, 0, 0}};  ///< geometry::unit of the index's area vector
  bool valid() const { return i >= 0; }
};

class Analyzer {
  /// A facet at a vertex: the facet, the loop and position of the vertex in
  /// it, and whether that is a strictly convex corner of a convex facet.
  struct Corner {
    int f, loop, r;
    bool fast;
  };

 public:
  Analyzer(const PLC& plc, const PlcIndex& index, const AnalysisOptions& options)
      : plc_(plc), index_(index), options_(options) {}

  Analysis run() {
    normals_.resize(plc_.facets.size());
    for (int f = 0; f < static_cast<int>(plc_.facets.size()); ++f) {
      normals_[f] = exact_triple(f);
      normals_[f].unit = geometry::unit(index_.frames[f].area);
    }
    // The index's corners (the first one of each facet at each vertex), each
    // marked fast when it is a strictly convex corner of a convex facet: what
    // edge_facet_angles needs at each vertex.
    std::vector<std::vector<int>> turns(plc_.facets.size());
    std::vector<char> convex(plc_.facets.size());
    for (int f = 0; f < static_cast<int>(plc_.facets.size()); ++f) convex[f] = is_convex(f, turns[f]);
    const int nv = static_cast<int>(plc_.vertices.size());
    corners_.assign(nv, {});
    for (int u = 0; u < nv; ++u)
      for (const PlcIndex::Corner& c : index_.vertex_corners[u])
        corners_[u].push_back({c.facet, c.loop, c.position, convex[c.facet] && turns[c.facet][c.position] > 0});
    check_angle_budget();
    find_traversals();

    Analysis a;
    a.box_margin = options_.box_margin;
    boxes(a);
    edge_edge_angles(a);
    edge_facet_angles(a);
    dihedral_angles(a);
    sharp_elements(a);
    a.lfs = local_feature_sizes(plc_, index_, a.sharp_vertices, a.bounding_box);
    return a;
  }

 private:
  const Point3& P(int v) const { return plc_.vertices[v]; }

  // ---- facet normals ------------------------------------------------------------
  ExactNormal exact_triple(int f) const {
    ExactNormal fr;
    const PlcFacet& facet = plc_.facets[f];
    if (facet.loops.empty() || facet.loops[0].size() < 3) return fr;
    const auto& outer = facet.loops[0];
    const V& o = P(outer[0]);

    // The triple: outer[0], the loop vertex farthest from it, and the loop
    // vertex farthest from the line through those two (well conditioned).
    const int i = outer[0];
    int j = -1, k = -1;
    double best = -1;
    for (int v : outer) {
      const double d = dot(sub(P(v), o), sub(P(v), o));
      if (d > best) best = d, j = v;
    }
    best = -1;
    for (int v : outer) {
      const double d = norm(cross(sub(P(j), o), sub(P(v), o)));
      if (d > best) best = d, k = v;
    }
    auto collinear = [&](int a, int b, int c) {
      for (int q = 0; q < 3; ++q) {
        const int s = exact::sign([&](auto z) {
          using NT = decltype(z);
          const auto n = crossn(lift<NT>(P(b)) - lift<NT>(P(a)), lift<NT>(P(c)) - lift<NT>(P(a)));
          return q == 0 ? n.x : q == 1 ? n.y : n.z;
        });
        if (s != 0) return false;
      }
      return true;
    };
    if (j == i || k == i || k == j || collinear(i, j, k)) {
      // Rounding chose badly: search exactly for any non-collinear triple.
      j = k = -1;
      for (std::size_t m = 1; m < outer.size() && k < 0; ++m)
        for (std::size_t r = m + 1; r < outer.size() && k < 0; ++r)
          if (!collinear(i, outer[m], outer[r])) j = outer[m], k = outer[r];
      if (k < 0) return fr;  // degenerate facet (not a valid PLC): no normal
    }
    // Orient (p[j] - p[i]) x (p[k] - p[i]) like the exact Newell normal of
    // the outer loop, sum over its edges of p[m] x p[m+1]; the two are
    // parallel, so the sign of their dot product is the orientation.
    const int s = exact::sign([&](auto z) {
      using NT = decltype(z);
      const auto n = crossn(lift<NT>(P(j)) - lift<NT>(P(i)), lift<NT>(P(k)) - lift<NT>(P(i)));
      V3<NT> w{z, z, z};
      for (std::size_t m = 0; m < outer.size(); ++m) {
        const auto c = crossn(lift<NT>(P(outer[m])), lift<NT>(P(outer[(m + 1) % outer.size()])));
        w = {w.x + c.x, w.y + c.y, w.z + c.z};
      }
      return dotn(n, w);
    });
    if (s == 0) return fr;
    if (s < 0) std::swap(j, k);
    fr.i = i, fr.j = j, fr.k = k;
    return fr;
  }

  template <class NT>
  V3<NT> exact_normal(int f) const {
    const ExactNormal& fr = normals_[f];
    return crossn(lift<NT>(P(fr.j)) - lift<NT>(P(fr.i)), lift<NT>(P(fr.k)) - lift<NT>(P(fr.i)));
  }

  /// Sign of the orientation of point p with respect to the plane of facet f:
  /// positive on the outer side.
  int side_of_facet(int f, const Point3& p) const {
    return exact::sign([&](auto z) {
      using NT = decltype(z);
      return dotn(exact_normal<NT>(f), lift<NT>(p) - lift<NT>(P(normals_[f].i)));
    });
  }

  /// The angle between w and the plane of facet f, in degrees, in [0, 90]
  /// (from the component of w along the index's unit normal and the rest).
  double plane_degrees(const V& w, int f) const {
    const V& n = normals_[f].unit;
    const double wn = dot(w, n);
    return std::atan2(std::fabs(wn), norm(sub(w, geometry::mul(n, wn)))) * (180 / kPi);
  }

  // ---- boxes (section 2) ---------------------------------------------------------
  void boxes(Analysis& a) const {
    if (plc_.vertices.empty()) return;
    a.input_box = vertex_box(plc_);
    a.bounding_box = grown_box(a.input_box, options_.box_margin);
  }

  int other_end(int e, int u) const { return plc_.edges[e].a == u ? plc_.edges[e].b : plc_.edges[e].a; }

  // ---- edge-edge angles ------------------------------------------------------------
  /// Every pair of input edges at a common vertex u, edge1 < edge2, ordered by
  /// vertex then edges. Acute iff (v1 - u).(v2 - u) > 0, exactly.
  void edge_edge_angles(Analysis& a) const {
    for (int u = 0; u < static_cast<int>(plc_.vertices.size()); ++u) {
      const std::vector<int>& es = index_.vertex_edges[u];  // increasing
      for (std::size_t m = 0; m < es.size(); ++m)
        for (std::size_t r = m + 1; r < es.size(); ++r) {
          const int v1 = other_end(es[m], u), v2 = other_end(es[r], u);
          EdgeEdgeAngle ang{u, es[m], es[r], angle_degrees(sub(P(v1), P(u)), sub(P(v2), P(u))),
                            exact::dot_sign(P(u), P(v1), P(v2)) > 0};
          a.edge_edge.push_back(ang);
          a.phi_m_degrees = std::min(a.phi_m_degrees, ang.degrees);
        }
    }
  }

  // ---- edge-facet angles -----------------------------------------------------------
  /// For every edge uv and facet F with u a vertex of one of F's loops, uv not
  /// an edge of F, and v exactly off F's plane: min over p in F, p != u, of the
  /// angle puv. Ordered by vertex u, then edge, then facet.
  void edge_facet_angles(Analysis& a) const {
    for (int u = 0; u < static_cast<int>(plc_.vertices.size()); ++u) {
      const std::vector<int>& es = index_.vertex_edges[u];  // increasing
      for (int e : es) {
        const int v = other_end(e, u);
        for (const Corner& c : corners_[u]) {
          const int f = c.f;
          if (f == plc_.edges[e].facets[0] || f == plc_.edges[e].facets[1]) continue;
          if (!normals_[f].valid() || side_of_facet(f, P(v)) == 0) continue;
          EdgeFacetAngle ang = c.fast ? convex_edge_facet(u, v, f, c.r) : general_edge_facet(u, v, c);
          ang.edge = e;
          a.edge_facet.push_back(ang);
          a.phi_m_degrees = std::min(a.phi_m_degrees, ang.degrees);
        }
      }
    }
  }

  /// A facet with one loop and no reflex corner (straight ones allowed),
  /// decided exactly: at each corner u between a and b of the outer loop,
  /// (u - a) x (b - u) does not point against the exact outward normal. The
  /// loop is simple (a valid PLC), so the facet is then convex. turns[r] is
  /// the sign at corner r (> 0 strictly convex, 0 straight) when true.
  bool is_convex(int f, std::vector<int>& turns) const {
    const PlcFacet& facet = plc_.facets[f];
    if (facet.loops.size() != 1 || !normals_[f].valid()) return false;
    const auto& loop = facet.loops[0];
    const std::size_t m = loop.size();
    turns.assign(m, 0);
    for (std::size_t r = 0; r < m; ++r) {
      const int a = loop[(r + m - 1) % m], u = loop[r], b = loop[(r + 1) % m];
      const int s = exact::sign([&](auto z) {
        using NT = decltype(z);
        return dotn(exact_normal<NT>(f), crossn(lift<NT>(P(u)) - lift<NT>(P(a)), lift<NT>(P(b)) - lift<NT>(P(u))));
      });
      if (s < 0) return false;
      turns[r] = s;
    }
    return true;
  }

  /// The edge-facet angle of uv and the convex facet f, u at position r of
  /// its loop, a strictly convex corner (a straight one takes the general
  /// path: there F fills a half-plane, not the cone of a - u and b - u),
  /// in O(1) instead of O(|F|) (beyond the paper: the same value
  /// and the same exact decision as edge_facet_degrees and edge_facet_acute,
  /// which run over the whole facet). F lies in the cone at u spanned by
  /// a - u and b - u (a, b the loop neighbours of u) and fills it near u, so
  /// the linear (p - u).(v - u) is positive somewhere on F iff it is at a or
  /// b, and the directions from u to F are the directions of that cone
  /// (from b - u counter-clockwise, seen from outside, to a - u; at most 180
  /// degrees wide). The smallest angle between w = v - u and that cone is the
  /// angle between w and F's plane when w's projection on the plane lies in
  /// the cone, else the angle to the nearer of its two bounding rays.
  EdgeFacetAngle convex_edge_facet(int u, int v, int f, int r) const {
    const auto& loop = plc_.facets[f].loops[0];
    const std::size_t m = loop.size();
    const int a = loop[(r + m - 1) % m], b = loop[(r + 1) % m];
    const V w = sub(P(v), P(u));
    const double plane_angle = plane_degrees(w, f);
    const V da = sub(P(a), P(u)), db = sub(P(b), P(u));
    const double ea = angle_degrees(w, da), eb = angle_degrees(w, db);
    const V& n = normals_[f].unit;
    const bool inside = dot(cross(db, w), n) >= 0 && dot(cross(w, da), n) >= 0;
    const double degrees = inside ? std::min({plane_angle, ea, eb}) : std::min(ea, eb);
    const bool acute = exact::dot_sign(P(u), P(a), P(v)) > 0 || exact::dot_sign(P(u), P(b), P(v)) > 0;
    return EdgeFacetAngle{u, -1, f, degrees, acute};
  }

  /// The edge-facet angle of uv and any facet, u at corner c.r of loop c.loop.
  /// O(1) in two cases decided exactly (beyond the paper, same result as the
  /// literal definition): w = v - u perpendicular to F's plane (every
  /// direction in F makes the same angle with w, not acute: (p - u).w = 0),
  /// and w's projection on the plane pointing strictly into F's sector at u
  /// (the interior angle between the loop's sides at u, reflex or not), where
  /// u + t w' lies in F for small t > 0: the angle is the angle between w and
  /// the plane, the smallest possible, and acute. Otherwise the whole facet
  /// is searched (edge_facet_degrees, edge_facet_acute): O(|F|).
  EdgeFacetAngle general_edge_facet(int u, int v, const Corner& c) const {
    const int f = c.f;
    const auto& loop = plc_.facets[f].loops[c.loop];
    const std::size_t m = loop.size();
    const int a = loop[(c.r + m - 1) % m], b = loop[(c.r + 1) % m];
    auto w = [&](auto z) { return lift<decltype(z)>(P(v)) - lift<decltype(z)>(P(u)); };
    bool perpendicular = true;
    for (int q = 0; q < 3 && perpendicular; ++q)
      perpendicular = exact::sign([&](auto z) {
                        using NT = decltype(z);
                        const auto x = crossn(w(z), exact_normal<NT>(f));
                        return q == 0 ? x.x : q == 1 ? x.y : x.z;
                      }) == 0;
    const V wd = sub(P(v), P(u));
    const double plane_angle = plane_degrees(wd, f);
    if (perpendicular) return EdgeFacetAngle{u, -1, f, plane_angle, false};
    auto side = [&](int from, int to, bool w_first) {
      return exact::sign([&](auto z) {
        using NT = decltype(z);
        const auto d = lift<NT>(P(to)) - lift<NT>(P(from));
        return dotn(w_first ? crossn(w(z), d) : crossn(d, w(z)), exact_normal<NT>(f));
      });
    };
    const int s1 = side(u, b, false);  // (b - u) x w . N: w left of the side to b
    const int s2 = side(u, a, true);   // w x (a - u) . N: w right of the side to a
    const int turn = exact::sign([&](auto z) {
      using NT = decltype(z);
      return dotn(exact_normal<NT>(f), crossn(lift<NT>(P(u)) - lift<NT>(P(a)), lift<NT>(P(b)) - lift<NT>(P(u))));
    });
    const bool inside = turn > 0 ? (s1 > 0 && s2 > 0) : turn < 0 ? (s1 > 0 || s2 > 0) : s1 > 0;
    if (inside) return EdgeFacetAngle{u, -1, f, plane_angle, true};
    return EdgeFacetAngle{u, -1, f, edge_facet_degrees(u, v, f), edge_facet_acute(u, v, f)};
  }

  /// The analysis lists every edge-edge pair at a vertex and every edge-facet
  /// pair (section 2), about 1.5 k^2 entries at a vertex of degree k; beyond
  /// kMaxAngles entries (an upper bound counted before any is computed) the
  /// input is refused, as the report could not be held or written.
  void check_angle_budget() const {
    unsigned long long total = 0, worst = 0;
    int worst_vertex = -1;
    for (int u = 0; u < static_cast<int>(plc_.vertices.size()); ++u) {
      const unsigned long long k = index_.vertex_edges[u].size(), nf = corners_[u].size();
      const unsigned long long here = k * (k - (k > 0)) / 2 + k * nf;
      total += here;
      if (here > worst) worst = here, worst_vertex = u;
    }
    if (total <= kMaxAngles) return;
    throw InputError(InputErrorKind::too_large,
                     "the analysis would list up to " + std::to_string(total) +
                         " edge-edge and edge-facet angles, beyond its budget of " + std::to_string(kMaxAngles) +
                         " angles (PLC vertex " + std::to_string(worst_vertex) + " has " +
                         std::to_string(index_.vertex_edges[worst_vertex].size()) + " edges and " +
                         std::to_string(corners_[worst_vertex].size()) + " facets)");
  }

  /// Exact: the angle is acute iff (p - u).(v - u) > 0 for some p in F. That
  /// function of p is linear, so over the polygon F it is largest at a
  /// vertex; it is 0 at u, so the test runs over the other loop vertices.
  bool edge_facet_acute(int u, int v, int f) const {
    for (const auto& loop : plc_.facets[f].loops)
      for (int p : loop)
        if (p != u && exact::dot_sign(P(u), P(p), P(v)) > 0) return true;
    return false;
  }

  /// Value (double precision). Every ray from u through a point p of F leaves
  /// F through its boundary, so the directions from u to F \ {u} are the
  /// directions to the boundary of F. For each boundary segment ab of F we take
  /// the smallest angle between w = v - u and the arc of directions that ab
  /// subtends from u: a segment with endpoint u subtends the single direction
  /// to its other end; otherwise the arc is the cone spanned by a - u and
  /// b - u (less than 180 degrees wide). If the projection of w on F's plane
  /// lies inside that cone, the smallest angle is the angle between w and the
  /// plane; else, as the angle to a direction varies unimodally along the arc,
  /// it is the angle to the nearer endpoint direction. The answer is the
  /// minimum over all segments of all loops.
  ///
  /// This is the paper's definition taken literally: p ranges over all of F,
  /// not only near u. On a non-convex facet a part of F seen from u across a
  /// notch counts too, so the angle can be much smaller than the local angle
  /// between uv and the sector of F at u (fandisk.off: 0.003 degrees where an
  /// almost coplanar triangle fills a notch of a merged facet, against about
  /// 40 degrees locally). The exact acuteness test above is literal too.
  double edge_facet_degrees(int u, int v, int f) const {
    const V w = sub(P(v), P(u));
    const double plane_angle = plane_degrees(w, f);
    double best = 180;
    for (const auto& loop : plc_.facets[f].loops) {
      const std::size_t m = loop.size();
      for (std::size_t r = 0; r < m; ++r) {
        const int a = loop[r], b = loop[(r + 1) % m];
        if (a == u || b == u) {
          best = std::min(best, angle_degrees(w, sub(P(a == u ? b : a), P(u))));
          continue;
        }
        const V da = sub(P(a), P(u)), db = sub(P(b), P(u));
        const V c = cross(da, db);
        const double ea = angle_degrees(w, da), eb = angle_degrees(w, db);
        // cross(da, w).c only sees the component of w in the plane, as does
        // cross(w, db).c; both non-negative means inside the cone.
        const bool inside = norm(c) > 0 && dot(cross(da, w), c) >= 0 && dot(cross(w, db), c) >= 0;
        best = std::min(best, inside ? std::min({plane_angle, ea, eb}) : std::min(ea, eb));
      }
    }
    return best;
  }

  // ---- dihedral angles ---------------------------------------------------------------
  /// Fills traversal_: for every edge and each of its two facets, the
  /// direction (from, to) in which a loop of that facet runs along it, or
  /// (-1, -1) when none does (outside the contract of a valid PLC). One pass
  /// over the loops; each segment finds its edge among the edges of its
  /// endpoint of smaller degree.
  void find_traversals() {
    traversal_.assign(plc_.edges.size(), {{{-1, -1}, {-1, -1}}});
    for (int f = 0; f < static_cast<int>(plc_.facets.size()); ++f)
      for (const auto& loop : plc_.facets[f].loops) {
        const std::size_t m = loop.size();
        for (std::size_t r = 0; r < m; ++r) {
          const int x = loop[r], y = loop[(r + 1) % m];
          const int w = index_.vertex_edges[x].size() <= index_.vertex_edges[y].size() ? x : y;
          for (int e : index_.vertex_edges[w]) {
            if (other_end(e, w) != (w == x ? y : x)) continue;
            for (int side = 0; side < 2; ++side)
              if (plc_.edges[e].facets[side] == f && traversal_[e][side].first < 0) {
                traversal_[e][side] = {x, y};
                break;
              }
          }
        }
      }
  }

  /// At edge ab with facets F1, F2: t_i = n_i x e_i, where n_i is F_i's exact
  /// outward normal and e_i the edge direction in F_i's loop, is the direction
  /// into F_i perpendicular to ab (the interior of a facet is to the left of
  /// its boundary seen from outside). The angle between t1 and t2 is the
  /// dihedral angle on one side; the edge is convex iff F2 goes to the inner
  /// side of F1's plane, n1.t2 < 0, and then internal = angle(t1, t2), else
  /// internal = 360 - angle(t1, t2). The edge is sharp iff the internal angle
  /// (convex edge) or the external one (reflex edge) is acute, that is iff
  /// t1.t2 > 0 in both cases. Both signs are exact (polynomials of degree 5
  /// and 6 in the input).
  void dihedral_angles(Analysis& a) const {
    for (int e = 0; e < static_cast<int>(plc_.edges.size()); ++e) {
      const int f1 = plc_.edges[e].facets[0], f2 = plc_.edges[e].facets[1];
      // Outside the contract (a missing or degenerate facet, an edge not on
      // its facet's boundary) the edge gets 180 / 180, not sharp, and does not
      // count for phi_m: analyze never throws.
      DihedralAngle d{e, 180, 180, false};
      if (f1 < 0 || f2 < 0 || !normals_[f1].valid() || !normals_[f2].valid()) {
        a.dihedral.push_back(d);
        continue;
      }
      const auto [x1, y1] = traversal_[e][0];
      const auto [x2, y2] = traversal_[e][1];
      if (x1 < 0 || x2 < 0) {
        a.dihedral.push_back(d);
        continue;
      }
      auto tangent = [&](int f, int x, int y, auto z) {
        using NT = decltype(z);
        return crossn(exact_normal<NT>(f), lift<NT>(P(y)) - lift<NT>(P(x)));
      };
      const int convex_sign = exact::sign([&, x2 = x2, y2 = y2](auto z) {
        using NT = decltype(z);
        return dotn(exact_normal<NT>(f1), tangent(f2, x2, y2, z));
      });
      const int wedge_sign = exact::sign([&, x1 = x1, y1 = y1, x2 = x2, y2 = y2](auto z) {
        return dotn(tangent(f1, x1, y1, z), tangent(f2, x2, y2, z));
      });
      const V t1 = cross(normals_[f1].unit, geometry::unit(sub(P(y1), P(x1))));
      const V t2 = cross(normals_[f2].unit, geometry::unit(sub(P(y2), P(x2))));
      const double wedge = angle_degrees(t1, t2);
      const bool convex = convex_sign < 0;
      d.internal_degrees = convex ? wedge : 360 - wedge;
      d.external_degrees = 360 - d.internal_degrees;
      d.sharp = wedge_sign > 0;
      a.dihedral.push_back(d);
      a.phi_m_degrees = std::min({a.phi_m_degrees, d.internal_degrees, d.external_degrees});
    }
  }

  // ---- sharp elements ------------------------------------------------------------------
  void sharp_elements(Analysis& a) const {
    std::vector<char> sharp(plc_.vertices.size(), 0);
    for (const auto& ang : a.edge_edge)
      if (ang.acute) sharp[ang.vertex] = 1;
    for (const auto& ang : a.edge_facet)
      if (ang.acute) sharp[ang.vertex] = 1;
    for (const auto& d : a.dihedral)
      if (d.sharp) {
        a.sharp_edges.push_back(d.edge);
        sharp[plc_.edges[d.edge].a] = sharp[plc_.edges[d.edge].b] = 1;
      }
    for (int v = 0; v < static_cast<int>(sharp.size()); ++v)
      if (sharp[v]) a.sharp_vertices.push_back(v);
  }

  const PLC& plc_;
  const PlcIndex& index_;
  AnalysisOptions options_;
  /// Per vertex: the index's corners with their fast flags.
  std::vector<std::vector<Corner>> corners_;
  std::vector<ExactNormal> normals_;
  /// Per edge, per facet side: the direction a loop of that facet runs along it.
  std::vector<std::array<std::pair<int, int>, 2>> traversal_;
};

}  // namespace

Analysis analyze(const PLC& plc, const AnalysisOptions& options) {
  // Beyond the paper: the analysis runs on the input normalised (translated
  // when far from the origin, scaled by 2^-E; exact, see scaling.h), so that
  // its formulas cannot overflow or underflow, and reports f(u) and the
  // boxes in the input's units. Inputs that cannot be represented so are
  // refused (out_of_range).
  const Normalisation n = normalisation(plc);
  check_representable(plc, n, options.box_margin);
  // The index is built here once, on the PLC the analysis runs on, and kept
  // in the Analysis for the mesher (which runs on the same normalised copy).
  if (n.exponent == 0 && !n.translated()) {
    auto index = std::make_shared<const PlcIndex>(plc);
    Analysis a = Analyzer(plc, *index, options).run();
    a.index = std::move(index);
    return a;
  }
  const PLC normalised = normalised_plc(plc, n);
  auto index = std::make_shared<const PlcIndex>(normalised);
  Analysis a = Analyzer(normalised, *index, options).run();
  analysis_to_input(a, n);
  a.index = std::move(index);
  return a;
}

}  // namespace wqmesh
