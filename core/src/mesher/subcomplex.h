// wqmesh: the vocabulary of the subcomplex (private; paper, section 4): the
// vertices of V and where they lie, subsegments (of the edges of P, and the
// shield subsegments of the vertex balls, section 4.1), subfacets (the
// triangles of the planar Delaunay triangulation of V ∩ F that lie in F), and
// the point SPLITE, SPLITF or ENCROACH decides to insert.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>

#include "wqmesh/types.h"

namespace wqmesh::mesher {

using Tri = std::array<int, 3>;

/// The key of the edge (subsegment) ab, the same for ba.
inline std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b);
}
inline Tri sorted(Tri t) {
  if (t[0] > t[1]) std::swap(t[0], t[1]);
  if (t[1] > t[2]) std::swap(t[1], t[2]);
  if (t[0] > t[1]) std::swap(t[0], t[1]);
  return t;
}
struct TriHash {
  std::size_t operator()(const Tri& t) const {
    std::uint64_t h = std::uint64_t(std::uint32_t(t[0])) * 0x9E3779B97F4A7C15ull;
    h ^= std::uint64_t(std::uint32_t(t[1])) + 0x632BE59BD9B4E019ull + (h << 6) + (h >> 2);
    h ^= std::uint64_t(std::uint32_t(t[2])) + 0x85157AF5ull + (h << 6) + (h >> 2);
    return std::size_t(h);
  }
};

/// A cell named by its sorted vertex ids.
using TetKey = std::array<int, 4>;
struct TetKeyHash {
  std::size_t operator()(const TetKey& t) const {
    std::uint64_t h = 1469598103934665603ull;
    for (int x : t) h = (h ^ std::uint64_t(std::uint32_t(x))) * 1099511628211ull;
    return std::size_t(h);
  }
};

// ---- Mesh vertices -------------------------------------------------------------
/// Where a vertex of V lies: on a vertex, edge or facet of P, or free (inside a
/// volume: circumcenters of tets).
enum class On : char { vertex, edge, facet, free };
struct MVertex {
  On on = On::free;
  int element = -1;  ///< P vertex, edge or facet index
  int sector = -1;   ///< on a vertex-ball arc (shield subsegment endpoint)
  double angle = 0;  ///< its angle on that arc
  int ball = -1;     ///< the sharp vertex u when the vertex lies on the sphere of û
};

// ---- Subsegments ---------------------------------------------------------------
/// A subsegment ab of a P edge, or a shield subsegment (a chord of a sector's
/// arc, sector >= 0, with the arc angles ta of a and tb of b).
struct Subsegment {
  int a = -1, b = -1;
  int edge = -1;
  int sector = -1;
  double ta = 0, tb = 0;
  bool in_ball = false;  ///< inside a vertex ball: protected, never split
  bool sharp = false;    ///< on a sharp edge, outside the vertex balls
};

/// A subfacet: a triangle of facet f's planar Delaunay triangulation lying in f.
struct Subfacet {
  int facet = -1;
  Tri v{{-1, -1, -1}};
};

/// A point to insert, as decided by SPLITE, SPLITF or ENCROACH.
struct Insertion {
  Point3 p{{0, 0, 0}};
  On on = On::free;
  int element = -1;
  std::uint64_t split_segment = 0;  ///< the subsegment it splits (if has_segment)
  bool has_segment = false;
  int sector = -1;
  double angle = 0;
  int ball = -1;
  int hint = -1;
  bool none = false;  ///< nothing to insert (see SPLITF in a vertex ball)
};

}  // namespace wqmesh::mesher
