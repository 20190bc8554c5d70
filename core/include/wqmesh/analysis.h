// wqmesh: input angles, sharp elements and local feature sizes
// (paper, section 2, and section 4.1 for the vertex balls).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "wqmesh/types.h"

namespace wqmesh {

/// An angle between two input edges at a common vertex (edge-edge angle).
struct EdgeEdgeAngle {
  int vertex, edge1, edge2;
  double degrees;
  bool acute;  ///< decided exactly (a right angle is not acute)
};

/// The angle between an edge uv and a facet F incident to u, where uv is
/// neither an edge of F nor coplanar with F: min over p in F, p != u, of the
/// angle puv (edge-facet angle). Literal: p ranges over the whole facet, so on
/// a non-convex facet a part of F far from u can give a smaller angle than the
/// sector of F at u. Coplanar means v exactly in F's plane.
struct EdgeFacetAngle {
  int vertex, edge, facet;
  double degrees;
  bool acute;  ///< decided exactly
};

/// The dihedral angles at an input edge, inside and outside the polyhedron.
struct DihedralAngle {
  int edge;
  double internal_degrees;  ///< in (0, 360), 180 excluded (no coplanar pair)
  double external_degrees;  ///< 360 - internal
  bool sharp;               ///< internal or external one acute, decided exactly
};

/// An axis-aligned box, the bounding box B of the paper (section 2).
struct Box {
  Point3 lo{{0, 0, 0}}, hi{{0, 0, 0}};
};

struct AnalysisOptions {
  /// B is the bounding box of the input grown on every side by this fraction
  /// of its largest extent.
  double box_margin = 0.5;
};

struct PlcIndex;  // private (core/src/plc_index.h)

/// The paper's input analysis. Sharp edge: internal or external dihedral angle
/// acute. Sharp vertex: an acute edge-edge or edge-facet angle at it, or an
/// endpoint of a sharp edge. f(u) at a sharp vertex u: the distance from u to
/// the nearest input vertex, edge or facet not adjacent to u (not containing
/// u), which is the radius of the smallest ball at u meeting two non-adjacent
/// elements. B is part of the PLC (section 2), so the distance from u to the
/// boundary of B also bounds f(u).
struct Analysis {
  std::vector<EdgeEdgeAngle> edge_edge;
  std::vector<EdgeFacetAngle> edge_facet;
  std::vector<DihedralAngle> dihedral;  ///< one per input edge, same order
  std::vector<int> sharp_vertices;      ///< increasing
  std::vector<int> sharp_edges;         ///< increasing
  std::vector<double> lfs;              ///< f(u) per sharp vertex, same order
  double phi_m_degrees = 180;           ///< smallest input angle
  Box input_box, bounding_box;
  double box_margin = 0.5;
  /// Private: the PLC's vertex incidence and facet frames (core/src/plc_index.h),
  /// built once by analyze, in the coordinates it ran on (the input scaled by
  /// 2^-E), and reused by the mesher when it meshes the same PLC. Empty in an
  /// Analysis made otherwise: the mesher then builds it.
  std::shared_ptr<const PlcIndex> index;
};

Analysis analyze(const PLC& plc, const AnalysisOptions& options = {});

/// f(u) (paper, sections 2 and 4.1) at each vertex u in `vertices` (indices
/// into plc.vertices), in the same order: the distance from u to the nearest
/// input vertex, edge or facet not containing u (a facet contains u when u is
/// a vertex of one of its loops), or to the boundary of `bounding_box` when
/// that is nearer. The distance to a facet is the distance to its plane when
/// the projection of u falls inside the polygon (holes excluded), else the
/// distance to its boundary. Uses a bounding volume hierarchy over the input
/// elements, so it runs in about O(n log n) for n elements.
std::vector<double> local_feature_sizes(const PLC& plc, const std::vector<int>& vertices, const Box& bounding_box);

class JsonWriter;
/// Writes the analysis as one JSON object value (the caller has written the
/// key, if any): angles in degrees, sharp elements, f(u), phi_m, boxes.
/// Keys: "counts" {sharp_vertices, sharp_edges, edge_edge_angles,
/// acute_edge_edge_angles, edge_facet_angles, acute_edge_facet_angles,
/// dihedral_angles}; "phi_m_degrees"; "sharp_vertices" and "sharp_edges"
/// (indices); "lfs" [{vertex, f}]; "dihedral" [{edge, internal, external,
/// sharp}]; "edge_edge" [{vertex, edge1, edge2, degrees, acute}];
/// "edge_facet" [{vertex, edge, facet, degrees, acute}]; "input_box" and
/// "bounding_box" {lo: [x, y, z], hi: [x, y, z]}; "box_margin". The same
/// layout as AnalysisReport in wasm/index.d.ts.
void write_analysis_json(JsonWriter& json, const Analysis& analysis);

}  // namespace wqmesh
