// wqmesh: the improvement phase after PUMP (beyond the paper: Cheng, Dey and
// Ray's WQMESH ends with PUMP; MeshOptions::improve = false keeps its output
// bit for bit). After Klingner and Shewchuk, "Aggressive Tetrahedral Mesh
// Improvement" (IMR 2007): the objective is the smallest sine of the six
// dihedral angles of a tet (min-sine), raised by topological operations on
// interior faces and edges (2-3 flips; edge removal, whose rings of 3 and 4
// tets are the 3-2 and 4-4 flips; multi-face removal), 2-2 flips of boundary triangles inside
// one input facet, smoothing of interior Steiner vertices and insertion of
// interior Steiner points. Unlike Stellar, the boundary is kept as it is
// (only exactly coplanar 2-2 flips inside one facet change it), a vertex on
// a boundary triangle moves only along a coordinate axis that leaves it on
// its facets exactly as before, or in the polish along a direction checked
// exactly to do so ("Boundary operations" below), and every change must pass
// two guards beyond the paper's rule (see Improver::accept).
//
// Contract of every change: a set of tets is replaced by another set with the
// same boundary faces; it is accepted only if the worst min-sine of the new
// tets is strictly greater than the worst of the old ones and every new tet
// is positively oriented by CGAL's exact predicate (EPICK orientation), so
// the new tets fill exactly the old region, the worst tet of the mesh never
// gets worse and nothing is ever inverted. One exception, beyond the rule:
// a change made to remove violations (Improver::fix_violations) may also be
// kept when its new worst is at least sin(kImproveTargetDeg), or, where no
// such change removes the violation, sin(kFixSecondDeg), and beats the mesh's
// worst, so the worst tet of the mesh never gets worse.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include "mesher/classify.h"
#include "mesher/protecting_balls.h"
#include "wqmesh/mesher.h"

namespace wqmesh::mesher {

/// Regular passes at most (each: contraction, flips, smoothing, contraction,
/// over the tets below kImproveTargetDeg; insertion where a sliver is left
/// only in a pass after a stalled one, and in the last regular pass when the
/// pass before it raised the smallest dihedral angle: Improver::run); the
/// phase stops earlier after a stalled pass with insertion.
constexpr int kImprovePasses = 6;
/// Beyond the paper, a choice (issue 14; mpi.off's figures in BENCHMARKS.md,
/// "Session 14 (2026-12-04), h1" and "Session 15 (2026-12-07), h1"): after
/// the regular passes, up to kImproveExtraPasses more, each with insertion,
/// follow while the pass just made extends (Improver::pass_extends): it
/// leaves the mesh's smallest dihedral angle under kExtraPassBelowDeg and
/// raises it by more than the factor kExtraPassRise or cuts the count under
/// kQualityCountDeg by more than the share kExtraPassCut. On mpi.off (worst
/// tets near small input angles that still move) 10 passes reach 0.0557
/// degrees where 6 left 0.0158 (TetGen -pq1.414/10: 0.04); without the
/// 0.5-degree bound part.off takes an extra pass (4.983 -> 4.990 degrees) for
/// about a tenth of its phase's time; extending while any measure improves
/// gives slit-1 14 passes and part a second tet under 5 degrees.
constexpr int kImproveExtraPasses = 8;
constexpr double kExtraPassBelowDeg = 0.5;
constexpr double kExtraPassRise = 1.5;
constexpr double kExtraPassCut = 0.1;
/// Beyond the paper, a choice (issue 14's measures): a pass stalls when it
/// neither raises the mesh's smallest dihedral angle nor lowers the count of
/// tets whose smallest dihedral angle is under kQualityCountDeg degrees
/// (Improver::pass_improves).
constexpr double kQualityCountDeg = 5;
/// Tets whose min-sine is below sin(kImproveTargetDeg) are worked on (20:
/// on the 20mm cube and slit-1 the same smallest angle as with 30, in a
/// fifth to a third of the time).
constexpr double kImproveTargetDeg = 20;
/// Insertion is tried on the tets still below sin(kInsertBelowDeg) after a
/// pass's flips and smoothing.
constexpr double kInsertBelowDeg = 10;
/// Beyond the paper: a choice for the phase's time (issue 14);
/// insert_boundary() refuses a candidate whose new tets' worst min-sine at
/// the point before its ascent is below kInsertBoundaryStart times its
/// cavity's worst (0.7: on wedge-1 it refuses 14,218 of 20,695 candidates,
/// 8 of the 148 that were the best of their tet among them; on the 21 models
/// no smallest angle and no count of tets under 5 degrees gets worse, wedge-1
/// 211 -> 190 under 5 degrees; 0.8 gives wedge 83 -> 97).
constexpr double kInsertBoundaryStart = 0.7;
/// fix_violations' second rule: where no change with a new worst of at least
/// sin(kImproveTargetDeg) removes a violation, one with a new worst of at
/// least sin(kFixSecondDeg) (and above the mesh's worst) may (10: no new tet
/// where insertion would be tried, none under issue 14's 5 degrees).
constexpr double kFixSecondDeg = 10;
/// Edge removal handles rings of at most this many tets (the dynamic
/// programme over the ring's polygon is O(n^3)).
constexpr int kMaxRing = 7;
/// Smoothing steps per vertex and pass.
constexpr int kSmoothSteps = 3;
/// An insertion is refused when the mesh would hold more than
/// max(kMaxTetGrowth times the tets it started with, those plus
/// kMinTetSlack) (issue 14: at most 10% more tets).
constexpr double kMaxTetGrowth = 1.1;
constexpr std::size_t kMinTetSlack = 8;
/// An insertion cavity holds at most this many tets.
constexpr int kMaxCavity = 48;
/// Vertex removal (improve_contract.cpp) is tried on the vertices of the
/// tets below sin(kContractBelowDeg) (10: on wedge and wedge-1, 696 tets
/// under 5 degrees left where 5 leaves 708, 3 leaves 757, 20 leaves 728).
constexpr double kContractBelowDeg = 10;
/// A work bound (beyond the paper and Klingner-Shewchuk): a vertex whose
/// star holds more than kContractMaxStar tets is not contracted. A vertex
/// with a star of n tets has about n / 2 targets, each judged in O(n) (the
/// star's vertex list once per vertex: removal()), so O(n^2) per vertex;
/// before that list was sorted per target (O(n^2 log n)), mpi.off's default
/// run spent more than 30 CPU minutes in contract_pass without the bound.
/// Stars of sound meshes hold 10-100 tets.
constexpr std::size_t kContractMaxStar = 256;
/// The relaxed rule counts the tets below sin(kContractCountDeg) (issue 14's
/// measure: tets under 5 degrees).
constexpr double kContractCountDeg = 5;
/// Whether contract_pass() also takes contractions by the relaxed rule (from
/// its second call on; see the block "Vertex removal" below).
constexpr bool kContractRelaxed = true;
/// polish() (see the block "Polish" below): each round works on the
/// kPolishTets tets of the smallest dihedral angles below the mesh's smallest
/// plus kPolishBandDeg; at most kPolishRounds rounds, and it stops after
/// kPolishStalls rounds in a row that began with the smallest angle risen
/// by less than kPolishRiseDeg. On slit.off (18.52 degrees after the passes)
/// band 8 and 64 tets give 28.19 (48 tets: 27.30, 80: 31.07, band 6: 28.05,
/// band 10: 25.90; with the atan2 decisions of before: 29.00, 16 tets: 23.22,
/// 32: 24.08, every tet of the band: 31.97 for about three times the work):
/// the outcome of such local searches is sensitive to these (80 tets give
/// edge_facet 28.06 and the 20mm cube 17.56, against 28.88 and 18.61). The 64 tets
/// bound a round's work (the 20mm cube's phase stays under REFINE + PUMP's
/// time: 0.75 of it, 1.94 with every tet of the band). Its floor is never below
/// kPolishFloorDeg (issue 14's measure: polish makes no tet under 5 degrees).
constexpr double kPolishBandDeg = 8;
constexpr int kPolishTets = 64;
constexpr int kPolishRounds = 30;
constexpr int kPolishStalls = 2;
constexpr double kPolishRiseDeg = 0.01;
constexpr double kPolishFloorDeg = 5;
/// ascend_dihedral(): steps per smoothing, and the cosines counted as
/// nearly the largest (within kDihedralActive of it, in cosine).
constexpr int kDihedralSteps = 8;
constexpr double kDihedralActive = 1e-2;
/// The polish's ties: a cosine must be below the one it beats by this much
/// (1e-12, about 1e-10 degrees; why: improve_polish.cpp).
constexpr double kPolishTieCos = 1e-12;
/// The six edges ij of a tet, each with the two other vertices k and l (the
/// polish's cosines, improve_polish.cpp, and their gradients,
/// improve_dihedral.cpp, in this order).
constexpr int kEdgeAndOthers[6][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2},
                                      {1, 2, 0, 3}, {1, 3, 0, 2}, {2, 3, 0, 1}};
/// The polish is off by default (MeshOptions::polish = false) because of
/// issue 14's time goal (the phase under REFINE + PUMP's time): on slit,
/// edge_facet, extrusion and slit-1 it takes the phase to 3 to 8 times
/// REFINE + PUMP's time (slit: 30 rounds, 4,372 operations tried and 1,874
/// made on 279 tets; three quarters of the smoothings tried succeed: the
/// work is progress in small steps, not retries; BENCHMARKS.md, "The polish:
/// why it stays off by default"). On,
/// smallest angle: slit 18.52 -> 28.19, edge_facet 20.21 -> 28.88, 20mm
/// cube 15.43 -> 18.61, extrusion 11.82 -> 14.04, slit-1 11.56 -> 16.98, box
/// 35.26 -> 45, with fewer or equal tets, none under 5 degrees and no
/// violation.

/// Coarsening (improve_coarsen.cpp, Improver::coarsen(); beyond the paper
/// and beyond Stellar, issue 14's goal for slit.off: at least TetGen's 27.54
/// degrees). It runs only when the passes leave the mesh's smallest
/// dihedral angle D at kImproveTargetDeg or more (of the 21 models: box,
/// slit, spike, edge_facet), at most kCoarsenRounds times: at most
/// kCoarsenSweeps sweeps of contraction over every vertex, then the
/// polish's second stage cut to ceil(T / kCoarsenPolishShare) changes (T:
/// the live tets when the step begins). Why each value (slit's figures;
/// BENCHMARKS.md, "Session 14 ..., h2"; all but the sweeps' with the sweeps
/// unbounded):
/// - rounds 3 and cut tets / 16 (session 13's experiment): 27.81 degrees; 2
///   rounds gave 26.82, 4 gave 27.97; tets / 12 gave 25.47, / 24 26.55 (a
///   local search: not monotone in the cut);
/// - sweeps 2 a round: 28.62 degrees with 69 tets; 1 gave 28.81 with 104, 3
///   gave 25.15, unbounded 27.81 with 74 for about 3% more of the step's time;
/// - kCoarsenRiseDeg 1: a contraction may make its star worse, but every new
///   tet's min-sine must beat min(the star's worst, sin(D + 1 degree)), so
///   the tets it makes stay a degree clear of the mesh's smallest angle,
///   which the polish then raises (0, the strict rule at the floor, gave
///   26.45, 0.5 gave 27.18, 2 gave 24.99);
/// - kCoarsenStallDeg 1.5: a round after the first runs only when the one
///   before raised D by that much (the step's time, issue 14: the phase under
///   REFINE + PUMP's time). Slit's first two rounds raise it by 4.46 and 2.19
///   degrees; edge_facet's by 1.24 and 0.99, where its second and third
///   rounds cost about as much as the first for 1.0 degree more; spike's by
///   1.28;
/// - kCoarsenWork 3: the work budget, operations tried per live tet when the
///   step begins (a contraction of a vertex over all its targets; in the
///   polish, a topological operation on a tet, a smoothing or a contraction
///   of a vertex), whatever the clock, so that the step's work is bounded by
///   the mesh's size: above what the four models' steps try (slit at most
///   1.7 per tet, edge_facet 0.85), a bound for larger meshes, not a setting.
constexpr int kCoarsenRounds = 3, kCoarsenSweeps = 2;
constexpr std::size_t kCoarsenPolishShare = 16, kCoarsenWork = 3;
constexpr double kCoarsenRiseDeg = 1, kCoarsenStallDeg = 1.5;

/// The smallest sine of the six dihedral angles of tet abcd (each sine is
/// 6 V l_ij / (|n_k| |n_l|), n_k the area normal of the face opposite k);
/// negative when abcd is negatively oriented, 0 when a face is degenerate.
double min_sine(const Point3& a, const Point3& b, const Point3& c, const Point3& d);
/// min_sine(a, b, c, d), bit for bit, when abcd's orientation determinant
/// (as min_sine() computes it) is positive; else some value at most 0 (the
/// min-sine is then at most 0 too) without the rest of the work. The
/// phase's time (issue 14): for callers that refuse every value at most 0.
double min_sine_if_positive(const Point3& a, const Point3& b, const Point3& c, const Point3& d);

/// The improvement phase on an extracted mesh (r.mesh: vertices, tets,
/// boundary triangles with their facets; r.nearest_neighbour, r.input_vertex,
/// r.mesh.weights kept per vertex). The input vertices never move; the
/// vertices of boundary triangles only slide (slide_axes). New vertices get weight 0 (when r.mesh has
/// weights), input_vertex -1 and nearest_neighbour = their shortest edge.
/// Guards beyond the paper's rule (and Stellar's): with the protecting balls
/// (set_classes), a change may not leave more violations (TetClass, by
/// classify.h's TetClassifier, the code of the statistics) among the tets
/// whose class it can change than there were; with max_size > 0, no new
/// tet's circumradius exceeds max(max_size, the largest old one). A tet is
/// retried only after a change touched one of its vertices (and a vertex
/// smoothed again only after its star changed), so later passes cost what
/// the previous one changed.
class Improver {
 public:
  using Tet = std::array<int, 4>;
  Improver(MeshResult& r, double rho, double max_size, const std::function<bool()>& keep_going = {});

  /// With the protecting balls and theta (degrees): a change may not leave
  /// more violations (TetClass) than there were among the tets whose class
  /// it can change: its new tets, and the tets at a vertex whose L_v (the
  /// shortest edge at v, which "near" depends on) it changes. Computes L_v
  /// and the shape of every tet (the phase keeps them current).
  void set_classes(const ProtectingBalls* balls, double theta_deg);
  /// Runs up to kImprovePasses regular passes, then up to
  /// kImproveExtraPasses extra ones while pass_extends() holds of the pass
  /// just made; false when keep_going returned false (the mesh is then valid
  /// but only partly improved). Call finish() after. A pass stalls when it
  /// changes nothing or does not improve the quality measures
  /// (pass_improves); a pass after a stalled one adds insertion, so does the
  /// last regular pass when the pass before it raised the smallest dihedral
  /// angle, and every extra pass; the phase stops after a stalled pass with
  /// insertion. So at most two passes in a row leave the measures as they
  /// were.
  bool run();
  /// The phase's quality measures of the live tets (issue 14's): the
  /// smallest dihedral angle (degrees; 180 without tets) and the count of
  /// tets under kQualityCountDeg.
  struct QualityMeasures {
    double smallest_dihedral_deg = 180;
    std::size_t under_count_deg = 0;
  };
  QualityMeasures quality_measures() const;
  /// Whether a pass from `before` to `after` improves the measures: the
  /// smallest dihedral angle rises or the count under kQualityCountDeg falls
  /// (strictly; either is enough).
  static bool pass_improves(const QualityMeasures& before, const QualityMeasures& after);
  /// The phase's time (issue 14): a min-sine that shows, without the six
  /// angles, that a tet's smallest dihedral angle is above `deg` degrees: a
  /// tet whose min_sine() is above sine_above(deg) has tet_min_dihedral_deg()
  /// above deg (+infinity when no min-sine shows it: deg of 60 or more). The
  /// smallest dihedral angle theta of a tet is below 90 degrees and every
  /// dihedral angle's sine is at least the min-sine q, so theta >= asin(q);
  /// the margins (1e-6 relative on the angle and on the sine, 1e-12 absolute)
  /// exceed the rounding of min_sine() and of tet_min_dihedral_deg() on any
  /// tet whose min-sine is above 1e-12. quality_measures(), mesh_worst() and
  /// the contraction's floor test skip the angles of such tets.
  static double sine_above(double deg);
  /// Whether an extra pass follows a pass from `before` to `after` (see
  /// kImproveExtraPasses): after's smallest dihedral angle is under
  /// kExtraPassBelowDeg, and either it is above kExtraPassRise times
  /// before's or after's count under kQualityCountDeg is below
  /// (1 - kExtraPassCut) times before's. It implies pass_improves().
  static bool pass_extends(const QualityMeasures& before, const QualityMeasures& after);
  /// What each pass of run() did, in order (for the tests of the loop's
  /// contract): the measures before and after it (after = before when it
  /// changed nothing) and whether it inserted.
  struct PassRecord {
    QualityMeasures before, after;
    bool inserted = false;
  };
  const std::vector<PassRecord>& pass_records() const { return pass_records_; }
  /// Writes the mesh back into r (live tets and boundary triangles, compact)
  /// and fills r.improve's operation counts and passes.
  void finish();

  // The operations, each on a live tet t; true when a change was accepted.
  /// 2-3 flip of t's face opposite its vertex k (an interior face).
  bool flip23(int t, int k);
  /// Removes the interior edge of t between its vertices i and j (ring of
  /// 3 to kMaxRing tets: 3-2 flip, 4-4 flip, edge removal).
  bool remove_edge(int t, int i, int j);
  /// 2-2 flip of the boundary edge of t between its vertices i and j: the
  /// two boundary triangles at it lie in one input facet, their four points
  /// are exactly coplanar, and exactly two tets hold the edge.
  bool flip22(int t, int i, int j);
  /// Moves free vertex v (on no boundary triangle, no input vertex) to raise
  /// the worst min-sine of its star, or a boundary vertex along its
  /// slide_axes(); false if it did not move.
  bool smooth(int v);
  /// Inserts an interior Steiner point in or near t (candidates: its
  /// circumcenter, its centroid, the apex of a regular tet on each of its
  /// faces on t's side), re-triangulating a star-shaped cavity of tets around
  /// it (grown from the tets whose circumsphere holds the point until every
  /// outer face sees it; boundary triangles may bound the cavity, they are
  /// kept). Each candidate is first moved by ascend() within its cavity; the
  /// best accepted one is inserted.
  bool insert(int t);

  /// Tries every topological operation on t; true when one was accepted.
  bool improve_tet(int t);

  // Read access for the tests.
  const std::vector<Tet>& tets() const { return tets_; }
  bool alive(int t) const { return tets_[t][0] >= 0; }
  double quality(int t) const { return q_[t]; }
  /// The class guard's L_v^2 of v (kept current through every change; +inf
  /// without set_classes).
  double shortest_edge2(int v) const { return v < int(L2_.size()) ? L2_[v] : HUGE_VAL; }
  const std::vector<Point3>& points() const { return P_; }
  bool movable(int v) const { return !fixed_[v]; }
  const ImproveStats& stats() const { return st_; }
  /// The worst min-sine over the live tets.
  double worst() const;
  /// The class of live tet t by the phase's own L_v and shapes (good when
  /// set_classes was not called): what classify_tets gives for it.
  TetClass tet_class(int t) const;

 private:
  /// With `floor` (not NaN), the new tets must beat floor instead of the old
  /// set's worst (contract()'s relaxed rule; the other guards are the same).
  bool accept(const std::vector<int>& old, const std::vector<Tet>& fresh, double& worst_new,
              double floor = std::numeric_limits<double>::quiet_NaN()) const;
  /// Replaces the tets `old` by `fresh` (faces matched to each other and to
  /// the old set's outer faces; `boundary` lists replacement boundary
  /// triangles as (index, triangle), a triangle {-1, -1, -1} deletes that
  /// one); false, and nothing changed, when the faces do not match (every
  /// vertex of the old set must stay but `vanishing`). `judged`: the last
  /// call of accept() or classes_change() was an accept() of exactly this
  /// change (the same old and fresh, at the same points) that returned true;
  /// the L_v after it that its class guard computed are then taken (after_;
  /// the phase's time, issue 14: the same values as learn()'s star walks),
  /// and the new tets' min-sines it computed (accept_q_: the same values).
  bool replace(const std::vector<int>& old, const std::vector<Tet>& fresh,
               const std::vector<std::pair<int, std::array<int, 3>>>& boundary = {}, int vanishing = -1,
               bool judged = false);
  bool has(int t, int v) const;
  int slot(int t, int v) const;
  /// The tets around v (its star), from vtet_; empty if v has none. With
  /// `outer`, it also gets the codes nb_[t][k] < 0 (boundary triangles, or
  /// an open face) of the faces of the star's tets that hold v, in star
  /// order and then k (removal() read them in a second scan; the phase's
  /// time, issue 14).
  void star(int v, std::vector<int>& out, std::vector<int>* outer = nullptr) const;
  bool ring(int t, int a, int b, std::vector<int>& tets, std::vector<int>& verts) const;
  // ---- The phase's time (issue 14, h3): sets of tets or vertices with O(1)
  // membership, emptied in O(1) (a stamp per slot), for star() and the class
  // guard (they were linear searches, quadratic in a star's size; a vertex
  // near a small input angle has stars of a hundred tets and more). They
  // change no result: the same sets in the same order.
  struct Marks {
    std::vector<std::uint32_t> at;  ///< at[i] == stamp: i is in the set
    std::vector<int> value;         ///< what put() stored with i
    std::uint32_t stamp = 0;
    /// Empties the set; slots 0 .. n-1 may be used.
    void reset(std::size_t n) {
      if (at.size() < n) at.resize(n, 0), value.resize(n, 0);
      if (++stamp == 0) std::fill(at.begin(), at.end(), 0), stamp = 1;
    }
    bool has(int i) const { return at[i] == stamp; }
    void put(int i, int val = 0) { at[i] = stamp, value[i] = val; }
    /// The value put with i, or -1 when i is not in the set.
    int get(int i) const { return at[i] == stamp ? value[i] : -1; }
  };
  // The class guard (beyond the paper; classify.h's TetClassifier). A
  // change replaces the tets `old` by `fresh`; the classes it can change are
  // those of `fresh` and of the tets outside `old` at a vertex whose L_v it
  // changes (only "near" depends on L_v, so only tets of a bad shape count).
  /// What the guard needs from before a change: the violations among `old`
  /// and, per vertex of `old`, its shortest edge among old's tets (squared),
  /// both at the current points (taken before a smoothing step moves one).
  struct ClassesBefore {
    int violations = 0;
    /// The vertices of `old`, in the order of their first tet in `old`
    /// (index() finds one through `slot`), and per vertex its shortest edge
    /// (squared) on old's tets and how many of old's tets at it are of a bad
    /// shape.
    std::vector<int> verts;
    Marks slot;  ///< v -> its index in verts
    std::vector<double> inside;
    std::vector<int> bad_inside;
    /// classes_change()'s, per entry of verts, once computed (the tets
    /// outside `old` do not change while the same change is judged again,
    /// as smooth() does at each step): the vertex's shortest edge (squared)
    /// on tets outside `old` (outside_known), and the index into bad_lists
    /// of its tets of a bad shape outside `old`, in star order (-1: not yet).
    mutable std::vector<double> outside;
    mutable std::vector<char> outside_known;
    mutable std::vector<int> bad_list;
    mutable std::vector<std::vector<int>> bad_lists;  ///< the first bad_used are in use (the rest: spare capacity)
    mutable std::size_t bad_used = 0;
    /// The index of v in verts, or -1.
    int index(int v) const { return v >= 0 && v < int(slot.at.size()) ? slot.get(v) : -1; }
  };
  /// Fills b for `old` (b's vectors are reused: no allocation once they are
  /// large enough).
  void classes_before(const std::vector<int>& old, ClassesBefore& b) const;
  /// How many more violations there are when `old` is replaced by `fresh`
  /// at the current points (negative: fewer; 0 without balls). `fresh_q`,
  /// when given, holds min_sine() of each tet of fresh at the current
  /// points, bit for bit (the caller has them; they are not computed again).
  int classes_change(const std::vector<int>& old, const ClassesBefore& before, const std::vector<Tet>& fresh,
                     const std::vector<double>* fresh_q = nullptr) const;
  /// The min-sine rule: a change whose new worst is worst_new may replace
  /// tets whose worst is worst_old when it is strictly greater; while
  /// fixing_ (a violation worked on), also when it is at least
  /// sin(kImproveTargetDeg) (see fix_violations).
  bool beats(double worst_new, double worst_old) const;
  /// Works on the violations left (TetClass::violation): flips, then the
  /// insertion of a Steiner point (first candidate: the circumcenter, as
  /// rule 4/5 of REFINE inserts the circumcenter of a skinny tet outside the
  /// protecting balls), then the contraction of one of its Steiner vertices
  /// (contract_vertex). Beyond the phase's min-sine rule: such a change must
  /// remove violations, and its new worst min-sine must beat the old one or
  /// be at least fix_min_ and beat fix_floor_ (the mesh's worst, by min-sine
  /// and by smallest dihedral angle, when the fixing starts), so the worst
  /// tet of the mesh never gets worse by either measure. fix_min_ is
  /// sin(kImproveTargetDeg); a violation that no such change removes is
  /// tried again with sin(kFixSecondDeg) (the violation count first: a
  /// change below the phase's target but with no new tet under 10 degrees;
  /// anchor.off's last violation, a skinny tet of R/l 2.27 whose best fixes
  /// reach 19.6-19.9 degrees). Returns the changes.
  std::size_t fix_violations();
  /// L_v^2 of v from its star at the current points (+infinity without one),
  /// ignoring the tets of `skip`.
  double shortest_at(int v, const std::vector<int>& skip = {}) const;
  /// The class upkeep of a commit: forget() before the tets `ids` change or
  /// die, learn() after (their shapes, the bad-tet counts at their vertices
  /// and L_v of their vertices). With moved >= 0, ids is the star of vertex
  /// `moved`, the only one that changed place (from `from`; smooth()).
  /// forget() also records, per vertex of `ids`, its shortest edge on them
  /// (forgot_l2_); the next learn() without `moved` reads it (see below).
  /// With `judged` (replace()'s, after forget()), L_v of ids' vertices is
  /// read from after_ (classes_change()'s, for these new tets) instead.
  void forget(const std::vector<int>& ids);
  void learn(const std::vector<int>& ids, int moved = -1, const Point3& from = {}, bool judged = false);
  /// The max_size guard: T's circumradius is at most size_cap (<= 0: none).
  bool admissible(const Tet& T, double size_cap) const;
  bool poll();
  /// Nonsmooth ascent of vertex v (at P_[v]) on the worst min-sine of
  /// `tets` (each holds v; `current` is their worst): up to kSmoothSteps
  /// steps along the sum of the unit gradients of the nearly worst ones, each
  /// the longest step of a halving line search (from lmin / 5) that raises the
  /// worst and passes valid(). Leaves P_[v] at the best point; returns its worst.
  /// Only the coordinates of `axes` (bit i: axis i) change.
  double ascend(int v, const std::vector<Tet>& tets, double current, double lmin, const std::function<bool()>& valid,
                int axes = 7);
  /// Moves v to x if valid() holds there (true), else leaves it where it
  /// was (ascend(), ascend_in_plane()).
  bool move_if_valid(int v, const Point3& x, const std::function<bool()>& valid);
  /// The worst min-sine and the smallest dihedral angle (degrees) of the
  /// live tets (HUGE_VAL and 180 without any): the floors of the relaxed
  /// rules (fix_floor_, set_contract_floors).
  struct MeshWorst {
    double sine, dihedral_deg;
  };
  MeshWorst mesh_worst() const;
  /// Places the new vertex p_id (at P_[p_id]; vertex 3 of every tet of its
  /// star `fresh`) by ascend() on the worst min-sine of fresh from lmin / 5,
  /// lmin its shortest edge, keeping every tet of fresh positive (EPICK's
  /// exact orientation); only the coordinates of `axes` change (bit i: axis
  /// i). Beyond the paper: the insertions (insert(), insert_boundary())
  /// place their point so before they are judged. Returns fresh's worst
  /// min-sine at the point placed (what accept() computes for it, bit for
  /// bit: the callers skip the guards of a candidate that cannot beat the
  /// best one so far). `start` is fresh's worst min-sine at the point before
  /// the ascent (worst_min_sine(fresh)), which the caller may have needed too.
  double ascend_new_point(int p_id, const std::vector<Tet>& fresh, double start, int axes = 7);
  /// The smallest min-sine of the tets `fresh` (indices into P_), in their order.
  double worst_min_sine(const std::vector<Tet>& fresh) const;
  /// The worst min-sine of the live tets `live` (q_; HUGE_VAL if none).
  double worst_of(const std::vector<int>& live) const;

  MeshResult& r_;
  double rho_, max_size_;
  const ProtectingBalls* balls_ = nullptr;     ///< set_classes'
  std::unique_ptr<TetClassifier> classifier_;  ///< with set_classes
  /// L2_[v]: L_v^2 (classify.h), current; shape_[t]: the shape of live tet
  /// t; bad_at_[v]: how many live tets at v are of a bad shape.
  std::vector<double> L2_;
  std::vector<TetClassifier::Shape> shape_;
  std::vector<int> bad_at_;
  /// The phase's time (issue 14): tet_class(t) kept from its last
  /// computation. A class depends on the tet's shape and points (learn()
  /// forgets the kept class of each tet it is given: the new tets of
  /// replace(), the star of a moved vertex) and on L_v of its vertices:
  /// l2_at_[v] is the l2_clock_ of the last change of L2_[v] (set_l2()),
  /// class_at_[t] the l2_clock_ when tet t's class was kept, so the kept
  /// class holds while no vertex of t has a later change.
  mutable std::vector<signed char> class_;  ///< -1: not kept
  mutable std::vector<std::int64_t> class_at_;
  std::vector<std::int64_t> l2_at_;
  std::int64_t l2_clock_ = 0;
  void set_l2(int v, double l2) {
    if (L2_[v] != l2) L2_[v] = l2, l2_at_[v] = ++l2_clock_;
  }
  bool fixing_ = false;  ///< in fix_violations()
  /// While fixing_: max(the worst min-sine of the mesh, the sine of its
  /// smallest dihedral angle) at the start of fix_violations(); a relaxed
  /// change must beat it (a new tet whose min-sine beats sin(D) has every
  /// dihedral angle above D).
  double fix_floor_ = 0;
  /// While fixing_: the least worst min-sine a relaxed change must reach
  /// (sin(kImproveTargetDeg), then sin(kFixSecondDeg); see fix_violations).
  double fix_min_ = 0;
  std::vector<std::int64_t> fix_tried_;
  std::function<bool()> keep_going_;  ///< a copy: callers pass temporaries
  std::vector<Point3>& P_;
  std::vector<Tet> tets_;
  /// nb_[t][k]: the tet across the face opposite vertex k, or -(1 + b) for
  /// boundary triangle b.
  std::vector<Tet> nb_;
  std::vector<double> q_;
  std::vector<int> free_slots_;  ///< a min-heap (std::greater) of dead tets' slots
  std::vector<std::array<int, 3>> bnd_;
  std::vector<int> vtet_;
  std::vector<char> fixed_;
  std::vector<int> inserted_;
  /// clock_ counts the accepted changes; vtime_[v] is the clock of the last
  /// change of v's star; tried_[t], smoothed_[v], insert_tried_[t]: the clock
  /// of the last failed attempt (-1: none).
  std::int64_t clock_ = 0;
  std::size_t initial_tets_ = 0;
  std::vector<std::int64_t> vtime_, tried_, smoothed_, insert_tried_;
  void touch(const Tet& T);
  bool fresh_since(std::int64_t at, const Tet& T) const;
  ImproveStats st_;
  bool cancelled_ = false;
  std::vector<PassRecord> pass_records_;  ///< pass_records()

  // ---- The phase's time (issue 14, h3): the sets of Marks (above) for star()
  // and the class guard.
  mutable Marks star_marks_;  ///< star()'s
  mutable Marks set_marks_;   ///< shortest_at()'s skip, classes_change()'s and replace()'s old
  mutable Marks cav_marks_;   ///< the cavity of insert(), sphere_cavity() and boundary_cavity()
  mutable Marks vert_marks_;  ///< classes_change()'s vertices of the new tets
  /// Scratch kept to spare allocations (issue 15; they change no result):
  /// accept()'s and smooth()'s ClassesBefore, classes_change()'s vertices of
  /// the new tets (vertex, L_v^2 after) and those whose L_v changes (vertex,
  /// index in the ClassesBefore), the stars read by shortest_at() and
  /// classes_change(), learn()'s vertices and their shortest new edges.
  mutable ClassesBefore accept_before_, smooth_before_;
  mutable std::vector<std::pair<int, double>> after_;
  mutable std::vector<std::pair<int, int>> changed_;
  mutable std::vector<int> shortest_star_, change_star_, bad_scratch_, learn_verts_;
  std::vector<double> learn_fresh_;
  Marks learn_marks_;  ///< learn()'s vertices: v -> its index in learn_verts_
  /// smooth()'s star and its tets, ascend()'s qualities and order (neither
  /// runs inside another call of itself).
  std::vector<int> smooth_star_, ascend_order_;
  /// While ascend() asks valid() about a trial point: the min-sines of its
  /// `tets` there (ascend_qx_, every one computed), for smooth()'s class
  /// guard; null otherwise (ascend_in_plane(), ascend_dihedral()).
  const std::vector<double>* valid_q_ = nullptr;
  /// accept()'s min-sines of the new tets, for its class guard.
  mutable std::vector<double> accept_q_;
  std::vector<Tet> smooth_tets_;
  std::vector<double> ascend_q_, ascend_qx_;
  /// insert()'s candidates, cavity [0] and best cavity [1], their new tets,
  /// and the faces known to see the point; contraction()'s star of u.
  std::vector<Point3> insert_candidates_;
  /// The old tets and new ones of flip23() and flip22(), and remove_edge()'s
  /// ring (its tets in op_old_; no result depends on what they held before).
  std::vector<int> op_old_, ring_verts_;
  std::vector<Tet> op_fresh_;
  std::vector<int> insert_old_[2];
  std::vector<Tet> insert_fresh_[2];
  std::vector<char> insert_known_;
  mutable std::vector<int> contract_star_u_;
  /// replace()'s (kept to spare allocations; no result depends on what they
  /// held before): the old set's outer faces (outward, canonical rotation;
  /// what lies beyond each and its slot there; whether a new face took it),
  /// their indices sorted by key, the new tets' faces (outward and sorted),
  /// their links and slots, and the new tets' vertices (replace_marks_).
  struct ReplaceOuter {
    std::array<int, 3> key;
    int beyond, beyond_slot;
    bool used;
  };
  struct ReplaceFace {
    std::array<int, 3> key, sorted;
    int i, k;
  };
  std::vector<ReplaceOuter> replace_outer_;
  std::vector<int> replace_by_key_, replace_id_;
  std::vector<ReplaceFace> replace_faces_;
  std::vector<std::pair<std::uint64_t, int>> replace_sorted_;  ///< the new faces' order by sorted key
  std::vector<Tet> replace_link_;
  Marks replace_marks_;
  /// The smallest dihedral angle (degrees) of live tet t, kept from its last
  /// computation until forget_dihedral(t) (wherever q_[t] is set anew), so
  /// that mesh_worst() does not recompute every tet's angles on each call.
  double dihedral(int t) const;
  /// Whether dihedral(t) > deg, where `sine` is sine_above(deg): from q_[t]
  /// when it reaches `sine`, else by dihedral(t) itself (the same answer).
  bool dihedral_above(int t, double deg, double sine) const { return q_[t] > sine || dihedral(t) > deg; }
  void forget_dihedral(int t) {
    if (t < int(dih_.size())) dih_[t] = std::numeric_limits<double>::quiet_NaN();
  }
  mutable std::vector<double> dih_;  ///< NaN: not known

  // ---- The phase's time on large meshes (issue 15, h4). On mpi.off (2.2M
  // tets) learn()'s star walk per vertex of the new tets (shortest_at) took
  // a quarter of the phase: a vertex with a large star (up to 1,498 tets in
  // its final mesh) is walked at every change beside it. A change replaces tets
  // `old` by new ones, so L_v after is the shorter of v's edges on the new
  // tets and v's edges outside `old`; when L_v before was shorter than every
  // edge of v on `old` (forgot_l2_), it is an edge outside `old` and stays,
  // so no walk is needed. The same values as the walk (a minimum of the
  // same distances), bit for bit.
  Marks forgot_marks_;             ///< v -> its index in forgot_l2_ (forget() to learn())
  std::vector<double> forgot_l2_;  ///< v's shortest edge on the tets forget() was given
  bool forgot_ = false;            ///< forgot_l2_ is that of the tets learn() replaces

  // ---- Boundary operations (improve_boundary.cpp; beyond the paper and
  // beyond Stellar, which moves boundary vertices freely). Conformity stays
  // exact: a Steiner vertex of the boundary (on boundary triangles, not an
  // input vertex) moves only along a coordinate axis i that each of its
  // facets runs along (the facet's input vertices, seen along axis i, lie on
  // one line by CGAL's exact orientation, so the facet's plane equation has
  // an exact 0 at coordinate i). Only coordinate i changes, so the vertex
  // lies on each of its facets' planes, and on their common input edge, as
  // exactly as before (the same residual, bit for bit); the star's tets
  // staying positive keeps its boundary triangles unfolded in their facets.
  // In the polish only (improve_polish.cpp), a vertex also slides along
  // plane_direction(v) (for a facet whose plane runs along exactly one axis,
  // a wall slanted about it: the difference d of two of its input corners,
  // that coordinate zeroed); a step to p + t d (t a short dyadic number, so
  // the sums are exact where they can be) is taken only when
  // on_planes_as_before() finds, in exact MP_Float arithmetic, the new
  // point's residual from each of v's facets' planes equal to the old one
  // (n . (p' - p) = 0), so v stays on its facets and on its input edge
  // exactly as before; where the sums round, no step is taken.
 public:
  /// The axes (bit i: axis i) along which boundary vertex v may slide; 0 for
  /// input vertices, free vertices, and vertices of a facet without such an
  /// axis.
  int slide_axes(int v) const;
  /// The axes along which smooth() may move v: all three for a free vertex,
  /// slide_axes(v) for one of the boundary, with the bit kPlaneSlide when v
  /// may also slide along its in-plane direction (plane_direction()).
  int movable_axes(int v) const;
  /// Bit 3 of movable_axes(): a slide along plane_direction(v).
  static constexpr int kPlaneSlide = 8;
  /// A direction in every facet of boundary vertex v (0 for none) that is no
  /// coordinate axis: for a facet whose plane runs along exactly one axis i
  /// (a slanted wall, e.g. slit.off's V sides, which run along z), the
  /// difference of two of its input corners with coordinate i zeroed, used
  /// when it lies in v's other facet too (v on an input edge: the edge's
  /// direction). A slide along it keeps v exactly where it was with respect
  /// to each facet plane (on_planes_as_before(), in exact arithmetic).
  Point3 plane_direction(int v) const;
  /// Whether p has the same exact residual as v's current point from the
  /// plane of each facet v lies on (the plane through three input corners of
  /// the facet, n . (p - a) in MP_Float): p then lies on every facet of v
  /// exactly as v does (exactly on it if v is).
  bool on_planes_as_before(int v, const Point3& p) const;
  /// Inserts a Steiner point p on a boundary triangle of t (candidates: the
  /// triangle's circumcenter, centroid and edge midpoints, each with the
  /// coordinates off its facet's axes copied from a point of the facet, so
  /// that p lies on the facet's plane exactly as that point does: an input
  /// corner for an axis-aligned facet, a vertex of the triangle otherwise).
  /// The cavity: the tets whose circumsphere holds p, grown from t until
  /// every outer face off the facet sees p; the facet's triangles on the
  /// cavity's surface (a disk without inner vertices) become the fan from p
  /// over their outline. Each candidate is first slid by ascend() along the
  /// facet's axes; the best accepted one is inserted (accept(), no more
  /// tets under kInsertBelowDeg than in the cavity, the tet budget as
  /// insert()). Refused before the ascent: a candidate whose outline bound
  /// (the angles at the fan's outline edges, which the ascent does not
  /// change) cannot beat its cavity's worst or the best so far, and one whose
  /// new tets start below kInsertBoundaryStart times the cavity's worst.
  /// False on a mesh that is not closed.
  bool insert_boundary(int t);

 private:
  using Tri3 = std::array<int, 3>;
  /// Computes slide_, facet_axes_, facet_corner_ and closed_ (from bnd_, the
  /// mesh's boundary_facet and the input vertices); called by the constructor.
  void init_slides();
  /// Adds point p (index P_.size()) replacing the tets `old` by `fresh` and
  /// the boundary triangles by `boundary` (replace()), unless the mesh would
  /// then exceed the tet budget (kMaxTetGrowth, kMinTetSlack); `facet` >= 0:
  /// p lies on that facet (it then slides along its axes, and the new
  /// boundary triangles are its). Used by insert() and insert_boundary().
  bool add_point(const Point3& p, const std::vector<int>& old, const std::vector<Tet>& fresh,
                 const std::vector<std::pair<int, Tri3>>& boundary, int facet);
  /// Whether `fresh` holds more tets under sin(kInsertBelowDeg) than the
  /// tets `old` (beyond accept(): a point on a facet near a small input angle
  /// would otherwise multiply the tets the angle keeps bad).
  bool more_bad_tets(const std::vector<int>& old, const std::vector<Tet>& fresh) const;
  /// The tets whose circumsphere holds p strictly, grown from t through
  /// inner faces (at most kMaxCavity; insert() and boundary_cavity()).
  void sphere_cavity(int t, const Point3& p, std::vector<int>& cav) const;
  /// insert_boundary's cavity for p on boundary triangle b (facet f) of t:
  /// the old tets, the new ones (p has index P_.size()) and the fan of
  /// boundary triangles (index, triangle; indices from bnd_.size() are new);
  /// false when no cavity is star-shaped from p within kMaxCavity tets.
  bool boundary_cavity(int t, int b, int f, const Point3& p, std::vector<int>& cav, std::vector<Tet>& fresh,
                       std::vector<std::pair<int, Tri3>>& fan) const;
  /// insert_boundary()'s and boundary_cavity()'s working vectors, kept to
  /// spare their allocations per candidate (the phase's time, issue 14: on
  /// wedge-1 about 25,000 candidates); no result depends on what they held.
  struct BoundaryScratch {
    std::vector<Point3> tried;  ///< the candidates of the boundary triangle at hand
    std::vector<int> cav, flat;
    std::vector<Tet> fresh;
    std::vector<std::pair<int, Tri3>> fan;
    std::vector<char> known;
    std::vector<std::pair<int, int>> edges, outline;
  };
  mutable BoundaryScratch boundary_scratch_;
  std::vector<std::uint8_t> slide_;
  /// Per facet: the axes its plane runs along, and one input corner (-1: none).
  std::vector<int> facet_axes_, facet_corner_;
  /// Per facet: three input corners not on a line ({-1, -1, -1}: none) and
  /// the in-plane direction of plane_direction() (0: none). Per vertex: the
  /// facets of its boundary triangles (at most two; -1 unused).
  std::vector<std::array<int, 3>> facet_plane_;
  std::vector<Point3> facet_dir_;
  std::vector<std::array<int, 2>> vertex_facets_;
  std::vector<int> plane_facet_;  ///< per vertex: the facet of its plane_direction() (-1: none)
  /// A nonsmooth ascent of v along plane_direction(v) (the contract of
  /// ascend(): leaves P_[v] at the best point found, returns its worst), each
  /// step's point snapped to one that on_planes_as_before() accepts.
  double ascend_in_plane(int v, const std::vector<Tet>& tets, double current, double lmin,
                         const std::function<bool()>& valid);
  /// The point x = base + t plane_direction(v) nearest to base + s times its
  /// unit vector with t a short dyadic number, if on_planes_as_before(v, x)
  /// accepts it (and x is not P_[v]); false, x unspecified, otherwise. base
  /// differs from P_[v] only along slide_axes(v) (or is P_[v]).
  bool snap_in_plane(int v, const Point3& base, double s, Point3& x) const;
  bool closed_ = false;  ///< no face without a neighbour or a boundary triangle

  // ---- Vertex removal by edge contraction (improve_contract.cpp; beyond
  // the paper, after Stellar's vertex removal by edge contraction). Edge
  // (v, u) is contracted by replacing v with u in every tet of v's star and
  // deleting the tets that hold both; no coordinate changes. v is a Steiner
  // vertex (never an input vertex, never a point on the sphere of a vertex
  // ball: see contract_targets) and u is compatible: v interior -> any
  // neighbour; v on one input facet -> a neighbour along a boundary edge of
  // that facet (on the facet or on its boundary); v on an input edge -> one
  // of its two neighbours along that edge. The new boundary triangles keep
  // their facet labels and must not fold in their facet (exact 2D
  // orientation) nor pin a violation (pins_violation()), the input edge's
  // subsegments still chain from end to end,
  // the link condition holds, and the change passes accept() like every
  // other (strictly better worst min-sine of the star, exact orientation,
  // the class, skinny and max_size guards).
  // The relaxed rule (beyond the phase's contract, in contract_pass() from
  // its second call on): a contraction whose star's worst gets worse is
  // still taken when the star then holds fewer tets below
  // sin(kContractCountDeg) and every new tet's min-sine beats both the
  // worst min-sine of the whole mesh and the sine of its smallest dihedral
  // angle (both kept current), with all of accept()'s other guards: the
  // worst tet of the mesh never gets worse, by min-sine or by smallest
  // dihedral angle. On wedge and wedge-1, 1,044 tets under 5 degrees are
  // left with the strict rule alone, 708 with the relaxed one.
 public:
  /// The vertices v may be contracted onto (empty when v may not be removed).
  void contract_targets(int v, std::vector<int>& out) const;
  /// Contracts edge (v, u) (u one of contract_targets(v)); true when accepted.
  bool contract(int v, int u);
  /// The best accepted contraction of v over contract_targets(v). With
  /// floor_sine (not NaN; coarsen() only, beyond the phase's contract
  /// rule): a contraction is also taken when every new tet's min-sine beats
  /// min(the star's worst, floor_sine), whatever the count below
  /// sin(kContractCountDeg), with all of accept()'s other guards.
  bool contract_vertex(int v, double floor_sine = std::numeric_limits<double>::quiet_NaN());
  /// A pass over the Steiner vertices of the live tets below
  /// sin(kContractBelowDeg), worst tets first; returns the contractions made.
  std::size_t contract_pass();
  /// Whether v was removed by a contraction (it is in no live tet).
  bool removed(int v) const { return v < int(removed_.size()) && removed_[v]; }

 private:
  /// What contraction() needs of v's star for every target u, computed once
  /// per vertex by removal() (each target then costs O(star + star of u):
  /// before, each rebuilt and sorted the star's vertex list, O(n^2 log n)
  /// per vertex of a star of n tets).
  struct Removal {
    int v = -1;
    std::vector<int> star, bnd, targets;  ///< v's tets, boundary triangles (into bnd_), targets
    /// Per triangle of bnd: its facet's dominant axis (of the area normals
    /// of v's triangles in that facet), the sign of the normal along it, and
    /// whether the triangle itself is seen with that sign.
    std::vector<signed char> drop, sign, old_ok;
    double worst_old = 0;       ///< the star's worst min-sine
    int bad_old = 0;            ///< the star's tets below sin(kContractCountDeg)
    double floor = 0;           ///< the relaxed rule's floor (NaN: strict rule only)
    bool coarsen = false;       ///< the floor is coarsen()'s (no count below kContractCountDeg asked)
    std::size_t witness = 0;    ///< the star's tet that refused the last target (tried first)
    bool facets_known = false;  ///< drop, sign and old_ok filled (removal_facets())
  };
  /// Fills `r` for v but drop, sign and old_ok; false when v may not be
  /// removed. Marks the star's vertices in contract_marks_ (value 0).
  bool removal(int v, Removal& r) const;
  /// Fills r.drop, r.sign and r.old_ok once per removal(): asked only by a
  /// target that passes the min-sine rules (the phase's time, issue 14: most
  /// targets do not, and these need the area normals and exact orientations
  /// of v's boundary triangles).
  void removal_facets(Removal& r) const;
  /// The new tets and boundary changes of contracting (r.v, u), and their
  /// worst min-sine; -HUGE_VAL when a check or accept() refuses it (fresh
  /// and boundary are then unspecified). Needs
  /// contract_marks_ as removal(r) left it (each call marks its own shared
  /// vertices with u + 1).
  double contraction(Removal& r, int u, std::vector<Tet>& fresh,
                     std::vector<std::pair<int, std::array<int, 3>>>& boundary) const;
  /// contraction() in two parts (the phase's time, issue 14; the same
  /// outcome): contraction_bound() applies the cheap refusals (a fold
  /// already there, the min-sine rules, the tets at vu) and returns the new
  /// tets' worst min-sine, with `rule` 1 (strict) or 2 (relaxed), or
  /// -HUGE_VAL; contraction_rest() then the link condition, the boundary
  /// checks and accept() under that rule.
  double contraction_bound(Removal& r, int u, int& rule) const;
  double contraction_rest(Removal& r, int u, int rule, std::vector<Tet>& fresh,
                          std::vector<std::pair<int, std::array<int, 3>>>& boundary) const;
  /// Beyond the paper and Stellar (issue 14): whether a new boundary
  /// triangle of `boundary` (a contraction's; {-1, -1, -1} entries are
  /// deletions) is skinny by itself, its circumradius above rho0 times its
  /// shortest edge, while the tet of `fresh` on it is not near a small input
  /// angle (classify.h, with the L_v before the change). Every tet on such a
  /// triangle has R/l above rho0 (a tet's circumradius is at least that of
  /// each face, its shortest edge at most the face's), so no flip, smoothing
  /// or interior insertion removes the violation while the triangle stays,
  /// and the phase replaces a boundary triangle only by flip22() (exactly
  /// coplanar points, which Steiner points on a facet not along the axes are
  /// not), insert_boundary() or a contraction. On capsule-7 (BENCHMARKS.md,
  /// "Session 16 (2026-12-07), h5") a contraction traded a sliver for such
  /// a tet, the one violation the phase left. contraction_rest() refuses
  /// such a change. False without set_classes.
  bool pins_violation(const std::vector<std::pair<int, std::array<int, 3>>>& boundary,
                      const std::vector<Tet>& fresh) const;
  struct ContractCandidate {
    double worst;
    int u, rule;
  };
  std::vector<ContractCandidate> contract_candidates_;  ///< contract_vertex()'s
  /// removal()'s boundary edges at v (other end, facet of its first
  /// triangle; per end its count and the facet of its last triangle; end ->
  /// index), the ends along an input edge and v's facets, and star()'s codes
  /// of v's boundary triangles (kept to spare allocations).
  mutable std::vector<std::pair<int, int>> removal_ends_;
  mutable std::vector<std::array<int, 2>> removal_end_more_;
  mutable Marks removal_end_marks_;
  mutable std::vector<int> removal_along_, removal_facets_, removal_outer_;
  /// Applies an accepted contraction of r.v (fresh and boundary from
  /// contraction()); false when replace() refuses it.
  bool apply_contraction(const Removal& r, const std::vector<Tet>& fresh,
                         const std::vector<std::pair<int, std::array<int, 3>>>& boundary);
  mutable Marks contract_marks_;  ///< the star's vertices (removal, contraction)
  /// contract_vertex()'s (kept to spare allocations): the removal, and the
  /// new tets and boundary of the target being judged (the first accepted
  /// one is applied, so no second copy for the best is kept).
  Removal contract_removal_;
  std::vector<Tet> contract_fresh_;
  std::vector<std::pair<int, std::array<int, 3>>> contract_boundary_;
  /// Whether v lies on or inside the sphere of a vertex ball (cached in
  /// ball_point_ until v moves: smooth() clears its entry).
  bool on_vertex_ball(int v) const;
  /// Called by finish(): drops the removed vertices from r (renumbering the
  /// others in order; input vertices keep their indices) and the deleted
  /// boundary triangles. After it the Improver's own arrays are stale.
  void drop_removed();
  std::vector<char> removed_;
  mutable std::vector<signed char> ball_point_;
  /// on_vertex_ball()'s index: the vertex balls of vertex_balls_of_ sorted by
  /// the x of their centres, and the largest radius (with the slack).
  mutable const ProtectingBalls* vertex_balls_of_ = nullptr;
  mutable std::vector<ProtectingBall> vertex_balls_;
  mutable double vertex_ball_reach_ = 0;
  std::vector<std::int64_t> contract_tried_;
  /// In contract_pass(): the worst min-sine and the smallest dihedral angle
  /// (degrees) of the mesh, the relaxed rule's floors; NaN outside it (the
  /// strict rule only).
  double contract_floor_ = std::numeric_limits<double>::quiet_NaN(), contract_dihedral_ = 0;
  /// The relaxed rule's floor in min-sine, max(contract_floor_,
  /// sin(contract_dihedral_)), set with them (removal() read it per vertex).
  double contract_floor_sine_ = 0;
  /// Sets both floors from the live tets.
  void set_contract_floors();
  int contract_passes_ = 0;

  // ---- Multi-face removal (improve_faces.cpp; Klingner and Shewchuk 2007,
  // the inverse of edge removal). The faces sandwiched between two vertices
  // a and b (each face f interior, with the tets (f, a) and (f, b)) that form
  // a tree grown from one face are removed, and the region of their 2F tets
  // is filled by the F + 2 tets (p, q, b, a), one per edge pq of the
  // polygon they triangulate, around the new edge ab. Which faces: the
  // dynamic programme over the tree (Shewchuk's) that maximises the worst
  // new tet, a face taken only when strictly better than stopping at its
  // edge. The change obeys the phase's contract (accept, replace: exact
  // orientation, the guards, the same outer faces, no vertex lost); it never
  // adds tets (F >= 2: a single face is the 2-3 flip, flip23).
 public:
  /// Multi-face removal from t's face opposite its vertex k (an interior
  /// face) with a = that vertex and b the apex beyond the face; true when a
  /// change of at least two faces was accepted.
  bool remove_faces(int t, int k);
  /// The most sandwiched faces one removal considers.
  static constexpr int kMaxSandwich = 16;
  /// remove_faces()'s choice before its guards (for the tests): the old tets
  /// (2F, F >= 2) and the new ones (F + 2) of the tree the dynamic programme
  /// chooses from t's face opposite k, when its worst new tet beats the worst
  /// of those old tets; else false. With `bound` (remove_faces() asks for
  /// it) the programme stops at a subtree that cannot matter (see
  /// improve_faces.cpp): the same answer, old and fresh as without it.
  bool remove_faces_choice(int t, int k, bool bound, std::vector<int>& old, std::vector<Tet>& fresh);

 private:
  struct Sandwich {
    std::array<int, 3> u;      ///< oriented: (u0, u1, u2, a) is positive
    std::array<int, 3> key;    ///< u sorted
    int ta, tb;                ///< the tets (u, a) and (u, b)
    std::array<int, 3> child;  ///< per edge u_e u_(e+1): the face of the tree beyond it, or -1
    std::array<int, 3> next;   ///< per edge: the chosen face beyond it (child or -1)
    double value;              ///< the best worst new tet of its subtree
  };
  /// Grows the tree of sandwiched faces beyond the edges of face f of
  /// `faces` but `back` (the edge to its parent, -1 at the root), depth
  /// first, each edge in order, at most kMaxSandwich faces; sets child[].
  void grow_sandwich(std::vector<Sandwich>& faces, int f, int back, int a, int b) const;
  /// The dynamic programme at face f (after grow_sandwich): sets next[] and
  /// value from the subtrees beyond f's edges but `back`, returns value. Its
  /// value V is the smallest over those edges of max(stop, V of the child),
  /// stop the min-sine of the tet (p, q, b, a) closing the edge pq; the
  /// child is chosen when its V beats stop. The phase's time (issue 14):
  /// when V <= `bound` the programme may stop early and return a value at
  /// most `bound` (next[] then unfinished); when V > bound it returns V and
  /// sets next[] as without the bound (see improve_faces.cpp).
  double sandwich_value(std::vector<Sandwich>& faces, int f, int back, int a, int b, double bound);
  /// The face beyond edge e of `face` when it is sandwiched between a and b
  /// (the tets across the faces (p, q, a) and (p, q, b) share their fourth
  /// vertex w) and reads (q, p, w) with a on its positive side: true, with
  /// that face u and its tets na (at a) and nb (at b).
  bool sandwiched(const Sandwich& face, int e, int a, int b, std::array<int, 3>& u, int& na, int& nb) const;
  std::vector<Sandwich> sandwich_faces_;  ///< remove_faces()'s (kept to spare its allocation)
  std::vector<int> faces_old_;            ///< remove_faces()'s old tets (kept to spare allocations)
  std::vector<Tet> faces_fresh_;          ///< and its new ones
  /// t's vertex other than x, y and z (-1 if none).
  int other_vertex(int t, int x, int y, int z) const;

  // ---- Polish (improve_polish.cpp; beyond the paper and beyond Stellar).
  // After the passes, rounds that raise the mesh's smallest dihedral angle
  // D: each round works on the kPolishTets live tets of the smallest
  // dihedral angles below D + kPolishBandDeg, smallest first, with flips
  // (improve_tet), smoothing of their vertices (boundary vertices also along
  // their in-plane direction, plane_direction(): only here) and contraction
  // of their vertices (contract_vertex, the strict rule). Beyond accept()'s
  // rule, while a round runs every new tet's smallest dihedral angle must
  // exceed the floor max(D, kPolishFloorDeg) (admissible(), so smoothing
  // is held to it too), and a change may add tets only while the live
  // tets stay at most as many as when polish() began (accept()). So the
  // mesh's smallest dihedral angle never drops, no tet under
  // kPolishFloorDeg is made, the tets never become more than the passes
  // left, and the class guard keeps the violations from growing. A round
  // without a change ends it, as do kPolishStalls rounds in a row without a
  // rise of D by kPolishRiseDeg.
  // Two stages of such rounds (session 9): the first judges every change
  // by min-sine as above; when it stops, the second (polish_dihedral_, every
  // retry stamp forgotten) judges them by the smallest dihedral angle: a
  // change must lower the largest cosine of the dihedral angles of the tets
  // it replaces (polish_lowers_cosine(); smoothing by ascend_dihedral()),
  // and no new tet's min-sine may fall below the mesh's worst when polish()
  // began (polish_sine_floor_: the phase's contract, the worst tet never
  // worse by min-sine), with the same floor, tet bound and guards. The
  // first stage is the polish of before bit for bit, and the second only
  // raises D, so D is never below what the first stage alone reaches.
  // Every decision compares cosines of dihedral angles made with +, -, *, /
  // and sqrt only (largest_cosine()), no libm call: the native and the wasm
  // builds give the same mesh.
 public:
  /// The rounds, every one the stopping rules allow; returns the changes
  /// made (run() calls it after the passes when set_polish(true)).
  std::size_t polish();
  /// smooth(v) as a round of polish() makes it (for the tests): under the
  /// floors of a round that begins now, on the smallest dihedral angle of
  /// v's star (ascend_dihedral); true when v moved.
  bool smooth_in_polish(int v);
  /// Whether run() polishes (MeshOptions::polish; off by default).
  void set_polish(bool on) { polish_on_ = on; }
  /// The largest cosine of T's six dihedral angles (the cosine of its
  /// smallest; 1 when a face is degenerate).
  double largest_cosine(const Tet& T) const;

 private:
  bool polish_on_ = false;  ///< set_polish()
  /// The largest cosine of the dihedral angles of the live tets (the cosine
  /// of the mesh's smallest angle; -1: no tet).
  double largest_mesh_cosine() const;
  /// Whether new tet T passes polish's floor (admissible() asks, while
  /// polishing_).
  bool polish_admits(const Tet& T) const;
  /// Whether replacing old_tets tets by new_tets keeps the live tets at
  /// most polish_cap_ (accept() asks, while polishing_).
  bool polish_room(std::size_t old_tets, std::size_t new_tets) const;
  /// True inside a round of polish().
  bool polishing_ = false;
  /// The floor: a new tet's largest cosine must be below polish_floor_cos_;
  /// polish_floor_sine_ is the floor angle's sine (a min-sine above it
  /// admits the tet at once).
  double polish_floor_cos_ = 1, polish_floor_sine_ = 0;
  std::size_t polish_cap_ = 0;  ///< the live tets when polish() began
  /// Forgets the retry stamps of the flips, the smoothing and the
  /// contractions (the polish's second stage judges by another rule).
  void forget_tries();
  /// The rounds of one stage of polish(); returns the changes made. It
  /// stops after max_changes changes, and, with `work`, when *work
  /// operations were tried (each taken from it; coarsen()'s budget).
  std::size_t polish_rounds(std::size_t max_changes = std::numeric_limits<std::size_t>::max(),
                            std::size_t* work = nullptr);
  /// In polish()'s second stage: smoothing by ascend_dihedral(), and the
  /// other changes judged by the smallest dihedral angle (beats() asks only
  /// for the min-sine floor polish_sine_floor_, accept() for
  /// polish_lowers_cosine()).
  bool polish_dihedral_ = false;
  /// Whether the largest cosine of the tets `fresh` is below that of the
  /// live tets `old` (by kPolishTieCos: a tie is refused).
  bool polish_lowers_cosine(const std::vector<int>& old, const std::vector<Tet>& fresh) const;
  /// Sets the floors of a round whose mesh has the largest cosine C
  /// (polish_floor_cos_, polish_floor_sine_).
  void set_polish_floor(double C);
  /// The mesh's worst min-sine when polish() began: no tet the polish's
  /// smoothing makes is worse by min-sine (the phase's contract).
  double polish_sine_floor_ = 0;
  std::vector<Point3> dihedral_gradients_;  ///< ascend_dihedral()'s (kept to spare allocations)
  /// polish()'s smoothing (improve_dihedral.cpp; smooth() calls it while
  /// polishing_, with its valid() and the star's tets `tets`, each holding
  /// v): up to kDihedralSteps steps of a nonsmooth descent of the largest
  /// cosine of the dihedral angles of `tets` over P_[v], within
  /// movable_axes(v) (`axes`; the in-plane slide through snap_in_plane()).
  /// Each step's direction is minus the point of least norm of the convex
  /// hull of the gradients (in the movable coordinates) of the cosines within
  /// kDihedralActive of the largest; its length the longest of a halving line
  /// search from lmin / 5 that lowers the largest cosine by more than
  /// kPolishTieCos, keeps every
  /// tet's min-sine at least polish_sine_floor_ and passes valid(). Leaves
  /// P_[v] at the best point; true when it moved. Only +, -, *, / and sqrt
  /// decide (native = wasm, as the rest of the polish).
  bool ascend_dihedral(int v, const std::vector<Tet>& tets, double lmin, const std::function<bool()>& valid, int axes);

  // ---- Coarsening (improve_coarsen.cpp; beyond the paper and beyond
  // Stellar, issue 14; the constants kCoarsen* above). Fewer vertices give
  // the polish fewer and larger tets to raise: on slit.off the passes end at
  // 20.16 degrees with 252 tets, every one of them above kContractBelowDeg,
  // so contract_pass() tries none of its vertices. The step runs only when
  // the passes leave the mesh's smallest dihedral angle D at
  // kImproveTargetDeg or more; then each round is (1) sweeps of
  // contract_vertex() with the coarsening floor over every vertex (worst
  // star first; a vertex retried only after its star changed; until a sweep
  // contracts nothing, at most kCoarsenSweeps), under the polish's floors (polishing_: no new tet's
  // smallest dihedral angle at or below max(D, kPolishFloorDeg), the tets
  // never more than when the step began, the class and max_size guards),
  // and (2) the polish's second stage (polish_rounds() judged by the
  // smallest dihedral angle, every retry stamp forgotten) cut to
  // ceil(T / kCoarsenPolishShare) changes. Every operation tried counts
  // against the budget kCoarsenWork times T; the step stops when it is
  // spent. So D never drops, no tet under kPolishFloorDeg is made, the tets
  // never grow, and the worst min-sine never drops (the phase's contract).
 public:
  /// The step (run() calls it after the passes, before the polish of
  /// MeshOptions::polish, unless set_coarsen(false): the polish then starts
  /// from the coarse mesh and only raises D, so polish = true never gives a
  /// smaller angle than the default); returns the changes made (0, and
  /// nothing changed, when D < kImproveTargetDeg).
  std::size_t coarsen();
  /// Whether run() ends with coarsen() (on by default; off: the tests call
  /// it on the passes' mesh).
  void set_coarsen(bool on) { coarsen_on_ = on; }

 private:
  bool coarsen_on_ = true;  ///< set_coarsen()
  /// The sweeps of one round, each operation tried taken from `work`;
  /// returns the contractions made.
  std::size_t coarsen_sweeps(std::size_t& work);
  /// coarsen_sweeps()'s retry stamps (the clock of the last failure).
  std::vector<std::int64_t> coarsen_tried_;

  // ---- The polish's time (session 11, h3; improve_polish.cpp and
  // improve_dihedral.cpp): the same decisions, hence the same meshes, bit
  // for bit, with less arithmetic (ascend_dihedral(): the gradients of the
  // nearly largest cosines only, the tet that failed the last trial point
  // tried first, min_sine() only where the cosines leave it in doubt).
 public:
  /// largest_cosine(T) when it is below `bound` (the same value, bit for
  /// bit), else some cosine of T at least `bound` (the edges after it are not
  /// computed); largest_abs: the largest |cosine| of the edges computed (1
  /// when a face is degenerate). largest_cosine(T) is it with bound +inf.
  double largest_cosine_within(const Tet& T, double bound, double& largest_abs) const;
};

/// The phase on a finished, conforming run's extracted mesh r: records the
/// smallest dihedral angle and the class counts before, improves r.mesh,
/// then recomputes r.quality and the classes (with `balls` and opt's
/// thresholds) and the smallest dihedral angle after, in r.improve. Calls
/// `progress` (phase "improve") at its start and after every kImprovePoll
/// operations tried; false when it returned false (the run is cancelled: r's
/// mesh is then valid but its classes are not recomputed and r.quality is
/// empty: it is freed while the phase works).
bool improve_phase(MeshResult& r, const ProtectingBalls& balls, const MeshOptions& opt,
                   const ProgressCallback& progress);
/// Operations (tets or vertices tried) between two progress calls.
constexpr int kImprovePoll = 64;

}  // namespace wqmesh::mesher
