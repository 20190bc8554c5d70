// wqmesh: the only translation unit that instantiates CGAL's triangulations
// (see triangulation.h for the contracts).
// SPDX-License-Identifier: GPL-3.0-or-later
#include "triangulation.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <new>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Regular_triangulation_3.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <CGAL/iterator.h>

#include "exact.h"

namespace wqmesh {

namespace {

// Kernel: exact predicates, inexact constructions.
using K = CGAL::Exact_predicates_inexact_constructions_kernel;

// Weighted Delaunay triangulation (paper, section 3). Vertex info = our id.
// Hidden points are discarded: the weights of WQMESH (at most N(v)^2/9) never
// hide a vertex, and a hidden insertion is reported to the caller.
using Vb3 = CGAL::Triangulation_vertex_base_with_info_3<int, K, CGAL::Regular_triangulation_vertex_base_3<K>>;
// The hidden-point container of the cells: with Discard_hidden_points CGAL
// never stores into it and only asks for its (empty) range, but the default
// one, a std::list, is still a member of every cell (24 bytes: 96 instead
// of 72 a cell). Beyond CGAL's defaults (issue 15, the peak memory: the
// cells are most of the triangulation, 2.2 per output tet): an empty range
// with no storage, so a cell is its vertices, neighbours and TDS mark.
struct NoHiddenPoints {
  using iterator = K::Weighted_point_3*;
  using const_iterator = const K::Weighted_point_3*;
  iterator end() { return nullptr; }
  const_iterator end() const { return nullptr; }
};
using RCb3 = CGAL::Regular_triangulation_cell_base_3<K, CGAL::Triangulation_cell_base_3<K>, CGAL::Discard_hidden_points,
                                                     NoHiddenPoints>;
// The label byte of the scans (triangulation.h), in the cell's padding.
// Beyond CGAL's info (issue 15): every cell is made kUnlabelled (CGAL leaves
// a char info uninitialised), so that complete_labels knows the cells made
// since the labels were set, by an insertion or a weight change alike.
struct CellLabel {
  char value = RegularTriangulation::kUnlabelled;
};
using Cb3 = CGAL::Triangulation_cell_base_with_info_3<CellLabel, K, RCb3>;
using Tds3 = CGAL::Triangulation_data_structure_3<Vb3, Cb3>;
using RtBase = CGAL::Regular_triangulation_3<K, Tds3>;
// CGAL's regular triangulation with one more way in (beyond the paper, issue
// 15): the insertion into a conflict zone the caller found, as CGAL's own
// insert does it once its find_conflicts is done (the hidden-point
// visitor's bookkeeping, then the small-hole or the general star of the new
// vertex), so that a zone found once is not searched again.
class Rt : public RtBase {
 public:
  /// Inserts p into the hole of `cells`, the cells whose power spheres hold
  /// p, marked in conflict (tds_data), in the order CGAL's find_conflicts
  /// gives them from the cell that holds p, with `facets` its boundary
  /// facets in its order (the last one starts the star). The same
  /// triangulation, cells and vertex cells as insert(p, lt, c, li, lj) with
  /// that zone. Needs dimension 3.
  template <class Cells, class Facets>
  Vertex_handle insert_in_found_zone(const Weighted_point& p, const Cells& cells, const Facets& facets) {
    get_hidden_point_visitor().process_cells_in_conflict(cells.begin(), cells.end());
    const Vertex_handle v =
        tds().is_small_hole(facets.size())
            ? _insert_in_small_hole(p, cells, facets)
            : _insert_in_hole(p, cells.begin(), cells.end(), facets.back().first, facets.back().second);
    get_hidden_point_visitor().reinsert_vertices(v);
    return v;
  }
};
// 4 vertices, 4 neighbours, the TDS mark and the label byte (72 bytes
// natively); the bound leaves a pointer's room for a compiler's padding, not
// the list's three.
static_assert(sizeof(Rt::Cell) <= 10 * sizeof(void*),
              "a cell: 4 vertices, 4 neighbours, the TDS mark and the label byte, no more");
using WPoint = K::Weighted_point_3;
using BPoint = K::Point_3;

}  // namespace

// ---- RegularTriangulation ----------------------------------------------------

struct RegularTriangulation::Impl {
  Rt rt;
  std::vector<Rt::Vertex_handle> handles;  // by id
  std::vector<Point3> points;
  std::vector<double> weights;

  int id_of(Rt::Vertex_handle v) const { return rt.is_infinite(v) ? kInfinite : v->info(); }

  Tet tet_of(Rt::Cell_handle c) const {
    return {{id_of(c->vertex(0)), id_of(c->vertex(1)), id_of(c->vertex(2)), id_of(c->vertex(3))}};
  }

  // The label scans' steps (flood_labels, complete_labels): for each facet
  // k in the bit mask `need`, flip[k] = 1 when the facet of c opposite its
  // vertex k is a wall (finite, its three vertices on_walls, and wall()
  // holds), else 0. Each vertex of c is read once and wall(), a search of
  // the walls, asked only where all three vertices may be on one (issue
  // 15: most cells have at most two vertices on P).
  void wall_flips(Rt::Cell_handle c, int need, const std::function<bool(int)>& on_walls,
                  const std::function<bool(int, int, int)>& wall, std::array<char, 4>& flip) const {
    std::array<int, 4> id;
    std::array<char, 4> on;
    int count = 0;
    for (int i = 0; i < 4; ++i) {
      id[i] = id_of(c->vertex(i));
      on[i] = id[i] != kInfinite && on_walls(id[i]);
      count += on[i];
    }
    for (int k = 0; k < 4; ++k)
      flip[k] = (need >> k & 1) && count - on[k] == 3 && wall(id[(k + 1) % 4], id[(k + 2) % 4], id[(k + 3) % 4]);
  }
  void set_label(Rt::Cell_handle c, char parity, const std::function<bool(const Tet&)>& excluded) const {
    c->info().value = parity && excluded && excluded(tet_of(c)) ? RegularTriangulation::kExcludedOdd : parity;
  }
  // The fill's step from the labelled cell c: each unlabelled neighbour
  // takes c's parity, flipped across a wall, and is pushed onto `stack`.
  void pass_labels_on(Rt::Cell_handle c, const std::function<bool(int)>& on_walls,
                      const std::function<bool(int, int, int)>& wall, const std::function<bool(const Tet&)>& excluded,
                      std::vector<Rt::Cell_handle>& stack) const {
    int need = 0;
    for (int k = 0; k < 4; ++k) need |= (c->neighbor(k)->info().value == RegularTriangulation::kUnlabelled) << k;
    if (!need) return;
    std::array<char, 4> flip;
    wall_flips(c, need, on_walls, wall, flip);
    const char from = c->info().value & 1;
    for (int k = 0; k < 4; ++k) {
      if (!(need >> k & 1)) continue;
      const Rt::Cell_handle x = c->neighbor(k);
      set_label(x, from ^ flip[k], excluded);
      stack.push_back(x);
    }
  }

  Rt::Cell_handle start_cell(int hint) const {
    if (hint >= 0 && hint < static_cast<int>(handles.size()) && handles[hint] != Rt::Vertex_handle())
      return handles[hint]->cell();
    return Rt::Cell_handle();
  }

  // Whether ab is an edge, walking the cells around a (through their faces
  // at a) and stopping at the first cell that holds b; c, i, j as CGAL's
  // is_edge gives them. Same answer as Rt::is_edge, which first collects the
  // whole star of a. Needs dimension 3.
  mutable std::vector<Rt::Cell_handle> walk, walk_b;
  //
  // Beyond a one-sided walk (issue 15): the stars of a and b are walked in
  // turn, one cell of each, so that an edge at a vertex of high degree (an
  // input corner, a fan apex) costs the star of its other end. The cell
  // found may differ from a one-sided walk's: callers that use it (edge_ring)
  // circulate around the whole edge, so their answer does not depend on it.
  bool find_edge(Rt::Vertex_handle a, Rt::Vertex_handle b, Rt::Cell_handle& c, int& i, int& j) const {
    if (rt.dimension() < 3) return rt.is_edge(a, b, c, i, j);
    // Each walk marks its cells in its own state of the cells' tds_data
    // (processed around a, on_boundary around b); a cell holding both a and
    // b ends both walks, and a walk that ends without one proves there is
    // no edge ab. Bounded by the two stars.
    walk.clear();
    walk_b.clear();
    walk.push_back(a->cell());
    a->cell()->tds_data().mark_processed();
    if (b->cell()->tds_data().is_clear()) {
      walk_b.push_back(b->cell());
      b->cell()->tds_data().mark_on_boundary();
    }
    bool found = false;
    std::size_t na = 0, nb = 0;
    auto step = [&](std::vector<Rt::Cell_handle>& w, std::size_t& n, Rt::Vertex_handle u, bool around_a) {
      const Rt::Cell_handle x = w[n++];
      if (x->has_vertex(around_a ? b : a)) {
        c = x;
        i = x->index(a);
        j = x->index(b);
        found = true;
        return;
      }
      for (int k = 0; k < 4; ++k) {
        if (x->vertex(k) == u) continue;
        const Rt::Cell_handle y = x->neighbor(k);
        if (!y->tds_data().is_clear()) continue;
        if (around_a)
          y->tds_data().mark_processed();
        else
          y->tds_data().mark_on_boundary();
        w.push_back(y);
      }
    };
    // A cell marked by the other walk holds both ends only if it holds the
    // walker's vertex too, which step() tests when that walk pops it; the
    // cells each walk skips for the other's mark hold its own vertex and so
    // are in the other's star, where that walk finds them.
    while (!found && na < walk.size() && nb < walk_b.size()) {
      step(walk, na, a, true);
      if (!found) step(walk_b, nb, b, false);
    }
    // One walk ended: finish the other (the skipped cells, see above).
    while (!found && na < walk.size()) step(walk, na, a, true);
    while (!found && nb < walk_b.size()) step(walk_b, nb, b, false);
    for (const Rt::Cell_handle& x : walk) x->tds_data().clear();
    for (const Rt::Cell_handle& x : walk_b) x->tds_data().clear();
    return found;
  }
  // Whether abv is a facet (c, i, j, k as CGAL's is_facet). Beyond a walk
  // of the star of a (issue 15): the edge ab is found by find_edge (the
  // stars of a and b in turn), then the cells around ab are circulated for
  // one holding v; abv is a facet exactly when a cell around ab holds v.
  bool find_facet(Rt::Vertex_handle a, Rt::Vertex_handle b, Rt::Vertex_handle v, Rt::Cell_handle& c, int& i, int& j,
                  int& k) const {
    if (rt.dimension() < 3) return rt.is_facet(a, b, v, c, i, j, k);
    Rt::Cell_handle e;
    int ei, ej;
    if (!find_edge(a, b, e, ei, ej)) return false;
    bool found = false;
    circulate_edge(e, ei, ej, [&](Rt::Cell_handle x) {
      if (!x->has_vertex(v, k)) return false;
      c = x;
      i = x->index(a);
      j = x->index(b);
      found = true;
      return true;
    });
    return found;
  }
  // Visits the cells around the edge (c, i, j) until `stop` says so. The
  // cells around an edge have distinct opposite vertices: at most one per
  // vertex of the triangulation, the infinite one included; past that bound
  // the triangulation is broken (LoopBoundError).
  template <class Stop>
  void circulate_edge(Rt::Cell_handle c, int i, int j, Stop&& stop) const {
    const std::size_t bound = rt.number_of_vertices() + 1;
    std::size_t n = 0;
    auto cell = rt.incident_cells(c, i, j), done = cell;
    do {
      if (++n > bound)
        throw LoopBoundError("RegularTriangulation: the cells around edge " + std::to_string(id_of(c->vertex(i))) +
                             "-" + std::to_string(id_of(c->vertex(j))) + " passed their bound of " +
                             std::to_string(bound) + " (the number of vertices plus 1)");
      if (stop(Rt::Cell_handle(cell))) return;
    } while (++cell != done);
  }
  // The cell behind a CellRef when that slot still holds a cell (the cells
  // live in a Compact_container whose blocks are never freed while the
  // triangulation lives: the slot can be read, and says if it is used);
  // else a null handle.
  Rt::Cell_handle cell_of(CellRef ref) const {
    if (ref == nullptr) return Rt::Cell_handle();
    using Cell = Rt::Triangulation_data_structure::Cell;
    using Cells = Rt::Triangulation_data_structure::Cell_range;
    const Rt::Cell_handle c = Cells::s_iterator_to(const_cast<Cell&>(*static_cast<const Cell*>(ref)));
    return rt.tds().cells().is_used(c) ? c : Rt::Cell_handle();
  }
  // cell_of(ref), which must be a cell (label(), set_label(), neighbour()).
  Rt::Cell_handle live_cell(CellRef ref) const {
    const Rt::Cell_handle c = cell_of(ref);
    if (c == Rt::Cell_handle()) throw std::logic_error("RegularTriangulation: a CellRef of no cell");
    return c;
  }
  // The vertices of the cells around edge (c, i, j) other than its ends,
  // sorted, without repeats (edge_ring's answer).
  void ring_of(Rt::Cell_handle c, int i, int j, std::vector<int>& out) const {
    out.clear();
    const Rt::Vertex_handle a = c->vertex(i), b = c->vertex(j);
    circulate_edge(c, i, j, [&](Rt::Cell_handle x) {
      for (int k = 0; k < 4; ++k) {
        const Rt::Vertex_handle v = x->vertex(k);
        if (v != a && v != b) out.push_back(id_of(v));
      }
      return false;
    });
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
  }
  // Visits the cells around a (through their faces at a) until `stop` says
  // so; returns whether it did. Bounded by the number of cells: a
  // breadth-first walk that marks each cell it queues, so none twice.
  template <class Stop>
  bool walk_star(Rt::Vertex_handle a, Stop&& stop) const {
    walk.clear();
    walk.push_back(a->cell());
    a->cell()->tds_data().mark_processed();
    bool found = false;
    for (std::size_t n = 0; n < walk.size() && !found; ++n) {
      const Rt::Cell_handle x = walk[n];
      if (stop(x)) {
        found = true;
        break;
      }
      for (int k = 0; k < 4; ++k) {
        if (x->vertex(k) == a) continue;
        const Rt::Cell_handle y = x->neighbor(k);
        if (y->tds_data().is_clear()) {
          y->tds_data().mark_processed();
          walk.push_back(y);
        }
      }
    }
    for (const Rt::Cell_handle& x : walk) x->tds_data().clear();
    return found;
  }

  Rt::Vertex_handle handle(int v) const {
    if (v < 0 || v >= static_cast<int>(handles.size()))
      throw std::out_of_range("RegularTriangulation: no vertex " + std::to_string(v));
    return handles[v];
  }

  // Inserts a weighted point; returns the CGAL handle (null when hidden), or
  // the existing vertex at the same position. Throws if the insertion hid
  // an existing vertex (outside the contract of WQMESH's weights).
  // The last conflict zone asked for (conflict_cells), while the
  // triangulation has not changed since; and the cavity of the last
  // insertion when its zone was that one (last_cavity). Beyond the paper
  // (issue 15, step 6).
  mutable bool zone_valid = false;
  mutable Point3 zone_p{};
  mutable double zone_w = 0;
  mutable std::vector<Tet> zone;
  /// find_conflicts' output in conflict_cells, kept so that a call allocates
  /// nothing once it has grown (issue 15; no other use).
  mutable std::vector<Rt::Cell_handle> conflict_scratch;
  bool cavity_valid = false;
  std::vector<Tet> cavity;
  /// replay_zone's output: the kept zone in find_conflicts' order from the
  /// cell that holds the point, and its boundary facets.
  std::vector<Rt::Cell_handle> replay_cells, replay_stack;
  std::vector<Rt::Facet> replay_facets;
  std::size_t kept_zone_insertions = 0;  ///< see RegularTriangulation::kept_zone_insertions
  /// The kept zone (conflict_scratch, the cells of `zone`) as CGAL's
  /// find_conflicts would give it from c (the cell the location found):
  /// the same depth-first walk (a stack, the neighbours in index order),
  /// with membership read from marks instead of the power test, into
  /// replay_cells and replay_facets, the cells left marked in conflict as
  /// insert_in_found_zone needs them. Returns false, every mark cleared,
  /// when c is not in the zone or the walk from c does not reach all of it
  /// (then the zone is not the one the insertion would find: the caller
  /// inserts by CGAL's own search). Beyond the paper (issue 15).
  bool replay_zone(Rt::Cell_handle c) {
    // "On boundary" marks a cell of the zone not reached yet, "in conflict"
    // one reached; the cells outside the zone are clear.
    for (const Rt::Cell_handle& x : conflict_scratch) x->tds_data().mark_on_boundary();
    replay_cells.clear();
    replay_facets.clear();
    replay_stack.clear();
    if (c->tds_data().is_on_boundary()) {
      c->tds_data().mark_in_conflict();
      replay_cells.push_back(c);
      replay_stack.push_back(c);
    }
    while (!replay_stack.empty()) {
      const Rt::Cell_handle x = replay_stack.back();
      replay_stack.pop_back();
      for (int i = 0; i < 4; ++i) {
        const Rt::Cell_handle y = x->neighbor(i);
        if (y->tds_data().is_in_conflict()) continue;
        if (y->tds_data().is_on_boundary()) {
          y->tds_data().mark_in_conflict();
          replay_cells.push_back(y);
          replay_stack.push_back(y);
          continue;
        }
        replay_facets.emplace_back(x, i);
      }
    }
    if (replay_cells.size() == conflict_scratch.size() && !replay_facets.empty()) return true;
    for (const Rt::Cell_handle& x : conflict_scratch) x->tds_data().clear();
    return false;
  }
  /// conflict_cells' common end: the cells whose power spheres hold wp
  /// (p with weight w), found by CGAL's walk from c, a cell of that set, into
  /// `out`, and remembered as the last zone asked for.
  void collect_zone(const Point3& p, double w, const WPoint& wp, Rt::Cell_handle c, std::vector<Tet>& out) const {
    conflict_scratch.clear();
    rt.find_conflicts(wp, c, CGAL::Emptyset_iterator(), std::back_inserter(conflict_scratch));
    for (const Rt::Cell_handle& cell : conflict_scratch) out.push_back(tet_of(cell));
    remember_zone(p, w, out);
  }
  void remember_zone(const Point3& p, double w, const std::vector<Tet>& out) const {
    zone_valid = !out.empty();
    zone_p = p;
    zone_w = w;
    zone = out;
  }
  // Every change of the triangulation goes through here (or through
  // forget_zone first): a kept zone is then stale.
  void forget_zone() {
    zone_valid = false;
    cavity_valid = false;
  }

  Rt::Vertex_handle insert_point(const Point3& p, double w, Rt::Cell_handle start, bool& existed) {
    // The zone kept for this very point and weight is the set of cells the
    // insertion destroys (the same exact conflict test), if it inserts.
    const bool known = zone_valid && zone_p == p && zone_w == w;
    zone_valid = false;
    cavity_valid = false;
    const WPoint wp(BPoint(p[0], p[1], p[2]), w);
    Rt::Locate_type lt;
    int li = 0, lj = 0;
    const Rt::Cell_handle c = rt.locate(wp, lt, li, lj, start);
    existed = false;
    if (lt == Rt::VERTEX && rt.dimension() >= 0) {
      existed = true;
      return c->vertex(li);
    }
    const std::size_t before = rt.number_of_vertices();
    // The zone kept for this point is inserted without a second search
    // (beyond the paper, issue 15): the same cells in the same order, so the
    // same triangulation as CGAL's insert.
    Rt::Vertex_handle v;
    if (known && rt.dimension() == 3 && replay_zone(c)) {
      v = rt.insert_in_found_zone(wp, replay_cells, replay_facets);
      ++kept_zone_insertions;
    } else {
      v = rt.insert(wp, lt, c, li, lj);
    }
    if (v == Rt::Vertex_handle()) return v;
    if (rt.number_of_vertices() != before + 1)
      throw std::logic_error("RegularTriangulation: a weighted insertion hid an existing vertex");
    if (known) {
      cavity.swap(zone);
      cavity_valid = true;
    }
    return v;
  }
};

RegularTriangulation::RegularTriangulation() : impl_(new Impl) {}
RegularTriangulation::~RegularTriangulation() = default;

int RegularTriangulation::insert(const Point3& p, double w, int hint) {
  bool existed = false;
  const Rt::Vertex_handle v = impl_->insert_point(p, w, impl_->start_cell(hint), existed);
  if (v == Rt::Vertex_handle()) return -1;
  if (existed) return v->info();
  const int id = static_cast<int>(impl_->handles.size());
  v->info() = id;
  impl_->handles.push_back(v);
  impl_->points.push_back(p);
  impl_->weights.push_back(w);
  return id;
}

std::size_t RegularTriangulation::kept_zone_insertions() const { return impl_->kept_zone_insertions; }

void RegularTriangulation::insert_all(const std::vector<Point3>& points) {
  std::vector<WPoint> wps;
  wps.reserve(points.size());
  for (const Point3& p : points) wps.emplace_back(BPoint(p[0], p[1], p[2]), 0.0);
  impl_->forget_zone();
  impl_->rt.insert(wps.begin(), wps.end());
}

bool RegularTriangulation::set_weight(int v, double w) {
  const Rt::Vertex_handle old = impl_->handle(v);
  if (impl_->weights[v] == w) return true;
  const Rt::Cell_handle near = old->cell();
  Rt::Vertex_handle neighbour;
  for (int i = 0; i < 4; ++i)
    if (near->vertex(i) != old && !impl_->rt.is_infinite(near->vertex(i))) neighbour = near->vertex(i);
  impl_->forget_zone();
  impl_->rt.remove(old);
  const Rt::Cell_handle start = neighbour != Rt::Vertex_handle() ? neighbour->cell() : Rt::Cell_handle();
  bool existed = false;
  Rt::Vertex_handle nv = impl_->insert_point(impl_->points[v], w, start, existed);
  bool ok = true;
  if (nv == Rt::Vertex_handle()) {  // hidden: put the old weight back
    ok = false;
    nv = impl_->insert_point(impl_->points[v], impl_->weights[v], start, existed);
    if (nv == Rt::Vertex_handle())
      throw std::logic_error("RegularTriangulation: cannot restore vertex " + std::to_string(v));
  } else {
    impl_->weights[v] = w;
  }
  nv->info() = v;
  impl_->handles[v] = nv;
  return ok;
}

const Point3& RegularTriangulation::point(int v) const { return impl_->points.at(v); }
double RegularTriangulation::weight(int v) const { return impl_->weights.at(v); }
int RegularTriangulation::number_of_vertices() const { return static_cast<int>(impl_->handles.size()); }
std::size_t RegularTriangulation::number_of_finite_cells() const { return impl_->rt.number_of_finite_cells(); }

bool RegularTriangulation::is_edge(int a, int b) const {
  Rt::Cell_handle c;
  int i, j;
  return impl_->find_edge(impl_->handle(a), impl_->handle(b), c, i, j);
}

bool RegularTriangulation::is_facet(int a, int b, int c) const {
  Rt::Cell_handle cell;
  int i, j, k;
  return impl_->find_facet(impl_->handle(a), impl_->handle(b), impl_->handle(c), cell, i, j, k);
}

bool RegularTriangulation::is_cell(const Tet& t) const {
  for (int v : t)
    if (v < 0) return false;
  if (impl_->rt.dimension() < 3) return false;
  const Rt::Vertex_handle b = impl_->handle(t[1]), c = impl_->handle(t[2]), d = impl_->handle(t[3]);
  return impl_->walk_star(impl_->handle(t[0]),
                          [&](Rt::Cell_handle x) { return x->has_vertex(b) && x->has_vertex(c) && x->has_vertex(d); });
}

std::vector<Tet> RegularTriangulation::finite_cells() const {
  std::vector<Tet> out;
  out.reserve(impl_->rt.number_of_finite_cells());
  for (auto c = impl_->rt.finite_cells_begin(); c != impl_->rt.finite_cells_end(); ++c) out.push_back(impl_->tet_of(c));
  return out;
}

void RegularTriangulation::finite_cells(std::vector<Tet>& out, std::vector<CellRef>& refs) const {
  out.clear();
  refs.clear();
  out.reserve(impl_->rt.number_of_finite_cells());
  refs.reserve(impl_->rt.number_of_finite_cells());
  for (auto c = impl_->rt.finite_cells_begin(); c != impl_->rt.finite_cells_end(); ++c) {
    out.push_back(impl_->tet_of(c));
    refs.push_back(static_cast<CellRef>(&*c));
  }
}

void RegularTriangulation::incident_cells(int v, std::vector<Tet>& out, std::vector<CellRef>* refs) const {
  out.clear();
  if (refs) refs->clear();
  std::vector<Rt::Cell_handle> cells;
  impl_->rt.incident_cells(impl_->handle(v), std::back_inserter(cells));
  for (const Rt::Cell_handle& c : cells) {
    out.push_back(impl_->tet_of(c));
    if (refs) refs->push_back(static_cast<CellRef>(&*c));
  }
}

bool RegularTriangulation::is_cell(const Tet& t, CellRef ref) const {
  if (ref == nullptr) return is_cell(t);
  const Rt::Cell_handle c = impl_->cell_of(ref);
  if (c == Rt::Cell_handle()) return false;
  Tet a = impl_->tet_of(c), b = t;
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  return a == b;
}

void RegularTriangulation::prefetch(const Tet& t, CellRef ref, int stage) const {
  if (ref == nullptr) return;
  using Cell = Rt::Triangulation_data_structure::Cell;
  const Cell* c = static_cast<const Cell*>(ref);
  if (stage == 0) {
    __builtin_prefetch(c);
    return;
  }
  // The slot may be free or reused: its vertex fields are then other bits,
  // and a prefetch of any address is harmless (no load, no fault).
  for (int i = 0; i < 4; ++i) __builtin_prefetch(&*c->vertex(i));
  for (int v : t)
    if (v >= 0 && v < static_cast<int>(impl_->points.size())) __builtin_prefetch(&impl_->points[v]);
}

void RegularTriangulation::adjacent_vertices(int v, std::vector<int>& out) const {
  out.clear();
  std::vector<Rt::Vertex_handle> vs;
  impl_->rt.finite_adjacent_vertices(impl_->handle(v), std::back_inserter(vs));
  for (const Rt::Vertex_handle& u : vs) out.push_back(u->info());
}

bool RegularTriangulation::edge_ring(int a, int b, std::vector<int>& out) const {
  out.clear();
  Rt::Cell_handle c;
  int i, j;
  if (!impl_->find_edge(impl_->handle(a), impl_->handle(b), c, i, j)) return false;
  impl_->ring_of(c, i, j, out);
  return true;
}

bool RegularTriangulation::edge_ring(int a, int b, std::vector<int>& out, CellRef& cell) const {
  out.clear();
  const Rt::Vertex_handle va = impl_->handle(a), vb = impl_->handle(b);
  Rt::Cell_handle c = impl_->rt.dimension() == 3 ? impl_->cell_of(cell) : Rt::Cell_handle();
  int i, j;
  if (c == Rt::Cell_handle() || !c->has_vertex(va, i) || !c->has_vertex(vb, j)) {
    cell = nullptr;
    if (!impl_->find_edge(va, vb, c, i, j)) return false;
    cell = static_cast<CellRef>(&*c);
  }
  impl_->ring_of(c, i, j, out);
  return true;
}

bool RegularTriangulation::is_edge(int a, int b, CellRef& cell) const {
  const Rt::Vertex_handle va = impl_->handle(a), vb = impl_->handle(b);
  const Rt::Cell_handle c = impl_->rt.dimension() == 3 ? impl_->cell_of(cell) : Rt::Cell_handle();
  if (c != Rt::Cell_handle() && c->has_vertex(va) && c->has_vertex(vb)) return true;
  cell = nullptr;
  Rt::Cell_handle found;
  int i, j;
  if (!impl_->find_edge(va, vb, found, i, j)) return false;
  if (impl_->rt.dimension() == 3) cell = static_cast<CellRef>(&*found);
  return true;
}

bool RegularTriangulation::facet_cells(int a, int b, int c, Tet& first, Tet& second) const {
  Rt::Cell_handle cell;
  int i, j, k;
  if (!impl_->find_facet(impl_->handle(a), impl_->handle(b), impl_->handle(c), cell, i, j, k)) return false;
  const int l = 6 - i - j - k;
  first = impl_->tet_of(cell);
  second = impl_->tet_of(cell->neighbor(l));
  return true;
}

void RegularTriangulation::conflict_cells(const Point3& p, double w, int hint, std::vector<Tet>& out) const {
  out.clear();
  if (impl_->rt.dimension() < 3) return;
  const WPoint wp(BPoint(p[0], p[1], p[2]), w);
  Rt::Locate_type lt;
  int li = 0, lj = 0;
  const Rt::Cell_handle c = impl_->rt.locate(wp, lt, li, lj, impl_->start_cell(hint));
  impl_->zone_valid = false;
  if (lt == Rt::VERTEX) return;
  impl_->collect_zone(p, w, wp, c, out);
}

const std::vector<Tet>* RegularTriangulation::last_cavity() const {
  return impl_->cavity_valid ? &impl_->cavity : nullptr;
}

void RegularTriangulation::conflict_cells(const Point3& p, double w, int hint, std::vector<Tet>& out,
                                          CellRef start) const {
  out.clear();
  const Rt::Cell_handle c = impl_->rt.dimension() == 3 ? impl_->cell_of(start) : Rt::Cell_handle();
  const WPoint wp(BPoint(p[0], p[1], p[2]), w);
  // Only when p lies strictly inside c's power sphere (exact, unperturbed):
  // then p is at no vertex (every vertex has a non-negative power to it) and
  // c is in the conflict zone, which is connected, so the walk from c finds
  // the same set as the walk from the cell that holds p.
  if (c != Rt::Cell_handle() && impl_->rt.side_of_power_sphere(c, wp, false) == CGAL::ON_BOUNDED_SIDE) {
    impl_->collect_zone(p, w, wp, c, out);
    return;
  }
  conflict_cells(p, w, hint, out);
}

int RegularTriangulation::nearest_vertex(const Point3& p, int hint) const {
  const Rt::Vertex_handle v = impl_->rt.nearest_power_vertex(BPoint(p[0], p[1], p[2]), impl_->start_cell(hint));
  return v == Rt::Vertex_handle() || impl_->rt.is_infinite(v) ? -1 : v->info();
}

namespace {

// The index of each cell of a triangulation by its address, for cell_graph:
// open addressing with linear probing in a table of at least 5/4 as many
// slots as cells (a power of two: at most 4/5 full), so a look-up touches a
// few slots where std::unordered_map follows a node per entry (the
// whole-mesh cell graph was 3-8% of a run with it; issue 15). The table is
// a transient beside the triangulation at the run's peak (12 bytes a slot:
// at least twice as many slots took about 80 bytes per output tet on
// anchor.off).
class CellIndex {
 public:
  explicit CellIndex(std::size_t n) {
    std::size_t size = 16;
    while (4 * size < 5 * n) size *= 2;
    mask_ = size - 1;
    keys_.assign(size, nullptr);
    values_.assign(size, -1);
  }
  void add(const void* key, int value) {
    std::size_t i = slot(key);
    while (keys_[i] != nullptr) i = (i + 1) & mask_;
    keys_[i] = key;
    values_[i] = value;
  }
  /// The value of a key added before; -1 for any other.
  int find(const void* key) const {
    for (std::size_t i = slot(key);; i = (i + 1) & mask_) {
      if (keys_[i] == key) return values_[i];
      if (keys_[i] == nullptr) return -1;
    }
  }

 private:
  std::size_t slot(const void* key) const {
    const std::uint64_t x = static_cast<std::uint64_t>(reinterpret_cast<std::uintptr_t>(key));
    return static_cast<std::size_t>(((x >> 4) * 0x9E3779B97F4A7C15ull) >> 20) & mask_;
  }
  std::size_t mask_ = 0;
  std::vector<const void*> keys_;
  std::vector<int> values_;
};

}  // namespace

RegularTriangulation::CellGraph RegularTriangulation::cell_graph(const std::function<bool(std::size_t)>& poll) const {
  CellGraph g;
  constexpr std::size_t kEvery = 1024;
  std::size_t n = 0;
  auto stop = [&] { return poll && ++n % kEvery == 0 && !poll(kEvery); };
  const std::size_t cells = impl_->rt.number_of_cells();
  CellIndex index(cells);
  g.cells.reserve(cells);
  for (auto c = impl_->rt.all_cells_begin(); c != impl_->rt.all_cells_end(); ++c) {
    if (stop()) return {};
    index.add(&*c, static_cast<int>(g.cells.size()));
    g.cells.push_back(impl_->tet_of(c));
  }
  g.neighbor.resize(g.cells.size());
  int i = 0;
  for (auto c = impl_->rt.all_cells_begin(); c != impl_->rt.all_cells_end(); ++c, ++i) {
    if (stop()) return {};
    for (int k = 0; k < 4; ++k) g.neighbor[i][k] = index.find(&*c->neighbor(k));
  }
  return g;
}

namespace {

/// The parity of a label (triangulation.h): 1 for 1 and kExcludedOdd.
inline char parity(char label) { return static_cast<char>(label & 1); }

}  // namespace

bool RegularTriangulation::flood_labels(const std::function<bool(int)>& on_walls,
                                        const std::function<bool(int, int, int)>& wall,
                                        const std::function<bool(const Tet&)>& excluded,
                                        const std::function<bool(std::size_t)>& poll, std::size_t* wall_faces) const {
  constexpr std::size_t kEvery = 1024;
  std::size_t n = 0;
  auto stop = [&] { return poll && ++n % kEvery == 0 && !poll(kEvery); };
  const Rt& rt = impl_->rt;
  std::vector<Rt::Cell_handle> stack;
  std::array<char, 4> flip;
  for (auto c = rt.all_cells_begin(); c != rt.all_cells_end(); ++c) {
    if (stop()) return false;
    c->info().value = kUnlabelled;
  }
  if (rt.dimension() < 3) return true;
  rt.incident_cells(rt.infinite_vertex(), std::back_inserter(stack));
  for (const Rt::Cell_handle& c : stack) c->info().value = 0;
  // Each cell is pushed once (labelled when pushed): at most |cells| pops.
  while (!stack.empty()) {
    if (stop()) return false;
    const Rt::Cell_handle c = stack.back();
    stack.pop_back();
    impl_->pass_labels_on(c, on_walls, wall, excluded, stack);
  }
  if (wall_faces) {
    // Each facet once: from the cell of the lower address.
    *wall_faces = 0;
    for (auto c = rt.all_cells_begin(); c != rt.all_cells_end(); ++c) {
      if (stop()) return false;
      int need = 0;
      for (int k = 0; k < 4; ++k) need |= !(&*c->neighbor(k) < &*c) << k;
      impl_->wall_flips(c, need, on_walls, wall, flip);
      for (int k = 0; k < 4; ++k) *wall_faces += flip[k];
    }
  }
  return true;
}

bool RegularTriangulation::complete_labels(const std::function<bool(int)>& on_walls,
                                           const std::function<bool(int, int, int)>& wall, std::size_t walls,
                                           const std::function<bool(const Tet&)>& excluded,
                                           const std::function<bool(std::size_t)>& poll) const {
  constexpr std::size_t kEvery = 1024;
  std::size_t n = 0;
  auto stop = [&] { return poll && ++n % kEvery == 0 && !poll(kEvery); };
  const Rt& rt = impl_->rt;
  if (rt.dimension() < 3) return walls == 0;
  // The unlabelled cells (made since the labels were set) take the label of
  // a labelled neighbour, an infinite one 0, and pass theirs on to the
  // unlabelled cells around them: each cell is pushed once.
  std::vector<Rt::Cell_handle> stack;
  std::array<char, 4> flip;
  for (auto c = rt.all_cells_begin(); c != rt.all_cells_end(); ++c) {
    if (stop()) return false;
    if (c->info().value != kUnlabelled) continue;
    if (rt.is_infinite(c)) {
      c->info().value = 0;
      stack.push_back(c);
      continue;
    }
    for (int k = 0; k < 4; ++k) {
      const char across = c->neighbor(k)->info().value;
      if (across == kUnlabelled) continue;
      impl_->wall_flips(c, 1 << k, on_walls, wall, flip);
      impl_->set_label(c, parity(across) ^ flip[k], excluded);
      stack.push_back(c);
      break;
    }
  }
  while (!stack.empty()) {
    if (stop()) return false;
    const Rt::Cell_handle c = stack.back();
    stack.pop_back();
    impl_->pass_labels_on(c, on_walls, wall, excluded, stack);
  }
  // The check: every infinite cell even, and the facets across which the
  // parities differ (each facet once, from the cell of the lower address)
  // are `walls` in number and each a wall. There are at most `walls` wall
  // facets (a triangle is one facet at most), so they are then exactly the
  // wall facets, and every wall is one: the parities differ exactly at the
  // walls. Such labels are the only ones (every cell is joined to an
  // infinite one by a path of facets), so they are any flood fill's. Only
  // the facets of differing parities are asked whether they are walls (the
  // cells' vertices are not read for the others).
  std::size_t differ = 0;
  for (auto c = rt.all_cells_begin(); c != rt.all_cells_end(); ++c) {
    if (stop()) return false;
    const char label = c->info().value;
    if (label == kUnlabelled || (parity(label) && rt.is_infinite(c))) return false;
    int need = 0;
    for (int k = 0; k < 4; ++k) {
      const Rt::Cell_handle x = c->neighbor(k);
      need |= (!(&*x < &*c) && parity(label) != parity(x->info().value)) << k;
    }
    if (!need) continue;
    impl_->wall_flips(c, need, on_walls, wall, flip);
    for (int k = 0; k < 4; ++k) {
      if (!(need >> k & 1)) continue;
      if (!flip[k] || ++differ > walls) return false;
    }
  }
  return differ == walls;
}

bool RegularTriangulation::visit_labels(const std::function<void(const Tet&, char&)>& visit,
                                        const std::function<bool(std::size_t)>& poll) const {
  constexpr std::size_t kEvery = 1024;
  std::size_t n = 0;
  for (auto c = impl_->rt.all_cells_begin(); c != impl_->rt.all_cells_end(); ++c) {
    if (poll && ++n % kEvery == 0 && !poll(kEvery)) return false;
    visit(impl_->tet_of(c), c->info().value);
  }
  return true;
}

bool RegularTriangulation::visit_cells(const std::function<void(const Tet&, CellRef, char)>& visit,
                                       const std::function<bool(std::size_t)>& poll) const {
  constexpr std::size_t kEvery = 1024;
  std::size_t n = 0;
  for (auto c = impl_->rt.all_cells_begin(); c != impl_->rt.all_cells_end(); ++c) {
    if (poll && ++n % kEvery == 0 && !poll(kEvery)) return false;
    visit(impl_->tet_of(c), static_cast<CellRef>(&*c), c->info().value);
  }
  return true;
}

namespace {
// The loop of both visit_labelled: visit(c) for every cell c labelled
// `label`, in cell_graph's order, polled as visit_labels polls.
template <class Visit>
bool for_each_labelled(const Rt& rt, char label, const std::function<bool(std::size_t)>& poll, Visit&& visit) {
  constexpr std::size_t kEvery = 1024;
  std::size_t n = 0;
  for (auto c = rt.all_cells_begin(); c != rt.all_cells_end(); ++c) {
    if (poll && ++n % kEvery == 0 && !poll(kEvery)) return false;
    if (c->info().value == label) visit(Rt::Cell_handle(c));
  }
  return true;
}
}  // namespace

bool RegularTriangulation::visit_labelled(char label,
                                          const std::function<void(const Tet&, const std::array<char, 4>&)>& visit,
                                          const std::function<bool(std::size_t)>& poll) const {
  return for_each_labelled(impl_->rt, label, poll, [&](Rt::Cell_handle c) {
    const std::array<char, 4> across{{c->neighbor(0)->info().value, c->neighbor(1)->info().value,
                                      c->neighbor(2)->info().value, c->neighbor(3)->info().value}};
    visit(impl_->tet_of(c), across);
  });
}

bool RegularTriangulation::visit_labelled(char label, const std::function<void(const Tet&)>& visit,
                                          const std::function<bool(std::size_t)>& poll) const {
  return for_each_labelled(impl_->rt, label, poll, [&](Rt::Cell_handle c) { visit(impl_->tet_of(c)); });
}

char RegularTriangulation::label(CellRef ref) const { return impl_->live_cell(ref)->info().value; }

void RegularTriangulation::set_label(CellRef ref, char label) const { impl_->live_cell(ref)->info().value = label; }

CellRef RegularTriangulation::neighbour(CellRef ref, int k, Tet& across) const {
  const Rt::Cell_handle n = impl_->live_cell(ref)->neighbor(k);
  across = impl_->tet_of(n);
  return static_cast<CellRef>(&*n);
}

// ---- PlanarDelaunay ----------------------------------------------------------

namespace {

// The in-plane metric of a facet in its projection: for a displacement
// (dx, dy) of the projected coordinates within the plane of normal n (the
// dropped coordinate `axis` follows from the plane), the squared 3D length
// times n[axis]^2 is Q(dx, dy) = a dx^2 + b dx dy + c dy^2 with
// a = n_a^2 + n_i^2, b = 2 n_i n_j, c = n_a^2 + n_j^2 (i, j the kept axes).
// The coefficients are fixed doubles (the normal's rounding only tilts the
// metric by as much); Q is positive definite since |n_a| is the largest.
struct PlaneMetric {
  double a = 1, b = 0, c = 1;
};

// The 2D traits of a facet's triangulation: Epick's exact orientation of the
// projected points, and the in-circle test of the plane's metric, evaluated
// exactly (exact::sign: interval arithmetic, then MP_Float). The in-circle
// test is that of a fixed strictly convex lift, so the triangulation is a
// plain Delaunay triangulation (of the points mapped linearly to the plane):
// every inserted point is a vertex, none can be hidden, whatever the
// rounding of the points off the plane.
struct PlaneTraits : K {
  PlaneMetric metric;
  PlaneTraits() = default;
  explicit PlaneTraits(const PlaneMetric& m) : metric(m) {}
  struct Side_of_oriented_circle_2 {
    PlaneMetric m;
    CGAL::Oriented_side operator()(const K::Point_2& p, const K::Point_2& q, const K::Point_2& r,
                                   const K::Point_2& t) const {
      // The rows (p - t, Q(p - t)), ...: positive when t lies inside the
      // ellipse of the metric through p, q, r counter-clockwise.
      const int s = exact::sign([&](auto z) {
        using NT = decltype(z);
        const NT tx(t.x()), ty(t.y()), A(m.a), B(m.b), C(m.c);
        const NT px = NT(p.x()) - tx, py = NT(p.y()) - ty;
        const NT qx = NT(q.x()) - tx, qy = NT(q.y()) - ty;
        const NT rx = NT(r.x()) - tx, ry = NT(r.y()) - ty;
        const NT pq = A * px * px + B * px * py + C * py * py;
        const NT qq = A * qx * qx + B * qx * qy + C * qy * qy;
        const NT rq = A * rx * rx + B * rx * ry + C * ry * ry;
        return px * (qy * rq - ry * qq) - py * (qx * rq - rx * qq) + pq * (qx * ry - rx * qy);
      });
      return s > 0 ? CGAL::ON_POSITIVE_SIDE : s < 0 ? CGAL::ON_NEGATIVE_SIDE : CGAL::ON_ORIENTED_BOUNDARY;
    }
  };
  Side_of_oriented_circle_2 side_of_oriented_circle_2_object() const { return {metric}; }
};

}  // namespace

// ---- The facets' planar triangulations' storage (issue 15, the peak memory) --
// Beyond CGAL's defaults: the vertex and face blocks of every planar
// triangulation come from one pool of 1 MB chunks instead of the heap. CGAL's
// Compact_container allocates a block of 16, 32, 48, ... elements at a time,
// so the many small facets of a model (fandisk.off) scatter their blocks of
// a few KB among REFINE's other small blocks; freed after REFINE
// (Subcomplex::freeze) they left holes that malloc_trim could not give back
// and PUMP's large tables could not reuse (fandisk.off: 41 MB of blocks
// freed, the resident memory down by 6 MB). From the pool, they are freed
// as whole chunks (fandisk's peak RSS 185.0 -> 163.1 MB; the same meshes).
// Contract: a freed block is reused only by a block of the same size, and
// when the last block is freed every chunk goes back to the heap
// (Compact_container frees its blocks only when it is cleared or destroyed,
// and allocates the same sequence of sizes in every triangulation, so the
// blocks of a triangulation freed while others live serve the next ones).
// One pool for the process, behind a mutex (a block is allocated per 16
// to a few thousand vertices or faces).
namespace planar_pool {

class Pool {
 public:
  // Never destroyed, so that a triangulation freed during the program's
  // exit still finds it.
  static Pool& get() {
    static Pool* const pool = new Pool;
    return *pool;
  }
  void* allocate(std::size_t bytes) {
    bytes = (bytes + kAlign - 1) / kAlign * kAlign;
    std::lock_guard<std::mutex> lock(mutex_);
    // Exception safety: the reserve and free_'s entry for this size (a
    // std::map insert) are the only steps here that can throw, and both come
    // before any change of the pool's counts, so a bad_alloc leaves the pool
    // as it was (the entry is created here, for deallocate, which must not
    // throw); then no push_back below throws.
    if (chunks_.size() == chunks_.capacity()) chunks_.reserve(2 * chunks_.size() + 16);
    void* p;
    if (void*& head = free_[bytes]) {  // a freed block of this size
      p = head;
      head = *static_cast<void**>(p);
    } else if (bytes > kChunk / 4) {  // a large block: a chunk of its own
      p = take(bytes);
      chunks_.push_back(p);
      bytes_ += bytes;
    } else {
      if (bytes > std::size_t(end_ - next_)) {
        next_ = static_cast<char*>(take(kChunk));
        end_ = next_ + kChunk;
        chunks_.push_back(next_);
        bytes_ += kChunk;
      }
      p = next_;
      next_ += bytes;
    }
    ++live_;
    return p;
  }
  std::size_t bytes() {
    std::lock_guard<std::mutex> lock(mutex_);
    return bytes_;
  }
  void deallocate(void* p, std::size_t bytes) {
    bytes = (bytes + kAlign - 1) / kAlign * kAlign;
    std::lock_guard<std::mutex> lock(mutex_);
    if (--live_ > 0) {
      // Never an insert (deallocate runs in CGAL's destructors and must not
      // throw): allocate made this size's entry, and free_ is cleared only
      // when no block is live.
      const auto it = free_.find(bytes);
      assert(it != free_.end());
      void*& head = it->second;
      *static_cast<void**>(p) = head;
      head = p;
      return;
    }
    for (void* c : chunks_) ::operator delete(c);
    std::vector<void*>().swap(chunks_);
    free_.clear();
    next_ = end_ = nullptr;
    bytes_ = 0;
  }

 private:
  static constexpr std::size_t kChunk = std::size_t(1) << 20;
  static constexpr std::size_t kAlign = alignof(std::max_align_t);
  // The chunks by ::operator new, so that a count of the C++ heap
  // (tests/benchmark/heap_phases.cpp) sees them.
  static void* take(std::size_t bytes) { return ::operator new(bytes); }
  std::mutex mutex_;
  std::vector<void*> chunks_;
  /// Freed blocks by size, each list linked through the blocks' first
  /// bytes: reused by the next block of that size (a triangulation replaced
  /// while others live, as PlanarDelaunay::set_plane replaces the empty one
  /// it starts with, leaves its first blocks here).
  std::map<std::size_t, void*> free_;
  char* next_ = nullptr;
  char* end_ = nullptr;
  std::size_t live_ = 0;   ///< blocks handed out and not yet freed
  std::size_t bytes_ = 0;  ///< the chunks' bytes
};

/// A vertex or face base B of the planar triangulation whose blocks
/// std::allocator (specialised below) takes from the pool: B itself, as a
/// type of this program's.
template <class B>
struct Pooled : B {
  using B::B;
  template <class TDS2>
  struct Rebind_TDS {
    using Other = Pooled<typename B::template Rebind_TDS<TDS2>::Other>;
  };
};

}  // namespace planar_pool

std::size_t planar_pool_bytes() { return planar_pool::Pool::get().bytes(); }

}  // namespace wqmesh

/// The allocator CGAL's Compact_container takes for the pooled vertex and
/// face types (std::allocator, specialised for a program-defined type).
template <class B>
class std::allocator<wqmesh::planar_pool::Pooled<B>> {
 public:
  using value_type = wqmesh::planar_pool::Pooled<B>;
  using size_type = std::size_t;
  using difference_type = std::ptrdiff_t;
  using propagate_on_container_move_assignment = std::true_type;
  using is_always_equal = std::true_type;
  allocator() noexcept = default;
  template <class U>
  allocator(const std::allocator<U>&) noexcept {}
  value_type* allocate(std::size_t n) {
    if (n > std::numeric_limits<std::size_t>::max() / sizeof(value_type)) throw std::bad_array_new_length();
    return static_cast<value_type*>(wqmesh::planar_pool::Pool::get().allocate(n * sizeof(value_type)));
  }
  void deallocate(value_type* p, std::size_t n) noexcept {
    wqmesh::planar_pool::Pool::get().deallocate(p, n * sizeof(value_type));
  }
  // What libstdc++'s allocator_traits<std::allocator<T>> calls directly.
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
  template <class U>
  void destroy(U* p) {
    p->~U();
  }
  std::size_t max_size() const noexcept { return std::numeric_limits<std::size_t>::max() / sizeof(value_type); }
  friend bool operator==(const allocator&, const allocator&) noexcept { return true; }
  friend bool operator!=(const allocator&, const allocator&) noexcept { return false; }
};

namespace wqmesh {
namespace {

using Vb2 = planar_pool::Pooled<CGAL::Triangulation_vertex_base_with_info_2<int, PlaneTraits>>;
using Fb2 = planar_pool::Pooled<CGAL::Triangulation_face_base_2<PlaneTraits>>;
using Tds2 = CGAL::Triangulation_data_structure_2<Vb2, Fb2>;
using Dt2 = CGAL::Delaunay_triangulation_2<PlaneTraits, Tds2>;

}  // namespace

// The vertices of a facet's triangulation by caller id: open addressing with
// linear probing, at most half full (std::unordered_map's node per entry
// made these look-ups about 4% of a run; issue 15). Ids are the 3D vertex
// ids (>= 0); any int may be looked up.
class VertexById {
 public:
  VertexById() { clear(); }
  void clear() {
    keys_.assign(16, kEmpty);
    values_.assign(16, Dt2::Vertex_handle());
    size_ = 0;
  }
  /// The vertex with caller id `id`, or null.
  Dt2::Vertex_handle find(int id) const {
    for (std::size_t i = slot(id);; i = (i + 1) & (keys_.size() - 1)) {
      if (keys_[i] == id && id != kEmpty) return values_[i];
      if (keys_[i] == kEmpty) return Dt2::Vertex_handle();
    }
  }
  /// Sets the vertex of `id` (>= 0).
  void set(int id, Dt2::Vertex_handle v) {
    if (2 * (size_ + 1) > keys_.size()) grow();
    std::size_t i = slot(id);
    while (keys_[i] != kEmpty && keys_[i] != id) i = (i + 1) & (keys_.size() - 1);
    if (keys_[i] == kEmpty) ++size_;
    keys_[i] = id;
    values_[i] = v;
  }

 private:
  static constexpr int kEmpty = std::numeric_limits<int>::min();
  std::size_t slot(int id) const {
    const std::uint64_t h = std::uint64_t(std::uint32_t(id)) * 0x9E3779B97F4A7C15ull;
    return static_cast<std::size_t>(h >> 32) & (keys_.size() - 1);
  }
  void grow() {
    std::vector<int> keys;
    std::vector<Dt2::Vertex_handle> values;
    keys.swap(keys_);
    values.swap(values_);
    keys_.assign(2 * keys.size(), kEmpty);
    values_.assign(2 * keys.size(), Dt2::Vertex_handle());
    size_ = 0;
    for (std::size_t i = 0; i < keys.size(); ++i)
      if (keys[i] != kEmpty) set(keys[i], values[i]);
  }
  std::vector<int> keys_;
  std::vector<Dt2::Vertex_handle> values_;
  std::size_t size_ = 0;
};

struct PlanarDelaunay::Impl {
  /// The triangulation, made by set_plane with the plane's traits, or on
  /// first use with z = 0's when no set_plane came first: one Dt2 per facet,
  /// where building a default one at construction and replacing it in
  /// set_plane made two (their blocks from the pool each time).
  mutable std::optional<Dt2> made;
  Dt2& dt() const {
    if (!made) made.emplace(PlaneTraits());
    return *made;
  }
  VertexById by_id;
  int axis = 2;
  Dt2::Vertex_handle last;

  // A star walk around v may visit at most this many faces: the degree of a
  // vertex is below the number of vertices, plus the infinite face(s).
  std::size_t star_bound() const { return dt().number_of_vertices() + 2; }
  [[noreturn]] void exceeded(const char* loop, int id) const {
    throw LoopBoundError(std::string("PlanarDelaunay::") + loop + ": the star walk around vertex " +
                         std::to_string(id) + " passed its bound of " + std::to_string(star_bound()) +
                         " faces (the number of vertices of the facet plus 2)");
  }
};

PlanarDelaunay::PlanarDelaunay() : impl_(new Impl) {}
PlanarDelaunay::~PlanarDelaunay() = default;
PlanarDelaunay::PlanarDelaunay(PlanarDelaunay&&) noexcept = default;
PlanarDelaunay& PlanarDelaunay::operator=(PlanarDelaunay&&) noexcept = default;

void PlanarDelaunay::set_plane(const Point3& normal) {
  int a = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(normal[k]) > std::abs(normal[a])) a = k;
  if (!(normal[a] != 0) || !std::isfinite(normal[a]))
    throw std::invalid_argument("PlanarDelaunay: the plane's normal is zero or not finite");
  // Scaled so that the largest component is 1 (the metric's scale is free).
  const double na = 1, ni = normal[(a + 1) % 3] / std::abs(normal[a]), nj = normal[(a + 2) % 3] / std::abs(normal[a]);
  PlaneMetric m;
  m.a = na * na + ni * ni;
  m.b = 2 * ni * nj;
  m.c = na * na + nj * nj;
  impl_->axis = a;
  impl_->made.emplace(PlaneTraits(m));
  impl_->by_id.clear();
  impl_->last = Dt2::Vertex_handle();
}

int PlanarDelaunay::insert(const Point3& p, int id, int hint) {
  // (x, y) keep the cyclic order of the axes so that the projection of a
  // facet whose normal points along +axis is counter-clockwise.
  const int a = impl_->axis, i = (a + 1) % 3, j = (a + 2) % 3;
  const K::Point_2 q(p[i], p[j]);
  // The walk starts at the hint's vertex when it is in this triangulation,
  // else at the last one inserted: insertions come in spatial runs, and a
  // walk from an arbitrary face costs O(sqrt n) on a large facet.
  Dt2::Face_handle start;
  const Dt2::Vertex_handle near = impl_->by_id.find(hint);
  if (near != Dt2::Vertex_handle())
    start = near->face();
  else if (impl_->last != Dt2::Vertex_handle())
    start = impl_->last->face();
  Dt2::Locate_type lt;
  int li = 0;
  Dt2& dt = impl_->dt();
  const Dt2::Face_handle f = dt.locate(q, lt, li, start);
  if (lt == Dt2::VERTEX) return f->vertex(li)->info();
  const Dt2::Vertex_handle v = dt.insert(q, lt, f, li);
  v->info() = id;
  impl_->by_id.set(id, v);
  impl_->last = v;
  return id;
}

std::vector<std::array<int, 3>> PlanarDelaunay::triangles() const {
  std::vector<std::array<int, 3>> out;
  const Dt2& dt = impl_->dt();
  for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f)
    out.push_back({{f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()}});
  return out;
}

void PlanarDelaunay::incident_triangles(int id, std::vector<std::array<int, 3>>& out) const {
  incident_triangles(id, out, std::numeric_limits<std::size_t>::max());
}

bool PlanarDelaunay::incident_triangles(int id, std::vector<std::array<int, 3>>& out, std::size_t cap) const {
  out.clear();
  const Dt2::Vertex_handle v = impl_->by_id.find(id);
  const Dt2& dt = impl_->dt();
  if (v == Dt2::Vertex_handle() || dt.dimension() < 2) return true;
  auto f = dt.incident_faces(v), done = f;
  if (f == nullptr) return true;
  const std::size_t bound = impl_->star_bound();
  std::size_t seen = 0;
  do {
    if (++seen > cap) return false;
    if (seen > bound) impl_->exceeded("incident_triangles", id);
    if (!dt.is_infinite(f)) out.push_back({{f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()}});
  } while (++f != done);
  return true;
}

void PlanarDelaunay::edge_triangles(int a, int b, std::vector<std::array<int, 3>>& out) const {
  out.clear();
  const Dt2& dt = impl_->dt();
  if (a == b || dt.dimension() < 2) return;
  const Dt2::Vertex_handle va = impl_->by_id.find(a), vb = impl_->by_id.find(b);
  if (va == Dt2::Vertex_handle() || vb == Dt2::Vertex_handle()) return;
  // Walk the star of a looking for b and the star of b looking for a, one
  // face of each in turn; the first walk to find the edge wins, and the first
  // to end without it proves there is no edge ab. Each walk is bounded by
  // star_bound() faces.
  auto fa = dt.incident_faces(va), done_a = fa;
  auto fb = dt.incident_faces(vb), done_b = fb;
  if (fa == nullptr || fb == nullptr) return;
  const std::size_t bound = impl_->star_bound();
  Dt2::Face_handle hit;
  bool more_a = true, more_b = true;
  for (std::size_t n = 0; hit == Dt2::Face_handle() && more_a && more_b; ++n) {
    if (n >= bound) impl_->exceeded("edge_triangles", a);
    if (fa->has_vertex(vb)) hit = fa;
    more_a = ++fa != done_a;
    if (hit == Dt2::Face_handle()) {
      if (fb->has_vertex(va)) hit = fb;
      more_b = ++fb != done_b;
    }
  }
  if (hit == Dt2::Face_handle()) return;
  // The edge's two faces: hit and its neighbour across the edge.
  const int i = 3 - hit->index(va) - hit->index(vb);
  for (const Dt2::Face_handle& g : {hit, hit->neighbor(i)})
    if (!dt.is_infinite(g)) out.push_back({{g->vertex(0)->info(), g->vertex(1)->info(), g->vertex(2)->info()}});
}

bool PlanarDelaunay::find_triangle(int a, int b, int c, std::array<int, 3>& out) const {
  const Dt2& dt = impl_->dt();
  if (a == b || b == c || a == c || dt.dimension() < 2) return false;
  const std::array<Dt2::Vertex_handle, 3> v{{impl_->by_id.find(a), impl_->by_id.find(b), impl_->by_id.find(c)}};
  for (const Dt2::Vertex_handle& x : v)
    if (x == Dt2::Vertex_handle()) return false;
  // Each walk visits the star of its vertex looking for a face holding the
  // other two; a walk that ends without one proves there is no such face
  // (it would be in every one of the three stars).
  std::array<Dt2::Face_circulator, 3> f{{dt.incident_faces(v[0]), dt.incident_faces(v[1]), dt.incident_faces(v[2])}};
  const std::array<Dt2::Face_circulator, 3> done = f;
  for (const Dt2::Face_circulator& x : f)
    if (x == nullptr) return false;
  const std::size_t bound = impl_->star_bound();
  const std::array<int, 3> ids{{a, b, c}};
  for (std::size_t n = 0;; ++n) {
    for (int k = 0; k < 3; ++k) {
      if (n >= bound) impl_->exceeded("find_triangle", ids[k]);
      if (f[k]->has_vertex(v[(k + 1) % 3]) && f[k]->has_vertex(v[(k + 2) % 3])) {
        out = {{f[k]->vertex(0)->info(), f[k]->vertex(1)->info(), f[k]->vertex(2)->info()}};
        return true;
      }
      if (++f[k] == done[k]) return false;
    }
  }
}

std::size_t PlanarDelaunay::size() const { return impl_->dt().number_of_vertices(); }

}  // namespace wqmesh
