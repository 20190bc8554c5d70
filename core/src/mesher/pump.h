// wqmesh: PUMP (private; paper, section 4.3): the weights of the sliver
// vertices. It reads the mesher through its public interface only (the
// triangulation's weights are all it changes): the inside/outside labels of
// cells kept as the weighted triangulation changes, the walls (input
// subfacets) and, per vertex, the subfacets whose presence must be kept.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include "mesher/mesher.h"

namespace wqmesh::mesher {

class Pump {
 public:
  explicit Pump(Mesher& m);
  /// N(v) for every vertex, cell labels, walls. Called by run().
  void prepare();
  void run();
  /// (smallest dihedral, vertex) for the vertices of inside tets with a
  /// dihedral angle <= theta, worst first, as found by prepare().
  std::vector<std::pair<double, int>> candidates() const;
  /// N(v)^2/9.
  double weight_bound(int v) const;

  struct Features {
    std::vector<std::uint64_t> segments;
    std::vector<Tri> subfacets;
  };
  /// The features whose presence a weight change of v must keep.
  Features features_around(int v) const;
  /// Sets v's weight to w; returns the smallest dihedral angle of the inside
  /// tets around v, or -1 when w hides v or removes one of `f`.
  double evaluate(int v, double w, const Features& f);

  struct Choice {
    double weight = 0, quality = -1, base = -1;
  };
  /// Chooses, and sets, the weight of v in [0, N(v)^2/9] maximising the
  /// smallest dihedral angle around v, searching the interval at its critical
  /// weights; keeps the old weight unless the new one is strictly better.
  Choice pump_vertex(int v);

  /// At most kLabelRounds rounds of label propagation for a new cell.
  static constexpr int kLabelRounds = 64;
  /// At most kCriticalSteps critical weights visited per vertex (a choice:
  /// stars change at a few dozen weights in practice).
  static constexpr int kCriticalSteps = 256;

 private:
  double angle_of(const Tet& t) const;
  bool is_wall(int a, int b, int c) const;
  char label(const Tet& t);
  double next_critical(int v, double w, double cap) const;
  bool present(const Features& f) const;

  Mesher& m_;
  RegularTriangulation& tri_;
  std::vector<double> nn_;  ///< N(v), measured by prepare()
  std::unordered_map<TetKey, char, TetKeyHash> labels_;
  std::unordered_set<Tri, TriHash> walls_;
  std::vector<std::vector<Tri>> vertex_facets_;
  std::vector<std::pair<double, int>> candidates_;
};

}  // namespace wqmesh::mesher
