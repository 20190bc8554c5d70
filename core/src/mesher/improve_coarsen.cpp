// wqmesh: the improvement phase's coarsening (beyond the paper, and beyond
// Stellar): after the passes, when they reach their target, contraction of
// every vertex it can take under the polish's floors, then a short polish,
// a few times. See improve.h, the block "Coarsening", for the contract.
//
// Why (issue 14, slit.off: 20.16 degrees after the passes, TetGen 27.54):
// the passes contract only the vertices of tets under kContractBelowDeg, and
// after the first pass slit has none; its 252 tets keep the boundary
// Steiner vertices REFINE put on the slit's facets and edges. Removing them
// leaves fewer, larger tets, which the polish's second stage raises further
// than it raises the fine mesh (74 tets, 27.81 degrees). The polish alone
// (MeshOptions::polish) reaches 28.19 but in 3 to 8 times REFINE + PUMP's
// time; here the rounds stop when one raises the smallest angle by less
// than kCoarsenStallDeg, and every operation tried is taken from one budget
// of kCoarsenWork per tet, so the step's work is bounded by the mesh's
// size, not by a clock (the same mesh on every machine).
//
// Decisions on cosines and sines made with +, -, *, / and sqrt only (no
// libm call), as the polish's: the native and wasm builds agree.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "mesher/improve.h"

namespace wqmesh::mesher {

namespace {

/// cos 20 degrees (kImproveTargetDeg); cos and sin of 1 degree
/// (kCoarsenRiseDeg) and of 1.5 degrees (kCoarsenStallDeg): decimal
/// literals, so that no libm call makes them.
constexpr double kCosTarget = 0.939692620785908384054;
constexpr double kCosRise = 0.999847695156391239157, kSinRise = 0.0174524064372835128194;
constexpr double kCosStall = 0.999657324975557280037, kSinStall = 0.0261769483078731526106;
static_assert(kImproveTargetDeg == 20 && kCoarsenRiseDeg == 1 && kCoarsenStallDeg == 1.5,
              "kCosTarget, kCosRise, kSinRise, kCosStall and kSinStall are their cosines and sines");

/// The cosine of D + a (D the angle of cosine C, D + a below 180 degrees)
/// from a's cosine and sine: C cos a - sin D sin a.
double cos_plus(double C, double cos_a, double sin_a) {
  return C * cos_a - std::sqrt(std::max(0.0, 1 - C * C)) * sin_a;
}

}  // namespace

std::size_t Improver::coarsen() {
  const std::size_t T = tets_.size() - free_slots_.size();
  if (cancelled_ || T == 0) return 0;
  // Only when the passes reached their target: D >= kImproveTargetDeg, in
  // cosine (C, the cosine of D, at most cos 20 degrees).
  double C = largest_mesh_cosine();
  if (!(C <= kCosTarget)) return 0;
  std::size_t work = kCoarsenWork * T, n = 0;
  const std::size_t cut = (T + kCoarsenPolishShare - 1) / kCoarsenPolishShare;
  // The polish's floors for both parts: the tets never more than now, no new
  // tet worse by min-sine than the mesh's worst now.
  polish_cap_ = T;
  polish_sine_floor_ = worst();
  for (int round = 0; round < kCoarsenRounds && work > 0 && poll(); ++round) {
    if (round > 0) {
      // The previous round must have raised D by kCoarsenStallDeg.
      const double now = largest_mesh_cosine();
      if (!(now <= cos_plus(C, kCosStall, kSinStall))) break;
      C = now;
    }
    n += coarsen_sweeps(work);
    forget_tries();
    polish_dihedral_ = true;
    n += polish_rounds(cut, &work);
    polish_dihedral_ = false;
  }
  forget_tries();  // what failed here may pass by polish()'s first rule
  return n;
}

std::size_t Improver::coarsen_sweeps(std::size_t& work) {
  if (coarsen_tried_.size() < P_.size()) coarsen_tried_.resize(P_.size(), -1);
  std::vector<double> star_worst(P_.size());
  std::vector<std::pair<double, int>> order;
  std::size_t n = 0;
  int sweeps = 0;
  polishing_ = true;
  polish_dihedral_ = false;
  for (;;) {
    // The floors of this sweep: D's cosine C (no new tet at or below
    // max(D, kPolishFloorDeg)) and sin(D + kCoarsenRiseDeg), the cosine of
    // 90 degrees - D - 1 degree (D is below 89 degrees: a tet has a
    // dihedral angle of at most 70.53 degrees, the regular tet's).
    const double C = largest_mesh_cosine();
    set_polish_floor(C);
    const double floor_sine = std::sqrt(std::max(0.0, 1 - C * C)) * kCosRise + C * kSinRise;
    // The Steiner vertices, worst star (by min-sine) first.
    std::fill(star_worst.begin(), star_worst.end(), HUGE_VAL);
    for (std::size_t t = 0; t < tets_.size(); ++t)
      if (alive(int(t)))
        for (int v : tets_[t]) star_worst[v] = std::min(star_worst[v], q_[t]);
    order.clear();
    for (std::size_t v = 0; v < P_.size(); ++v)
      if (star_worst[v] < HUGE_VAL && !(v < r_.input_vertex.size() && r_.input_vertex[v] >= 0))
        order.push_back({star_worst[v], int(v)});
    std::sort(order.begin(), order.end());
    std::size_t made = 0;
    for (const auto& entry : order) {
      const int v = entry.second;
      if (work == 0 || !poll()) break;
      if (removed(v) || (coarsen_tried_[v] >= 0 && vtime_[v] <= coarsen_tried_[v])) continue;
      --work;
      if (contract_vertex(v, floor_sine))
        ++made;
      else
        coarsen_tried_[v] = clock_;
    }
    n += made;
    if (made == 0 || work == 0 || cancelled_ || ++sweeps >= kCoarsenSweeps) break;
  }
  polishing_ = false;
  return n;
}

}  // namespace wqmesh::mesher
