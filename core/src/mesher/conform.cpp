// wqmesh: CONFORM (paper, section 4.3): rules 1-3 until the edges and facets
// of P are unions of Delaunay edges and triangles, then the protecting balls.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

#include "mesher/phases.h"

namespace wqmesh::mesher {

void Conform::run() {
  queues_.fill(false);
  if (!queues_.process(ins_)) return;
  if (opt_.max_size > 0 && !split_long_sharp_subsegments()) return;
  // Rule 3 passes until one inserts nothing, at most Caps::kRule3Passes.
  // Every insertion meanwhile (rule 3's and the rules 1-2 it sets off)
  // marks the new vertex's neighbours (Rule3State::touched; see rule3_pass).
  Rule3State& state = state_;
  state = {};
  std::vector<int> ring;
  // The caller's observer is back when this scope ends, however it ends.
  const ScopedObserver scope(ins_, [&](const Insertion&, int, int id) {
    if (id < 0) return;
    if (state.touched.size() < std::size_t(tri_.number_of_vertices()))
      state.touched.resize(tri_.number_of_vertices(), 0);
    tri_.adjacent_vertices(id, ring);
    for (int x : ring) state.touched[x] = std::max(state.touched[x], id);
  });
  int passes = 0;
  while (!meter_.stopped() && passes < Caps::kRule3Passes && rule3_pass()) ++passes;
  if (passes == Caps::kRule3Passes) meter_.cap_reached();
  make_protecting_balls();
}

std::vector<std::uint64_t> Conform::sharp_subsegment_keys() const {
  std::vector<std::uint64_t> keys;
  for (const auto& [k, s] : sub_.subsegments())
    if (s.sharp) keys.push_back(k);
  std::sort(keys.begin(), keys.end());
  return keys;
}

bool Conform::rule3_unchanged(const Rule3Record& r) const {
  for (int x : r.zone)
    if (std::size_t(x) < state_.touched.size() && state_.touched[x] >= int(r.tested_at)) return false;
  return true;
}

bool Conform::rule3_test(std::uint64_t k, const Subsegment& s, Insertion& ins, Rule3Scratch& w) const {
  std::vector<std::uint64_t>& segs = w.segs;
  std::vector<Subfacet>& facets = w.facets;
  const int ea = dom_.p.edges[s.edge].a, eb = dom_.p.edges[s.edge].b;
  const Point3 m = midpoint(tri_.point(s.a), tri_.point(s.b));
  sub_.encroached_by_point(m, s.a, segs, facets, nullptr, &w.zone);
  auto disjoint_facet = [&](int f) { return !dom_.facet_has_vertex(f, ea) && !dom_.facet_has_vertex(f, eb); };
  for (std::uint64_t g : segs) {
    if (g == k) continue;
    const Subsegment& gs = sub_.subsegment(g);
    const bool disjoint = gs.sector >= 0
                              ? disjoint_facet(sub_.sector(gs.sector).facet)
                              : (gs.edge != s.edge && dom_.p.edges[gs.edge].a != ea && dom_.p.edges[gs.edge].a != eb &&
                                 dom_.p.edges[gs.edge].b != ea && dom_.p.edges[gs.edge].b != eb);
    if (disjoint) {
      ins = sub_.splite(gs);
      return true;
    }
  }
  for (const Subfacet& h : facets)
    if (disjoint_facet(h.facet)) {
      ins = sub_.splitf(h);
      return true;
    }
  return false;
}

bool Conform::rule3_records_hold() const {
  Rule3Scratch w;
  for (const auto& [k, r] : state_.records) {
    const auto it = sub_.subsegments().find(k);
    if (it == sub_.subsegments().end() || !rule3_unchanged(r)) continue;
    Insertion ins;
    if (rule3_test(k, it->second, ins, w)) return false;
  }
  return true;
}

bool Conform::rule3_pass() {
  // Rule 3: the midpoint of a sharp subsegment s on edge e that encroaches a
  // subsegment or subfacet h, h and e in disjoint elements of P: split h.
  //
  // Beyond the paper (issue 15: every pass tested every sharp subsegment
  // again, a third of CONFORM on mpi.off, whose passes insert a few points
  // each): a subsegment whose last test found nothing is tested again only
  // when an insertion since may have changed what its midpoint m sees. V
  // only grows here (unweighted insertions, none hidden). The test reads the
  // cells C(m) whose circumballs hold m (a connected set, from the cell
  // holding m), their edges and triangles that are subsegments and
  // subfacets, and fixed geometry. An insertion of v changes C(m) only if it
  // destroys a cell of C(m) or a cell e across a face F of one (only then
  // can m conflict with a new cell: the first new cell on a path in the new
  // conflict set from the cell holding m is v joined to such an F), and the
  // vertices of every destroyed cell become v's neighbours: so some vertex
  // of C(m) gets a neighbour inserted after the test (Rule3State::touched,
  // kept by run()'s observer). While C(m) is unchanged the features among
  // its cells can only be lost (a split removes a subsegment, a facet's
  // retriangulation removes triangles; every new subsegment and subfacet
  // holds a new vertex), so the test still finds nothing: skipping it
  // changes no answer, no insertion and no order.
  Rule3State& state = state_;
  const std::vector<std::uint64_t> keys = sharp_subsegment_keys();
  bool acted = false;
  Rule3Scratch w;
  for (std::uint64_t k : keys) {
    meter_.step_done();
    if (!meter_.poll(1)) break;
    const auto it = sub_.subsegments().find(k);
    if (it == sub_.subsegments().end()) continue;
    const auto rec = state.records.find(k);
    if (rec != state.records.end()) {
      if (rule3_unchanged(rec->second)) {  // the same test would find nothing again
        ++state.skipped;
        continue;
      }
      state.records.erase(rec);
    }
    const Subsegment s = it->second;
    const std::uint32_t tested_at = static_cast<std::uint32_t>(tri_.number_of_vertices());
    Insertion ins;
    const bool found = rule3_test(k, s, ins, w);
    if (!found) state.records[k] = {tested_at, w.zone};
    if (found && ins_.insert(ins, Rule::rule3_split_near_sharp_subsegment) >= 0) {
      acted = true;
      meter_.tick();
      if (!queues_.process(ins_)) break;
    }
  }
  return acted;
}

bool Conform::split_long_sharp_subsegments() {
  // Beyond the paper: the size bound max_size of rule 6. Rule 6 never inserts
  // inside a protecting ball, and the ball of a sharp subsegment ab has radius
  // |ab| (make_protecting_balls), so near a long sharp edge the bound would go
  // unmet. A tet whose circumcenter z lies in that ball has a or b on or
  // outside its circumsphere, so its circumradius is at most |z - a| <= 1.5 |ab|:
  // splitting every sharp subsegment longer than 2/3 max_size, at its midpoint
  // as rule 1 does, keeps those tets within the bound. Conformity is restored
  // after each split. (Inside a vertex ball the circumradius stays at most the
  // ball's radius f(u)/4, which INITIALIZE fixes.)
  const double bound = 2.0 / 3.0 * opt_.max_size;
  // Each pass halves every sharp subsegment longer than the bound, so the
  // passes are at most log2(longest / bound) + 1: below kPasses for any two
  // positive doubles (their exponents span less than 2100).
  constexpr int kPasses = 2100;
  int passes = 0;
  for (bool again = true; again;) {
    if (++passes > kPasses)
      throw LoopBoundError("split_long_sharp_subsegments: more than " + std::to_string(kPasses) + " passes");
    again = false;
    std::vector<std::uint64_t> keys;
    for (const auto& [k, s] : sub_.subsegments())
      if (s.sharp && dist2(tri_.point(s.a), tri_.point(s.b)) > bound * bound) keys.push_back(k);
    std::sort(keys.begin(), keys.end());
    for (std::uint64_t k : keys) {
      const auto it = sub_.subsegments().find(k);
      if (it == sub_.subsegments().end()) continue;
      // Counted with rule 6, whose size bound this serves.
      if (ins_.insert(sub_.splite(it->second), Rule::rule6_split_skinny_tet) < 0) continue;
      again = true;
      if (!meter_.tick() || !queues_.process(ins_)) return false;
    }
  }
  return !meter_.stopped();
}

void Conform::make_protecting_balls() {
  std::vector<ProtectingBall> balls;
  for (int u = 0; u < static_cast<int>(dom_.p.vertices.size()); ++u)
    if (dom_.ball_radius[u] > 0) balls.push_back({dom_.p.vertices[u], dom_.ball_radius[u], true});
  // At the end of CONFORM, the diametric balls of sharp subsegments doubled.
  const std::vector<std::uint64_t> keys = sharp_subsegment_keys();
  for (std::uint64_t k : keys) {
    const Subsegment& s = sub_.subsegment(k);
    const Point3 &a = tri_.point(s.a), &b = tri_.point(s.b);
    balls.push_back({midpoint(a, b), std::sqrt(dist2(a, b)), false});
  }
  balls_.set(std::move(balls));
}

}  // namespace wqmesh::mesher
