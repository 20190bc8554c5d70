// wqmesh: PUMP (paper, section 4.3; sliver exudation of Cheng, Dey,
// Edelsbrunner, Facello and Teng, adapted with nearest-neighbour distances).
// Each vertex of a tet with a dihedral angle of theta or less, whose weighted
// point (weight N(v)^2/9) does not encroach the two-times expansion of a
// protecting ball, gets the weight in [0, N(v)^2/9] that maximises the smallest
// dihedral angle of its incident tets inside the polyhedron, in the weighted
// Delaunay triangulation.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <unordered_set>

#include "mesher/pump.h"

#include "geometry.h"
#include "mesher/extract.h"
#include "wqmesh/quality.h"

namespace wqmesh::mesher {

namespace {

TetKey key_of(Tet t) {
  std::sort(t.begin(), t.end());
  return t;
}

// The orthosphere of the four weighted vertices of t (geometry.h).
bool orthosphere(const RegularTriangulation& tri, const Tet& t, Point3& z, double& z2) {
  const Point3 p[4] = {tri.point(t[0]), tri.point(t[1]), tri.point(t[2]), tri.point(t[3])};
  const double w[4] = {tri.weight(t[0]), tri.weight(t[1]), tri.weight(t[2]), tri.weight(t[3])};
  return geometry::orthosphere(p, w, z, z2);
}

}  // namespace

// No cell has a vertex id below kInfinite (-1): the key of an empty slot.
constexpr int kNoKey = -2;

namespace {
// Key equality by its four ints (std::array's operator== was a call to
// memcmp per probe: a fifth of PUMP on mpi.off; issue 15). Same answers.
inline bool same_key(const TetKey& a, const TetKey& b) {
  return a[0] == b[0] && a[1] == b[1] && a[2] == b[2] && a[3] == b[3];
}
}  // namespace

void CellLabels::add_table(std::size_t n) {
  // Exactly 4/3 n slots (at least 16), not the next power of two, which held
  // up to twice as many (issue 15: 17 bytes a slot of every cell).
  const std::size_t size = std::max<std::size_t>(16, (4 * n + 2) / 3);
  Table t;
  t.keys.assign(size, TetKey{{kNoKey, kNoKey, kNoKey, kNoKey}});
  t.labels.assign(size, 0);
  tables_.push_back(std::move(t));
}

void CellLabels::reset(std::size_t n) {
  tables_.clear();
  tables_.shrink_to_fit();
  used_ = 0;
  add_table(n);
}

std::size_t CellLabels::Table::slot(const TetKey& t) const {
  // The hash's high 32 bits scaled to [0, size): any size, no modulo.
  const std::uint64_t h = (std::uint64_t(TetKeyHash()(t)) * 0x9E3779B97F4A7C15ull) >> 32;
  const std::size_t size = keys.size();
  std::size_t i = static_cast<std::size_t>((h * std::uint64_t(size)) >> 32);
  while (!same_key(keys[i], t) && keys[i][0] != kNoKey)
    if (++i == size) i = 0;
  return i;
}

const char* CellLabels::find(const TetKey& t) const {
  for (const Table& table : tables_) {
    const std::size_t i = table.slot(t);
    if (same_key(table.keys[i], t)) return &table.labels[i];
  }
  return nullptr;
}

void CellLabels::set(const TetKey& t, char label) {
  for (Table& table : tables_) {
    const std::size_t i = table.slot(t);
    if (same_key(table.keys[i], t)) {
      table.labels[i] = label;
      return;
    }
  }
  if (tables_.empty() || 4 * (tables_.back().used + 1) > 3 * tables_.back().keys.size())
    add_table(std::max<std::size_t>(16, used_ / 2));
  Table& table = tables_.back();
  const std::size_t i = table.slot(t);
  table.keys[i] = t;
  table.labels[i] = label;
  ++table.used;
  ++used_;
}

void Pump::prepare() {
  // N(v), the nearest-neighbour distance in the unweighted Del V at the end
  // of REFINE; it bounds the weights and does not change when they do.
  // A scan of the whole mesh: it polls, and stops early (meter_.stopped()) when
  // the run must stop; run() then does nothing more.
  const auto poll = [&](std::size_t n) { return meter_.poll(n, false); };
  if (!mesher::nearest_neighbours(tri_, nn_, poll) || meter_.stopped()) return;
  candidates_.clear();
  if (cell_labels_) {
    // The labels in the cells (use_cell_labels) stay there: label() reads
    // and completes them in place, no table (beyond the paper, issue 15, the
    // peak memory: the table was 24 bytes a cell at PUMP's peak). The
    // candidates from the inside cells.
    cell_labels_ = false;
    in_cells_ = true;
    const bool done = tri_.visit_labelled(
        1,
        [&](const Tet& t, const std::array<char, 4>&) {
          if (std::count(t.begin(), t.end(), kInfinite)) return;
          const double a = angle_of(t);
          if (a <= theta_key_)
            for (int v : t) candidates_.push_back({a, v});
        },
        poll);
    if (!done) return;
  } else {
    prepare_from_scan();
    if (meter_.stopped()) return;
  }
  std::sort(candidates_.begin(), candidates_.end());
  const std::vector<Subfacet> subfacets = sub_.subfacets();
  walls_.clear();
  for (const Subfacet& h : subfacets)
    if (!dom_.is_box_facet(h.facet)) walls_.push_back(sorted(h.v));
  std::sort(walls_.begin(), walls_.end());
  walls_.erase(std::unique(walls_.begin(), walls_.end()), walls_.end());
  walls_.shrink_to_fit();
  vertex_facet_start_.assign(verts_.size() + 1, 0);
  for (const Subfacet& h : subfacets)
    for (int x : h.v) ++vertex_facet_start_[x + 1];
  for (std::size_t v = 0; v < verts_.size(); ++v) vertex_facet_start_[v + 1] += vertex_facet_start_[v];
  vertex_facets_.assign(vertex_facet_start_.back(), Tri{});
  std::vector<std::size_t> next(vertex_facet_start_.begin(), vertex_facet_start_.end() - 1);
  for (const Subfacet& h : subfacets) {
    const Tri s = sorted(h.v);
    for (int x : h.v) vertex_facets_[next[x]++] = s;
  }
}

void Pump::prepare_from_scan() {
  // The scan handed by use_scan (the sliver count's, of the same
  // triangulation), else one of its own.
  RegularTriangulation::CellGraph g;
  std::vector<char> inside;
  g.cells.swap(scan_.cells);
  g.neighbor.swap(scan_.neighbor);
  inside.swap(scan_labels_);
  if (g.cells.empty()) {
    g = meter_.scan_cell_graph(tri_);
    if (meter_.stopped()) return;
    inside = interior_labels(dom_, sub_, g, meter_, true);
    if (meter_.stopped()) return;
  }
  labels_.reset(g.cells.size() + g.cells.size() / kNewCellRoom);
  for (std::size_t i = 0; i < g.cells.size(); ++i) {
    if (!meter_.poll(1, false)) return;
    labels_.set(key_of(g.cells[i]), inside[i]);
  }
  // Vertices of inside tets with a dihedral angle <= theta (prepare sorts
  // them, worst first).
  for (std::size_t i = 0; i < g.cells.size(); ++i) {
    if (!meter_.poll(1, false)) return;
    if (!inside[i] || std::count(g.cells[i].begin(), g.cells[i].end(), kInfinite)) continue;
    const double a = angle_of(g.cells[i]);
    if (a <= theta_key_)
      for (int v : g.cells[i]) candidates_.push_back({a, v});
  }
}

std::vector<std::pair<double, int>> Pump::candidates() const { return candidates_; }

double Pump::weight_bound(int v) const { return nn_[v] * nn_[v] / 9; }

void Pump::run() {
  prepare();
  if (meter_.stopped()) return;
  std::vector<std::pair<double, int>> cand = candidates();
  for (int pass = 0; pass < opt_.max_pump_passes && !cand.empty(); ++pass) {
    std::sort(cand.begin(), cand.end());
    std::vector<char> seen(verts_.size(), 0);
    std::vector<std::pair<double, int>> next;
    bool improved = false;
    for (const auto& [a, v] : cand) {
      if (seen[v]) continue;
      seen[v] = 1;
      if (!meter_.tick()) return;
      if (balls_.expansion_encroached(tri_.point(v), weight_bound(v))) continue;
      const Choice c = pump_vertex(v);
      if (c.quality > c.base) improved = true;
      // Slivers left or made around v are visited in the next pass.
      std::vector<Tet> star;
      std::vector<CellRef> refs;
      tri_.incident_cells(v, star, &refs);
      for (std::size_t i = 0; i < star.size(); ++i) {
        const Tet& t = star[i];
        if (std::count(t.begin(), t.end(), kInfinite) || !label(t, refs[i])) continue;
        const double b = angle_of(t);
        if (b <= theta_key_)
          for (int x : t) next.push_back({b, x});
      }
    }
    if (!improved) break;
    cand.swap(next);
  }
  for (std::size_t v = 0; v < verts_.size(); ++v) pumped_vertices_ += tri_.weight(int(v)) > 0;
}

namespace {

// The pseudo-angle of the angle whose cosine and sine are x and y (y >= 0)
// times one positive factor: y / (x + y) for x >= 0, else
// 1 + (-x) / (y - x); in [0, 2], increasing with the angle (0 at 0 degrees,
// 1 at 90, 2 at 180), and accurate near 0 (no cancellation). x = y = 0 (a
// flat face) gives 0, as quality.cpp's angle_deg takes it.
double pseudo_angle(double x, double y) {
  if (x >= 0) return x + y > 0 ? y / (x + y) : 0;
  return 1 + (-x) / (y - x);
}

}  // namespace

double Pump::angle_key(double deg) {
  // cos and sin by their Taylor series (+, * and /: the same doubles on
  // every platform), for 0 <= deg <= 180; 30 terms are past double's
  // precision there.
  const double x = deg * (geometry::kPi / 180), x2 = x * x;
  double c = 0, s = 0, tc = 1, ts = x;
  for (int n = 0; n < 30; ++n) {
    c += tc;
    s += ts;
    tc *= -x2 / ((2 * n + 1) * (2 * n + 2));
    ts *= -x2 / ((2 * n + 2) * (2 * n + 3));
  }
  return pseudo_angle(c, std::max(0.0, s));
}

double Pump::angle_of(const Tet& t) const {
  // The dihedral angle at edge ij is the angle between n_k = e x (p_k - p_i)
  // and n_l = e x (p_l - p_i), e = p_j - p_i (quality.cpp's dihedral_deg):
  // its cosine and sine are n_k . n_l and |n_k x n_l| over |n_k| |n_l|.
  static constexpr int kEdges[6][4] = {{0, 1, 2, 3}, {0, 2, 3, 1}, {0, 3, 1, 2},
                                       {1, 2, 0, 3}, {1, 3, 2, 0}, {2, 3, 0, 1}};
  const Point3 p[4] = {tri_.point(t[0]), tri_.point(t[1]), tri_.point(t[2]), tri_.point(t[3])};
  double smallest = 2;
  for (const auto& e : kEdges) {
    const Point3 d = geometry::sub(p[e[1]], p[e[0]]);
    const Point3 nk = geometry::cross(d, geometry::sub(p[e[2]], p[e[0]]));
    const Point3 nl = geometry::cross(d, geometry::sub(p[e[3]], p[e[0]]));
    smallest = std::min(smallest, pseudo_angle(geometry::dot(nk, nl), geometry::norm(geometry::cross(nk, nl))));
  }
  return smallest;
}

bool Pump::is_wall(int a, int b, int c) const {
  return std::binary_search(walls_.begin(), walls_.end(), sorted({{a, b, c}}));
}

int Pump::known(const Tet& t, CellRef ref) const {
  if (in_cells_) {
    // 0, 1, or kExcludedOdd (outside, as the table has it) once labelled.
    const char byte = tri_.label(ref);
    return byte == RegularTriangulation::kUnlabelled ? -1 : int(byte == 1);
  }
  const char* label = labels_.find(key_of(t));
  return label ? *label : -1;
}

void Pump::learn(const Tet& t, CellRef ref, char label) {
  if (in_cells_)
    tri_.set_label(ref, label);
  else
    labels_.set(key_of(t), label);
}

char Pump::label(const Tet& t, CellRef ref) {
  // Inside (1) or outside (0). Cells made by a weight change take the label
  // of a neighbour across a facet, flipped when the facet is a wall; the
  // changed region is surrounded by cells known before.
  //
  // In the cells (in_cells_), every cell a weight change makes is new,
  // those with the vertices of a cell that was labelled before included
  // (the table kept their labels by key). They take theirs across facets
  // too, and it is the same label: PUMP labels only where every wall is a
  // facet (evaluate() checks the features around v before and after the
  // change; the labels in the cells are label_cells_in_place's, whose walls
  // are even, so the labels are the only consistent ones), where the label
  // of a cell of nonzero volume is the parity of the walls crossed by a path
  // from its interior to infinity, fixed by its four points, whatever the
  // triangulation around it (flat tets in a facet are no part of it: 0
  // below and skipped as neighbours).
  if (std::count(t.begin(), t.end(), kInfinite) || sub_.flat_on_facet(t)) return 0;
  if (const int label = known(t, ref); label >= 0) return char(label);
  struct Cell {
    Tet t;
    CellRef ref;
  };
  const auto by_key = [](const Cell& a, const Cell& b) { return key_of(a.t) < key_of(b.t); };
  const auto same = [](const Cell& a, const Cell& b) { return key_of(a.t) == key_of(b.t); };
  // At most kLabelRounds rounds, each over a deduplicated list of cells.
  std::vector<Cell> todo{{t, ref}};
  for (int round = 0; round < kLabelRounds && !todo.empty(); ++round) {
    std::sort(todo.begin(), todo.end(), by_key);
    todo.erase(std::unique(todo.begin(), todo.end(), same), todo.end());
    meter_.poll(todo.size());
    std::vector<Cell> later;
    for (const Cell& c : todo) {
      if (known(c.t, c.ref) >= 0) continue;
      bool done = false;
      for (int k = 0; k < 4 && !done; ++k) {
        const int a = c.t[(k + 1) % 4], b = c.t[(k + 2) % 4], d = c.t[(k + 3) % 4];
        if (a == kInfinite || b == kInfinite || d == kInfinite) continue;
        // The cell across facet abd (facet_cells' other cell, in O(1)).
        Cell other;
        other.ref = tri_.neighbour(c.ref, k, other.t);
        if (sub_.flat_on_facet(other.t)) continue;  // its label says nothing
        char lo;
        if (std::count(other.t.begin(), other.t.end(), kInfinite)) {
          lo = 0;
        } else {
          const int label = known(other.t, other.ref);
          if (label < 0) {
            later.push_back(other);
            continue;
          }
          lo = char(label);
        }
        learn(c.t, c.ref, is_wall(a, b, d) ? char(1 - lo) : lo);
        done = true;
      }
      if (!done) later.push_back(c);
    }
    if (known(t, ref) < 0) later.push_back({t, ref});  // retry after its neighbours
    todo.swap(later);
  }
  const int label = known(t, ref);
  if (label < 0) meter_.cap_reached();  // kLabelRounds: taken as outside
  return label >= 0 ? char(label) : 0;
}

Pump::Features Pump::features_around(int v) const {
  // The subsegments and subfacets at v and at its neighbours: a weight change
  // of v only changes its star, so only these can disappear.
  std::vector<int> ring;
  tri_.adjacent_vertices(v, ring);
  ring.push_back(v);
  Features f;
  for (int x : ring) {
    for (std::uint64_t k : sub_.subsegments_at(x)) f.segments.push_back(k);
    for (std::size_t i = vertex_facet_start_[x]; i < vertex_facet_start_[x + 1]; ++i)
      f.subfacets.push_back(vertex_facets_[i]);
  }
  std::sort(f.segments.begin(), f.segments.end());
  f.segments.erase(std::unique(f.segments.begin(), f.segments.end()), f.segments.end());
  std::sort(f.subfacets.begin(), f.subfacets.end());
  f.subfacets.erase(std::unique(f.subfacets.begin(), f.subfacets.end()), f.subfacets.end());
  return f;
}

bool Pump::present(const Features& f) const {
  for (std::uint64_t k : f.segments) {
    const Subsegment& s = sub_.subsegment(k);
    if (!tri_.is_edge(s.a, s.b)) return false;
  }
  for (const Tri& t : f.subfacets)
    if (!tri_.is_facet(t[0], t[1], t[2])) return false;
  return true;
}

double Pump::evaluate(int v, double w, const Features& f) {
  if (!tri_.set_weight(v, w)) return -1;
  // The features around v before and after the change: a star that grows
  // swallows cells whose facets join the new neighbours of v.
  if (!present(f) || !present(features_around(v))) return -1;
  std::vector<Tet> star;
  std::vector<CellRef> refs;
  tri_.incident_cells(v, star, &refs);
  meter_.poll(star.size() + f.segments.size() + f.subfacets.size());
  double worst = 2;  // the key of 180 degrees
  for (std::size_t i = 0; i < star.size(); ++i)
    if (!std::count(star[i].begin(), star[i].end(), kInfinite) && label(star[i], refs[i]))
      worst = std::min(worst, angle_of(star[i]));
  return worst;
}

double Pump::next_critical(int v, double w, double cap) const {
  // The next weight above w at which the star of v changes: a cell across a
  // facet of v's link joins the star when v's power distance to its
  // orthosphere becomes negative.
  std::vector<Tet> star;
  tri_.incident_cells(v, star);
  double next = cap;
  const Point3& pv = tri_.point(v);
  for (const Tet& t : star) {
    int i = 0;
    while (i < 4 && t[i] != v) ++i;  // at most 4
    if (i == 4)
      throw LoopBoundError("Pump::next_critical: a cell of the star of vertex " + std::to_string(v) +
                           " does not hold it");
    const int a = t[(i + 1) % 4], b = t[(i + 2) % 4], c = t[(i + 3) % 4];
    if (a == kInfinite || b == kInfinite || c == kInfinite) continue;
    Tet c1, c2;
    if (!tri_.facet_cells(a, b, c, c1, c2)) continue;
    const Tet& other = std::count(c1.begin(), c1.end(), v) ? c2 : c1;
    if (std::count(other.begin(), other.end(), kInfinite)) continue;
    Point3 z;
    double z2;
    if (!orthosphere(tri_, other, z, z2)) continue;
    const double critical = dist2(pv, z) - z2;
    if (critical > w && critical < next) next = critical;
  }
  return next;
}

Pump::Choice Pump::pump_vertex(int v) {
  const double wmax = weight_bound(v);
  const Features f = features_around(v);
  const double w0 = tri_.weight(v);
  Choice choice;
  choice.base = evaluate(v, w0, f);
  choice.quality = choice.base;
  choice.weight = w0;
  // Walk [0, wmax] from one critical weight to the next; between two of them
  // the star, hence the smallest angle, does not change: one sample each.
  double cw = 0;
  tri_.set_weight(v, cw);  // only the star at cw matters to next_critical
  // At most kCriticalSteps critical weights are visited (pump.h).
  int step = 0;
  for (; step < kCriticalSteps; ++step) {
    const double c = next_critical(v, cw, wmax);
    const double sample = 0.5 * (cw + c);
    const double q = evaluate(v, sample, f);
    if (q > choice.quality) {
      choice.quality = q;
      choice.weight = sample;
    }
    if (c >= wmax) break;
    cw = c + 1e-9 * wmax;  // just past the critical weight
    if (cw >= wmax) break;
    tri_.set_weight(v, cw);
  }
  if (step == kCriticalSteps) meter_.cap_reached();
  evaluate(v, choice.weight, f);
  return choice;
}

}  // namespace wqmesh::mesher
