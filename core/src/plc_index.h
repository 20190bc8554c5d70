// wqmesh: the index of a PLC (private), built once by analyze and reused by
// the mesher's domain P (paper, section 2): the edges and facets at each
// vertex, and a 2D frame per facet (origin, e1, e2, Newell's unit normal, the
// loops in the frame).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "wqmesh/analysis.h"
#include "wqmesh/types.h"

namespace wqmesh {

/// Vertex incidence and facet frames of a PLC. Built by analyze on the PLC it
/// analyses (the input scaled by 2^-E, see scaling.h) and kept in
/// Analysis::index; the mesher's Domain copies it and extends it with the
/// bounding box B. Holds no reference to the PLC: `fingerprint` tells whether
/// it was built from a given one.
struct PlcIndex {
  /// A facet's 2D frame: origin at the first vertex of its outer loop, n its
  /// Newell unit normal (geometry::unit of geometry::newell_normal of the
  /// outer loop, so pointing to the side from which that loop turns
  /// counter-clockwise), e1 along its first edge made perpendicular to n,
  /// e2 = n x e1; `loops` are the facet's loops in (e1, e2) coordinates; the
  /// mesher's projections, sectors and point-in-facet tests use them.
  /// `area` is geometry::fan_area_vector of the outer loop (the same
  /// direction as n, rounded on differences from the origin) and plane_n =
  /// area / |area|, which f(u)'s distances to facets use; the analysis' angle
  /// values use geometry::unit(area). Roundings that differ in the last bits,
  /// kept because each decides meshes bit for bit: n the mesher's frames,
  /// plane_n the ball radii f(u)/4 (with n for f(u) too, f(u) moves in the
  /// last bits on fandisk, part, example012 and the 20 mm cube, and fandisk's
  /// mesh with it: 309,019 -> 308,897 tets), unit(area) the angle values, from
  /// which the domain takes the SOS asymmetry. All zero for a facet whose
  /// outer loop has fewer than 3 vertices (outside the contract of a valid
  /// PLC).
  struct Frame {
    Point3 origin{{0, 0, 0}}, e1{{0, 0, 0}}, e2{{0, 0, 0}}, n{{0, 0, 0}};
    Point3 area{{0, 0, 0}}, plane_n{{0, 0, 0}};
    std::vector<std::vector<std::array<double, 2>>> loops;
  };
  /// Where a vertex first appears in a facet: loop `loop`, position `position`.
  struct Corner {
    int facet, loop, position;
  };

  std::vector<std::vector<int>> vertex_edges;       ///< edges at each vertex, increasing
  std::vector<std::vector<int>> vertex_facets;      ///< facets whose loops hold the vertex, increasing
  std::vector<std::vector<Corner>> vertex_corners;  ///< per vertex, one per facet of vertex_facets, same order
  std::vector<Frame> frames;                        ///< per facet
  /// How many vertices, edges and facets are indexed: elements [0, count).
  std::size_t indexed_vertices = 0, indexed_edges = 0, indexed_facets = 0;

  PlcIndex() = default;
  explicit PlcIndex(const PLC& plc) { extend(plc); }
  /// Indexes the elements of `plc` beyond those already indexed (the mesher
  /// adds B's vertices, edges and facets after the input's); `plc` must start
  /// with the elements indexed so far, unchanged, and new edges and facets may
  /// touch old vertices only if those vertices gain no facet or edge out of
  /// order (B's elements touch only B's vertices).
  void extend(const PLC& plc);

  std::array<double, 2> to2d(int f, const Point3& x) const;
  /// Whether x (projected on the plane of facet f) lies inside f (even-odd rule
  /// over its loops).
  bool inside_facet(int f, const Point3& x) const;
  bool facet_has_vertex(int f, int v) const;

  /// A 64-bit checksum of plc's coordinates (their bits), edge ends and facet
  /// loops: the index of `plc` is `*this` when fingerprint(plc) equals
  /// `fingerprint_` and the counts match (built_from).
  static std::uint64_t fingerprint(const PLC& plc);
  bool built_from(const PLC& plc) const;

 private:
  std::uint64_t fingerprint_ = 0;
};

/// f(u) at the given vertices (see local_feature_sizes in wqmesh/analysis.h)
/// with the facets' planes and incidence taken from `index`, the index of plc.
std::vector<double> local_feature_sizes(const PLC& plc, const PlcIndex& index, const std::vector<int>& vertices,
                                        const Box& bounding_box);

}  // namespace wqmesh
