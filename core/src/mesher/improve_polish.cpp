// wqmesh: the improvement phase's polish (beyond the paper, and beyond
// Stellar, whose objective is the worst min-sine alone): after the passes,
// rounds on the tets whose smallest dihedral angle is nearest the mesh's
// smallest, under a floor that keeps the mesh's smallest dihedral angle from
// ever dropping. See improve.h, the block "Polish", for the contract.
//
// Why (issue 14, slit.off): the passes work on the tets below
// kImproveTargetDeg (20 degrees) by min-sine; slit's smallest angle was 18.52
// where TetGen reaches 27.54. Raising the passes' target to 30 made it worse
// (16.1: a higher min-sine of a star can come with a smaller dihedral angle
// in it), hence the dihedral floor here; the in-plane slides of
// improve_boundary.cpp run only under it.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <algorithm>
#include <cmath>

#include "geometry.h"
#include "mesher/improve.h"
#include "wqmesh/quality.h"

namespace wqmesh::mesher {

bool Improver::polish_admits(const Tet& T) const {
  // A min-sine above sin(floor) puts every dihedral angle in (floor, 180 - floor).
  if (min_sine(P_[T[0]], P_[T[1]], P_[T[2]], P_[T[3]]) > polish_floor_sine_) return true;
  return tet_min_dihedral_deg(P_[T[0]], P_[T[1]], P_[T[2]], P_[T[3]]) > polish_floor_deg_;
}

bool Improver::polish_room(std::size_t old_tets, std::size_t new_tets) const {
  return new_tets <= old_tets || tets_.size() - free_slots_.size() + (new_tets - old_tets) <= polish_cap_;
}

double Improver::smallest_dihedral_deg() const {
  // The smallest dihedral angle D0 of the tet of the smallest min-sine
  // bounds the search: a tet whose min-sine is above sin(D0) has no angle
  // below D0 (mesh_worst() measures every tet).
  int first = -1;
  for (std::size_t t = 0; t < tets_.size(); ++t)
    if (alive(int(t)) && (first < 0 || q_[t] < q_[first])) first = int(t);
  if (first < 0) return 180;
  const auto angle = [&](std::size_t t) {
    const Tet& T = tets_[t];
    return tet_min_dihedral_deg(P_[T[0]], P_[T[1]], P_[T[2]], P_[T[3]]);
  };
  double D = angle(std::size_t(first));
  const double bound = std::sin(D * geometry::kPi / 180);
  for (std::size_t t = 0; t < tets_.size(); ++t)
    if (alive(int(t)) && q_[t] <= bound) D = std::min(D, angle(t));
  return D;
}

std::size_t Improver::polish(double work_per_tet) {
  if (!(work_per_tet > 0)) return 0;
  polish_cap_ = tets_.size() - free_slots_.size();
  // The budget: operations tried (flips of a tet, smoothing or contraction of
  // a vertex), per live tet.
  const double budget = work_per_tet * double(polish_cap_);
  double work = 0;
  std::size_t n = 0;
  double last = -HUGE_VAL;
  int stalls = 0;
  for (int round = 0; round < kPolishRounds && poll(); ++round) {
    const double D = smallest_dihedral_deg();
    if (D < last + kPolishRiseDeg) {
      if (++stalls >= kPolishStalls) break;
    } else {
      stalls = 0;
    }
    last = D;
    // The kPolishTets tets of the smallest angles below D + kPolishBandDeg
    // (a tet whose min-sine is at least sin(D + band) has no angle below it).
    const double band = D + kPolishBandDeg, cut = std::sin(band * geometry::kPi / 180);
    std::vector<std::pair<double, int>> list;
    for (std::size_t t = 0; t < tets_.size(); ++t)
      if (alive(int(t)) && q_[t] < cut) {
        const Tet& T = tets_[t];
        const double d = tet_min_dihedral_deg(P_[T[0]], P_[T[1]], P_[T[2]], P_[T[3]]);
        if (d < band) list.push_back({d, int(t)});
      }
    std::sort(list.begin(), list.end());
    if (list.size() > std::size_t(kPolishTets)) list.resize(std::size_t(kPolishTets));
    const std::size_t before = n;
    polish_floor_deg_ = std::max(D, kPolishFloorDeg);
    polish_floor_sine_ = std::sin(polish_floor_deg_ * geometry::kPi / 180);
    for (const auto& entry : list) {
      const int t = entry.second;
      if (!poll() || work >= budget) break;
      if (!alive(t)) continue;
      // Each operation is retried only after a change touched the tet or the
      // vertex (the passes' own marks: the floor only rises, so what failed
      // would fail again).
      if (fresh_since(tried_[t], tets_[t])) {
        ++work;
        if (improve_tet(t)) {
          ++n;
          continue;
        }
        tried_[t] = clock_;
      }
      const Tet T = tets_[t];
      bool done = false;
      for (int v : T) {
        if (done || !movable_axes(v) || (smoothed_[v] >= 0 && vtime_[v] <= smoothed_[v])) continue;
        ++work;
        if (smooth(v))
          done = true;
        else
          smoothed_[v] = clock_;
      }
      for (int v : T) {
        if (done || !alive(t)) continue;
        if (v >= int(contract_tried_.size())) contract_tried_.resize(P_.size(), -1);
        if (contract_tried_[v] >= 0 && v < int(vtime_.size()) && vtime_[v] <= contract_tried_[v]) continue;
        ++work;
        if (contract_vertex(v))
          done = true;
        else
          contract_tried_[v] = clock_;
      }
      n += done;
    }
    polish_floor_deg_ = polish_floor_sine_ = 0;
    if (n == before) break;
  }
  return n;
}

}  // namespace wqmesh::mesher
