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
  /// the peak memory). Transient memory beyond the result: one cell graph
  /// with its labels and the interior cells' canonical order (see the body).
  MeshResult mesh();
  /// The inside slivers run() would count now (QMESH's, before PUMP),
  /// without building the mesh; polls, and gives 0 once the run must stop.
  /// `scan` and `scan_labels` get the cell graph's cells (CGAL's order; no
  /// neighbours: PUMP does not read them) and their interior_labels, which
  /// PUMP's prepare takes instead of scanning the same triangulation again
  /// (Pump::use_scan); empty when stopped.
  std::size_t count_qmesh_slivers(RegularTriangulation::CellGraph& scan, std::vector<char>& scan_labels);

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
