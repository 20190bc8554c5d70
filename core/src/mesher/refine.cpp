// wqmesh: REFINE (paper, section 4.3): rules 4-5 (in the queues), rule 6
// (skinny tets) and rule 7 (preparing PUMP).
// SPDX-License-Identifier: GPL-3.0-or-later
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <unordered_set>

#include "mesher/extract.h"
#include "mesher/phases.h"
#include "wqmesh/quality.h"

namespace wqmesh::mesher {

namespace {

// The smallest dihedral angle of a tet, in degrees, when it is at most
// `bound` (the same double as tet_min_dihedral_deg); else a value above it.
double min_dihedral_upto(const RegularTriangulation& tri, const Tet& t, double bound) {
  return tet_min_dihedral_deg_upto(tri.point(t[0]), tri.point(t[1]), tri.point(t[2]), tri.point(t[3]), bound);
}
}  // namespace

std::string Refine::input_feature(const Insertion& ins) const {
  char text[160];
  if (ins.on == On::edge && ins.element >= dom_.input_edges) {
    std::snprintf(text, sizeof text, "an edge of the bounding box");
  } else if (ins.on == On::edge) {
    const auto& e = dom_.p.edges[ins.element];
    std::snprintf(text, sizeof text, "input edge %d (vertices %d-%d)", ins.element, e.a, e.b);
  } else if (ins.on == On::facet && dom_.is_box_facet(ins.element)) {
    std::snprintf(text, sizeof text, "a facet of the bounding box");
  } else if (ins.on == On::facet) {
    std::snprintf(text, sizeof text, "input facet %d%s", ins.element, ins.sector >= 0 ? " (a shield arc)" : "");
  } else {
    std::snprintf(text, sizeof text, "a point off the input's elements");
  }
  return text;
}

void Refine::run() {
  // Beyond the paper: the runaway guard (WorkMeter::refine_insertion) sees
  // every insertion of REFINE; it names the input feature of the last one,
  // and past its count cap weighs the new vertex's spacing against the
  // smallest protecting ball (B's extent if there is none).
  double smallest = 0;
  for (int q = 0; q < 3; ++q) smallest = std::max(smallest, dom_.box.hi[q] - dom_.box.lo[q]);
  for (const ProtectingBall& b : balls_.all())
    if (b.radius > 0) smallest = std::min(smallest, b.radius);
  const ScopedObserver scope(ins_, [this, smallest](const Insertion& ins, int rule, int id) {
    if (id < 0) return;
    // Passed by reference: a std::function of this closure (three
    // captures) would allocate on every insertion.
    const auto spacing = [&] { return nearest_neighbour(tri_, id) / smallest; };
    meter_.refine_insertion(
        static_cast<Rule>(rule), verts_.size(), [&] { return input_feature(ins); }, std::cref(spacing));
  });
  queues_.fill(true);
  if (!process_queues()) return;
  if (!opt_.pump) return;
  // Rule 7 passes until one inserts nothing, at most Caps::kRule7Passes.
  int pass = 0;
  for (; pass < Caps::kRule7Passes && !meter_.stopped(); ++pass)
    if (!rule7_pass()) break;
  if (pass == Caps::kRule7Passes) meter_.cap_reached();
  queues_.sliver_record().clear();  // (its memory back before PUMP)
}

bool Refine::process_queues() {
  return queues_.process(ins_, [this](const Tet& t, CellRef ref) { return rule6_split_skinny_tet(t, ref); });
}

bool Refine::rule6_split_skinny_tet(const Tet& t, CellRef ref) {
  // Rule 6: a tet with circumradius-edge ratio above rho0 (or, beyond the
  // paper, circumradius above max_size) is split at its circumcenter z unless
  // z lies on or inside a protecting ball; ENCROACH(z) decides the point.
  if (!tri_.is_cell(t, ref)) return false;
  // Four vertices on the sphere of one vertex ball: that sphere is the
  // circumsphere (computed in floating point, the circumcenter of such a flat
  // tet lands anywhere), its center u lies in the ball, and rule 6 refuses it.
  const int u = verts_[t[0]].ball;
  if (u >= 0 && verts_[t[1]].ball == u && verts_[t[2]].ball == u && verts_[t[3]].ball == u) return false;
  const Point3 &a = tri_.point(t[0]), &b = tri_.point(t[1]), &c = tri_.point(t[2]), &d = tri_.point(t[3]);
  double r2;
  const Point3 z = circumcenter(a, b, c, d, r2);
  if (!std::isfinite(r2)) return false;
  double l2 = dist2(a, b);
  for (const auto& [p, q] : {std::pair{&a, &c}, {&a, &d}, {&b, &c}, {&b, &d}, {&c, &d}})
    l2 = std::min(l2, dist2(*p, *q));
  const bool skinny = r2 > opt_.rho0 * opt_.rho0 * l2;
  bool large = false;
  if (opt_.max_size > 0 && r2 > opt_.max_size * opt_.max_size) {
    large = true;
    for (int i = 0; i < 3; ++i)
      if (z[i] < dom_.input_box.lo[i] || z[i] > dom_.input_box.hi[i]) large = false;
  }
  if (!skinny && !large) return false;
  for (int i = 0; i < 3; ++i)  // never insert outside B (section 5)
    if (!(z[i] > dom_.box.lo[i] && z[i] < dom_.box.hi[i])) return false;
  if (balls_.contains(z)) return false;
  // When ENCROACH rejects z for a point on a subsegment or subfacet, the tet
  // is looked at again afterwards (it may survive that insertion).
  const Insertion ins = sub_.encroach(z, t[0], ref);
  if (ins_.insert(ins, Rule::rule6_split_skinny_tet) < 0) return false;
  if (ins.on != On::free && queues_.may_retry({{t[0], t[1], t[2]}})) queues_.push_tet(t, ref);
  return true;
}

bool Refine::rule7_pass() {
  // Rule 7: for a vertex v of a tet with a dihedral angle of theta or less,
  // weighted with N(v)^2/9, unless it encroaches the two-times expansion of a
  // protecting ball: (i) split a subsegment it encroaches; (ii) split the
  // non-guarded subfacet it encroaches that contains its projection; (iii)
  // split a guarded subfacet it removes from the weighted Delaunay
  // triangulation. Only tets inside the polyhedron are considered (those
  // outside are discarded at the end), and the features examined are those
  // incident to v and to its neighbours (a choice: the paper does not say how
  // far to look).
  std::vector<std::pair<double, int>> candidates;
  const auto add = [&](const Tet& t) {
    if (std::find(t.begin(), t.end(), kInfinite) != t.end()) return;
    // Only the angles at theta or less matter: the others are skipped
    // (issue 15; the same candidates and angles).
    const double angle = min_dihedral_upto(tri_, t, opt_.theta_deg);
    if (angle <= opt_.theta_deg)
      for (int v : t) candidates.push_back({angle, v});
  };
  // The inside cells by the labels in the cells when they do not depend on
  // the cells' order (label_cells_in_place: no cell graph beside the
  // triangulation, issue 15, the peak memory), else on a cell graph in
  // CGAL's order; the candidates are sorted, so their order is free.
  Queues::SliverRecord& record = queues_.sliver_record();
  if (label_cells_in_place(dom_, sub_, tri_, meter_, true)) {
    // Beyond the paper (issue 15): the cells with an angle at theta or less
    // are recorded whatever their label (Queues::SliverRecord), and a pass
    // after one that recorded them reads only those that live on and the
    // cells made since, instead of every cell: the same candidates.
    if (!record.update(tri_, opt_.theta_deg, candidates, [&](std::size_t n) { return meter_.poll(n, false); }))
      return false;
  } else {
    record.clear();
    if (meter_.stopped()) return false;
    const RegularTriangulation::CellGraph g = meter_.scan_cell_graph(tri_);
    if (meter_.stopped()) return false;
    const std::vector<char> inside = interior_labels(dom_, sub_, g, meter_, true);
    if (meter_.stopped()) return false;
    for (std::size_t i = 0; i < g.cells.size(); ++i) {
      if (!meter_.poll(1, false)) return false;
      if (inside[i]) add(g.cells[i]);
    }
  }
  std::sort(candidates.begin(), candidates.end());
  std::vector<char> done(verts_.size(), 0);
  bool acted = false;
  std::vector<int> ring, fs;
  std::vector<Tri> around;
  for (const auto& [angle, v] : candidates) {
    meter_.step_done();  // each candidate is a step of the watchdog
    if (!meter_.poll(1)) break;
    if (done[v]) continue;
    done[v] = 1;
    const Point3 pv = tri_.point(v);
    const double nv = nearest_neighbour(tri_, v);
    const double w = nv * nv / 9;
    if (balls_.expansion_encroached(pv, w)) continue;
    tri_.adjacent_vertices(v, ring);
    ring.push_back(v);
    meter_.poll(ring.size());
    // (i) subsegments: power distance to the diametric ball <= 0.
    std::vector<std::uint64_t> seg_keys;
    for (int x : ring)
      for (std::uint64_t k : sub_.subsegments_at(x)) seg_keys.push_back(k);
    std::sort(seg_keys.begin(), seg_keys.end());
    seg_keys.erase(std::unique(seg_keys.begin(), seg_keys.end()), seg_keys.end());
    bool has = false;
    Insertion ins;
    for (std::uint64_t k : seg_keys) {
      const Subsegment& s = sub_.subsegment(k);
      if (s.in_ball || s.a == v || s.b == v) continue;
      const Point3 &a = tri_.point(s.a), &b = tri_.point(s.b);
      if (dist2(pv, midpoint(a, b)) - w - 0.25 * dist2(a, b) <= 0) {
        ins = sub_.splite(s);
        has = true;
        break;
      }
    }
    if (!has) {
      std::unordered_set<Tri, TriHash> seen;
      std::vector<Subfacet> nonguarded;
      const Subfacet* removed = nullptr;
      std::vector<Subfacet> guarded_list;
      for (int x : ring) {
        sub_.facets_of(x, fs);
        for (int f : fs) {
          sub_.subfacets_at(f, x, around);
          for (const Tri& t : around) {
            if (!seen.insert(sorted(t)).second) continue;
            if (t[0] == v || t[1] == v || t[2] == v) continue;
            const Subfacet h{f, t};
            double r2;
            const Point3 cc = circumcenter(tri_.point(t[0]), tri_.point(t[1]), tri_.point(t[2]), r2);
            if (!sub_.guarded(h)) {
              if (dist2(pv, cc) - w - r2 < 0) nonguarded.push_back(h);
            } else {
              guarded_list.push_back(h);
            }
          }
        }
      }
      // (ii): the encroached non-guarded subfacet containing the projection
      // of v, else the first (rounding can leave none containing it).
      if (!nonguarded.empty()) {
        const Subfacet* pick = &nonguarded.front();
        for (const Subfacet& h : nonguarded) {
          const Point3 &a = tri_.point(h.v[0]), &b = tri_.point(h.v[1]), &c = tri_.point(h.v[2]);
          const Point3 n = cross(sub(b, a), sub(c, a));
          if (dot(cross(sub(b, a), sub(pv, a)), n) >= 0 && dot(cross(sub(c, b), sub(pv, b)), n) >= 0 &&
              dot(cross(sub(a, c), sub(pv, c)), n) >= 0) {
            pick = &h;
            break;
          }
        }
        ins = sub_.splitf(*pick);
        has = true;
      } else {
        // (iii): a guarded subfacet abc stays in the weighted Delaunay
        // triangulation iff some sphere of the pencil through a, b, c has a
        // non-negative power distance to every weighted vertex. Along the
        // pencil (center cc + t n) the power distance of x is affine in t;
        // the two cells at abc bound t in the unweighted triangulation, v-hat
        // adds one constraint.
        for (const Subfacet& h : guarded_list) {
          Tet c1, c2;
          if (!tri_.facet_cells(h.v[0], h.v[1], h.v[2], c1, c2)) continue;
          const Point3 &a = tri_.point(h.v[0]), &b = tri_.point(h.v[1]), &c = tri_.point(h.v[2]);
          double r2;
          const Point3 cc = circumcenter(a, b, c, r2);
          Point3 n = cross(sub(b, a), sub(c, a));
          n = mul(n, 1 / std::sqrt(dot(n, n)));
          double lo = -HUGE_VAL, hi = HUGE_VAL;
          auto constrain = [&](const Point3& x, double wx) {
            const double alpha = dist2(x, cc) - wx - r2, beta = dot(sub(x, cc), n);
            if (beta > 0)
              hi = std::min(hi, alpha / (2 * beta));
            else if (beta < 0)
              lo = std::max(lo, alpha / (2 * beta));
            else if (alpha < 0)
              lo = HUGE_VAL;
          };
          for (const Tet* cell : {&c1, &c2})
            for (int x : *cell)
              if (x != kInfinite && x != h.v[0] && x != h.v[1] && x != h.v[2]) constrain(tri_.point(x), x == v ? w : 0);
          constrain(pv, w);
          if (lo > hi) {
            removed = &h;
            break;
          }
        }
        if (removed) {
          ins = sub_.splitf(*removed);
          has = true;
        }
      }
    }
    if (has && ins_.insert(ins, Rule::rule7_split_for_pumping) >= 0) {
      acted = true;
      meter_.tick();
      if (!process_queues()) break;
    }
  }
  return acted;
}

}  // namespace wqmesh::mesher
