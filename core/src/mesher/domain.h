// wqmesh: the domain P of WQMESH (private): the input PLC with the bounding
// box B (paper, section 2), indexed once for every phase: the facets and
// edges at each vertex, a 2D frame per facet, the sharp vertices and edges,
// and the vertex balls with their sectors (section 4.1).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "geometry.h"
#include "plc_index.h"
#include "wqmesh/analysis.h"
#include "wqmesh/types.h"

namespace wqmesh::mesher {

// ---- Shield sectors (section 4.1) ----------------------------------------------
/// The sector of facet `facet` at sharp vertex u inside the vertex ball: the
/// points u + r d, d a unit vector of the facet's plane (normal n) that turns
/// counter-clockwise about n from e1 (on the sector's first edge) to eb (on
/// its second). A point of its arc is named by its direction d, never by an
/// angle: every decision on arcs is made with +, -, *, / and sqrt, which round
/// alike on every platform (std::cos, std::sin and std::atan2 do not: glibc
/// and the wasm libc differ in the last bit, and the meshes did).
struct Sector {
  int u = -1, facet = -1;
  Point3 center, n, e1, eb;
  double r = 0;
  /// How far off the middle SOS splits an arc: Domain::sos_asymmetry[u] (the
  /// paper splits at the middle, delta = 0; see domain.cpp).
  double delta = 0;
  /// The point of the sphere in direction d (unit).
  Point3 at(const Point3& d) const { return geometry::add(center, geometry::mul(d, r)); }
  /// Whether the arc from da counter-clockwise to db (unit directions of the
  /// plane) is below pi: cross(da, db) along n. An arc of pi exactly is not.
  bool below_pi(const Point3& da, const Point3& db) const { return geometry::dot(geometry::cross(da, db), n) > 0; }
  /// Whether direction d (any length; its part along n is ignored) lies on
  /// the arc from da counter-clockwise to db, ends included.
  bool holds(const Point3& da, const Point3& db, const Point3& d) const;
  /// The unit direction at which SOS splits the arc from da counter-clockwise
  /// to db (section 4.1; see domain.cpp): the arc's middle turned toward db.
  Point3 sos_direction(const Point3& da, const Point3& db) const;
  /// How many SOS splits INITIALIZE makes in this sector so that every arc
  /// is below pi (section 4.1): it splits the arc from e1 to eb, then the
  /// piece from e1 (the larger) while it is not below pi; 0, 1 or 2.
  int initial_splits() const;
};

// ---- P: the input PLC with the bounding box B (section 2) --------------------
/// P with its index (PlcIndex: vertex_edges, vertex_facets, frames, to2d,
/// inside_facet, facet_has_vertex over P's elements, B's included): the
/// index analyze built for the input, copied and extended with B, or built
/// here when the Analysis does not carry the index of this PLC.
struct Domain : PlcIndex {
  PLC p;  ///< input elements first, then B's 8 vertices, 12 edges, 6 facets
  int input_vertices = 0, input_edges = 0, input_facets = 0;
  std::vector<char> sharp_vertex, sharp_edge;
  std::vector<double> ball_radius;  ///< f(u)/4 at sharp vertices, else 0
  /// Per vertex: how far off the middle SOS splits the arcs of its ball
  /// (Sector::delta), min(kSosAsymmetry, a^2/64), a the smallest input angle
  /// at the vertex in radians (beyond the paper; see domain.cpp).
  std::vector<double> sos_asymmetry;
  static constexpr double kSosAsymmetry = geometry::kPi / 1000;
  Box box;  ///< B
  Box input_box;

  Domain(const PLC& plc, const Analysis& analysis);
  bool is_box_facet(int f) const { return f >= input_facets; }
  /// The sector of facet f at the sharp vertex u, whose loop runs prev, u,
  /// next: it turns counter-clockwise about the facet normal from the edge
  /// u-next (t = 0) to the edge u-prev (t = span), inside the vertex ball.
  Sector sector(int u, int f, int prev, int next) const;
  /// Calls fn(f, prev, next) for every corner at u of a loop of a facet at
  /// u (one per sector), in the order INITIALIZE makes the shield
  /// subsegments; initialize_points counts along the same walk.
  template <class F>
  void for_each_corner(int u, F&& fn) const {
    for (int f : vertex_facets[u])
      for (const auto& loop : p.facets[f].loops)
        for (std::size_t i = 0, m = loop.size(); i < m; ++i)
          if (loop[i] == u) fn(f, loop[(i + m - 1) % m], loop[(i + 1) % m]);
  }
  /// The number of vertices INITIALIZE inserts (section 4.1): the vertices of
  /// P and B, one ball point per edge end at a sharp vertex, and the SOS
  /// splits of the sectors of angle pi or more (Sector::initial_splits). Known before meshing, so a vertex limit
  /// below it is refused at once.
  std::size_t initialize_points() const;
};

}  // namespace wqmesh::mesher
