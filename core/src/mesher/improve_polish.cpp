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
//
// Every decision here is made on cosines of dihedral angles computed with
// +, -, *, / and sqrt only (largest_cosine()), never on an angle from atan2
// or acos or on std::sin: IEEE 754 rounds those five exactly, so the native
// build and the wasm build (glibc's and musl's libm differ in the last bit of
// atan2) take the same decisions and give the same mesh.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <algorithm>
#include <cmath>

#include "geometry.h"
#include "mesher/improve.h"

namespace wqmesh::mesher {

namespace {

/// cos 8 degrees and sin 8 degrees (kPolishBandDeg), cos 5 degrees
/// (kPolishFloorDeg): decimal literals, so that no libm call makes them.
constexpr double kCosBand = 0.99026806874157031508, kSinBand = 0.13917310096006544411;
constexpr double kCosFloorMin = 0.99619469809174553230;
static_assert(kPolishBandDeg == 8 && kPolishFloorDeg == 5, "kCosBand, kSinBand and kCosFloorMin are their cosines");
/// The prefilters by min-sine are widened by this relative margin, so that
/// the rounding of min_sine() and of the cut never drops a tet the cosine
/// test would take.
constexpr double kPrefilterMargin = 1e-9;
// kPolishTieCos (improve.h): a new tet must beat the floor's cosine by this much, so that a tie at the
// floor (a new tet whose smallest angle is the floor's exactly, e.g. after
// an in-plane slide of a boundary vertex, which leaves the dihedral angle at
// a tet's edge in that plane as it was) is refused whatever the rounding.
// Without it, the rounding decided such ties, differently in each build: on
// slit.off the polish gave 29.00 degrees with glibc's atan2, 27.20 with
// musl's (wasm), 26.14 with these cosines; with it, 28.19 with any margin
// from 1e-15 to 1e-10. 1e-12 in cosine is about 1e-10 degrees. A min-sine
// above sin(floor) (1 + kPrefilterMargin) puts the angle more than 1e-11
// above the floor in cosine (the floor is at least 5 degrees), so the quick
// test of polish_admits() agrees.

}  // namespace

double Improver::largest_cosine(const Tet& T) const {
  double largest_abs;
  return largest_cosine_within(T, HUGE_VAL, largest_abs);
}

double Improver::largest_cosine_within(const Tet& T, double bound, double& largest_abs) const {
  const Point3* p[4] = {&P_[T[0]], &P_[T[1]], &P_[T[2]], &P_[T[3]]};
  // The dihedral angle at edge ij is the angle between e x (p_k - p_i) and
  // e x (p_l - p_i), e = p_j - p_i (as wqmesh/quality.h's dihedral_deg):
  // its cosine is their dot product over the square root of the product of
  // their squared lengths. A degenerate face gives 1 (the angle 0).
  double c = -1;
  largest_abs = 0;
  for (const auto& ijkl : kEdgeAndOthers) {
    const Point3& a = *p[ijkl[0]];
    const Point3 e = geometry::sub(*p[ijkl[1]], a);
    const Point3 nk = geometry::cross(e, geometry::sub(*p[ijkl[2]], a));
    const Point3 nl = geometry::cross(e, geometry::sub(*p[ijkl[3]], a));
    const double den = geometry::dot(nk, nk) * geometry::dot(nl, nl);
    if (!(den > 0)) return largest_abs = 1;
    const double ce = geometry::dot(nk, nl) / std::sqrt(den);
    c = std::max(c, ce);
    largest_abs = std::max(largest_abs, std::fabs(ce));
    if (!(c < bound)) return c;
  }
  return c;
}

bool Improver::polish_admits(const Tet& T) const {
  // A min-sine above sin(floor) puts every dihedral angle in (floor, 180 -
  // floor): no cosine above the floor's (the margin covers the roundings).
  if (min_sine(P_[T[0]], P_[T[1]], P_[T[2]], P_[T[3]]) > polish_floor_sine_ * (1 + kPrefilterMargin)) return true;
  return largest_cosine(T) < polish_floor_cos_ - kPolishTieCos;
}

bool Improver::polish_room(std::size_t old_tets, std::size_t new_tets) const {
  return new_tets <= old_tets || tets_.size() - free_slots_.size() + (new_tets - old_tets) <= polish_cap_;
}

double Improver::largest_mesh_cosine() const {
  // The largest cosine C0 of the tet of the smallest min-sine bounds the
  // search: a tet whose min-sine is above sin(D0) = sqrt(1 - C0^2) has every
  // angle above D0 (mesh_worst() measures every tet).
  int first = -1;
  for (std::size_t t = 0; t < tets_.size(); ++t)
    if (alive(int(t)) && (first < 0 || q_[t] < q_[first])) first = int(t);
  if (first < 0) return -1;
  double C = largest_cosine(tets_[std::size_t(first)]);
  const double bound = std::sqrt(std::max(0.0, 1 - C * C)) * (1 + kPrefilterMargin);
  for (std::size_t t = 0; t < tets_.size(); ++t)
    if (alive(int(t)) && (C >= 0 ? q_[t] <= bound : true)) C = std::max(C, largest_cosine(tets_[t]));
  return C;
}

bool Improver::polish_lowers_cosine(const std::vector<int>& old, const std::vector<Tet>& fresh) const {
  double c_old = -1, c_new = -1;
  for (int t : old) c_old = std::max(c_old, largest_cosine(tets_[t]));
  for (const Tet& T : fresh) {
    c_new = std::max(c_new, largest_cosine(T));
    if (!(c_new < c_old - kPolishTieCos)) return false;
  }
  return true;
}

void Improver::set_polish_floor(double C) {
  // The floor max(D, kPolishFloorDeg): a cosine below min(C, cos 5).
  polish_floor_cos_ = std::min(C, kCosFloorMin);
  polish_floor_sine_ = std::sqrt(std::max(0.0, 1 - polish_floor_cos_ * polish_floor_cos_));
}

bool Improver::smooth_in_polish(int v) {
  polish_cap_ = tets_.size() - free_slots_.size();
  polish_sine_floor_ = worst();
  set_polish_floor(largest_mesh_cosine());
  polishing_ = polish_dihedral_ = true;
  const bool moved = smooth(v);
  polishing_ = polish_dihedral_ = false;
  return moved;
}

std::size_t Improver::polish() {
  polish_cap_ = tets_.size() - free_slots_.size();
  polish_sine_floor_ = worst();
  polish_dihedral_ = false;
  std::size_t n = polish_rounds();
  // The second stage: what failed by the min-sine rule may pass by the
  // angle's, so every stamp is forgotten.
  forget_tries();
  polish_dihedral_ = true;
  n += polish_rounds();
  polish_dihedral_ = false;
  return n;
}

void Improver::forget_tries() {
  std::fill(tried_.begin(), tried_.end(), -1);
  std::fill(smoothed_.begin(), smoothed_.end(), -1);
  std::fill(contract_tried_.begin(), contract_tried_.end(), -1);
}

std::size_t Improver::polish_rounds(std::size_t max_changes, std::size_t* work) {
  std::size_t n = 0;
  double last = HUGE_VAL;
  int stalls = 0;
  // coarsen()'s budget: every operation tried is taken from *work.
  const auto budget_left = [work] { return work == nullptr || *work > 0; };
  const auto spend = [&] {
    if (!budget_left()) return false;
    if (work != nullptr) --*work;
    return true;
  };
  for (int round = 0; round < kPolishRounds && n < max_changes && budget_left() && poll(); ++round) {
    // C: the cosine of the mesh's smallest dihedral angle D; S = sin D.
    const double C = largest_mesh_cosine();
    if (C <= 0) break;  // every angle 90 degrees or more: nothing to raise
    const double S = std::sqrt(std::max(0.0, 1 - C * C));
    // A rise of D by kPolishRiseDeg lowers C by about S times it in radians.
    if (last - C < S * (kPolishRiseDeg * geometry::kPi / 180)) {
      if (++stalls >= kPolishStalls) break;
    } else {
      stalls = 0;
    }
    last = C;
    // The kPolishTets tets of the smallest angles below D + kPolishBandDeg:
    // cosine above cos(D + band) = C cos(band) - S sin(band). A tet whose
    // min-sine is at least sin(D + band) = S cos(band) + C sin(band) (D +
    // band below 90) has no angle below D + band.
    const double band_cos = C * kCosBand - S * kSinBand;
    const double cut = band_cos > 0 ? (S * kCosBand + C * kSinBand) * (1 + kPrefilterMargin) : HUGE_VAL;
    std::vector<std::pair<double, int>> list;
    for (std::size_t t = 0; t < tets_.size(); ++t)
      if (alive(int(t)) && q_[t] < cut) {
        const double c = largest_cosine(tets_[t]);
        if (c > band_cos) list.push_back({-c, int(t)});
      }
    std::sort(list.begin(), list.end());
    if (list.size() > std::size_t(kPolishTets)) list.resize(std::size_t(kPolishTets));
    const std::size_t before = n;
    polishing_ = true;
    set_polish_floor(C);
    for (const auto& entry : list) {
      const int t = entry.second;
      if (n >= max_changes || !budget_left() || !poll()) break;
      if (!alive(t)) continue;
      // Each operation is retried only after a change touched the tet or the
      // vertex (the passes' own marks: the floor only rises, so what failed
      // would fail again).
      if (fresh_since(tried_[t], tets_[t])) {
        if (!spend()) break;
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
        if (!spend()) break;
        if (smooth(v))
          done = true;
        else
          smoothed_[v] = clock_;
      }
      for (int v : T) {
        if (done || !alive(t)) continue;
        if (v >= int(contract_tried_.size())) contract_tried_.resize(P_.size(), -1);
        if (contract_tried_[v] >= 0 && v < int(vtime_.size()) && vtime_[v] <= contract_tried_[v]) continue;
        if (!spend()) break;
        if (contract_vertex(v))
          done = true;
        else
          contract_tried_[v] = clock_;
      }
      n += done;
    }
    polishing_ = false;
    if (n == before) break;
  }
  return n;
}

}  // namespace wqmesh::mesher
