// wqmesh: CONFORM (rules 1-3) and REFINE (rules 4-7) of WQMESH (paper,
// section 4.3). Rules are applied in priority order: a rule runs only when no
// rule with a smaller number applies. Work is driven by queues filled around
// every inserted vertex (the features an insertion can encroach or destroy are
// those of the cells it conflicts with, whose vertices become its neighbours).
// SPDX-License-Identifier: GPL-3.0-or-later
#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_set>

#include "mesher_state.h"
#include "wqmesh/quality.h"

namespace wqmesh::mesher {

namespace {

// The smallest dihedral angle of a tet, in degrees.
double min_dihedral(const RegularTriangulation& tri, const Tet& t) {
  return tet_quality(tri.point(t[0]), tri.point(t[1]), tri.point(t[2]), tri.point(t[3])).min_dihedral_deg;
}
}  // namespace

bool Mesher::tick() {
  ++steps_;
  step_done();
  if (steps_ % 256 == 0) next_poll_ = work_;  // a progress call at least every 256 steps
  return poll(0, false);
}

bool Mesher::poll(std::uint64_t units, bool in_step) {
  work_ += units;
  if (in_step) {
    step_work_ += units;
    if (step_work_ > opt_.stall_work && stop_reason_.empty()) {
      static const char* kNames[] = {"initialize", "conform", "refine", "pump", "done"};
      stop_reason_ = "stalled";
      stop_message_ = std::string("a step of ") + kNames[int(phase_)] + " (step " + std::to_string(steps_ + 1) +
                      ", at " + std::to_string(verts_.size()) + " vertices) did more than " +
                      std::to_string(opt_.stall_work) +
                      " units of work without finishing: the stuck-step watchdog ended the run";
    }
  }
  if (work_ >= next_poll_) {
    next_poll_ = work_ + kPollWork;
    report_progress();
  }
  return stop_reason_.empty();
}

RegularTriangulation::CellGraph Mesher::scan_cell_graph() {
  return tri_.cell_graph([this](std::size_t cells) { return poll(cells, false); });
}

void Mesher::report_progress() {
  if (progress_) {
    Progress p;
    p.phase = phase_ == Phase::conform ? "conform" : phase_ == Phase::refine ? "refine" : phase_ == Phase::pump ? "pump" : "initialize";
    p.vertices = verts_.size();
    p.steps = steps_;
    // Refinement has no known end; the fraction grows with the vertex count
    // towards the limit (an estimate), inside the phase's share of the run.
    const double base = phase_ == Phase::conform ? 0.05 : phase_ == Phase::refine ? 0.3 : 0.8;
    const double share = phase_ == Phase::conform ? 0.25 : phase_ == Phase::refine ? 0.5 : 0.15;
    p.fraction = base + share * (1 - 1 / (1 + double(steps_) / 20000));
    if (!progress_(p) && stop_reason_.empty()) stop_reason_ = "cancelled";
  }
}

void Mesher::enqueue_around(int v) {
  if (phase_ == Phase::initialize) return;
  // The star of v gives both its new cells and its neighbours.
  std::vector<Tet> cells;
  std::vector<CellRef> refs;
  tri_.incident_cells(v, cells, &refs);
  // The upkeep always completes (a stop is seen by the caller's loop).
  poll(cells.size());
  std::vector<int> ring;
  for (const Tet& c : cells)
    for (int x : c)
      if (x != kInfinite) ring.push_back(x);
  std::sort(ring.begin(), ring.end());
  ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
  auto in_ring = [&](int x) { return std::binary_search(ring.begin(), ring.end(), x); };
  // Subsegments: the new ones, and those the new vertex may encroach.
  for (int x : ring)
    for (std::uint64_t k : vertex_segs_[x]) {
      const Subsegment& s = segs_.at(k);
      if (in_ring(s.a) && in_ring(s.b)) seg_queue_.push_back(k);
    }
  // Subfacets: those with all vertices in the ring (new ones, and those the
  // vertex may encroach or remove from Del V).
  std::unordered_set<Tri, TriHash> seen;
  std::vector<int> fs;
  std::vector<Tri> around;
  // The subfacets at v are new (in its facets' planar triangulations) and
  // may be missing from Del V whatever their vertices. The cheap tests come
  // first: lies_in_facet runs once per candidate.
  auto consider = [&](int f, const Tri& t) {
    if (seen.insert(sorted(t)).second && lies_in_facet(f, t)) facet_queue_.push_back({f, t});
  };
  // A vertex of the ring may be the apex of a long fan in a facet (its far
  // edge split finely, as between nearly touching edges): walking its whole
  // star on every insertion nearby would make refinement quadratic, so its
  // triangles are then found from its edges to the other ring vertices.
  constexpr std::size_t kFan = 48;
  std::vector<Tri> pair;
  for (int x : ring) {
    facets_of(x, fs);
    for (int f : fs) {
      // v's own star is always walked whole.
      const std::size_t cap = x == v ? std::numeric_limits<std::size_t>::max() : kFan;
      poll(1);
      if (facet_dt_[f].incident_triangles(x, around, cap)) {
        poll(around.size());
        for (const Tri& t : around)
          if (x == v || (in_ring(t[0]) && in_ring(t[1]) && in_ring(t[2]))) consider(f, t);
        continue;
      }
      for (int y : ring) {
        if (y == x || y == v) continue;
        poll(1);
        facet_dt_[f].edge_triangles(x, y, pair);
        for (const Tri& t : pair)
          if (in_ring(t[0]) && in_ring(t[1]) && in_ring(t[2])) consider(f, t);
      }
    }
  }
  if (phase_ == Phase::refine)
    for (std::size_t i = 0; i < cells.size(); ++i)
      if (std::find(cells[i].begin(), cells[i].end(), kInfinite) == cells[i].end())
        tet_queue_.push_back({cells[i], refs[i]});
}

bool Mesher::process_queues(bool refine_phase) {
  // Bounded by the queues: each pass takes one element off a queue, and
  // elements are pushed only by insertions (at most a star's worth each, and
  // the vertex limit bounds the insertions) or again after one (at most
  // kRetries times per feature).
  while (stop_reason_.empty()) {
    step_done();  // each queue element is a step of the watchdog
    if (!poll(1)) break;
    if (!seg_queue_.empty()) {
      // Rule 1 / rule 4: split an encroached subsegment.
      const std::uint64_t k = seg_queue_.front();
      seg_queue_.pop_front();
      const auto it = segs_.find(k);
      if (it == segs_.end() || !segment_encroached(it->second)) continue;
      insert(splite(it->second), refine_phase ? 4 : 1);
      tick();
      continue;
    }
    if (!facet_queue_.empty()) {
      const Subfacet h = facet_queue_.front();
      facet_queue_.pop_front();
      if (!is_subfacet(h.facet, h.v)) continue;
      bool split;
      if (!refine_phase) {
        // Rule 2: a subfacet of B that is encroached, or one of the input
        // that does not appear in Del V.
        split = dom_.is_box_facet(h.facet) ? subfacet_encroached(h) : !subfacet_present(h);
      } else {
        // Rule 5: a non-guarded subfacet that is encroached, or a guarded one
        // that does not appear in Del V.
        split = guarded(h) ? !subfacet_present(h) : subfacet_encroached(h);
      }
      if (split) {
        // SPLITF may reject the circumcenter and split a subsegment instead;
        // then the subfacet is looked at again once that is done.
        const Insertion ins = splitf(h);
        if (insert(ins, refine_phase ? 5 : 2) >= 0 && ins.has_segment && ++retries_[sorted(h.v)] <= kRetries)
          facet_queue_.push_back(h);
        tick();
      }
      continue;
    }
    if (refine_phase && !tet_queue_.empty()) {
      const auto [t, ref] = tet_queue_.front();
      tet_queue_.pop_front();
      if (check_tet(t, ref)) tick();
      continue;
    }
    break;
  }
  return stop_reason_.empty();
}

bool Mesher::check_tet(const Tet& t, CellRef ref) {
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
  if (in_protecting_ball(z)) return false;
  // When ENCROACH rejects z for a point on a subsegment or subfacet, the tet
  // is looked at again afterwards (it may survive that insertion).
  const Insertion ins = encroach(z, t[0]);
  if (insert(ins, 6) < 0) return false;
  if (ins.on != On::free && ++retries_[sorted({{t[0], t[1], t[2]}})] <= kRetries) tet_queue_.push_back({t, ref});
  return true;
}

bool Mesher::rule3() {
  // Rule 3: the midpoint of a sharp subsegment s on edge e that encroaches a
  // subsegment or subfacet h, h and e in disjoint elements of P: split h.
  std::vector<std::uint64_t> keys;
  for (const auto& [k, s] : segs_)
    if (s.sharp) keys.push_back(k);
  std::sort(keys.begin(), keys.end());
  bool acted = false;
  std::vector<std::uint64_t> segs;
  std::vector<Subfacet> facets;
  for (std::uint64_t k : keys) {
    step_done();
    if (!poll(1)) break;
    const auto it = segs_.find(k);
    if (it == segs_.end()) continue;
    const Subsegment s = it->second;
    const int ea = dom_.p.edges[s.edge].a, eb = dom_.p.edges[s.edge].b;
    const Point3 m = midpoint(tri_.point(s.a), tri_.point(s.b));
    encroached_by_point(m, s.a, segs, facets);
    auto disjoint_facet = [&](int f) { return !dom_.facet_has_vertex(f, ea) && !dom_.facet_has_vertex(f, eb); };
    Insertion ins;
    bool found = false;
    for (std::uint64_t g : segs) {
      if (g == k) continue;
      const Subsegment& gs = segs_.at(g);
      const bool disjoint =
          gs.sector >= 0 ? disjoint_facet(sectors_[gs.sector].facet)
                         : (gs.edge != s.edge && dom_.p.edges[gs.edge].a != ea && dom_.p.edges[gs.edge].a != eb &&
                            dom_.p.edges[gs.edge].b != ea && dom_.p.edges[gs.edge].b != eb);
      if (disjoint) {
        ins = splite(gs);
        found = true;
        break;
      }
    }
    if (!found)
      for (const Subfacet& h : facets)
        if (disjoint_facet(h.facet)) {
          ins = splitf(h);
          found = true;
          break;
        }
    if (found && insert(ins, 3) >= 0) {
      acted = true;
      tick();
      if (!process_queues(false)) break;
    }
  }
  return acted;
}

void Mesher::conform() {
  phase_ = Phase::conform;
  for (const auto& [k, s] : segs_) seg_queue_.push_back(k);
  for (const Subfacet& h : subfacets()) facet_queue_.push_back(h);
  std::sort(seg_queue_.begin(), seg_queue_.end());
  if (!process_queues(false)) return;
  if (opt_.max_size > 0 && !split_long_sharp_subsegments()) return;
  // Rule 3 passes until one inserts nothing, at most kRule3Passes.
  constexpr int kRule3Passes = 1000;
  for (int passes = 0; stop_reason_.empty() && passes < kRule3Passes && rule3(); ++passes) {
  }
  make_protecting_balls();
}

bool Mesher::split_long_sharp_subsegments() {
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
    for (const auto& [k, s] : segs_)
      if (s.sharp && dist2(tri_.point(s.a), tri_.point(s.b)) > bound * bound) keys.push_back(k);
    std::sort(keys.begin(), keys.end());
    for (std::uint64_t k : keys) {
      const auto it = segs_.find(k);
      if (it == segs_.end()) continue;
      // Counted with rule 6, whose size bound this serves.
      if (insert(splite(it->second), 6) < 0) continue;
      again = true;
      if (!tick() || !process_queues(false)) return false;
    }
  }
  return stop_reason_.empty();
}

std::vector<char> Mesher::interior_labels(const RegularTriangulation::CellGraph& g, bool scan) {
  // Flood fill from the infinite cells; the subfacets of input facets are the
  // walls.
  std::unordered_set<Tri, TriHash> walls;
  for (const Subfacet& h : subfacets())
    if (!dom_.is_box_facet(h.facet)) walls.insert(sorted(h.v));
  // Crossing a wall flips inside and outside (a polyhedron may have several
  // shells). 1 = inside.
  std::vector<char> label(g.cells.size(), 2);  // 2 = unknown
  std::vector<int> stack;
  for (std::size_t i = 0; i < g.cells.size(); ++i)
    if (std::find(g.cells[i].begin(), g.cells[i].end(), kInfinite) != g.cells[i].end()) {
      label[i] = 0;
      stack.push_back(static_cast<int>(i));
    }
  // Each cell is pushed once (labelled when pushed): at most |cells| pops.
  while (!stack.empty()) {
    if (scan && !poll(1, false)) return label;
    const int c = stack.back();
    stack.pop_back();
    for (int k = 0; k < 4; ++k) {
      const int n = g.neighbor[c][k];
      if (label[n] != 2) continue;
      const Tet& t = g.cells[c];
      const Tri f = sorted({{t[(k + 1) % 4], t[(k + 2) % 4], t[(k + 3) % 4]}});
      label[n] = walls.count(f) ? char(1 - label[c]) : label[c];
      stack.push_back(n);
    }
  }
  // Flat tets lying in an input facet pass the labels on correctly whatever
  // their own label; they belong to neither side and are left out.
  for (std::size_t i = 0; i < g.cells.size(); ++i)
    if (label[i] == 1 && flat_on_facet(g.cells[i])) label[i] = 0;
  return label;
}

bool Mesher::flat_on_facet(const Tet& t) const {
  if (std::find(t.begin(), t.end(), kInfinite) != t.end()) return false;
  std::vector<int> common, fs;
  facets_of(t[0], common);
  for (int k = 1; k < 4 && !common.empty(); ++k) {
    facets_of(t[k], fs);
    common.erase(std::remove_if(common.begin(), common.end(),
                                [&](int f) { return std::find(fs.begin(), fs.end(), f) == fs.end(); }),
                 common.end());
  }
  for (int f : common)
    if (!dom_.is_box_facet(f)) return true;
  return false;
}

bool Mesher::rule7_pass() {
  // Rule 7: for a vertex v of a tet with a dihedral angle of theta or less,
  // weighted with N(v)^2/9, unless it encroaches the two-times expansion of a
  // protecting ball: (i) split a subsegment it encroaches; (ii) split the
  // non-guarded subfacet it encroaches that contains its projection; (iii)
  // split a guarded subfacet it removes from the weighted Delaunay
  // triangulation. Only tets inside the polyhedron are considered (those
  // outside are discarded at the end), and the features examined are those
  // incident to v and to its neighbours (a choice: the paper does not say how
  // far to look).
  const RegularTriangulation::CellGraph g = scan_cell_graph();
  if (stopped()) return false;
  const std::vector<char> inside = interior_labels(g, true);
  if (stopped()) return false;
  std::vector<std::pair<double, int>> candidates;
  for (std::size_t i = 0; i < g.cells.size(); ++i) {
    if (!poll(1, false)) return false;
    if (!inside[i] || std::find(g.cells[i].begin(), g.cells[i].end(), kInfinite) != g.cells[i].end()) continue;
    const double angle = min_dihedral(tri_, g.cells[i]);
    if (angle <= opt_.theta_deg)
      for (int v : g.cells[i]) candidates.push_back({angle, v});
  }
  std::sort(candidates.begin(), candidates.end());
  std::vector<char> done(verts_.size(), 0);
  bool acted = false;
  std::vector<int> ring, fs;
  std::vector<Tri> around;
  for (const auto& [angle, v] : candidates) {
    step_done();  // each candidate is a step of the watchdog
    if (!poll(1)) break;
    if (done[v]) continue;
    done[v] = 1;
    const Point3 pv = tri_.point(v);
    const double nv = nearest_neighbour(v);
    const double w = nv * nv / 9;
    if (encroaches_expanded_ball(pv, w)) continue;
    tri_.adjacent_vertices(v, ring);
    ring.push_back(v);
    poll(ring.size());
    // (i) subsegments: power distance to the diametric ball <= 0.
    std::vector<std::uint64_t> seg_keys;
    for (int x : ring)
      for (std::uint64_t k : vertex_segs_[x]) seg_keys.push_back(k);
    std::sort(seg_keys.begin(), seg_keys.end());
    seg_keys.erase(std::unique(seg_keys.begin(), seg_keys.end()), seg_keys.end());
    bool has = false;
    Insertion ins;
    for (std::uint64_t k : seg_keys) {
      const Subsegment& s = segs_.at(k);
      if (s.in_ball || s.a == v || s.b == v) continue;
      const Point3 &a = tri_.point(s.a), &b = tri_.point(s.b);
      if (dist2(pv, midpoint(a, b)) - w - 0.25 * dist2(a, b) <= 0) {
        ins = splite(s);
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
        facets_of(x, fs);
        for (int f : fs) {
          subfacets_at(f, x, around);
          for (const Tri& t : around) {
            if (!seen.insert(sorted(t)).second) continue;
            if (t[0] == v || t[1] == v || t[2] == v) continue;
            const Subfacet h{f, t};
            double r2;
            const Point3 cc = circumcenter(tri_.point(t[0]), tri_.point(t[1]), tri_.point(t[2]), r2);
            if (!guarded(h)) {
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
        ins = splitf(*pick);
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
          ins = splitf(*removed);
          has = true;
        }
      }
    }
    if (has && insert(ins, 7) >= 0) {
      acted = true;
      tick();
      if (!process_queues(true)) break;
    }
  }
  return acted;
}

void Mesher::refine() {
  phase_ = Phase::refine;
  for (const auto& [k, s] : segs_) seg_queue_.push_back(k);
  std::sort(seg_queue_.begin(), seg_queue_.end());
  for (const Subfacet& h : subfacets()) facet_queue_.push_back(h);
  {
    std::vector<Tet> cells;
    std::vector<CellRef> refs;
    tri_.finite_cells(cells, refs);
    for (std::size_t i = 0; i < cells.size(); ++i) tet_queue_.push_back({cells[i], refs[i]});
  }
  if (!process_queues(true)) return;
  if (!opt_.pump) return;
  // Rule 7 passes until one inserts nothing, at most kRule7Passes.
  constexpr int kRule7Passes = 100;
  for (int pass = 0; pass < kRule7Passes && stop_reason_.empty(); ++pass)
    if (!rule7_pass()) break;
}

}  // namespace wqmesh::mesher
