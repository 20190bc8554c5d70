// SPDX-License-Identifier: GPL-3.0-or-later
// wqmesh: the local feature size f(u) at sharp vertices (paper, section 2 for
// the definition, section 4.1 for its use as the radius 4 r of the vertex
// ball of u).
//
// f(u) is the radius of the smallest ball centred at u meeting two
// non-adjacent elements of P (the PLC plus the bounding box B). Every element
// containing u meets every other element containing u, so the smallest such
// ball meets u and the nearest element not containing u: f(u) is the distance
// from u to the nearest input vertex, edge or facet not containing u, or to
// the boundary of B.
//
// The search runs over a bounding volume hierarchy (median splits of the
// element boxes) with the usual pruning by box distance. Distances are
// computed in double precision: f(u) is a size, no combinatorial decision
// depends on its exact value.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "geometry.h"
#include "plc_index.h"
#include "wqmesh/analysis.h"

namespace wqmesh {
namespace {

using V = Point3;
using geometry::dot;
using geometry::sub;

/// Squared distance from p to the closed segment ab.
double segment_distance2(const V& p, const V& a, const V& b) {
  const V ab = sub(b, a), ap = sub(p, a);
  const double len2 = dot(ab, ab);
  double t = len2 > 0 ? dot(ap, ab) / len2 : 0;
  t = std::clamp(t, 0.0, 1.0);
  const V q{{a[0] + t * ab[0], a[1] + t * ab[1], a[2] + t * ab[2]}};
  const V d = sub(p, q);
  return dot(d, d);
}

struct Aabb {
  V lo{{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
        std::numeric_limits<double>::infinity()}};
  V hi{{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
        -std::numeric_limits<double>::infinity()}};
  void add(const V& p) {
    for (int i = 0; i < 3; ++i) {
      lo[i] = std::min(lo[i], p[i]);
      hi[i] = std::max(hi[i], p[i]);
    }
  }
  void add(const Aabb& b) {
    add(b.lo);
    add(b.hi);
  }
  /// Squared distance from p to the box (0 inside).
  double distance2(const V& p) const {
    double s = 0;
    for (int i = 0; i < 3; ++i) {
      const double d = std::max({lo[i] - p[i], 0.0, p[i] - hi[i]});
      s += d * d;
    }
    return s;
  }
};

enum class Kind : std::uint8_t { vertex, edge, facet };

struct Element {
  Kind kind;
  int index;
  Aabb box;
  V centre;
};

struct Node {
  Aabb box;
  int left = -1, right = -1;  ///< children, or -1 for a leaf
  int begin = 0, end = 0;     ///< leaf: elements [begin, end)
};

class FeatureSearch {
 public:
  /// The facets' planes (origin and unit normal) and incidence come from
  /// the index's frames and vertex_facets.
  FeatureSearch(const PLC& plc, const PlcIndex& index) : plc_(plc), index_(index) {
    drop_.assign(plc.facets.size(), 2);
    for (int f = 0; f < static_cast<int>(plc.facets.size()); ++f) {
      const PlcFacet& facet = plc.facets[f];
      Aabb box;
      for (const auto& loop : facet.loops)
        for (int v : loop) box.add(plc.vertices[v]);
      // The axis dropped when projecting the facet to 2D: the normal's largest.
      const V& n = index.frames[f].plane_n;
      drop_[f] = 0;
      for (int k = 1; k < 3; ++k)
        if (std::fabs(n[k]) > std::fabs(n[drop_[f]])) drop_[f] = k;
      add(Kind::facet, f, box);
    }
    for (int e = 0; e < static_cast<int>(plc.edges.size()); ++e) {
      Aabb box;
      box.add(plc.vertices[plc.edges[e].a]);
      box.add(plc.vertices[plc.edges[e].b]);
      add(Kind::edge, e, box);
    }
    for (int v = 0; v < static_cast<int>(plc.vertices.size()); ++v) {
      Aabb box;
      box.add(plc.vertices[v]);
      add(Kind::vertex, v, box);
    }
    if (!elements_.empty()) build(0, static_cast<int>(elements_.size()));
  }

  /// Squared distance from vertex u to the nearest element not containing u,
  /// if below `best2`; else `best2`.
  double nearest2(int u, double best2) const {
    if (nodes_.empty()) return best2;
    const V& p = plc_.vertices[u];
    std::vector<int> stack{0};
    while (!stack.empty()) {
      const Node& node = nodes_[stack.back()];
      stack.pop_back();
      if (node.box.distance2(p) >= best2) continue;
      if (node.left < 0) {
        for (int i = node.begin; i < node.end; ++i) best2 = std::min(best2, distance2(elements_[i], u, best2));
        continue;
      }
      const double dl = nodes_[node.left].box.distance2(p);
      const double dr = nodes_[node.right].box.distance2(p);
      // Nearer child last, so that it is searched first.
      if (dl < dr) {
        if (dr < best2) stack.push_back(node.right);
        if (dl < best2) stack.push_back(node.left);
      } else {
        if (dl < best2) stack.push_back(node.left);
        if (dr < best2) stack.push_back(node.right);
      }
    }
    return best2;
  }

 private:
  void add(Kind kind, int index, const Aabb& box) {
    V c;
    for (int i = 0; i < 3; ++i) c[i] = 0.5 * (box.lo[i] + box.hi[i]);
    elements_.push_back({kind, index, box, c});
  }

  int build(int begin, int end) {
    const int id = static_cast<int>(nodes_.size());
    nodes_.push_back({});
    Aabb box, centres;
    for (int i = begin; i < end; ++i) {
      box.add(elements_[i].box);
      centres.add(elements_[i].centre);
    }
    nodes_[id].box = box;
    if (end - begin <= 4) {
      nodes_[id].begin = begin;
      nodes_[id].end = end;
      return id;
    }
    int axis = 0;
    for (int k = 1; k < 3; ++k)
      if (centres.hi[k] - centres.lo[k] > centres.hi[axis] - centres.lo[axis]) axis = k;
    const int mid = begin + (end - begin) / 2;
    std::nth_element(elements_.begin() + begin, elements_.begin() + mid, elements_.begin() + end,
                     [axis](const Element& a, const Element& b) { return a.centre[axis] < b.centre[axis]; });
    const int left = build(begin, mid);
    const int right = build(mid, end);
    nodes_[id].left = left;
    nodes_[id].right = right;
    return id;
  }

  bool facet_contains_vertex(int f, int u) const {
    const auto& list = index_.vertex_facets[u];
    return std::binary_search(list.begin(), list.end(), f);
  }

  /// Squared distance from vertex u to an element (infinity when the element
  /// contains u, or when it cannot beat `best2`).
  double distance2(const Element& el, int u, double best2) const {
    constexpr double inf = std::numeric_limits<double>::infinity();
    const V& p = plc_.vertices[u];
    if (el.box.distance2(p) >= best2) return inf;
    switch (el.kind) {
      case Kind::vertex: {
        if (el.index == u) return inf;
        const V d = sub(p, plc_.vertices[el.index]);
        return dot(d, d);
      }
      case Kind::edge: {
        const PlcEdge& e = plc_.edges[el.index];
        if (e.a == u || e.b == u) return inf;
        return segment_distance2(p, plc_.vertices[e.a], plc_.vertices[e.b]);
      }
      case Kind::facet: return facet_distance2(el.index, u, best2);
    }
    return inf;
  }

  /// The facet's contribution: the squared distance to its plane when the
  /// projection of u falls inside the polygon. When it falls outside, the
  /// nearest point of the facet is on its boundary, whose edges are elements
  /// of the search too (none of them contains u, since the facet does not),
  /// so the facet need not report it.
  double facet_distance2(int f, int u, double best2) const {
    constexpr double inf = std::numeric_limits<double>::infinity();
    const PlcIndex::Frame& plane = index_.frames[f];
    if (plane.plane_n[0] == 0 && plane.plane_n[1] == 0 && plane.plane_n[2] == 0) return inf;
    if (facet_contains_vertex(f, u)) return inf;
    const V& p = plc_.vertices[u];
    const double h = dot(sub(p, plane.origin), plane.plane_n);
    if (h * h >= best2) return inf;
    // Crossing-number test of q, the orthogonal projection of u on the
    // plane, in the 2D view that drops the dominant normal axis (a parallel
    // projection of the plane, so inside stays inside); holes by parity.
    const V q{{p[0] - h * plane.plane_n[0], p[1] - h * plane.plane_n[1], p[2] - h * plane.plane_n[2]}};
    const int ax = drop_[f] == 0 ? 1 : 0;
    const int ay = drop_[f] == 2 ? 1 : 2;
    const double px = q[ax], py = q[ay];
    bool inside = false;
    for (const auto& loop : plc_.facets[f].loops) {
      const std::size_t n = loop.size();
      for (std::size_t i = 0; i < n; ++i) {
        const V& a = plc_.vertices[loop[i]];
        const V& b = plc_.vertices[loop[(i + 1) % n]];
        if ((a[ay] > py) != (b[ay] > py)) {
          const double x = a[ax] + (py - a[ay]) * (b[ax] - a[ax]) / (b[ay] - a[ay]);
          if (x > px) inside = !inside;
        }
      }
    }
    return inside ? h * h : inf;
  }

  const PLC& plc_;
  const PlcIndex& index_;
  std::vector<int> drop_;  ///< per facet: the axis its 2D view drops
  std::vector<Element> elements_;
  std::vector<Node> nodes_;
};

}  // namespace

std::vector<double> local_feature_sizes(const PLC& plc, const std::vector<int>& vertices, const Box& bounding_box) {
  if (vertices.empty()) return {};
  return local_feature_sizes(plc, PlcIndex(plc), vertices, bounding_box);
}

std::vector<double> local_feature_sizes(const PLC& plc, const PlcIndex& index, const std::vector<int>& vertices,
                                        const Box& bounding_box) {
  std::vector<double> result;
  result.reserve(vertices.size());
  if (vertices.empty()) return result;
  const FeatureSearch search(plc, index);
  for (int u : vertices) {
    const V& p = plc.vertices[u];
    // Distance to the boundary of B (u is inside B).
    double box = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k)
      box = std::min({box, std::fabs(p[k] - bounding_box.lo[k]), std::fabs(bounding_box.hi[k] - p[k])});
    result.push_back(std::sqrt(search.nearest2(u, box * box)));
  }
  return result;
}

}  // namespace wqmesh
