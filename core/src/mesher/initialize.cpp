// wqmesh: INITIALIZE (paper, sections 4.1 and 4.3): the vertices of P, the
// vertex-ball points on the edges of P, the shield subsegments, and the SOS
// split of every sector of angle pi or more.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>

#include "mesher/phases.h"

namespace wqmesh::mesher {

// ---- INITIALIZE (section 4.1 and 4.3) ----------------------------------------------

void Initialize::run() {
  const PLC& P = dom_.p;
  // V starts as the vertices of P.
  for (int v = 0; v < static_cast<int>(P.vertices.size()); ++v) {
    Insertion ins;
    ins.p = P.vertices[v];
    ins.on = On::vertex;
    ins.element = v;
    ins.hint = v - 1;
    if (meter_.interrupted()) return;
    if (ins_.insert(ins) != v)
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
      if (meter_.interrupted()) return;
      const int id = ins_.insert(ins, Rule::initialize);
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
      queues_.push_segment(sub_.add_segment(s));
    }
  }
  // Shield subsegments: one per sector of a facet at a sharp vertex, between
  // the ball points on the sector's two edges; a sector of angle pi or more is
  // split by SOS (section 4.1) until every arc is below pi. SOS splits a
  // little off the middle, toward the arc's db end (Sector::sos_direction,
  // beyond the paper: see domain.cpp), so the larger arc, from da to the new
  // point, needs a second split when the sector is within 0.004 pi of 2 pi.
  for (int u = 0; u < static_cast<int>(P.vertices.size()); ++u) {
    if (dom_.ball_radius[u] <= 0) continue;
    dom_.for_each_corner(u, [&](int f, int prev, int next) {
      // The facet lies to the left of its loops seen from outside, so its
      // sector at u turns counter-clockwise (about n) from next to prev.
      const Sector s = dom_.sector(u, f, prev, next);
      const int sid = sub_.add_sector(u, s);
      Subsegment shield;
      shield.a = ball_point.at({u, edge_between(u, next)});
      shield.b = ball_point.at({u, edge_between(u, prev)});
      shield.sector = sid;
      shield.da = s.e1;
      shield.db = s.eb;
      queues_.push_segment(sub_.add_segment(shield));
      for (int k = s.initial_splits(); k > 0; --k) {
        const int id = ins_.insert(sub_.splite(shield), Rule::initialize);
        if (id < 0) throw std::runtime_error("INITIALIZE: an SOS point could not be inserted");
        shield = sub_.subsegment(edge_key(shield.a, id));  // from da to the new point, the larger piece
      }
    });
  }
}

int Initialize::edge_between(int u, int w) const {
  for (int e : dom_.vertex_edges[u])
    if (dom_.p.edges[e].a == w || dom_.p.edges[e].b == w) return e;
  throw std::logic_error("no edge of P between vertices " + std::to_string(u) + " and " + std::to_string(w));
}

}  // namespace wqmesh::mesher
