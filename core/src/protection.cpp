// wqmesh: the domain P (input PLC plus the bounding box B, paper section 2)
// and INITIALIZE (section 4.1): vertex balls at sharp vertices, their
// intersections with the edges of P, and SOS splitting of shield subsegments.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "mesher_state.h"

namespace wqmesh::mesher {

namespace {

constexpr double kPi = 3.14159265358979323846;

Point3 unit(const Point3& v) {
  const double n = std::sqrt(dot(v, v));
  return n > 0 ? mul(v, 1 / n) : v;
}

}  // namespace

// ---- geometry helpers ------------------------------------------------------------

Point3 circumcenter(const Point3& a, const Point3& b, const Point3& c, double& r2) {
  const Point3 ab = sub(b, a), ac = sub(c, a);
  const Point3 n = cross(ab, ac);
  const double d = 2 * dot(n, n);
  if (d == 0) {
    r2 = HUGE_VAL;
    return a;
  }
  // a + ((|ab|^2 ac - |ac|^2 ab) x n) / (2 |n|^2)
  const Point3 t = sub(mul(ac, dot(ab, ab)), mul(ab, dot(ac, ac)));
  const Point3 off = mul(cross(t, n), 1 / d);
  r2 = dot(off, off);
  return add(a, off);
}

Point3 circumcenter(const Point3& a, const Point3& b, const Point3& c, const Point3& d, double& r2) {
  const Point3 ab = sub(b, a), ac = sub(c, a), ad = sub(d, a);
  const double det = 2 * dot(ab, cross(ac, ad));
  if (det == 0) {
    r2 = HUGE_VAL;
    return a;
  }
  const Point3 t = add(add(mul(cross(ac, ad), dot(ab, ab)), mul(cross(ad, ab), dot(ac, ac))),
                       mul(cross(ab, ac), dot(ad, ad)));
  const Point3 off = mul(t, 1 / det);
  r2 = dot(off, off);
  return add(a, off);
}

Point3 Sector::at(double t) const {
  return add(center, add(mul(e1, r * std::cos(t)), mul(e2, r * std::sin(t))));
}

// ---- P = the input PLC with the bounding box B ----------------------------------

Domain::Domain(const PLC& plc, const Analysis& analysis) : p(plc) {
  input_vertices = static_cast<int>(plc.vertices.size());
  input_edges = static_cast<int>(plc.edges.size());
  input_facets = static_cast<int>(plc.facets.size());
  box = analysis.bounding_box;
  input_box = analysis.input_box;

  // B: corners i = x + 2y + 4z; edges join corners differing in one bit;
  // facets are oriented with their normals pointing out of B.
  for (int i = 0; i < 8; ++i)
    p.vertices.push_back({{(i & 1) ? box.hi[0] : box.lo[0], (i & 2) ? box.hi[1] : box.lo[1],
                           (i & 4) ? box.hi[2] : box.lo[2]}});
  const int c0 = input_vertices;
  const int faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  std::map<std::pair<int, int>, int> edge_index;
  for (int f = 0; f < 6; ++f) {
    PlcFacet facet;
    facet.loops.push_back({c0 + faces[f][0], c0 + faces[f][1], c0 + faces[f][2], c0 + faces[f][3]});
    const int axis = f / 2;
    facet.normal = {{0, 0, 0}};
    facet.normal[axis] = (f % 2) ? 1 : -1;
    const int fid = static_cast<int>(p.facets.size());
    for (int k = 0; k < 4; ++k) {
      int a = facet.loops[0][k], b = facet.loops[0][(k + 1) % 4];
      if (a > b) std::swap(a, b);
      auto it = edge_index.find({a, b});
      if (it == edge_index.end()) {
        PlcEdge e;
        e.a = a;
        e.b = b;
        e.facets = {{fid, -1}};
        edge_index[{a, b}] = static_cast<int>(p.edges.size());
        p.edges.push_back(e);
      } else {
        p.edges[it->second].facets[1] = fid;
      }
    }
    p.facets.push_back(facet);
  }

  const std::size_t nv = p.vertices.size();
  vertex_facets.assign(nv, {});
  vertex_edges.assign(nv, {});
  for (int e = 0; e < static_cast<int>(p.edges.size()); ++e) {
    vertex_edges[p.edges[e].a].push_back(e);
    vertex_edges[p.edges[e].b].push_back(e);
  }
  for (int f = 0; f < static_cast<int>(p.facets.size()); ++f)
    for (const auto& loop : p.facets[f].loops)
      for (int v : loop)
        if (vertex_facets[v].empty() || vertex_facets[v].back() != f) vertex_facets[v].push_back(f);
  for (auto& fs : vertex_facets) {
    std::sort(fs.begin(), fs.end());
    fs.erase(std::unique(fs.begin(), fs.end()), fs.end());
  }

  sharp_vertex.assign(nv, 0);
  sharp_edge.assign(p.edges.size(), 0);
  ball_radius.assign(nv, 0);
  for (std::size_t i = 0; i < analysis.sharp_vertices.size(); ++i) {
    const int u = analysis.sharp_vertices[i];
    sharp_vertex[u] = 1;
    ball_radius[u] = analysis.lfs.at(i) / 4;  // section 4.1: radius f(u)/4
  }
  for (int e : analysis.sharp_edges) sharp_edge[e] = 1;

  // A 2D frame per facet: origin at its first vertex, e1 along its first edge.
  frames.resize(p.facets.size());
  for (std::size_t f = 0; f < p.facets.size(); ++f) {
    Frame& fr = frames[f];
    const auto& loop = p.facets[f].loops[0];
    fr.origin = p.vertices[loop[0]];
    // Newell's normal of the outer loop (robust for non-convex facets).
    Point3 nw{{0, 0, 0}};
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const Point3& a = p.vertices[loop[i]];
      const Point3& b = p.vertices[loop[(i + 1) % loop.size()]];
      nw[0] += (a[1] - b[1]) * (a[2] + b[2]);
      nw[1] += (a[2] - b[2]) * (a[0] + b[0]);
      nw[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    fr.n = unit(nw);
    fr.e1 = unit(sub(p.vertices[loop[1]], fr.origin));
    fr.e1 = unit(sub(fr.e1, mul(fr.n, dot(fr.e1, fr.n))));
    fr.e2 = cross(fr.n, fr.e1);
    for (const auto& l : p.facets[f].loops) {
      fr.loops.emplace_back();
      for (int v : l) fr.loops.back().push_back(to2d(static_cast<int>(f), p.vertices[v]));
    }
  }
}

std::array<double, 2> Domain::to2d(int f, const Point3& x) const {
  const Frame& fr = frames[f];
  const Point3 d = sub(x, fr.origin);
  return {{dot(d, fr.e1), dot(d, fr.e2)}};
}

bool Domain::inside_facet(int f, const Point3& x) const {
  const std::array<double, 2> q = to2d(f, x);
  bool inside = false;
  for (const auto& loop : frames[f].loops) {
    const std::size_t n = loop.size();
    for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
      const auto &a = loop[i], &b = loop[j];
      if ((a[1] > q[1]) != (b[1] > q[1])) {
        const double x_cross = a[0] + (q[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1]);
        if (q[0] < x_cross) inside = !inside;
      }
    }
  }
  return inside;
}

Sector Domain::sector(int u, int f, int prev, int next) const {
  const Point3 n = frames[f].n;
  Sector s;
  s.u = u;
  s.facet = f;
  s.center = p.vertices[u];
  s.r = ball_radius[u];
  Point3 d1 = sub(p.vertices[next], s.center);
  d1 = sub(d1, mul(n, dot(d1, n)));
  s.e1 = mul(d1, 1 / std::sqrt(dot(d1, d1)));
  s.e2 = cross(n, s.e1);
  const Point3 d2 = sub(p.vertices[prev], s.center);
  double span = std::atan2(dot(d2, s.e2), dot(d2, s.e1));
  if (span <= 0) span += 2 * kPi;
  s.span = span;
  return s;
}

std::size_t Domain::initialize_points() const {
  std::size_t n = p.vertices.size();
  for (int u = 0; u < static_cast<int>(p.vertices.size()); ++u) {
    if (ball_radius[u] <= 0) continue;
    n += vertex_edges[u].size();
    for_each_corner(u, [&](int f, int prev, int next) { n += sector(u, f, prev, next).span >= kPi; });
  }
  return n;
}

bool Domain::facet_has_vertex(int f, int v) const {
  return std::binary_search(vertex_facets[v].begin(), vertex_facets[v].end(), f);
}

// ---- INITIALIZE (section 4.1 and 4.3) ----------------------------------------------

void Mesher::initialize() {
  phase_ = Phase::initialize;
  const PLC& P = dom_.p;
  // V starts as the vertices of P.
  for (int v = 0; v < static_cast<int>(P.vertices.size()); ++v) {
    Insertion ins;
    ins.p = P.vertices[v];
    ins.on = On::vertex;
    ins.element = v;
    ins.hint = v - 1;
    if (interrupted()) return;
    if (insert(ins) != v)
      throw std::runtime_error("INITIALIZE: input vertex " + std::to_string(v) + " could not be inserted");
  }
  // The points where the boundary of each vertex ball crosses the edges of P.
  std::map<std::pair<int, int>, int> ball_point;  // (sharp vertex, edge) -> vertex id
  for (int u = 0; u < static_cast<int>(P.vertices.size()); ++u) {
    const double r = dom_.ball_radius[u];
    if (r <= 0) continue;
    for (int e : dom_.vertex_edges[u]) {
      const int w = P.edges[e].a == u ? P.edges[e].b : P.edges[e].a;
      const Point3 dir = sub(P.vertices[w], P.vertices[u]);
      Insertion ins;
      ins.p = add(P.vertices[u], mul(dir, r / std::sqrt(dot(dir, dir))));
      ins.on = On::edge;
      ins.element = e;
      ins.ball = u;
      ins.hint = u;
      if (interrupted()) return;
      const int id = insert(ins, 0);
      if (id < 0) throw std::runtime_error("INITIALIZE: a vertex-ball point could not be inserted");
      ball_point[{u, e}] = id;
    }
  }
  // Subsegments: each edge of P cut at its ball points. The pieces inside a
  // vertex ball are protected by it and never split (section 4).
  for (int e = 0; e < static_cast<int>(P.edges.size()); ++e) {
    const int a = P.edges[e].a, b = P.edges[e].b;
    std::vector<int> chain{a};
    const auto pa = ball_point.find({a, e});
    const auto pb = ball_point.find({b, e});
    if (pa != ball_point.end()) chain.push_back(pa->second);
    if (pb != ball_point.end()) chain.push_back(pb->second);
    chain.push_back(b);
    for (std::size_t i = 0; i + 1 < chain.size(); ++i) {
      Subsegment s;
      s.a = chain[i];
      s.b = chain[i + 1];
      s.edge = e;
      s.in_ball = (i == 0 && pa != ball_point.end()) || (i + 2 == chain.size() && pb != ball_point.end());
      s.sharp = dom_.sharp_edge[e] && !s.in_ball;
      add_segment(s);
    }
  }
  // Shield subsegments: one per sector of a facet at a sharp vertex, between
  // the ball points on the sector's two edges; a sector of angle pi or more is
  // split at the midpoint of its arc (SOS, section 4.1).
  vertex_sectors_.assign(P.vertices.size(), {});
  for (int u = 0; u < static_cast<int>(P.vertices.size()); ++u) {
    if (dom_.ball_radius[u] <= 0) continue;
    dom_.for_each_corner(u, [&](int f, int prev, int next) {
      // The facet lies to the left of its loops seen from outside, so its
      // sector at u turns counter-clockwise (about n) from next to prev.
      const Sector s = dom_.sector(u, f, prev, next);
      const int sid = static_cast<int>(sectors_.size());
      sectors_.push_back(s);
      vertex_sectors_[u].push_back(sid);
      Subsegment shield;
      shield.a = ball_point.at({u, edge_between(u, next)});
      shield.b = ball_point.at({u, edge_between(u, prev)});
      shield.sector = sid;
      shield.ta = 0;
      shield.tb = s.span;
      add_segment(shield);
      if (s.span >= kPi) insert(splite(shield), 0);
    });
  }
}

int Mesher::edge_between(int u, int w) const {
  for (int e : dom_.vertex_edges[u])
    if (dom_.p.edges[e].a == w || dom_.p.edges[e].b == w) return e;
  throw std::logic_error("no edge of P between vertices " + std::to_string(u) + " and " + std::to_string(w));
}

}  // namespace wqmesh::mesher
