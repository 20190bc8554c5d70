// wqmesh: the work queues of CONFORM and REFINE (paper, section 4.3), filled
// around every inserted vertex, and the loop that applies the queued rules in
// priority order (rules 1-2 in CONFORM, 4-6 in REFINE).
// SPDX-License-Identifier: GPL-3.0-or-later
#include <algorithm>
#include <limits>
#include <unordered_set>

#include "mesher/queues.h"

#include "mesher/mesher.h"
#include "wqmesh/quality.h"

namespace wqmesh::mesher {

void Queues::queue(std::uint64_t k, const Subsegment& s, int by) {
  segments_.push_back(k);
  s.queued_at = static_cast<std::uint32_t>(tri_.number_of_vertices());
  if (by >= 0 && !s.ball_entered && sub_.counts_for_segment(s, by)) s.ball_entered = true;
}

void Queues::push_segment(std::uint64_t k) { queue(k, sub_.subsegment(k), -1); }

void Queues::fill(bool tets) {
  for (const auto& [k, s] : sub_.subsegments()) queue(k, s, -1);
  std::sort(segments_.begin(), segments_.end());
  for (const Subfacet& h : sub_.subfacets()) queue_subfacet(h);
  if (tets) {
    std::vector<Tet> cells;
    std::vector<CellRef> refs;
    tri_.finite_cells(cells, refs);
    for (std::size_t i = 0; i < cells.size(); ++i) tets_.push_back({cells[i], refs[i]});
  }
}

void Queues::queue_subfacet(const Subfacet& h) { subfacets_.push_back({h, sub_.facet_triangulation(h.facet).size()}); }

void Queues::enqueue_around(int v) {
  if (meter_.phase() == Phase::initialize) return;
  if (meter_.phase() == Phase::refine && !sub_.on_p(v))
    if (const std::vector<Tet>* cavity = tri_.last_cavity()) {
      enqueue_from_cavity(v, *cavity);
      return;
    }
  // The star of v gives both its new cells and its neighbours. (The buffers
  // are members, kept from call to call: no allocation per insertion.)
  std::vector<Tet>& cells = star_;
  std::vector<CellRef>& refs = star_refs_;
  tri_.incident_cells(v, cells, &refs);
  // The upkeep always completes (a stop is seen by the caller's loop).
  meter_.poll(cells.size());
  // The ring (v and its neighbours), sorted, and marked in ring_mark_ with
  // a stamp of this call: in_ring is O(1) (a binary search of the ring was a
  // tenth of a run; issue 15).
  // The marks also drop the repeats (each vertex is in several cells)
  // before the sort.
  std::vector<int>& ring = ring_;
  ring.clear();
  if (ring_mark_.size() < std::size_t(tri_.number_of_vertices())) ring_mark_.resize(tri_.number_of_vertices(), 0);
  if (++stamp_ == 0) {  // wrapped: no old stamp may match
    std::fill(ring_mark_.begin(), ring_mark_.end(), 0);
    stamp_ = 1;
  }
  for (const Tet& c : cells)
    for (int x : c)
      if (x != kInfinite && ring_mark_[x] != stamp_) {
        ring_mark_[x] = stamp_;
        ring.push_back(x);
      }
  std::sort(ring.begin(), ring.end());
  auto in_ring = [&](int x) { return ring_mark_[x] == stamp_; };
  // Subsegments: the new ones, and those the new vertex may encroach. The
  // key names both ends (edge_key), so the test needs no look-up. Every
  // insertion that changes the cells around a subsegment ab has a and b in
  // its ring (they are vertices of a destroyed cell, so on the boundary of
  // the cavity, so adjacent to v), so it queues ab here: what
  // split_encroached_subsegment's record of the last test relies on.
  for (int x : ring)
    for (std::uint64_t k : sub_.subsegments_at(x))
      if (in_ring(int(k >> 32)) && in_ring(int(k & 0xFFFFFFFFu))) queue(k, sub_.subsegment(k), v);
  // Subfacets: those with all vertices in the ring (new ones, and those the
  // vertex may encroach or remove from Del V).
  // `seen`: the triangles considered so far, sorted (a few dozen: a sorted
  // vector costs less than a hash set's node per entry; issue 15).
  std::vector<Tri>& seen = seen_;
  std::vector<int>& fs = fs_;
  std::vector<Tri>& around = around_;
  seen.clear();
  // The subfacets at v are new (in its facets' planar triangulations) and
  // may be missing from Del V whatever their vertices. The cheap tests come
  // first: lies_in_facet runs once per candidate.
  auto consider = [&](int f, const Tri& t) {
    const Tri s = sorted(t);
    const auto at = std::lower_bound(seen.begin(), seen.end(), s);
    if (at != seen.end() && *at == s) return;
    seen.insert(at, s);
    if (sub_.lies_in_facet(f, t)) queue_subfacet({f, t});
  };
  // A vertex of the ring may be the apex of a long fan in a facet (its far
  // edge split finely, as between nearly touching edges): walking its whole
  // star on every insertion nearby would make refinement quadratic, so its
  // triangles are then found from its edges to the other ring vertices
  // (kFan).
  std::vector<Tri>& pair = pair_;
  // The ring vertices on P with their facets, in the ring's order, and which
  // ring vertices each facet holds (only the vertices whose facets_of holds f
  // are in f's planar triangulation).
  std::vector<std::pair<int, int>>& on_facets = ring_facets_;
  std::vector<std::pair<int, int>>& facet_list = ring_facet_list_;
  on_facets.clear();
  facet_list.clear();
  for (int x : ring) {
    if (!sub_.on_p(x)) continue;
    sub_.facets_of(x, fs);
    for (int f : fs) {
      on_facets.push_back({x, f});
      facet_list.push_back({f, x});
    }
  }
  // facet_list holds (facet, ring vertex) pairs, sorted: the ring vertices of
  // facet f with ids above x are counted by a binary search.
  std::sort(facet_list.begin(), facet_list.end());
  auto ring_vertices_above = [&](int f, int x) {
    return std::upper_bound(facet_list.begin(), facet_list.end(), std::pair{f, std::numeric_limits<int>::max()}) -
           std::upper_bound(facet_list.begin(), facet_list.end(), std::pair{f, x});
  };
  // The walk at a ring vertex x other than v looks only for the triangles of
  // f whose smallest id is x (beyond the paper, issue 15, step 5): a triangle
  // of f with every vertex in the ring is first met at its smallest vertex,
  // which comes first in the ring's order (sorted by id), and that walk is
  // never skipped; at a larger vertex it is a repeat that `seen` would drop.
  // So the walk at x is skipped when f holds fewer than two ring vertices
  // above x (no such triangle), and the edge walks of a fan apex x go to the
  // ring vertices above x only. The same triangles are considered, in the
  // same order, as by walking every star; v's star is walked whole, as its
  // triangles are new whatever their vertices.
  auto starts_at = [](int x, const Tri& t) { return t[0] >= x && t[1] >= x && t[2] >= x; };
  for (const auto& [x, f] : on_facets) {
    if (x != v && ring_vertices_above(f, x) < 2) continue;
    // v's own star is always walked whole.
    const std::size_t cap = x == v ? std::numeric_limits<std::size_t>::max() : kFan;
    meter_.poll(1);
    if (sub_.facet_triangulation(f).incident_triangles(x, around, cap)) {
      meter_.poll(around.size());
      for (const Tri& t : around)
        if (x == v || (starts_at(x, t) && in_ring(t[0]) && in_ring(t[1]) && in_ring(t[2]))) consider(f, t);
      continue;
    }
    for (int y : ring) {
      if (y <= x || y == v || !sub_.on_p(y)) continue;  // a free y is in no facet
      meter_.poll(1);
      sub_.facet_triangulation(f).edge_triangles(x, y, pair);
      for (const Tri& t : pair)
        if (starts_at(x, t) && in_ring(t[0]) && in_ring(t[1]) && in_ring(t[2])) consider(f, t);
    }
  }
  if (meter_.phase() == Phase::refine) queue_finite_cells(cells, refs);
}

void Queues::enqueue_from_cavity(int v, const std::vector<Tet>& cavity) {
  // Beyond the paper (issue 15, step 6): the upkeep of a free vertex v (rule
  // 6's circumcenter, most of REFINE's insertions) from the cells its
  // insertion destroyed, instead of the subsegments and facet stars of its
  // whole ring. Why that queues every feature a rule may now have to split:
  // - A subsegment or subfacet whose cells changed is an edge or triangle
  //   of a destroyed cell (the cells around it are those holding it), with
  //   every vertex on P: all of those are queued, so the record of the last
  //   rule 4 test (Subsegment::queued_at) stays valid as enqueue_around
  //   keeps it.
  // - One v encroaches is too: when no feature was encroached by a vertex,
  //   a point inside a feature's diametric ball conflicts with a cell
  //   holding it (the pencil argument of Subcomplex::encroached_by_point).
  // - A feature that stays in Del V and that v does not encroach needs no
  //   new split (v, being free, adds no subfacet or subsegment).
  // What enqueue_around also queued, the features with every vertex in the
  // ring but outside the cavity, are unchanged by v; only a feature left
  // needing a split before v (a split SPLITF refused) was tried again there.
  std::vector<Tet>& cells = star_;
  std::vector<CellRef>& refs = star_refs_;
  tri_.incident_cells(v, cells, &refs);
  meter_.poll(cells.size() + cavity.size());
  // The cavity's subsegments (in key order) and its triangles with every
  // vertex on P and a facet holding them (sorted, no repeats): kept by
  // ENCROACH when it searched this very zone (Subcomplex::zone_features,
  // issue 15), else read from the cavity here.
  std::vector<const Subsegment*>& segs = cavity_segs_;
  segs.clear();
  const Subcomplex::ZoneFeatures* kept = sub_.zone_features(tri_.point(v), cavity);
  if (kept) {
    segs = kept->segments;
  } else {
    std::vector<std::uint64_t>& edges = cavity_edges_;
    std::vector<Tri>& tris = cavity_tris_;
    edges.clear();
    tris.clear();
    sub_.on_p_features(cavity, edges, tris);
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    // One look-up per key: the subsegment found is kept (the map's nodes
    // stay where they are until the next insertion).
    for (std::uint64_t k : edges) {
      const auto it = sub_.subsegments().find(k);
      if (it != sub_.subsegments().end()) segs.push_back(&it->second);
    }
    std::sort(tris.begin(), tris.end());
    tris.erase(std::unique(tris.begin(), tris.end()), tris.end());
  }
  const std::vector<Tri>& tris = kept ? kept->tris : cavity_tris_;
  // The features are queued in the order enqueue_around's walk of the ring
  // meets them (so that the rules split the same ones first): a subsegment
  // ab (a < b) at a, in the order of subsegments_at(a); a subfacet at its
  // smallest vertex x, by f's place in facets_of(x) and then the triangle's
  // place in x's star in f (or, for a fan apex, along its edges to the ring
  // vertices in id order).
  if (!segs.empty()) {
    auto& order = cavity_order_;
    order.clear();
    for (const Subsegment* s : segs) {
      const std::uint64_t k = edge_key(s->a, s->b);
      const int a = int(k >> 32);  // the smaller end
      const std::vector<std::uint64_t>& at = sub_.subsegments_at(a);
      const auto pos = std::find(at.begin(), at.end(), k) - at.begin();
      order.push_back({{a, int(pos), 0}, order.size()});
    }
    std::sort(order.begin(), order.end());
    for (const auto& o : order) {
      const Subsegment& s = *segs[o.second];
      queue(edge_key(s.a, s.b), s, v);
    }
  }
  if (!tris.empty()) {
    std::vector<int>& fs = fs_;
    std::vector<Tri>& pair = pair_;
    std::vector<int>&f1 = f1_, &f2 = f2_;
    auto& order = cavity_order_;
    order.clear();
    std::vector<Subfacet>& found = cavity_subfacets_;
    found.clear();
    for (const Tri& t : tris) {
      sub_.facets_of(t[0], fs);
      if (fs.empty()) continue;
      sub_.facets_of(t[1], f1);
      sub_.facets_of(t[2], f2);
      for (std::size_t fi = 0; fi < fs.size(); ++fi) {
        const int f = fs[fi];
        if (std::find(f1.begin(), f1.end(), f) == f1.end() || std::find(f2.begin(), f2.end(), f) == f2.end()) continue;
        // The triangle as f's planar triangulation holds it (its rotation
        // is the subfacet's, as the walk of enqueue_around gives it).
        meter_.poll(1);
        Tri u;
        if (sub_.facet_triangulation(f).find_triangle(t[0], t[1], t[2], u) && sub_.lies_in_facet(f, u)) {
          order.push_back({{t[0], int(fi), 0}, found.size()});
          found.push_back({f, u});
        }
      }
    }
    // The place in the star matters only between subfacets of one facet at
    // one smallest vertex (rare: a cavity at the boundary holds one or two).
    std::sort(order.begin(), order.end());
    std::vector<Tri>& around = around_;
    for (std::size_t i = 0; i + 1 < order.size(); ++i) {
      if (order[i].first != order[i + 1].first) continue;
      std::size_t j = i;
      while (j < order.size() && order[j].first == order[i].first) ++j;
      const int x = order[i].first[0], f = found[order[i].second].facet;
      const bool star = sub_.facet_triangulation(f).incident_triangles(x, around, kFan);
      for (std::size_t m = i; m < j; ++m) {
        const Tri s = sorted(found[order[m].second].v);
        int rank = 0;
        if (star) {
          meter_.poll(around.size());
          for (const Tri& u : around) {
            if (sorted(u) == s) break;
            ++rank;
          }
        } else {
          // A fan apex: met along its edge to the smaller other vertex
          // (s[1]), in the order edge_triangles gives.
          sub_.facet_triangulation(f).edge_triangles(x, s[1], pair);
          rank = s[1] * 2;
          if (!pair.empty() && sorted(pair[0]) != s) ++rank;
        }
        order[m].first[2] = rank;
      }
      std::sort(order.begin() + long(i), order.begin() + long(j));
      i = j - 1;
    }
    for (const auto& o : order) queue_subfacet(found[o.second]);
  }
  queue_finite_cells(cells, refs);
}

void Queues::queue_finite_cells(const std::vector<Tet>& cells, const std::vector<CellRef>& refs) {
  for (std::size_t i = 0; i < cells.size(); ++i)
    if (std::find(cells[i].begin(), cells[i].end(), kInfinite) == cells[i].end()) tets_.push_back({cells[i], refs[i]});
}

bool Queues::process(Inserter& inserter, const Rule6& rule6) {
  const bool refine_phase = static_cast<bool>(rule6);
  // Bounded by the queues: each pass takes one element off a queue, and
  // elements are pushed only by insertions (at most a star's worth each, and
  // the vertex limit bounds the insertions) or again after one (at most
  // Caps::kRetries times per feature).
  while (!meter_.stopped()) {
    meter_.step_done();  // each queue element is a step of the watchdog
    if (!meter_.poll(1)) break;
    if (!segments_.empty()) {
      const std::uint64_t k = segments_.front();
      segments_.pop_front();
      split_encroached_subsegment(
          inserter, k,
          refine_phase ? Rule::rule4_split_encroached_subsegment : Rule::rule1_split_encroached_subsegment);
      continue;
    }
    if (!subfacets_.empty()) {
      const QueuedSubfacet q = subfacets_.front();
      subfacets_.pop_front();
      const Subfacet& h = q.h;
      // Still a subfacet when its facet's planar triangulation is the one
      // it was queued from (QueuedSubfacet::facet_size), else by the walk.
      if (q.facet_size != sub_.facet_triangulation(h.facet).size() && !sub_.is_subfacet(h.facet, h.v)) continue;
      if (!refine_phase && rule2_needs_split(h))
        split_subfacet(inserter, h, Rule::rule2_split_missing_subfacet);
      else if (refine_phase && rule5_needs_split(h))
        split_subfacet(inserter, h, Rule::rule5_split_encroached_subfacet);
      continue;
    }
    if (refine_phase && !tets_.empty()) {
      // The queue's cells are read in order, long after they were queued:
      // fetched ahead (issue 15; no effect on any answer).
      constexpr std::size_t kAhead = 8;
      if (tets_.size() > kAhead) tri_.prefetch(tets_[kAhead].first, tets_[kAhead].second, 0);
      if (tets_.size() > kAhead / 2) tri_.prefetch(tets_[kAhead / 2].first, tets_[kAhead / 2].second, 1);
      const auto [t, ref] = tets_.front();
      tets_.pop_front();
      if (rule6(t, ref)) meter_.tick();
      continue;
    }
    break;
  }
  return !meter_.stopped();
}

void Queues::split_encroached_subsegment(Inserter& inserter, std::uint64_t k, Rule rule) {
  const auto it = sub_.subsegments().find(k);
  if (it == sub_.subsegments().end()) return;
  // The answer of a test made after the last queueing of k still holds
  // (Subsegment::queued_at): the cells around it are the same.
  const Subsegment& s = it->second;
  if (s.tested_at == 0 || s.tested_at < s.queued_at) {
    s.encroached = sub_.segment_encroached_update(s);
    s.tested_at = static_cast<std::uint32_t>(tri_.number_of_vertices());
    s.ball_entered = false;
  }
  if (!s.encroached) return;
  inserter.insert(sub_.splite(s), rule);
  meter_.tick();
}

bool Queues::rule2_needs_split(const Subfacet& h) const {
  return dom_.is_box_facet(h.facet) ? sub_.subfacet_encroached(h) : !sub_.subfacet_present(h);
}

bool Queues::rule5_needs_split(const Subfacet& h) const {
  // Rule 5 splits a guarded subfacet when it is missing from Del V, a
  // non-guarded one when it is missing or encroached: so a missing h needs
  // a split and a present one that no vertex encroaches does not, whatever
  // guarded(h) says, and guarded(h) (a search of the protecting balls'
  // grid, 3-4% of REFINE when asked first for every test; issue 15) is
  // asked only of a present, encroached h. The same answer as asking it
  // first.
  bool missing = false;
  return sub_.subfacet_encroached(h, &missing) && (missing || !sub_.guarded(h));
}

void Queues::split_subfacet(Inserter& inserter, const Subfacet& h, Rule rule) {
  // SPLITF may reject the circumcenter and split a subsegment instead; then
  // the subfacet is looked at again once that is done.
  const Insertion ins = sub_.splitf(h);
  // (The insertion may have changed h's facet: its size is not recorded.)
  if (inserter.insert(ins, rule) >= 0 && ins.has_segment && may_retry(h.v)) subfacets_.push_back({h, kUnknownSize});
  meter_.tick();
}

bool Queues::SliverRecord::update(const RegularTriangulation& tri, double theta_deg,
                                  std::vector<std::pair<double, int>>& candidates,
                                  const std::function<bool(std::size_t)>& poll) {
  // Why the stars of the new vertices and the recorded cells that live on
  // suffice: a cell that lived at the last update lives on unchanged (its
  // angle too) or was destroyed, and its slot, if reused, holds a cell of a
  // newer vertex (the insertions hide no vertex), which is_cell(t, ref)
  // tells apart; every cell made since holds a vertex inserted since, in
  // whose star it is, and is met there once, at the smallest such vertex.
  // The labels are read from the cells as they are now.
  std::vector<Cell> next;
  const auto note = [&](const Tet& t, CellRef ref, char label, double angle) {
    next.push_back({t, ref, angle});
    if (label == 1)
      for (int v : t) candidates.push_back({angle, v});
  };
  const auto angle_of = [&](const Tet& t) {
    return tet_min_dihedral_deg_upto(tri.point(t[0]), tri.point(t[1]), tri.point(t[2]), tri.point(t[3]), theta_deg);
  };
  const auto finite = [](const Tet& t) { return std::find(t.begin(), t.end(), kInfinite) == t.end(); };
  const int n = tri.number_of_vertices();
  const bool incremental = valid;
  valid = false;
  if (incremental) {
    for (const Cell& c : cells) {
      if (!poll(1)) return false;
      if (tri.is_cell(c.t, c.ref)) note(c.t, c.ref, tri.label(c.ref), c.angle);
    }
    std::vector<Tet> star;
    std::vector<CellRef> refs;
    for (int v = vertices; v < n; ++v) {
      tri.incident_cells(v, star, &refs);
      if (!poll(star.size())) return false;
      for (std::size_t i = 0; i < star.size(); ++i) {
        const Tet& t = star[i];
        if (!finite(t)) continue;
        int first = n;
        for (int x : t)
          if (x >= vertices) first = std::min(first, x);
        if (first != v) continue;
        const double angle = angle_of(t);
        if (angle <= theta_deg) note(t, refs[i], tri.label(refs[i]), angle);
      }
    }
  } else {
    const auto visit = [&](const Tet& t, CellRef ref, char label) {
      if (!finite(t)) return;
      const double angle = angle_of(t);
      if (angle <= theta_deg) note(t, ref, label, angle);
    };
    if (!tri.visit_cells(visit, poll)) return false;
  }
  cells.swap(next);
  vertices = n;
  valid = true;
  return true;
}

bool Queues::may_retry(const Tri& t) {
  if (++retries_[sorted(t)] <= Caps::kRetries) return true;
  meter_.cap_reached();
  return false;
}

}  // namespace wqmesh::mesher
