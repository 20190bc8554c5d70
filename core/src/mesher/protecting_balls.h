// wqmesh: the protecting balls of WQMESH (private; paper, section 4.3): the
// vertex balls of the sharp vertices and, from the end of CONFORM, the
// diametric balls of the sharp subsegments doubled. Rule 6 inserts no
// circumcenter inside one; rule 7 and PUMP skip the vertices whose weighted
// point encroaches the two-times expansion of one; a subfacet is guarded when
// its diametric ball lies inside one. Found through a uniform grid over the
// two-times expansions.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "wqmesh/mesher.h"
#include "wqmesh/types.h"

namespace wqmesh::mesher {

class ProtectingBalls {
 public:
  /// No balls yet; `box` (B) anchors the grid.
  explicit ProtectingBalls(const Box& box) : box_(box) {}
  /// Replaces the balls and indexes them.
  void set(std::vector<ProtectingBall> balls);
  const std::vector<ProtectingBall>& all() const { return balls_; }
  /// Whether x lies on or inside a protecting ball (rule 6).
  bool contains(const Point3& x) const;
  /// Whether the weighted point (v, w) encroaches the two-times expansion of a
  /// protecting ball (c, r): |v - c|^2 <= (2r)^2 + w (rule 7, PUMP).
  bool expansion_encroached(const Point3& v, double w) const;
  /// Whether the ball (c, sqrt(r2)) lies inside a protecting ball: the test of
  /// a guarded subfacet (rule 5), c and r2 its circumcenter and radius^2.
  bool guards(const Point3& c, double r2) const;

 private:
  template <class F>
  void for_balls_near(const Point3& x, double reach, F&& f) const;

  Box box_;
  std::vector<ProtectingBall> balls_;
  double cell_ = 1;
  std::unordered_map<std::uint64_t, std::vector<int>> grid_;
  std::vector<int> big_;  ///< balls spanning too many grid cells, always looked at
};

}  // namespace wqmesh::mesher
