// wqmesh: the tets inside the polyhedron (flood fill across the walls, the
// input subfacets) and their classes (classify.cpp): the mesh WQMESH returns.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <iterator>
#include <limits>
#include <unordered_map>
#include <unordered_set>

#include "mesher/classify.h"
#include "mesher/extract.h"
#include "mesher/improve.h"
#include "wqmesh/quality.h"

namespace wqmesh::mesher {

namespace {

/// Whether every edge of `walls` lies in an even number of them. The walls
/// are then a mod-2 2-cycle of the triangulation (with its infinite vertex a
/// 3-sphere, where every such cycle bounds), so the parity of the walls
/// crossed on the way from an infinite cell is the same along every path: the
/// flood fill of interior_labels gives every cell the same label whatever
/// the order of the cell graph. Not so with a facet that ends inside the
/// domain (a slit) or with holes (a run that does not conform).
bool even_walls(const std::vector<Tri>& walls) {
  std::vector<std::uint64_t> edges;
  edges.reserve(3 * walls.size());
  for (const Tri& t : walls)
    for (int k = 0; k < 3; ++k) edges.push_back(edge_key(t[k], t[(k + 1) % 3]));
  std::sort(edges.begin(), edges.end());
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    if ((j - i) % 2) return false;
    i = j;
  }
  return true;
}

}  // namespace

std::vector<char> interior_labels(const Domain& dom, const Subcomplex& sub, const RegularTriangulation::CellGraph& g,
                                  WorkMeter& meter, bool scan, bool* order_free) {
  // Flood fill from the infinite cells; the subfacets of input facets are the
  // walls.
  std::vector<Tri> wall_list;
  for (const Subfacet& h : sub.subfacets())
    if (!dom.is_box_facet(h.facet)) wall_list.push_back(sorted(h.v));
  if (order_free) *order_free = even_walls(wall_list);
  const std::unordered_set<Tri, TriHash> walls(wall_list.begin(), wall_list.end());
  // A triangle with a vertex off P (free, or the infinite one) is in no
  // facet's triangulation: no wall, without a look-up.
  const auto is_wall = [&](int a, int b, int c) {
    return sub.on_p(a) && sub.on_p(b) && sub.on_p(c) && walls.count(sorted({{a, b, c}}));
  };
  // Crossing a wall flips inside and outside (a polyhedron may have several
  // shells). 1 = inside.
  std::vector<char> label(g.cells.size(), 2);  // 2 = unknown
  std::vector<int> stack;
  for (std::size_t i = 0; i < g.cells.size(); ++i)
    if (std::find(g.cells[i].begin(), g.cells[i].end(), kInfinite) != g.cells[i].end()) {
      label[i] = 0;
      stack.push_back(static_cast<int>(i));
    }
  // Each cell is pushed once (labelled when pushed): at most |cells| pops.
  while (!stack.empty()) {
    if (scan && !meter.poll(1, false)) return label;
    const int c = stack.back();
    stack.pop_back();
    for (int k = 0; k < 4; ++k) {
      const int n = g.neighbor[c][k];
      if (label[n] != 2) continue;
      const Tet& t = g.cells[c];
      label[n] = is_wall(t[(k + 1) % 4], t[(k + 2) % 4], t[(k + 3) % 4]) ? char(1 - label[c]) : label[c];
      stack.push_back(n);
    }
  }
  // Flat tets lying in an input facet pass the labels on correctly whatever
  // their own label; they belong to neither side and are left out.
  for (std::size_t i = 0; i < g.cells.size(); ++i)
    if (label[i] == 1 && sub.flat_on_facet(g.cells[i])) label[i] = 0;
  return label;
}

bool label_cells_in_place(const Domain& dom, const Subcomplex& sub, const RegularTriangulation& tri, WorkMeter& meter,
                          bool scan) {
  std::vector<Tri> walls;
  for (const Subfacet& h : sub.subfacets())
    if (!dom.is_box_facet(h.facet)) walls.push_back(sorted(h.v));
  // A sorted list, not a hash set: the same answers in a third of the memory.
  std::sort(walls.begin(), walls.end());
  walls.erase(std::unique(walls.begin(), walls.end()), walls.end());
  // A triangle with a vertex off P (free) is in no facet's triangulation:
  // no wall, without a look-up.
  const auto on_p = [&](int v) { return sub.on_p(v); };
  const auto is_wall = [&](int a, int b, int c) {
    return std::binary_search(walls.begin(), walls.end(), sorted({{a, b, c}}));
  };
  // As interior_labels: flat tets lying in an input facet are left out
  // (kExcludedOdd instead of 1; a cell's flatness never changes).
  const auto flat = [&](const Tet& t) { return sub.flat_on_facet(t); };
  std::function<bool(std::size_t)> poll;
  if (scan) poll = [&](std::size_t n) { return meter.poll(n, false); };
  // Beyond the paper (issue 15): the labels an earlier call left in the
  // cells are completed and checked (complete_labels: only the cells made
  // since are labelled, every facet is checked), and the whole
  // triangulation is filled again only when the check fails; the same
  // labels and answer either way. The fill crosses only the walls that are facets of
  // the triangulation: the labels are free of the order when those are all
  // of them (a run that conforms; the rule 7 passes of REFINE need not) and
  // even_walls holds.
  // even_walls is asked only when the check fails (beyond the paper, issue
  // 15: its sort of every wall's edges was about 1% of a run), since labels
  // that pass the check imply it: around each edge the cells form a cycle
  // along which the parity changes an even number of times, and the check
  // says it changes exactly at the walls, each a facet (a wall listed twice
  // added two to each of its edges). When it fails, the answer is false as
  // before, only with the cells made since labelled by the failed
  // completion: a later call's check passes only on the one labelling free
  // of the order, which a flood fill gives otherwise, so the later answers
  // and labels are the same.
  if (tri.complete_labels(on_p, is_wall, walls.size(), flat, poll)) return true;
  if (scan && meter.stopped()) return false;
  if (!even_walls(walls)) return false;
  std::size_t faces = 0;
  if (!tri.flood_labels(on_p, is_wall, flat, poll, &faces)) return false;
  return faces == walls.size();
}

namespace {

/// The cell graph in a canonical order that depends only on the cells (their
/// vertex ids, which are insertion indices, and their orientation), not on
/// where CGAL's containers put them: CGAL's cell order follows the memory
/// history of the triangulation (removals with pointer-ordered sets, free
/// lists), which differs between native and wasm (32-bit pointers) even for
/// the same insertions. Within a cell the vertices are sorted, then the last
/// two swapped if that took an odd permutation (orientation kept; neighbours
/// follow their opposite vertices); cells are then sorted by that tuple, the
/// infinite vertex (kInfinite = -1) first. Beyond the paper: the flood fill of
/// interior_labels is order-independent only when every subfacet is a wall,
/// so on a stopped, non-conforming run the labels (and so the extracted tets,
/// violations and volume) were platform-dependent before this.
/// The vertex order of a cell in canonical(): `perm` takes the cell's
/// vertices to their canonical places (sorted, then the last two swapped if
/// that took an odd permutation, so the orientation is kept).
std::array<int, 4> canonical_perm(const Tet& t) {
  std::array<int, 4> perm{{0, 1, 2, 3}};
  std::sort(perm.begin(), perm.end(), [&](int a, int b) { return t[a] < t[b]; });
  int inversions = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) inversions += perm[i] > perm[j];
  if (inversions % 2) std::swap(perm[2], perm[3]);
  return perm;
}

Tet canonical_tet(const Tet& t) {
  const std::array<int, 4> perm = canonical_perm(t);
  return {{t[perm[0]], t[perm[1]], t[perm[2]], t[perm[3]]}};
}

RegularTriangulation::CellGraph canonical(const RegularTriangulation::CellGraph& g) {
  const std::size_t n = g.cells.size();
  // Each cell in its canonical vertex order with its index, sorted by the
  // vertices (no two cells have the same four vertices, so the order is
  // that of the tuples alone, whatever the sort).
  struct Entry {
    Tet t;
    int index;
  };
  std::vector<Entry> entries(n);
  for (std::size_t c = 0; c < n; ++c) entries[c] = {canonical_tet(g.cells[c]), static_cast<int>(c)};
  std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) { return a.t < b.t; });
  std::vector<int> rank(n);
  for (std::size_t i = 0; i < n; ++i) rank[entries[i].index] = static_cast<int>(i);
  RegularTriangulation::CellGraph out;
  out.cells.resize(n);
  out.neighbor.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const int c = entries[i].index;
    const std::array<int, 4> perm = canonical_perm(g.cells[c]);
    out.cells[i] = entries[i].t;
    for (int k = 0; k < 4; ++k) out.neighbor[i][k] = rank[g.neighbor[c][perm[k]]];
  }
  return out;
}

/// Beyond the paper: inside or outside of a point by the parity of the input
/// facets a ray from it along +x crosses, for the labels of a run that does
/// not conform (a stopped one), where the flood fill of interior_labels
/// leaks through the facets not yet recovered (a stopped 250-tip star prism
/// of volume 0.565 gave 22.4). A facet is crossed iff the point's (y, z)
/// lies in the facet's projection on the yz plane (even-odd over its loops)
/// and the facet's plane is ahead (x larger). Plain double arithmetic
/// (+, -, *, / only: the same on every platform); a point on or within
/// rounding of a facet may be given either side. Facets are found through a
/// uniform yz grid; `budget` counts the loop edges tested and the answer is
/// -1 once it is spent.
/// The yz grid of RayParity has at most kRayGridCells cells a side.
constexpr int kRayGridCells = 256;

class RayParity {
 public:
  RayParity(const PLC& p, int facets) : p_(p) {
    lo_ = {{std::numeric_limits<double>::max(), std::numeric_limits<double>::max()}};
    hi_ = {{-lo_[0], -lo_[1]}};
    std::vector<std::array<double, 4>> boxes;  // ylo, yhi, zlo, zhi
    for (int f = 0; f < facets; ++f) {
      const PlcFacet& F = p.facets[f];
      if (F.loops.empty() || F.normal[0] == 0) continue;  // parallel to the ray
      std::array<double, 4> b{{std::numeric_limits<double>::max(), -std::numeric_limits<double>::max(),
                               std::numeric_limits<double>::max(), -std::numeric_limits<double>::max()}};
      for (const auto& loop : F.loops)
        for (int v : loop) {
          const Point3& q = p.vertices[v];
          b = {{std::min(b[0], q[1]), std::max(b[1], q[1]), std::min(b[2], q[2]), std::max(b[3], q[2])}};
        }
      used_.push_back(f);
      boxes.push_back(b);
      lo_ = {{std::min(lo_[0], b[0]), std::min(lo_[1], b[2])}};
      hi_ = {{std::max(hi_[0], b[1]), std::max(hi_[1], b[3])}};
    }
    n_ = std::max(1, std::min(kRayGridCells, static_cast<int>(std::sqrt(double(used_.size()))) + 1));
    grid_.assign(static_cast<std::size_t>(n_) * n_, {});
    for (std::size_t i = 0; i < used_.size(); ++i) {
      const int y0 = cell(boxes[i][0], 0), y1 = cell(boxes[i][1], 0);
      const int z0 = cell(boxes[i][2], 1), z1 = cell(boxes[i][3], 1);
      for (int y = y0; y <= y1; ++y)
        for (int z = z0; z <= z1; ++z) grid_[static_cast<std::size_t>(y) * n_ + z].push_back(used_[i]);
    }
  }

  int inside(const Point3& c, long long& budget) const {
    if (used_.empty() || c[1] < lo_[0] || c[1] > hi_[0] || c[2] < lo_[1] || c[2] > hi_[1]) return 0;
    bool in = false;
    for (int f : grid_[static_cast<std::size_t>(cell(c[1], 0)) * n_ + cell(c[2], 1)]) {
      const PlcFacet& F = p_.facets[f];
      bool crossed = false;
      for (const auto& loop : F.loops) {
        budget -= static_cast<long long>(loop.size());
        for (std::size_t i = 0; i < loop.size(); ++i) {
          const Point3& a = p_.vertices[loop[i]];
          const Point3& b = p_.vertices[loop[(i + 1) % loop.size()]];
          if ((a[1] > c[1]) != (b[1] > c[1]) && c[2] < a[2] + (c[1] - a[1]) * (b[2] - a[2]) / (b[1] - a[1]))
            crossed = !crossed;
        }
      }
      if (budget < 0) return -1;
      if (!crossed) continue;
      // The plane n . (q - o) = 0 meets the ray at x = c_x + n . (o - c) / n_x.
      const Point3& o = p_.vertices[F.loops[0][0]];
      const Point3& n = F.normal;
      const double ahead = (n[0] * (o[0] - c[0]) + n[1] * (o[1] - c[1]) + n[2] * (o[2] - c[2])) / n[0];
      if (ahead > 0) in = !in;
    }
    return in ? 1 : 0;
  }

 private:
  int cell(double x, int axis) const {
    const double w = hi_[axis] - lo_[axis];
    if (!(w > 0)) return 0;
    const int k = static_cast<int>((x - lo_[axis]) / w * n_);
    return std::max(0, std::min(n_ - 1, k));
  }

  const PLC& p_;
  std::vector<int> used_;
  std::array<double, 2> lo_{}, hi_{};
  int n_ = 1;
  std::vector<std::vector<int>> grid_;
};

/// The work RayParity may do for one extraction: loop edges tested.
constexpr long long kRayParityBudget = 400'000'000;

}  // namespace

std::vector<char> Extract::labels(const RegularTriangulation::CellGraph& g, bool conforming, bool stoppable) {
  std::vector<char> inside = interior_labels(dom_, sub_, g, meter_, stoppable);
  if (stoppable && meter_.stopped()) return inside;
  if (!conforming) {
    // Beyond the paper: the walls have holes, so the flood fill's labels
    // leak; label each cell by its centroid instead (RayParity), unless that
    // costs more than kRayParityBudget edge tests (then the flood fill's
    // labels stay).
    const RayParity parity(dom_.p, dom_.input_facets);
    long long budget = kRayParityBudget;
    std::vector<char> by_ray(g.cells.size(), 0);
    bool done = true;
    for (std::size_t c = 0; c < g.cells.size() && done; ++c) {
      const Tet t = canonical_tet(g.cells[c]);
      if (std::find(t.begin(), t.end(), kInfinite) != t.end() || sub_.flat_on_facet(t)) continue;
      Point3 z{{0, 0, 0}};
      for (int v : t)
        for (int k = 0; k < 3; ++k) z[k] += tri_.point(v)[k];
      for (double& x : z) x *= 0.25;
      const int in = parity.inside(z, budget);
      if (in < 0) done = false;
      by_ray[c] = static_cast<char>(in == 1);
    }
    if (done)
      inside.swap(by_ray);
    else
      meter_.cap_reached();  // kRayParityBudget: the flood fill's labels stay
  }
  return inside;
}

std::size_t Extract::count_qmesh_slivers(RegularTriangulation::CellGraph& scan, std::vector<char>& scan_labels,
                                         bool& in_cells) {
  // The inside slivers run() would count now, without building the mesh:
  // the cells run() keeps, each measured in the vertex order run() gives it
  // (the canonical one), so that the count is run()'s.
  scan = {};
  scan_labels.clear();
  in_cells = false;
  const bool conforming = sub_.conforms();
  // run() counts a sliver where TetClassifier::shape of tet_quality's
  // measures says so (classify.cpp); the classifier's shape of the points
  // gives that answer bit for bit, computing the measures only near a
  // threshold (issue 15: the full tet_quality of every inside cell was 40%
  // of the count on anchor.off).
  const TetClassifier classifier(balls_, opt_.rho0, opt_.theta_deg);
  const auto is_sliver = [&](const Tet& cell) {
    const Tet t = canonical_tet(cell);
    const Point3 &a = tri_.point(t[0]), &b = tri_.point(t[1]), &c = tri_.point(t[2]), &d = tri_.point(t[3]);
    return classifier.shape(a, b, c, d, min_sine(a, b, c, d)) == TetClassifier::Shape::sliver;
  };
  // The labels in the cells when they do not depend on the cells' order
  // (then they are the flood fill's on any order, the ones run() takes):
  // no cell graph beside the triangulation (issue 15, the peak memory).
  if (conforming && label_cells_in_place(dom_, sub_, tri_, meter_, true)) {
    std::size_t slivers = 0;
    const bool done = tri_.visit_labelled(
        1, [&](const Tet& cell, const std::array<char, 4>&) { slivers += is_sliver(cell); },
        [&](std::size_t n) { return meter_.poll(n, false); });
    if (!done || meter_.stopped()) return 0;
    in_cells = true;
    return slivers;
  }
  if (meter_.stopped()) return 0;
  RegularTriangulation::CellGraph g = meter_.scan_cell_graph(tri_);
  if (meter_.stopped()) return 0;
  bool order_free = false;
  std::vector<char> flood = interior_labels(dom_, sub_, g, meter_, true, &order_free);
  if (meter_.stopped()) return 0;
  // The labels may depend on the order of the cells (see even_walls), or
  // come from RayParity: then take them as run() does, in canonical order.
  const bool as_is = conforming && order_free;
  const RegularTriangulation::CellGraph cg = as_is ? RegularTriangulation::CellGraph() : canonical(g);
  const std::vector<char> inside = as_is ? flood : labels(cg, conforming, true);
  if (meter_.stopped()) return 0;
  const std::vector<Tet>& cells = as_is ? g.cells : cg.cells;
  std::size_t slivers = 0;
  for (std::size_t c = 0; c < cells.size(); ++c) {
    if (!meter_.poll(1, false)) return 0;
    if (!inside[c]) continue;
    slivers += is_sliver(cells[c]);
  }
  // PUMP reads the scan's cells and labels only: the neighbours go now, so
  // that they are not held beside PUMP's label table (issue 15, the peak
  // memory: 16 bytes a cell).
  std::vector<std::array<int, 4>>().swap(g.neighbor);
  scan = std::move(g);
  scan_labels = std::move(flood);
  return slivers;
}

MeshResult Extract::run() {
  MeshResult r = mesh();
  // The quality and classes of the tets (classify.cpp).
  classify_tets(r, balls_, opt_);
  return r;
}

MeshResult Extract::mesh() {
  MeshResult r;
  r.stopped = meter_.stop_reason();
  r.conforming = sub_.conforms();
  r.protecting_balls = balls_.all();
  if (nn_.size() != verts_.size()) {
    std::vector<double> nn;
    nearest_neighbours(tri_, nn);
    nn_.swap(nn);
  }
  // The output is in canonical order (canonical() above), so that it is the
  // same on every platform: the interior cells sorted by their canonical
  // vertex tuples, each in its canonical vertex order. When the labels do
  // not depend on the order of the cells (a conforming run whose walls are a
  // mod-2 cycle: even_walls), they are kept in the cells themselves
  // (label_cells_in_place) and only the interior cells are listed, as their
  // canonical tuples (issue 15, the peak memory: the whole cell graph with
  // its labels was about 70 bytes per output tet on anchor.off, and a
  // second, canonical copy of it as much again); the same cells, the same
  // order, the same output. Otherwise (a slit, a run that does not conform)
  // the labels are taken on the canonical graph, as before.
  //
  // Each entry is a cell's canonical tuple with the sign bit of t[k] set
  // when the face opposite t[k] is a boundary face (the cell across it is
  // not inside): vertex ids are never negative in an interior cell, so the
  // entries sort by their tuples with the bits masked off, and the list then
  // becomes the result's tets in place (no second per-tet array).
  constexpr int kBit = std::numeric_limits<int>::min();
  const auto masked = [](const Tet& t) { return Tet{{t[0] & ~kBit, t[1] & ~kBit, t[2] & ~kBit, t[3] & ~kBit}}; };
  // Vertex k of t is vertex perm[k] of the cell, so the cell across t's
  // face k is the cell's neighbour perm[k].
  const auto entry = [](const Tet& cell, const std::array<char, 4>& outside) {
    const std::array<int, 4> perm = canonical_perm(cell);
    Tet t{{cell[perm[0]], cell[perm[1]], cell[perm[2]], cell[perm[3]]}};
    for (int k = 0; k < 4; ++k)
      if (outside[perm[k]]) t[k] |= kBit;
    return t;
  };
  std::vector<Tet> order;
  if (r.conforming && label_cells_in_place(dom_, sub_, tri_, meter_, false)) {
    std::size_t n = 0;
    tri_.visit_labelled(1, [&](const Tet&, const std::array<char, 4>&) { ++n; });
    order.reserve(n);
    tri_.visit_labelled(1, [&](const Tet& cell, const std::array<char, 4>& across) {
      order.push_back(entry(cell, {{across[0] != 1, across[1] != 1, across[2] != 1, across[3] != 1}}));
    });
  } else {
    RegularTriangulation::CellGraph g = canonical(tri_.cell_graph());
    const std::vector<char> inside = labels(g, r.conforming, false);
    order.reserve(static_cast<std::size_t>(std::count(inside.begin(), inside.end(), char(1))));
    for (std::size_t c = 0; c < g.cells.size(); ++c) {
      if (!inside[c]) continue;
      const std::array<int, 4>& nb = g.neighbor[c];
      order.push_back(entry(g.cells[c], {{!inside[nb[0]], !inside[nb[1]], !inside[nb[2]], !inside[nb[3]]}}));
    }
  }
  // No two cells have the same four vertices: the order is the tuples'.
  std::sort(order.begin(), order.end(), [&](const Tet& a, const Tet& b) { return masked(a) < masked(b); });

  // Which input facet each wall triangle lies in: the subfacets by their
  // sorted triangle, the last of equal ones as a map assigned in their
  // order would keep (a sorted list: a hash map took three times the memory).
  std::vector<std::pair<Tri, int>> facet_of;
  for (const Subfacet& h : sub_.subfacets())
    if (!dom_.is_box_facet(h.facet)) facet_of.push_back({sorted(h.v), h.facet});
  std::stable_sort(facet_of.begin(), facet_of.end(),
                   [](const std::pair<Tri, int>& a, const std::pair<Tri, int>& b) { return a.first < b.first; });
  const auto facet_lookup = [&](const Tri& f, int& facet) {
    const auto it = std::upper_bound(facet_of.begin(), facet_of.end(), f,
                                     [](const Tri& x, const std::pair<Tri, int>& e) { return x < e.first; });
    if (it == facet_of.begin() || std::prev(it)->first != f) return false;
    facet = std::prev(it)->second;
    return true;
  };

  // A wall triangle that is no subfacet: where cocircular points of a facet
  // make a flat tet in Del V (both diagonals of their quadrilateral are then
  // faces), the inside cell meets the flat tet at the other diagonal than
  // the facet's planar triangulation took. It lies in the one input facet
  // that holds its three vertices; -1 if there is none or more than one.
  std::vector<int> fa, fb, fc;
  auto common_facet = [&](const Tri& f) {
    sub_.facets_of(f[0], fa);
    sub_.facets_of(f[1], fb);
    sub_.facets_of(f[2], fc);
    int found = -1;
    for (int x : fa)
      if (!dom_.is_box_facet(x) && std::count(fb.begin(), fb.end(), x) && std::count(fc.begin(), fc.end(), x)) {
        if (found >= 0) return -1;
        found = x;
      }
    return found;
  };
  std::vector<int> new_id(verts_.size(), -1);
  TetMesh& mesh = r.mesh;
  bool weighted = false;
  for (std::size_t v = 0; v < verts_.size(); ++v) weighted = weighted || tri_.weight(int(v)) != 0;
  const auto is_input_vertex = [&](std::size_t v) {
    return verts_[v].on == On::vertex && verts_[v].element < dom_.input_vertices;
  };
  // The result's arrays at their exact sizes (the result outlives the
  // triangulation: no slack of a growing array at the peak): the vertices
  // are the input ones and those of the interior cells (marked -2 here, any
  // negative value is "no id yet" below), the boundary faces are the bits.
  std::size_t vertices = 0, faces = 0;
  for (const Tet& e : order)
    for (int k = 0; k < 4; ++k) {
      new_id[e[k] & ~kBit] = -2;
      faces += e[k] < 0;
    }
  for (std::size_t v = 0; v < verts_.size(); ++v) vertices += new_id[v] == -2 || is_input_vertex(v);
  mesh.vertices.reserve(vertices);
  if (weighted) mesh.weights.reserve(vertices);
  r.nearest_neighbour.reserve(vertices);
  r.input_vertex.reserve(vertices);
  mesh.boundary.reserve(faces);
  mesh.boundary_facet.reserve(faces);
  auto id = [&](int v) {
    if (new_id[v] < 0) {
      new_id[v] = static_cast<int>(mesh.vertices.size());
      mesh.vertices.push_back(tri_.point(v));
      if (weighted) mesh.weights.push_back(tri_.weight(v));
      r.nearest_neighbour.push_back(nn_[v]);
      r.input_vertex.push_back(is_input_vertex(v) ? verts_[v].element : -1);
    }
    return new_id[v];
  };
  // Input vertices first, in their order, so that vertex i of the PLC is
  // vertex i of the mesh.
  for (std::size_t v = 0; v < verts_.size(); ++v)
    if (is_input_vertex(v)) id(static_cast<int>(v));
  static const int kOutward[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  for (Tet& e : order) {
    const Tet bits = e;
    const Tet t = masked(e);
    e = {{id(t[0]), id(t[1]), id(t[2]), id(t[3])}};
    for (int k = 0; k < 4; ++k) {
      if (bits[k] >= 0) continue;  // the cell across face k is inside
      const Tri f{{t[kOutward[k][0]], t[kOutward[k][1]], t[kOutward[k][2]]}};
      mesh.boundary.push_back({{id(f[0]), id(f[1]), id(f[2])}});
      int facet = -1;
      mesh.boundary_facet.push_back(facet_lookup(sorted(f), facet) ? facet : common_facet(f));
    }
  }
  mesh.tets = std::move(order);
  return r;
}

}  // namespace wqmesh::mesher
