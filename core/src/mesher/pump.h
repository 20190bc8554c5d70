// wqmesh: PUMP (private; paper, section 4.3): the weights of the sliver
// vertices. It is handed V's triangulation, whose weights are all it changes,
// and reads the subcomplex, the protecting balls and the options; it keeps
// the inside/outside labels of cells as the weighted triangulation changes,
// the walls (input subfacets) and, per vertex, the subfacets whose presence
// must be kept.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include "mesher/domain.h"
#include "mesher/protecting_balls.h"
#include "mesher/subcomplex.h"
#include "mesher/work_meter.h"
#include "triangulation.h"
#include "wqmesh/mesher.h"

namespace wqmesh::mesher {

/// The inside/outside label of cells by their TetKey: open-addressing
/// tables (linear probing, each at most 3/4 full) with the labels in a byte
/// array beside the keys, 17 bytes a slot. Beyond the paper (issue 15, the
/// peak memory): it holds every cell of V's triangulation while PUMP runs
/// on labels that may depend on the cells' order (Pump::use_scan, or PUMP's
/// own scan; with use_cell_labels the labels stay in the cells and there is
/// no table), where a std::unordered_map took about 70 bytes a cell (a node per entry
/// and the buckets). PUMP adds the cells its weight changes make, so the
/// keys outgrow the first table: then a further table is added beside the
/// full ones, with room for half as many keys as there are, instead of
/// rehashing all into one of twice the size (the old and the new table
/// together were the peak of PUMP, 51 bytes a slot of the old). A key is in
/// one table only. Only look-ups and stores: the same answers as a map.
class CellLabels {
 public:
  /// Empties the table, with room for n keys.
  void reset(std::size_t n);
  /// The label of key t, or nullptr when it has none.
  const char* find(const TetKey& t) const;
  /// Sets the label of t (added when it had none).
  void set(const TetKey& t, char label);
  /// The tables (tests watch the growth).
  std::size_t tables() const { return tables_.size(); }

 private:
  struct Table {
    std::vector<TetKey> keys;
    std::vector<char> labels;
    std::size_t used = 0;
    /// The slot of t, or of the empty slot where t would go.
    std::size_t slot(const TetKey& t) const;
  };
  /// Adds an empty table with room for n keys.
  void add_table(std::size_t n);
  std::vector<Table> tables_;
  std::size_t used_ = 0;  ///< keys in all tables
};

class Pump {
 public:
  Pump(const Domain& domain, const MeshOptions& options, RegularTriangulation& tri,
       const std::vector<MVertex>& vertices, const Subcomplex& sub, const ProtectingBalls& balls, WorkMeter& meter)
      : dom_(domain), opt_(options), tri_(tri), verts_(vertices), sub_(sub), balls_(balls), meter_(meter) {}
  /// N(v) for every vertex, cell labels, walls. Called by run().
  void prepare();
  /// Hands prepare() the cells of the current triangulation's graph (CGAL's
  /// order; prepare reads no neighbours) and their interior_labels, so that
  /// it does not scan it again (beyond the paper:
  /// Extract::count_qmesh_slivers made them just before).
  void use_scan(RegularTriangulation::CellGraph g, std::vector<char> inside) {
    scan_ = std::move(g);
    scan_labels_ = std::move(inside);
  }
  /// Tells prepare() that the cells' label bytes of the current
  /// triangulation hold their interior_labels (label_cells_in_place, by
  /// Extract::count_qmesh_slivers just before): it reads them there, with
  /// no cell graph, and keeps PUMP's labels there too (no table; beyond
  /// the paper, issue 15, the peak memory).
  void use_cell_labels() { cell_labels_ = true; }
  void run();
  /// (angle_key of the smallest dihedral, vertex) for the vertices of
  /// inside tets with a dihedral angle <= theta, worst first (ties by
  /// vertex), as found by prepare().
  std::vector<std::pair<double, int>> candidates() const;
  /// N(v)^2/9.
  double weight_bound(int v) const;
  /// N(v) for every vertex, as prepare() measured it (the extraction reports
  /// these).
  const std::vector<double>& nearest_neighbours() const { return nn_; }
  /// The vertices with a weight once run() is done.
  std::size_t pumped_vertices() const { return pumped_vertices_; }

  struct Features {
    std::vector<std::uint64_t> segments;
    std::vector<Tri> subfacets;
  };
  /// The features whose presence a weight change of v must keep.
  Features features_around(int v) const;
  /// Sets v's weight to w; returns the angle_key of the smallest dihedral
  /// angle of the inside tets around v (2 with none), or -1 when w hides v
  /// or removes one of `f`.
  double evaluate(int v, double w, const Features& f);

  struct Choice {
    double weight = 0, quality = -1, base = -1;
  };
  /// Chooses, and sets, the weight of v in [0, N(v)^2/9] maximising the
  /// smallest dihedral angle around v (its angle_key: quality and base), searching the interval at its critical
  /// weights; keeps the old weight unless the new one is strictly better.
  Choice pump_vertex(int v);

  /// The label tables of prepare() and run() (tests watch the growth).
  std::size_t label_tables() const { return labels_.tables(); }

  /// Beyond the paper (issue 15, the peak memory): the first label table
  /// has room for the cells and 1/kNewCellRoom as many new ones, the cells
  /// PUMP's weight changes make (1.3% of the cells on anchor.off, 1.5% on
  /// fandisk.off, 0.4% on part.off), so that no second table (half the
  /// keys: 48 MB on mpi.off, BENCHMARKS.md, session 6 h8) is added for
  /// them; one is added beyond that room, as before.
  static constexpr std::size_t kNewCellRoom = 16;
  /// Beyond the paper (issue 15: native = wasm): PUMP compares dihedral
  /// angles by a key made with +, -, *, / and sqrt only, the pseudo-angle
  /// of the angle's cosine and sine (in [0, 2], increasing with the angle:
  /// 0 at 0 degrees, 1 at 90, 2 at 180), never by degrees from atan2, whose
  /// last bit glibc and the wasm libc round differently (BENCHMARKS.md,
  /// session 7, h6): anchor.off's candidate order, so its mesh, differed.
  /// The key of an angle of `deg` degrees, 0 <= deg <= 180 (theta's).
  static double angle_key(double deg);
  /// At most kLabelRounds rounds of label propagation for a new cell.
  static constexpr int kLabelRounds = 64;
  /// At most kCriticalSteps critical weights visited per vertex (a choice:
  /// stars change at a few dozen weights in practice).
  static constexpr int kCriticalSteps = 256;

 private:
  /// prepare()'s labels and candidates from a cell graph (use_scan's, or
  /// a scan of its own).
  void prepare_from_scan();
  /// The angle_key of t's smallest dihedral angle (its points' +, -, *, /
  /// and sqrt only).
  double angle_of(const Tet& t) const;
  bool is_wall(int a, int b, int c) const;
  /// The label of cell t, `ref` its CellRef (incident_cells'), found by
  /// propagation when it has none yet.
  char label(const Tet& t, CellRef ref);
  /// t's label (0 or 1) where PUMP keeps them, -1 when it has none.
  int known(const Tet& t, CellRef ref) const;
  void learn(const Tet& t, CellRef ref, char label);
  double next_critical(int v, double w, double cap) const;
  bool present(const Features& f) const;

  const Domain& dom_;
  const MeshOptions& opt_;
  RegularTriangulation& tri_;
  const std::vector<MVertex>& verts_;
  const Subcomplex& sub_;
  const ProtectingBalls& balls_;
  WorkMeter& meter_;
  const double theta_key_ = angle_key(opt_.theta_deg);
  std::size_t pumped_vertices_ = 0;
  std::vector<double> nn_;  ///< N(v), measured by prepare()
  CellLabels labels_;
  /// The walls (the input facets' subfacets), sorted, for binary search;
  /// and, per vertex v, its subfacets (sorted triangles) at
  /// vertex_facets_[vertex_facet_start_[v]] up to that of v + 1, in the
  /// subcomplex's order. Flat arrays (issue 15, the peak memory: a hash set
  /// and a vector per vertex took twice as much beside PUMP's labels).
  std::vector<Tri> walls_;
  std::vector<std::size_t> vertex_facet_start_;
  std::vector<Tri> vertex_facets_;
  std::vector<std::pair<double, int>> candidates_;
  RegularTriangulation::CellGraph scan_;  ///< use_scan's, until prepare()
  std::vector<char> scan_labels_;
  bool cell_labels_ = false;  ///< use_cell_labels(), until prepare()
  /// The labels are in the cells' label bytes (use_cell_labels), not in
  /// labels_, from prepare() on.
  bool in_cells_ = false;
};

}  // namespace wqmesh::mesher
