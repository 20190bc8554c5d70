// wqmesh: writing tetrahedral meshes (Medit, VTK, TetGen) and statistics.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <ostream>
#include <string>
#include <vector>

#include "wqmesh/quality.h"
#include "wqmesh/types.h"

namespace wqmesh {

class JsonWriter;

/// Per-tet flags written as cell data (VTK) and in the stats; values are the
/// classes of the mesher (0 good, 1 skinny-near, 2 sliver-near, 3 violation),
/// or empty.
struct TetLabels {
  std::vector<int> tet_class;
};

/// Medit .mesh (MeshVersionFormatted 2, Dimension 3): Vertices (reference 0),
/// Tetrahedra (reference 1), Triangles (the boundary, reference = input facet
/// + 1, so 0 where the facet is unknown), End; 1-based indices. Every section
/// is written, with count 0 when empty. Coordinates with round-trip precision
/// (format_double), so they read back bit-exact.
void write_medit(std::ostream& out, const TetMesh& mesh);

/// VTK XML UnstructuredGrid (.vtu, ASCII) with cell data: min_dihedral
/// (degrees), radius_edge (R/l, whatever `quality` holds: the command line
/// and the wasm writer pass the unweighted one, mesh_quality(mesh, {}, false)),
/// orthoradius_edge when the mesh is weighted (the paper's rho with the
/// weights), radius_ratio_R_over_r (circumradius over inradius, 3 for a
/// regular tet; not VTK's normalised aspect ratio), volume, and "class" when
/// labels are given; point data "weight" when the mesh is weighted
/// (mesh.weights not empty). The command line and the wasm writer pass every array on every run
/// (weights of 0 where PUMP moved nothing), so that files of two runs hold the
/// same arrays.
/// Cells are VTK_TETRA (10) with the mesh's vertex order. `quality` is either
/// empty (no quality arrays) or has one entry per tet (mesh_quality); the
/// labels, if given, one per tet; otherwise std::invalid_argument. Float64
/// values with round-trip precision; +-infinity (e.g. R/l of a flat tet) is
/// written as +-DBL_MAX and NaN as 0, since VTK's ASCII reader rejects them.
void write_vtu(std::ostream& out, const TetMesh& mesh, const std::vector<TetQuality>& quality,
               const TetLabels* labels = nullptr);

/// TetGen files: `base.node`, `base.ele`, `base.face`, `base.edge` (0-based
/// indices; face markers = input facet + 1). Throws std::runtime_error if a
/// file cannot be written. Formats: .node `n 3 0 0` then `i x y z` (weights
/// are not written); .ele `m 4 0` then `i a b c d` (the mesh's orientation);
/// .face `k 1` then `i a b c marker`; .edge `s 1` then `i a b 1`, the
/// boundary_segments (TetGen's `-rNEFC` reads them to check the segments).
void write_tetgen(const std::string& base, const TetMesh& mesh);
void write_tetgen(std::ostream& node, std::ostream& ele, std::ostream& face, std::ostream& edge, const TetMesh& mesh);
/// The first three files only (no .edge).
void write_tetgen(std::ostream& node, std::ostream& ele, std::ostream& face, const TetMesh& mesh);

/// The subsegments of the input edges: the boundary edges whose two boundary
/// triangles lie in different input facets (or whose facet is unknown, -1, or
/// that do not have exactly two boundary triangles), as vertex pairs, each
/// chain of subsegments oriented one way (a subsegment begins where the one
/// before it on its input edge ends, as TetGen's -r wants). Adjacent coplanar
/// faces are one facet of the PLC, so an edge between two facets lies on an
/// input edge.
std::vector<std::array<int, 2>> boundary_segments(const TetMesh& mesh);
/// The .edge file of write_tetgen: boundary_segments with marker 1.
void write_tetgen_edges(std::ostream& edge, const TetMesh& mesh);

/// The statistics as a JSON object (keys as in MeshStats, bins keyed by their
/// ranges: "0.6-1.4", "1.4-2.2", ">2.2" and "0-3", "3-5", "5-10").
/// Layout: {"vertices", "tets", "volume", "inverted", "min_dihedral_deg",
/// "max_dihedral_deg", "min_face_angle_deg", "max_radius_edge",
/// "max_aspect_ratio", "radius_edge_below", "radius_edge_bins": {"0.6-1.4",
/// "1.4-2.2", ">2.2"}, "dihedral_bins": {"0-3", "3-5", "5-10"}, "slivers",
/// "min_dihedral_histogram": [90 counts], "min_face_angle_histogram": [90]}.
/// Non-finite values (an infinite R/l of a flat tet) are written as null.
std::string stats_json(const MeshStats& stats, bool pretty = true);

/// Writes the two bin objects of the statistics into the open JSON object of
/// `j`: "radius_edge_bins" and "dihedral_bins", keyed as in stats_json. Shared
/// by stats_json and mesh_stats_json so that the two layouts cannot drift.
void write_quality_bins(JsonWriter& j, const MeshStats& stats);

}  // namespace wqmesh
