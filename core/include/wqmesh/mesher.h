// wqmesh: the mesher, WQMESH of Cheng, Dey and Ray (2005), section 4.3:
// INITIALIZE, CONFORM (rules 1-3), REFINE (rules 4-7) and PUMP.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "wqmesh/analysis.h"
#include "wqmesh/quality.h"
#include "wqmesh/types.h"

namespace wqmesh {

struct MeshOptions {
  /// rho0 of rule 6: tets with circumradius / shortest edge above it are split
  /// (the proof needs rho0 > 2 / (1 - tan(pi/8)) ~ 3.41; the paper's
  /// experiments, and this default, use 2.2).
  double rho0 = 2.2;
  /// theta of rule 7 and PUMP, in degrees: tets with a dihedral angle at most
  /// theta have their vertices prepared and pumped.
  double theta_deg = 3.0;
  /// false: QMESH alone (no rule 7, no PUMP).
  bool pump = true;
  /// Margin of the bounding box B, as a fraction of the input's largest extent.
  double box_margin = 0.5;
  /// The run stops with stopped = "limit" when the vertex count reaches it.
  std::size_t max_vertices = 1'000'000;
  /// Optional size bound beyond the paper (0: none): tets whose circumcenter
  /// lies in the input's bounding box and whose circumradius exceeds it are
  /// split as in rule 6, and sharp subsegments longer than 2/3 of it are split
  /// at the end of CONFORM, before the protecting balls are fixed, so that
  /// the bound holds next to sharp edges too. Tets whose circumcenter lies in
  /// a vertex ball keep a circumradius up to its radius f(u)/4.
  double max_size = 0;
  /// Beyond the paper: the improvement phase after PUMP (flips, smoothing of
  /// interior Steiner vertices, interior insertion; core/src/mesher/improve.h)
  /// raises the smallest dihedral angle while the boundary stays as it is.
  /// false: the WQMESH output of the paper, bit for bit.
  bool improve = true;
  /// Beyond the paper (and beyond Stellar): with `improve`, after the
  /// improvement phase's passes, a polish (core/src/mesher/improve_polish.cpp)
  /// raises the smallest dihedral angle D itself: rounds of flips, smoothing,
  /// contraction and in-plane slides across slanted facets on the tets of the
  /// smallest angles, every new tet's smallest angle above max(D, 5 degrees),
  /// never more tets than the passes left; then a second stage of rounds that
  /// judges every change by the smallest dihedral angle itself (smoothing by
  /// core/src/mesher/improve_dihedral.cpp's descent on the star's largest
  /// dihedral cosine). 2026-12-03: slit.off 20.15 (default) -> 30.78 degrees,
  /// edge_facet 28.94, the 20mm cube 18.66. Costs several times REFINE +
  /// PUMP's time on the small models (unbounded budget), hence off by
  /// default. Does nothing without `improve`.
  bool polish = false;
  /// PUMP visits the sliver vertices in passes; it stops after a pass that
  /// improves nothing or after this many passes.
  int max_pump_passes = 4;
  /// Also time a plain Delaunay triangulation of the final vertex set (the
  /// floor no refinement can beat), in MeshResult::delaunay_floor_s.
  bool measure_floor = false;
  /// The stuck-step watchdog (beyond the paper): a single step of the mesher
  /// (one insertion with its upkeep, one queue element, one rule-3 or rule-7
  /// candidate, one PUMP vertex) that does more than this many units of work
  /// ends the run with stopped = "stalled". A unit is a cell of a star, a
  /// feature or walk looked at, or a cell of a PUMP weight change, each
  /// bounded by the size of a star; the count is deterministic, so native and
  /// wasm stop at the same point. The default is far above any step of a
  /// sound run: the largest steps measured were 2e4 to 6e4 units (decimated
  /// spheres, fandisk.off) and 5e5 (anchor.off, in CONFORM).
  std::uint64_t stall_work = 100'000'000;
};

/// Progress report: phase name ("initialize", "conform", "refine", "pump",
/// "extract"), counts so far, and a fraction in [0, 1] of the whole run
/// (an estimate: refinement has no known end).
struct Progress {
  std::string phase;
  std::size_t vertices = 0;
  std::size_t steps = 0;  ///< insertions by the rules and PUMP vertices so far
  double fraction = 0;
};

/// Called at each phase change and after a bounded amount of work inside
/// every phase and every long step: at least every 256 steps and every 256
/// units of work (WorkMeter::kPollWork; a unit is bounded by the size of a star:
/// see MeshOptions::stall_work), INITIALIZE's insertions and the whole-mesh
/// scans of rule 7 and PUMP included, so a cancel takes effect within a few
/// milliseconds of work. Returns false to cancel the run. It may also throw
/// to abandon the run (the wasm bindings do when memory is short): it is
/// never called from inside a CGAL insertion.
using ProgressCallback = std::function<bool(const Progress&)>;

/// A protecting ball (section 4.2): a vertex ball (radius f(u)/4 at a sharp
/// vertex u) or the diametric ball of a sharp subsegment doubled at the end of
/// CONFORM.
struct ProtectingBall {
  Point3 center{{0, 0, 0}};
  double radius = 0;
  bool vertex_ball = false;
};

/// The class of an output tet, on the mesh as written (unweighted; the
/// definition and where it goes beyond the paper: core/src/mesher/classify.h).
/// skinny: R/l above rho0; sliver: R/l at most rho0 and a dihedral angle below
/// theta; near a small input angle: the circumcenter lies on or inside a
/// protecting ball (rule 6 refuses it) or a vertex v, weighted with L_v^2/9
/// (L_v its shortest edge in the mesh), encroaches the two-times expansion of
/// a protecting ball (c, r): |v - c|^2 <= (2r)^2 + L_v^2/9 (rule 7 and PUMP
/// skip it).
enum class TetClass { good = 0, skinny_near = 1, sliver_near = 2, violation = 3 };

/// The classes of the tets of a mesh and their counts (classify_mesh).
struct MeshClasses {
  std::vector<TetClass> tet_class;  ///< per tet
  std::size_t skinny = 0, slivers = 0, near_small_angle = 0, violations = 0;
};

/// The classes of every tet of `mesh` (its vertices as they are: weights are
/// not used) from the protecting balls and the thresholds rho0, theta_deg,
/// by the definition of TetClass: the same code as the mesher's, for a mesh
/// read back from a file with the balls of its statistics (`wqmesh measure
/// --stats`). Throws std::out_of_range on a bad vertex index.
MeshClasses classify_mesh(const TetMesh& mesh, const std::vector<ProtectingBall>& balls, double rho0, double theta_deg);

struct PhaseStats {
  std::string name;
  double time_s = 0;
  std::size_t points_inserted = 0;
};

/// What the improvement phase did (MeshResult::improve; all 0 when it did
/// not run). min_dihedral_before/after: the smallest dihedral angle of the
/// mesh before and after it, degrees. The class counts *_before: those of
/// the mesh before it.
struct ImproveStats {
  bool ran = false;
  int passes = 0;
  std::size_t flips23 = 0, flips32 = 0, flips44 = 0, flips22 = 0, edge_removals = 0, smoothed = 0, inserted = 0;
  std::size_t contractions = 0;  ///< vertices removed by edge contraction
  /// Of `smoothed`, the moves of boundary vertices (slides along an axis of
  /// their facets); of `inserted`, the points inserted on a facet.
  std::size_t slid = 0, inserted_on_boundary = 0;
  std::size_t multi_face_removals = 0;  ///< of at least two faces (one is a 2-3 flip)
  /// Of the changes above, those the polish made (0 unless MeshOptions::polish).
  std::size_t polished = 0;
  double min_dihedral_before = 0, min_dihedral_after = 0;
  std::size_t slivers_before = 0, skinny_before = 0, near_small_angle_before = 0, violations_before = 0;
  std::size_t tets_before = 0;  ///< the tets of the mesh before it
  /// Operations accepted in all (a mesh with none is the input mesh as it was).
  std::size_t changes() const {
    return flips23 + flips32 + flips44 + flips22 + edge_removals + smoothed + inserted + contractions +
           multi_face_removals;
  }
};

struct MeshResult {
  /// The interior tets (weighted: mesh.weights), their boundary triangles with
  /// the input facet of each.
  TetMesh mesh;
  /// Per tet, unweighted (the geometry of mesh.vertices; what the classes
  /// and the statistics use).
  std::vector<TetQuality> quality;
  /// Per tet: the paper's orthoradius-edge ratio rho (section 3) with the
  /// weights of mesh.weights, R/l where there are none. The weighted view,
  /// apart from the classes.
  std::vector<double> orthoradius_edge;
  std::vector<TetClass> tet_class;  ///< per tet (unweighted, see TetClass)
  /// Per vertex of mesh: N(v), the nearest-neighbour distance at the end of
  /// REFINE (the weight bound is N(v)^2/9).
  std::vector<double> nearest_neighbour;
  /// Per vertex of mesh: its index in the PLC when it is an input vertex, else -1.
  std::vector<int> input_vertex;
  std::vector<ProtectingBall> protecting_balls;
  /// "" when done, "limit" (max_vertices reached), "cancelled" (the progress
  /// callback returned false; the run then returns at once and holds no mesh:
  /// its partial mesh is not extracted) or "stalled" (a step went past
  /// MeshOptions::stall_work units of work: the watchdog; or REFINE's rules
  /// 4-5 split the boundary without end: the runaway guard, beyond the paper).
  std::string stopped;
  /// Why the run stopped, in words, when it did (for "limit": where the vertex
  /// budget went, or the input feature that needs more vertices than it; for
  /// "stalled": the phase, the step and the work it did, or for a runaway the
  /// rules, their counts and the input edge or facet of the last split).
  std::string stop_message;
  /// Every subsegment and subfacet is in the final triangulation.
  bool conforming = false;
  std::size_t input_points = 0;         ///< PLC vertices
  std::size_t sharp_elements = 0;       ///< sharp vertices + sharp edges
  std::size_t points_inserted = 0;      ///< all, in the box too (box corners excluded)
  std::size_t slivers_before_pump = 0;  ///< interior slivers at the end of REFINE
  std::size_t slivers = 0, skinny = 0, near_small_angle = 0, violations = 0;
  /// Tets whose orthoradius_edge is above rho0 (the paper's skinny for a
  /// weighted mesh); no class depends on it.
  std::size_t orthoradius_skinny = 0;
  std::size_t pumped_vertices = 0;
  /// Points inserted by each rule of CONFORM and REFINE: rule_points[i] for
  /// rule i (1..7); rule_points[0] counts those of INITIALIZE.
  std::array<std::size_t, 8> rule_points{};
  std::vector<PhaseStats> phases;
  /// With MeshOptions::measure_floor: seconds to build the plain Delaunay
  /// triangulation of every vertex of V (box included), else 0.
  double delaunay_floor_s = 0;
  std::size_t all_vertices = 0;  ///< |V|, the box and the outside included
  /// How often a loop cap of the mesher was reached (beyond the paper: each
  /// bounds a loop the paper lets run to its end; see CONTRIBUTING.md).
  std::size_t caps_reached = 0;
  /// The improvement phase (MeshOptions::improve).
  ImproveStats improve;
};

/// A lower estimate of the vertices WQMESH needs for the two input edges that
/// meet at the smallest edge-edge angle, weighed by their length (see
/// estimate_edge_points in mesher.cpp for the argument).
struct PointEstimate {
  double points = 0;  ///< 0 when no two edges meet at an acute angle
  int vertex = -1, edge1 = -1, edge2 = -1;
  double degrees = 0;
};
PointEstimate estimate_edge_points(const PLC& plc, const Analysis& analysis);

/// Meshes the polyhedron bounded by `plc` (validated by build_plc, analysed by
/// analyze) with WQMESH. When estimate_edge_points already exceeds
/// options.max_vertices, returns at once with stopped = "limit" and a
/// stop_message naming the two edges (no mesh); likewise when INITIALIZE
/// alone would insert more than options.max_vertices vertices. Otherwise a
/// run never holds more than options.max_vertices vertices plus the few one
/// insertion step adds. Deterministic: the same input and options give the
/// same mesh. Throws std::runtime_error on an internal failure.
MeshResult mesh_polyhedron(const PLC& plc, const Analysis& analysis, const MeshOptions& options = {},
                           const ProgressCallback& progress = {});

}  // namespace wqmesh

namespace wqmesh {

/// The volume enclosed by a PLC (divergence theorem over its facets' loops).
double plc_volume(const PLC& plc);

/// The statistics of a run as JSON, with at least the keys of the command
/// line's contract: input_points, sharp_elements, points_inserted, vertices,
/// tets, min_dihedral_deg, radius_edge_bins, dihedral_bins, slivers, skinny,
/// near_small_angle, violations, volume_input, volume_mesh, protecting_balls,
/// stopped, time_s, phases.
/// `peak_memory_mb` (the caller's measure; negative: not written).
std::string mesh_stats_json(const PLC& plc, const MeshResult& result, const MeshOptions& options, double time_s,
                            double peak_memory_mb = -1, bool pretty = true);

}  // namespace wqmesh
