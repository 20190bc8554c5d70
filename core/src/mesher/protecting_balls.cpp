// wqmesh: the protecting balls (paper, section 4.3) and their grid; see
// protecting_balls.h.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesher/protecting_balls.h"

#include <algorithm>
#include <cmath>

#include "geometry.h"

namespace wqmesh::mesher {

using namespace geometry;

namespace {
std::uint64_t cell_key(long long i, long long j, long long k) {
  const auto m = [](long long x) { return std::uint64_t(x + (1 << 20)) & 0x1FFFFF; };
  return (m(i) << 42) | (m(j) << 21) | m(k);
}
/// The grid has at most about kGridCells cells along the diagonal of B.
constexpr double kGridCells = 256;
/// A ball covering more grid cells than this is kept in a list of its own.
constexpr double kMaxBallCells = 512;
}  // namespace

void ProtectingBalls::set(std::vector<ProtectingBall> balls) {
  balls_ = std::move(balls);
  grid_.clear();
  big_.clear();
  const Point3 ext = sub(box_.hi, box_.lo);
  const double diag = std::sqrt(dot(ext, ext));
  double sum = 0;
  for (const ProtectingBall& b : balls_) sum += 4 * b.radius;
  cell_ = std::max(diag / kGridCells, balls_.empty() ? diag : sum / balls_.size());
  for (int i = 0; i < static_cast<int>(balls_.size()); ++i) {
    const ProtectingBall& b = balls_[i];
    const double r = 2 * b.radius;
    long long lo[3], hi[3];
    double cells = 1;
    for (int d = 0; d < 3; ++d) {
      lo[d] = static_cast<long long>(std::floor((b.center[d] - r - box_.lo[d]) / cell_));
      hi[d] = static_cast<long long>(std::floor((b.center[d] + r - box_.lo[d]) / cell_));
      cells *= double(hi[d] - lo[d] + 1);
    }
    // A ball much larger than the cells (the doubled ball of a long sharp
    // subsegment among many small ones) would fill up to 2^27 cells: it is
    // kept apart, in a list every query looks at, beyond kMaxBallCells.
    if (cells > kMaxBallCells) {
      big_.push_back(i);
      continue;
    }
    for (long long x = lo[0]; x <= hi[0]; ++x)
      for (long long y = lo[1]; y <= hi[1]; ++y)
        for (long long z = lo[2]; z <= hi[2]; ++z) grid_[cell_key(x, y, z)].push_back(i);
  }
}

template <class F>
void ProtectingBalls::for_balls_near(const Point3& x, double reach, F&& f) const {
  long long lo[3], hi[3];
  for (int d = 0; d < 3; ++d) {
    lo[d] = static_cast<long long>(std::floor((x[d] - reach - box_.lo[d]) / cell_));
    hi[d] = static_cast<long long>(std::floor((x[d] + reach - box_.lo[d]) / cell_));
  }
  const double cells = double(hi[0] - lo[0] + 1) * double(hi[1] - lo[1] + 1) * double(hi[2] - lo[2] + 1);
  if (cells > double(balls_.size())) {  // a long reach: look at every ball
    for (const ProtectingBall& b : balls_)
      if (f(b)) return;
    return;
  }
  for (int b : big_)
    if (f(balls_[b])) return;
  for (long long i = lo[0]; i <= hi[0]; ++i)
    for (long long j = lo[1]; j <= hi[1]; ++j)
      for (long long k = lo[2]; k <= hi[2]; ++k) {
        const auto it = grid_.find(cell_key(i, j, k));
        if (it == grid_.end()) continue;
        for (int b : it->second)
          if (f(balls_[b])) return;
      }
}

bool ProtectingBalls::contains(const Point3& x) const {
  bool hit = false;
  for_balls_near(x, 0, [&](const ProtectingBall& b) {
    hit = dist2(x, b.center) <= b.radius * b.radius;
    return hit;
  });
  return hit;
}

bool ProtectingBalls::expansion_encroached(const Point3& v, double w) const {
  bool hit = false;
  for_balls_near(v, std::sqrt(w), [&](const ProtectingBall& b) {
    hit = dist2(v, b.center) <= 4 * b.radius * b.radius + w;
    return hit;
  });
  return hit;
}

bool ProtectingBalls::guards(const Point3& c, double r2) const {
  const double r = std::sqrt(r2);
  bool hit = false;
  for_balls_near(c, 0, [&](const ProtectingBall& b) {
    hit = std::sqrt(dist2(c, b.center)) + r <= b.radius;
    return hit;
  });
  return hit;
}

}  // namespace wqmesh::mesher
