// wqmesh: the work queues of CONFORM and REFINE (paper, section 4.3), filled
// around every inserted vertex, and the loop that applies the queued rules in
// priority order (rules 1-2 in CONFORM, 4-6 in REFINE).
// SPDX-License-Identifier: GPL-3.0-or-later
#include <algorithm>
#include <limits>
#include <unordered_set>

#include "mesher/mesher.h"

namespace wqmesh::mesher {

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
      if (in_ring(s.a) && in_ring(s.b)) queues_.segments.push_back(k);
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
    if (seen.insert(sorted(t)).second && lies_in_facet(f, t)) queues_.subfacets.push_back({f, t});
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
        queues_.tets.push_back({cells[i], refs[i]});
}

bool Mesher::process_queues(bool refine_phase) {
  // Bounded by the queues: each pass takes one element off a queue, and
  // elements are pushed only by insertions (at most a star's worth each, and
  // the vertex limit bounds the insertions) or again after one (at most
  // Caps::kRetries times per feature).
  while (stop_reason_.empty()) {
    step_done();  // each queue element is a step of the watchdog
    if (!poll(1)) break;
    if (!queues_.segments.empty()) {
      const std::uint64_t k = queues_.segments.front();
      queues_.segments.pop_front();
      split_encroached_subsegment(
          k, refine_phase ? Rule::rule4_split_encroached_subsegment : Rule::rule1_split_encroached_subsegment);
      continue;
    }
    if (!queues_.subfacets.empty()) {
      const Subfacet h = queues_.subfacets.front();
      queues_.subfacets.pop_front();
      if (!is_subfacet(h.facet, h.v)) continue;
      if (!refine_phase && rule2_needs_split(h))
        split_subfacet(h, Rule::rule2_split_missing_subfacet);
      else if (refine_phase && rule5_needs_split(h))
        split_subfacet(h, Rule::rule5_split_encroached_subfacet);
      continue;
    }
    if (refine_phase && !queues_.tets.empty()) {
      const auto [t, ref] = queues_.tets.front();
      queues_.tets.pop_front();
      if (rule6_split_skinny_tet(t, ref)) tick();
      continue;
    }
    break;
  }
  return stop_reason_.empty();
}

void Mesher::split_encroached_subsegment(std::uint64_t k, Rule rule) {
  const auto it = segs_.find(k);
  if (it == segs_.end() || !segment_encroached(it->second)) return;
  insert(splite(it->second), rule);
  tick();
}

bool Mesher::rule2_needs_split(const Subfacet& h) const {
  return dom_.is_box_facet(h.facet) ? subfacet_encroached(h) : !subfacet_present(h);
}

bool Mesher::rule5_needs_split(const Subfacet& h) const {
  return guarded(h) ? !subfacet_present(h) : subfacet_encroached(h);
}

void Mesher::split_subfacet(const Subfacet& h, Rule rule) {
  // SPLITF may reject the circumcenter and split a subsegment instead; then
  // the subfacet is looked at again once that is done.
  const Insertion ins = splitf(h);
  if (insert(ins, rule) >= 0 && ins.has_segment) {
    if (++retries_[sorted(h.v)] <= Caps::kRetries)
      queues_.subfacets.push_back(h);
    else
      ++caps_reached;
  }
  tick();
}

}  // namespace wqmesh::mesher
