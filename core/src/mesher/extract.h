// wqmesh: the mesh WQMESH returns (private; paper, section 4.3): the tets of
// Del V inside the polyhedron, found by a flood fill across the walls (the
// input subfacets), their classes (classify.cpp) and statistics (extract.cpp).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <vector>

#include "mesher/domain.h"
#include "mesher/protecting_balls.h"
#include "mesher/subcomplex.h"
#include "mesher/work_meter.h"
#include "triangulation.h"
#include "wqmesh/mesher.h"

namespace wqmesh::mesher {

/// 1 for the cells of g inside the polyhedron. `scan`: poll `meter` while
/// labelling (a phase's scan); the labels are then unusable if it stops.
/// `order_free`, when given, says whether the labels are the same for every
/// order of g's cells (extract.cpp, even_walls).
std::vector<char> interior_labels(const Domain& dom, const Subcomplex& sub, const RegularTriangulation::CellGraph& g,
                                  WorkMeter& meter, bool scan = false, bool* order_free = nullptr);

/// Beyond the paper (issue 15, the peak memory): interior_labels without a
/// cell graph, kept in the label bytes of the cells of V's triangulation
/// (RegularTriangulation::flood_labels): 1 inside, 0 outside, and
/// RegularTriangulation::kExcludedOdd for the flat tets lying in an input
/// facet that interior_labels' fill reached as inside (interior_labels
/// gives them 0); that is, exactly interior_labels' labels with
/// kExcludedOdd read as 0, when those are the same for every order of the
/// cells (extract.cpp, even_walls, and every wall a facet of the
/// triangulation). A call completes the labels an earlier one left where
/// they still hold (RegularTriangulation::complete_labels: the cells made
/// since take theirs from their neighbours) and fills the whole
/// triangulation only where they do not. Returns false
/// when they may not be (the labels are then unusable:
/// take interior_labels on a cell graph in the order wanted) or, with
/// `scan`, when the meter stopped the run (polled as a phase's scan; the
/// labels are then unusable).
bool label_cells_in_place(const Domain& dom, const Subcomplex& sub, const RegularTriangulation& tri, WorkMeter& meter,
                          bool scan);

/// The extraction of the mesh from V, its triangulation and the subcomplex.
class Extract {
 public:
  /// `nn`: N(v) for every vertex, as PUMP measured it at the end of REFINE;
  /// measured (and stored there) when its size is not V's.
  Extract(const Domain& domain, const MeshOptions& options, const RegularTriangulation& tri,
          const std::vector<MVertex>& vertices, const Subcomplex& sub, const ProtectingBalls& balls,
          std::vector<double>& nn, WorkMeter& meter)
      : dom_(domain), opt_(options), tri_(tri), verts_(vertices), sub_(sub), balls_(balls), nn_(nn), meter_(meter) {}
  /// Interior tets, classes (classify_tets), statistics: mesh() then
  /// classify_tets.
  MeshResult run();
  /// The interior tets with their boundary triangles and per-vertex data
  /// (r.mesh, nearest_neighbour, input_vertex, conforming, stopped,
  /// protecting_balls), without the per-tet measures and classes: nothing of
  /// the result refers to the triangulation or the subcomplex, so the caller
  /// may free them before classify_tets (mesh_polyhedron.cpp does: issue 15,
  /// the peak memory). Transient memory beyond the result: the interior
  /// cells' canonical order, which becomes the result's tets, and, only when
  /// label_cells_in_place cannot label the cells, one cell graph with its
  /// labels (see the body).
  MeshResult mesh();
  /// The inside slivers run() would count now (QMESH's, before PUMP),
  /// without building the mesh; polls, and gives 0 once the run must stop.
  /// Its labels are kept for PUMP's prepare, which takes them instead of
  /// scanning the same triangulation again: `in_cells` says that they are
  /// in the cells' label bytes (label_cells_in_place; Pump::use_cell_labels),
  /// else `scan` and `scan_labels` get the cell graph's cells (CGAL's order;
  /// no neighbours: PUMP does not read them) and their interior_labels
  /// (Pump::use_scan); empty and false when stopped.
  std::size_t count_qmesh_slivers(RegularTriangulation::CellGraph& scan, std::vector<char>& scan_labels,
                                  bool& in_cells);

 private:
  /// The labels run() takes for g: interior_labels, or RayParity's when the
  /// run does not conform. `stoppable`: poll (count_qmesh_slivers' scan).
  std::vector<char> labels(const RegularTriangulation::CellGraph& g, bool conforming, bool stoppable);

  const Domain& dom_;
  const MeshOptions& opt_;
  const RegularTriangulation& tri_;
  const std::vector<MVertex>& verts_;
  const Subcomplex& sub_;
  const ProtectingBalls& balls_;
  std::vector<double>& nn_;
  WorkMeter& meter_;
};

}  // namespace wqmesh::mesher
