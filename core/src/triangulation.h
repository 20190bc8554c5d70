// wqmesh: a thin interface in front of CGAL's Regular_triangulation_3 (the
// weighted Delaunay triangulation of the paper, section 3) and of a planar
// Delaunay triangulation per facet (the subfacets of section 4). Private.
//
// This header has no CGAL in it: triangulation.cpp is the only translation
// unit that instantiates CGAL's triangulations, so the mesher's phases compile
// fast. Vertices are named by dense integer ids (0, 1, 2, ... in insertion
// order); cells by the ids of their four vertices, positively oriented.
// With every weight 0 the triangulation is Del V; REFINE keeps all weights 0
// (paper, rule 7: "we always maintain an unweighted Delaunay triangulation")
// and PUMP sets them.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "wqmesh/types.h"

namespace wqmesh {

/// A walk or circulator loop went past its stated bound (a broken
/// triangulation: an internal error). The message names the loop, the vertex
/// and the bound; the mesher adds the phase (see mesh_polyhedron).
class LoopBoundError : public std::logic_error {
 public:
  explicit LoopBoundError(const std::string& what) : std::logic_error(what) {}
};

/// Four vertex ids, positively oriented (orient3d > 0). The infinite vertex
/// has id kInfinite.
using Tet = std::array<int, 4>;
constexpr int kInfinite = -1;

/// An opaque reference to a cell, valid as a fast check of whether that cell
/// still exists (see RegularTriangulation::is_cell); never dereferenced by
/// callers.
using CellRef = const void*;

class RegularTriangulation {
 public:
  RegularTriangulation();
  ~RegularTriangulation();
  RegularTriangulation(const RegularTriangulation&) = delete;
  RegularTriangulation& operator=(const RegularTriangulation&) = delete;

  /// Inserts p with weight w (a squared radius). `hint` is a vertex near p
  /// (or -1) where the point location starts. Returns the new vertex id, or
  /// the id of the existing vertex at exactly p (nothing changes then), or -1
  /// when p would be hidden by the weights around it (nothing changes).
  /// When conflict_cells was last asked for this very p and w and nothing
  /// changed since, that zone is inserted without a second conflict search
  /// (beyond the paper, issue 15: ENCROACH's search serves the insertion),
  /// leaving the same triangulation, cell for cell and in the same order
  /// (the same cell of each vertex), as CGAL's own insertion.
  int insert(const Point3& p, double w = 0, int hint = -1);
  /// How many insertions so far reused a zone as insert() says (tests watch
  /// the reuse with it).
  std::size_t kept_zone_insertions() const;

  /// Inserts many unweighted points at once (CGAL sorts them along a space
  /// filling curve first); ids follow the order of `points` only when none
  /// coincide. For measuring the plain Delaunay triangulation of a vertex set.
  void insert_all(const std::vector<Point3>& points);

  /// Changes the weight of vertex v (removal and reinsertion; the id stays).
  /// Returns false, and keeps the old weight, when the new weighted point
  /// would be hidden.
  bool set_weight(int v, double w);

  const Point3& point(int v) const;
  double weight(int v) const;
  int number_of_vertices() const;  ///< ids handed out so far
  std::size_t number_of_finite_cells() const;

  bool is_edge(int a, int b) const;
  bool is_facet(int a, int b, int c) const;
  bool is_cell(const Tet& t) const;
  /// Whether t is still a cell, where `ref` is what incident_cells gave for it
  /// (the slot of a destroyed cell is kept, marked free, or reused by a cell
  /// with other vertices): O(1) instead of a search around a vertex.
  bool is_cell(const Tet& t, CellRef ref) const;

  /// A hint to the processor that is_cell(t, ref) and the points of t will
  /// be read soon (beyond the paper, issue 15: rule 6's queue reads its cells
  /// in order, long after they were made, and each read was a cache miss).
  /// `stage` 0 fetches the cell; 1, a little later, its vertices and t's
  /// points. Changes nothing and answers nothing.
  void prefetch(const Tet& t, CellRef ref, int stage) const;

  /// Every finite cell, positively oriented.
  std::vector<Tet> finite_cells() const;
  /// The same cells with a CellRef each (for is_cell(t, ref), which is O(1)).
  void finite_cells(std::vector<Tet>& out, std::vector<CellRef>& refs) const;
  /// The cells incident to v, finite or not (kInfinite in infinite ones),
  /// and, when `refs` is given, a CellRef for each.
  void incident_cells(int v, std::vector<Tet>& out, std::vector<CellRef>* refs = nullptr) const;
  /// The finite vertices adjacent to v.
  void adjacent_vertices(int v, std::vector<int>& out) const;
  /// The vertices (kInfinite included) of the cells around edge ab, other
  /// than a and b. Returns false when ab is not an edge.
  bool edge_ring(int a, int b, std::vector<int>& out) const;
  /// The same, with `cell` a hint the caller keeps per edge (beyond the
  /// paper, issue 15: an O(1) way to the edge instead of a star walk): when
  /// it is still a cell holding both a and b (checked in O(1), as
  /// is_cell(t, ref) checks) the ring is circulated from it; else the edge is
  /// found by the walk and `cell` set to a cell holding it (nullptr when ab is
  /// no edge). Same answer and `out` as without the hint.
  bool edge_ring(int a, int b, std::vector<int>& out, CellRef& cell) const;
  /// Whether ab is an edge, with `cell` the hint of edge_ring above (checked
  /// in O(1); else the edge is found by the walk and `cell` set, nullptr when
  /// ab is no edge). Same answer as is_edge(a, b); beyond the paper, issue
  /// 15: Subcomplex::segment_encroached_update's presence test.
  bool is_edge(int a, int b, CellRef& cell) const;
  /// The two cells sharing triangle abc (either may hold kInfinite), in no
  /// particular order (callers treat them alike). Returns false when abc is
  /// not a facet of the triangulation. Found by the edge test of ab (the
  /// stars of a and b walked in turn) and the ring of cells around ab, so a
  /// vertex of high degree costs no more than its partner (issue 15).
  bool facet_cells(int a, int b, int c, Tet& first, Tet& second) const;
  /// The cells, finite or not, whose orthospheres the weighted point (p, w)
  /// conflicts with (negative power distance): the cells an insertion of p
  /// would destroy. Empty if p coincides with a vertex.
  void conflict_cells(const Point3& p, double w, int hint, std::vector<Tet>& out) const;
  /// The same set (in another order, maybe), starting from `start` (as
  /// is_cell(t, ref) takes it) when that slot still holds a cell the point
  /// conflicts with, without a point location (beyond the paper, issue 15:
  /// rule 6's circumcenter conflicts with its own tet); else as above.
  void conflict_cells(const Point3& p, double w, int hint, std::vector<Tet>& out, CellRef start) const;
  /// The cells, finite or not, that the last insert() destroyed (its
  /// cavity), when conflict_cells was last asked for that very point and
  /// weight and the triangulation did not change in between: the same set,
  /// as both use the same exact conflict test. nullptr when unknown (no such
  /// query, or nothing inserted) and after any later change. Beyond the
  /// paper (issue 15, step 6): the upkeep of a free insertion reads the
  /// edges and triangles it changed from here instead of walking around the
  /// new vertex's ring. Valid until the next change.
  const std::vector<Tet>* last_cavity() const;
  /// The vertex nearest to p (power distance with the current weights).
  int nearest_vertex(const Point3& p, int hint = -1) const;

  /// All cells, infinite ones included, with their adjacency:
  /// neighbor[i][k] is the index in `cells` of the cell opposite cells[i][k].
  struct CellGraph {
    std::vector<Tet> cells;
    std::vector<std::array<int, 4>> neighbor;
  };
  /// `poll`, when given, is called with a count of cells every 1024 cells;
  /// when it returns false the graph comes back empty (the caller stops).
  CellGraph cell_graph(const std::function<bool(std::size_t)>& poll = {}) const;

  // ---- a label byte in every cell (beyond the paper, issue 15) ----
  // Each cell holds one byte for the labels of a whole-mesh scan, in room
  // CGAL's cell leaves unused (the cell is no larger with it), so that a scan
  // needs no cell graph and no table keyed by cells beside the triangulation
  // (at the run's peak those were 35-110 bytes per output tet). Like the
  // walks' marks it is scratch, no part of the triangulation: the calls are
  // const, and a cell made by a later change is kUnlabelled.
  // `poll` as cell_graph's; each call returns false when it stopped (the
  // labels are then unusable).
  /// The label byte's values beside the fill's 0 and 1: kUnlabelled, the
  /// value of every cell when it is made (by an insertion or a weight
  /// change) and of a cell a fill has not reached; kExcludedOdd, a cell of
  /// label 1 that the caller's `excluded` takes out (flat tets lying in an
  /// input facet: extract.cpp). The parity of a label is its lowest bit.
  static constexpr char kUnlabelled = 2, kExcludedOdd = 3;
  /// Labels every cell, finite or not, by a flood fill: the infinite cells
  /// 0; a cell reached across the facet abc of a labelled cell takes its
  /// parity, flipped when abc is a wall: a, b, c finite, on_walls holds for
  /// each (a filter: a vertex on no wall; wall() is asked only where it
  /// holds for all three) and wall(a, b, c) holds; as 0 or 1,
  /// or kExcludedOdd for an odd cell t when excluded(t) holds.
  /// The labels depend on the order of the fill unless every closed path of
  /// cells crosses an even number of walls (extract.cpp, even_walls).
  /// `wall_faces`, when given, gets the number of facets of the
  /// triangulation that are walls (each facet once).
  bool flood_labels(const std::function<bool(int v)>& on_walls, const std::function<bool(int a, int b, int c)>& wall,
                    const std::function<bool(const Tet&)>& excluded, const std::function<bool(std::size_t)>& poll = {},
                    std::size_t* wall_faces = nullptr) const;
  /// Beyond the paper (issue 15: rule 7's passes, the sliver count and the
  /// extraction each filled the whole triangulation): completes the labels
  /// a fill (or an earlier completion) left. Every kUnlabelled cell (made
  /// since) takes its label across a facet from a labelled neighbour as
  /// flood_labels would (an infinite one 0), then the labels are checked.
  /// `walls`: the number of distinct triangles for which wall() holds.
  /// Returns true when every infinite cell is even, every one of the walls
  /// is a facet and the parities across each facet differ exactly where it
  /// is a wall: such labels are the only ones (each cell is joined to an
  /// infinite one by facets), so they are flood_labels' whenever those are
  /// free of the order, and flood_labels would count `walls` wall facets.
  /// Returns false otherwise (a wall that is no facet, a wall made or lost
  /// between old cells, labels left by a fill that was not free of the
  /// order or was stopped: take flood_labels) or when `poll` stopped it;
  /// the labels are then unusable. One pass over the cells reading their
  /// labels, one over their neighbours' labels, and wall() asked only for
  /// the new cells' facets and those of differing parities: flood_labels
  /// fills every cell and asks wall() of every facet.
  bool complete_labels(const std::function<bool(int v)>& on_walls, const std::function<bool(int a, int b, int c)>& wall,
                       std::size_t walls, const std::function<bool(const Tet&)>& excluded,
                       const std::function<bool(std::size_t)>& poll = {}) const;
  /// Visits every cell, finite or not, in cell_graph's order, with its label,
  /// which `visit` may change.
  bool visit_labels(const std::function<void(const Tet& t, char& label)>& visit,
                    const std::function<bool(std::size_t)>& poll = {}) const;
  /// Visits every cell, finite or not, in cell_graph's order, with a CellRef
  /// of it (for is_cell(t, ref) and label(ref) while it lives) and its label;
  /// polled as visit_labels.
  bool visit_cells(const std::function<void(const Tet& t, CellRef ref, char label)>& visit,
                   const std::function<bool(std::size_t)>& poll = {}) const;
  /// Visits every cell whose label is `label`, in cell_graph's order, with
  /// the labels of its four neighbours (across[k]: the cell opposite t[k]).
  bool visit_labelled(char label, const std::function<void(const Tet& t, const std::array<char, 4>& across)>& visit,
                      const std::function<bool(std::size_t)>& poll = {}) const;
  /// The same cells in the same order, without their neighbours' labels
  /// (beyond the paper, issue 15: four reads of other cells, cache misses
  /// on a large triangulation, that a scan of the cells alone, such as rule
  /// 7's, does not need).
  bool visit_labelled(char label, const std::function<void(const Tet& t)>& visit,
                      const std::function<bool(std::size_t)>& poll = {}) const;
  /// The label byte of the cell behind `ref`, a CellRef of a cell that
  /// still exists (incident_cells' or neighbour's, the triangulation unchanged
  /// since; std::logic_error otherwise), and its setting: O(1), no search
  /// (beyond the paper, issue 15: PUMP keeps its labels there, not in a table
  /// keyed by cells).
  char label(CellRef ref) const;
  void set_label(CellRef ref, char label) const;
  /// The cell opposite t[k] across its facet, where t is the cell behind
  /// `ref` as incident_cells gave it (same contract as label()): its
  /// CellRef, and its vertices in `across` (kInfinite in an infinite one).
  /// The same cell as facet_cells gives for that facet, in O(1).
  CellRef neighbour(CellRef ref, int k, Tet& across) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The Delaunay triangulation of the mesh vertices lying on one facet (paper,
/// section 4: its triangles inside the facet are the subfacets). Ids are the
/// caller's (the 3D vertex ids).
///
/// Contract: the predicates see the 3D points' own coordinates, never rotated
/// 2D coordinates, so that points collinear in 3D (input vertices and the
/// points inserted on collinear input edges) are collinear here too and no
/// zero-area triangle arises that the 3D triangulation cannot contain.
/// Orientation is taken in the projection that drops the coordinate `axis`
/// (the largest component of the facet's normal), which is exact. The
/// in-circle test is that of the plane's own metric in that projection (the
/// squared 3D length of an in-plane displacement, a fixed positive definite
/// quadratic form of the projected coordinates, see PlaneMetric in
/// triangulation.cpp), evaluated exactly: for points on the plane this is the
/// Delaunay triangulation within the plane, and since the lift is one fixed
/// strictly convex function of the projected coordinates, every point
/// inserted is a vertex whatever its rounding off the plane (a point is never
/// hidden; issue 10: the former lift by the squared distance to the plane
/// hid rounded points and a star walk over a hidden vertex never ended).
/// The bytes of the pool that holds every PlanarDelaunay's vertex and face
/// blocks (issue 15, the peak memory; see triangulation.cpp): 0 when no
/// PlanarDelaunay holds a block, since the pool gives every chunk back when
/// the last block is freed.
std::size_t planar_pool_bytes();

class PlanarDelaunay {
 public:
  PlanarDelaunay();
  ~PlanarDelaunay();
  PlanarDelaunay(const PlanarDelaunay&) = delete;
  PlanarDelaunay& operator=(const PlanarDelaunay&) = delete;
  PlanarDelaunay(PlanarDelaunay&&) noexcept;
  PlanarDelaunay& operator=(PlanarDelaunay&&) noexcept;

  /// The plane's normal (any length, finite, nonzero): the projection drops
  /// its largest component, and it defines the in-plane metric. Call before
  /// the first insert (it empties the triangulation).
  void set_plane(const Point3& normal);
  /// Inserts the 3D point p (on the plane, up to rounding) with the caller's
  /// id. A point equal to an existing one in projection is ignored and that
  /// one's id returned; otherwise returns id (p is always a vertex).
  /// `hint`: the id of a vertex near p, where the point location starts when
  /// that vertex is in this triangulation (any value is allowed).
  int insert(const Point3& p, int id, int hint = -1);
  /// Every finite triangle, counter-clockwise in the projection, as caller ids.
  std::vector<std::array<int, 3>> triangles() const;
  /// The finite triangles incident to the point with caller id `id`.
  void incident_triangles(int id, std::vector<std::array<int, 3>>& out) const;
  /// The same, unless the point has more than `cap` incident triangles (the
  /// apex of a long fan): then returns false after O(cap) work, `out` unusable.
  bool incident_triangles(int id, std::vector<std::array<int, 3>>& out, std::size_t cap) const;
  /// The finite triangles (none, one or two, counter-clockwise) that hold the
  /// edge between the points with ids a and b; none if either point is not
  /// here or ab is no edge. O(the smaller of the two degrees): the stars of a
  /// and b are walked in turn, so a fan apex costs no more than its partner.
  /// Every star walk here is bounded by size() + 2 faces and throws
  /// LoopBoundError past it.
  void edge_triangles(int a, int b, std::vector<std::array<int, 3>>& out) const;
  /// Whether the points with ids a, b and c (in any order) span a finite
  /// triangle here; `out` then gets it as triangles() gives it (counter-
  /// clockwise, the same rotation). The same answer as edge_triangles(a, b)
  /// searched for c, in O(3 times the smallest of the three degrees): the
  /// stars of a, b and c are walked in turn (beyond the paper, issue 15: a
  /// subfacet's two older vertices are often fan apexes, its newest one
  /// seldom), each bounded as edge_triangles' walks.
  bool find_triangle(int a, int b, int c, std::array<int, 3>& out) const;
  std::size_t size() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace wqmesh
