// wqmesh: vertex removal by edge contraction in the improvement phase
// (beyond the paper: WQMESH never removes a vertex; after Klingner and
// Shewchuk's Stellar, whose vertex removal contracts an edge). See improve.h,
// the block "Vertex removal by edge contraction", for the contract.
//
// Why (issue 14): near a small input angle (wedge.off 0.94 degrees, wedge-1.off
// 1 degree) WQMESH refines densely, and a tet that spans the thin wedge between
// the two facets has a dihedral angle of about the input angle whatever its
// size; fewer vertices there means fewer such tets. On the models meshed at
// 1169785, every vertex of a tet under 5 degrees lies in a protecting ball,
// 90% of them are Steiner vertices of the two facets or of their edge.
//
// The protecting balls (paper, section 4.3). A contraction never adds a
// vertex, so every ball stays as empty as it was. What it could undo is the
// structure INITIALIZE builds at a sharp vertex: its vertex ball's sphere
// cuts each input edge and facet at the sharp vertex in points (the ball
// points and SOS points of section 4.1), so that the subsegments at the
// vertex end on the sphere and the ball holds only its centre. We keep that:
// a vertex on or inside a vertex ball's sphere (within 1e-9 of the radius) is
// never removed, so no subsegment or subfacet from a sharp vertex reaches
// past its ball (the ball's interior stays covered by tets at its centre
// only). The doubled diametric balls of the sharp subsegments are tied to no
// vertex: removing a Steiner vertex of a sharp edge merges two subsegments,
// whose doubled balls (kept in the statistics, where the classes read them)
// still cover the merged one; tets near the small angle keep being classified
// by the same balls, and accept()'s class guard refuses a change that would
// make more violations among its tets. Chosen so, because every vertex of a
// bad tet on wedge and wedge-1 lies in some protecting ball: a rule that kept
// every vertex inside a ball would remove none of them.
//
// When: at the end of each pass (after flips, smoothing and insertion), on
// what they left: contracting first, in the first pass, traded tets the
// other operations would have raised far (slit-1: 8.90 -> 3.94 degrees) for
// ones just better than before.
//
// Conformity stays exact: no coordinate changes, every new boundary triangle
// is made of vertices of the facet it replaces a triangle of (same label), an
// input edge loses one interior vertex and its two subsegments become one.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <algorithm>
#include <cmath>
#include <limits>

#include "cgal_types.h"
#include "geometry.h"
#include "mesher/improve.h"
#include "wqmesh/quality.h"

namespace wqmesh::mesher {

namespace {

using Tri = std::array<int, 3>;

/// A vertex this close to a vertex ball's sphere (relative to the radius)
/// counts as on it: INITIALIZE's points are computed on the sphere, rounded.
constexpr double kSphereSlack = 1e-9;

/// Orientation of triangle abc seen along axis `drop` (projected onto the
/// two other coordinates, in cyclic order): exact, by EPICK's 2D predicate.
/// Its sign is that of the triangle's normal's component `drop`.
int projected_orientation(const Point3& a, const Point3& b, const Point3& c, int drop) {
  const int i = (drop + 1) % 3, j = (drop + 2) % 3;
  using P2 = cgal::K::Point_2;
  return int(CGAL::orientation(P2(a[i], a[j]), P2(b[i], b[j]), P2(c[i], c[j])));
}

Tri with(Tri t, int v, int u) {
  for (int& x : t)
    if (x == v) x = u;
  return t;
}

bool holds(const Tri& t, int v) { return t[0] == v || t[1] == v || t[2] == v; }

/// sin(kContractCountDeg), computed once (removal() and contraction_bound()
/// computed it per call; the same value).
const double kContractCountSine = std::sin(kContractCountDeg * geometry::kPi / 180);

}  // namespace

bool Improver::on_vertex_ball(int v) const {
  if (balls_ == nullptr) return false;
  if (v >= int(ball_point_.size())) ball_point_.resize(P_.size(), -1);
  if (ball_point_[v] < 0) {
    // The vertex balls by the x of their centres (built once per set of
    // balls): only those within the largest radius of v's x can hold v.
    // The same test on fewer balls, so the same answer (fandisk: 4,512
    // balls were looked at per vertex).
    if (vertex_balls_of_ != balls_) {
      vertex_balls_of_ = balls_;
      vertex_balls_.clear();
      vertex_ball_reach_ = 0;
      for (const ProtectingBall& b : balls_->all())
        if (b.vertex_ball) {
          vertex_balls_.push_back(b);
          vertex_ball_reach_ = std::max(vertex_ball_reach_, b.radius * (1 + kSphereSlack));
        }
      std::sort(vertex_balls_.begin(), vertex_balls_.end(),
                [](const ProtectingBall& a, const ProtectingBall& b) { return a.center[0] < b.center[0]; });
      vertex_ball_reach_ *= 1 + 1e-6;  // beyond the rounding of the distance below
    }
    const double x = P_[v][0], reach = vertex_ball_reach_ + 1e-12 * std::fabs(x);  // and of x -+ reach
    auto it = std::lower_bound(vertex_balls_.begin(), vertex_balls_.end(), x - reach,
                               [](const ProtectingBall& b, double lo) { return b.center[0] < lo; });
    ball_point_[v] = 0;
    for (; it != vertex_balls_.end() && it->center[0] <= x + reach; ++it)
      if (std::sqrt(geometry::dist2(P_[v], it->center)) <= it->radius * (1 + kSphereSlack)) {
        ball_point_[v] = 1;
        break;
      }
  }
  return ball_point_[v] == 1;
}

bool Improver::pins_violation(const std::vector<std::pair<int, Tri>>& boundary, const std::vector<Tet>& fresh) const {
  if (!classifier_) return false;
  for (const auto& entry : boundary) {
    const Tri& n = entry.second;
    if (n[0] < 0) continue;  // a deletion
    const Point3 &a = P_[n[0]], &b = P_[n[1]], &c = P_[n[2]];
    // R = |ab| |bc| |ca| / (2 |ab x ac|) > rho0 l, squared (+, -, *, /
    // only: native and wasm decide alike).
    const double ab = geometry::dist2(a, b), bc = geometry::dist2(b, c), ca = geometry::dist2(c, a);
    const Point3 normal = geometry::cross(geometry::sub(b, a), geometry::sub(c, a));
    const double l2 = std::min({ab, bc, ca});
    if (!(ab * bc * ca > 4 * rho_ * rho_ * l2 * geometry::dot(normal, normal))) continue;
    for (const Tet& T : fresh) {
      int shared = 0;
      for (int x : T) shared += x == n[0] || x == n[1] || x == n[2];
      if (shared < 3) continue;
      if (!classifier_->near(P_[T[0]], P_[T[1]], P_[T[2]], P_[T[3]], {{L2_[T[0]], L2_[T[1]], L2_[T[2]], L2_[T[3]]}}))
        return true;
    }
  }
  return false;
}

bool Improver::removal(int v, Removal& r) const {
  r.v = v;
  std::vector<int>&S = r.star, &bt = r.bnd, &targets = r.targets;
  S.clear();
  bt.clear();
  targets.clear();
  if (v < 0 || v >= int(P_.size()) || removed(v)) return false;
  if (v < int(r_.input_vertex.size()) && r_.input_vertex[v] >= 0) return false;  // input vertices stay
  if (on_vertex_ball(v)) return false;
  star(v, S, &removal_outer_);
  if (S.empty() || S.size() > kContractMaxStar) return false;  // the work bound (improve.h)
  // v's boundary triangles: the faces at v of its star's tets that are one
  // (star() gives their codes in the order of the tets, then of the faces).
  const std::vector<int>& label = r_.mesh.boundary_facet;
  for (int n : removal_outer_) {
    const int b = -1 - n;
    if (b >= int(bnd_.size()) || b >= int(label.size()) || label[b] < 0) return false;  // open, or no facet
    bt.push_back(b);
  }
  if (bt.empty()) {
    if (fixed_[v]) return false;  // an open mesh's vertex
    for (int t : S)
      for (int x : tets_[t])
        if (x != v) targets.push_back(x);
  } else {
    // The boundary edges at v, each with the facets of its two triangles; a
    // feature edge (two facets) is a subsegment of an input edge.
    // The phase's time (issue 14): the ends are grouped through
    // removal_end_marks_ (end -> its index in `ends`) instead of sorted;
    // what follows depends only on each end's count and two facets (along
    // and targets are sorted below, facets here).
    std::vector<std::pair<int, int>>& ends = removal_ends_;     // (other end, facet), one per end
    std::vector<std::array<int, 2>>& more = removal_end_more_;  // per end: its count, its second facet
    ends.clear();
    more.clear();
    removal_end_marks_.reset(P_.size());
    for (int b : bt)
      for (int x : bnd_[b]) {
        if (x == v) continue;
        const int at = removal_end_marks_.get(x);
        if (at < 0) {
          removal_end_marks_.put(x, int(ends.size()));
          ends.push_back({x, label[b]});
          more.push_back({{1, -1}});
        } else {
          more[std::size_t(at)] = {{more[std::size_t(at)][0] + 1, label[b]}};
        }
      }
    std::vector<int>&along = removal_along_, &facets = removal_facets_;
    along.clear();
    facets.clear();
    for (std::size_t i = 0; i < ends.size(); ++i) {
      // A closed surface: every boundary edge at v lies on exactly two
      // boundary triangles.
      if (more[i][0] != 2) {
        targets.clear();  // contract_targets(): none
        return false;
      }
      if (ends[i].second != more[i][1]) along.push_back(ends[i].first);
      facets.push_back(ends[i].second);
      facets.push_back(more[i][1]);
      targets.push_back(ends[i].first);
    }
    std::sort(facets.begin(), facets.end());
    facets.erase(std::unique(facets.begin(), facets.end()), facets.end());
    if (along.empty() && facets.size() == 1) {
      // On one facet: onto a neighbour along a boundary edge of that facet.
    } else if (along.size() == 2 && facets.size() == 2) {
      targets = along;  // a Steiner point of an input edge: along it only
    } else {
      return false;  // a corner of the boundary that is no input vertex
    }
  }
  std::sort(targets.begin(), targets.end());
  targets.erase(std::unique(targets.begin(), targets.end()), targets.end());
  if (targets.empty()) return false;
  // Once per vertex, what no target changes: the star's vertices (marked),
  // its worst and its count below sin(kContractCountDeg), the relaxed
  // floor; per boundary triangle its facet's axis and sign later, when a
  // target asks (removal_facets()).
  contract_marks_.reset(P_.size());
  for (int t : S)
    for (int x : tets_[t]) contract_marks_.put(x, 0);
  const double below = kContractCountSine;
  r.worst_old = HUGE_VAL;
  r.bad_old = 0;
  for (int t : S) {
    r.worst_old = std::min(r.worst_old, q_[t]);
    r.bad_old += q_[t] < below;
  }
  r.floor = std::isnan(contract_floor_) ? contract_floor_ : contract_floor_sine_;
  r.coarsen = false;
  r.witness = 0;
  r.facets_known = false;
  return true;
}

void Improver::removal_facets(Removal& r) const {
  if (r.facets_known) return;
  r.facets_known = true;
  const std::vector<int>& bt = r.bnd;
  const std::vector<int>& label = r_.mesh.boundary_facet;
  r.drop.assign(bt.size(), 0);
  r.sign.assign(bt.size(), 0);
  r.old_ok.assign(bt.size(), 0);
  for (std::size_t i = 0; i < bt.size(); ++i) {
    bool done = false;  // an earlier triangle of the same facet has them
    for (std::size_t j = 0; j < i && !done; ++j)
      if (label[bt[j]] == label[bt[i]]) r.drop[i] = r.drop[j], r.sign[i] = r.sign[j], done = true;
    if (!done) {
      // The facet's direction: the area normals of v's triangles in it.
      Point3 normal{{0, 0, 0}};
      for (int o : bt)
        if (label[o] == label[bt[i]]) {
          const Tri& t = bnd_[o];
          normal = geometry::add(normal,
                                 geometry::cross(geometry::sub(P_[t[1]], P_[t[0]]), geometry::sub(P_[t[2]], P_[t[0]])));
        }
      int drop = 0;
      for (int k = 1; k < 3; ++k)
        if (std::fabs(normal[k]) > std::fabs(normal[drop])) drop = k;
      r.drop[i] = static_cast<signed char>(drop);
      r.sign[i] = normal[drop] > 0 ? 1 : -1;
    }
    const Tri& o = bnd_[bt[i]];
    r.old_ok[i] = projected_orientation(P_[o[0]], P_[o[1]], P_[o[2]], r.drop[i]) == r.sign[i];
  }
}

void Improver::set_contract_floors() {
  const MeshWorst w = mesh_worst();
  contract_floor_ = w.sine;
  contract_dihedral_ = w.dihedral_deg;
  contract_floor_sine_ = std::max(contract_floor_, std::sin(contract_dihedral_ * geometry::kPi / 180));
}

void Improver::contract_targets(int v, std::vector<int>& out) const {
  Removal r;
  removal(v, r);
  out.swap(r.targets);
}

double Improver::contraction_bound(Removal& r, int u, int& rule) const {
  const int v = r.v;
  const std::vector<int>&S = r.star, &bt = r.bnd;
  // The cheapest refusals first (each check refuses on its own, so their
  // order changes no result; the witness below only orders the scan). The
  // min-sine rule before the exact checks: the new tets' min-sines must
  // all beat the star's worst (the strict rule) or the relaxed floor, as
  // accept() will ask; from the tet that refused the last target on.
  const double below = kContractCountSine;
  bool strict = true, relaxed = !std::isnan(r.floor);
  int bad = r.bad_old, holding = 0;
  double worst = HUGE_VAL;
  // Where both rules refuse a new tet of min-sine 0, they refuse every one
  // at most 0 (beats() only grows with it): an inverted new tet's min-sine
  // need not be finished (the phase's time, issue 14; a target that passes
  // has every new tet positive, so its worst is exact).
  const bool zero_refused = !beats(0, r.worst_old) && !beats(0, r.floor);
  for (std::size_t k = 0; k < S.size(); ++k) {
    const std::size_t i = (r.witness + k) % S.size();
    Tet T = tets_[S[i]];
    if (T[0] == u || T[1] == u || T[2] == u || T[3] == u) {
      ++holding;
      continue;
    }
    for (int& x : T)
      if (x == v) x = u;
    const double m = zero_refused ? min_sine_if_positive(P_[T[0]], P_[T[1]], P_[T[2]], P_[T[3]])
                                  : min_sine(P_[T[0]], P_[T[1]], P_[T[2]], P_[T[3]]);
    strict = strict && beats(m, r.worst_old);
    relaxed = relaxed && beats(m, r.floor);
    bad -= m < below;
    worst = std::min(worst, m);
    if (!strict && !relaxed) {
      r.witness = i;
      return -HUGE_VAL;
    }
  }
  if (holding == 0 || holding == int(S.size())) return -HUGE_VAL;
  // The relaxed rule also needs fewer tets under kContractCountDeg.
  if (!strict && bad <= 0 && !r.coarsen) return -HUGE_VAL;  // not asked by coarsen()'s floor
  // The boundary: a triangle of a facet not seen with the facet's sign (a
  // fold already there) refuses every target off it.
  removal_facets(r);
  for (std::size_t i = 0; i < bt.size(); ++i)
    if (!r.old_ok[i] && !holds(bnd_[bt[i]], u)) return -HUGE_VAL;
  rule = strict ? 1 : 2;
  return worst;
}

double Improver::contraction_rest(Removal& r, int u, int rule, std::vector<Tet>& fresh,
                                  std::vector<std::pair<int, Tri>>& boundary) const {
  const int v = r.v;
  const std::vector<int>&S = r.star, &bt = r.bnd;
  fresh.clear();
  boundary.clear();
  removal_facets(r);  // (contraction_bound() filled them)
  // The link condition: a vertex adjacent to both v and u is a vertex of a
  // tet holding edge vu (else the contraction would double an edge). The
  // star's vertices are marked (removal()); those of the tets at vu get u + 1.
  for (int t : S) {
    if (has(t, u)) {
      for (int x : tets_[t]) contract_marks_.put(x, u + 1);
      continue;
    }
    Tet T = tets_[t];
    for (int& x : T)
      if (x == v) x = u;
    fresh.push_back(T);
  }
  std::vector<int>& SU = contract_star_u_;
  star(u, SU);
  for (int t : SU)
    for (int x : tets_[t]) {
      const int mark = contract_marks_.get(x);
      if (mark >= 0 && mark != u + 1) return -HUGE_VAL;
    }
  // The boundary: triangles at edge vu go, the others get u for v; in each
  // facet the fan must not fold (every triangle, old and new, seen along the
  // facet's dominant axis with the same exact orientation) and no new
  // triangle may be degenerate (three exactly collinear vertices).
  for (std::size_t i = 0; i < bt.size(); ++i) {
    const int b = bt[i];
    if (holds(bnd_[b], u)) {
      boundary.push_back({b, {{-1, -1, -1}}});
      continue;
    }
    const Tri n = with(bnd_[b], v, u);
    const Point3 &a = P_[n[0]], &c = P_[n[1]], &d = P_[n[2]];
    if (CGAL::collinear(cgal::to_cgal(a), cgal::to_cgal(c), cgal::to_cgal(d))) return -HUGE_VAL;
    if (projected_orientation(a, c, d, r.drop[i]) != r.sign[i]) return -HUGE_VAL;
    boundary.push_back({b, n});
  }
  // Beyond the paper (issue 14): no new boundary triangle may pin a
  // violation (improve.h, pins_violation).
  if (pins_violation(boundary, fresh)) return -HUGE_VAL;
  // The strict rule by the star's worst; the relaxed one (in a pass only):
  // fewer tets under the target in the star, and every new tet better than
  // the worst tet of the whole mesh. The floor in min-sine and in the
  // smallest dihedral angle: a new tet whose min-sine beats sin(D) has its
  // smallest dihedral above D. Where the strict rule holds, only it is
  // asked: accept()'s other guards do not depend on the floor, so where
  // they refuse the strict change they refuse the relaxed one too.
  double worst = -HUGE_VAL;
  if (rule == 1) return accept(S, fresh, worst) ? worst : -HUGE_VAL;
  return accept(S, fresh, worst, r.floor) ? worst : -HUGE_VAL;
}

double Improver::contraction(Removal& r, int u, std::vector<Tet>& fresh,
                             std::vector<std::pair<int, Tri>>& boundary) const {
  int rule = 0;  // contraction_rest() clears fresh and boundary
  if (contraction_bound(r, u, rule) == -HUGE_VAL) return -HUGE_VAL;
  return contraction_rest(r, u, rule, fresh, boundary);
}

bool Improver::apply_contraction(const Removal& r, const std::vector<Tet>& fresh,
                                 const std::vector<std::pair<int, Tri>>& boundary) {
  const int v = r.v;
  // Whether the star holds the mesh's worst tet (then the floors may rise).
  bool floor_tet = false;
  if (!std::isnan(contract_floor_)) {
    const double sine = sine_above(contract_dihedral_);  // the phase's time: dihedral(t) only where q_[t] cannot tell
    for (int t : r.star)
      floor_tet = floor_tet || q_[t] <= contract_floor_ || (q_[t] <= sine && dihedral(t) <= contract_dihedral_);
  }
  // Called right after contraction_rest()'s accept() of this change returned
  // true (contract_vertex(), contract()): its class guard's L_v are taken.
  if (!replace(r.star, fresh, boundary, v, true)) return false;
  if (floor_tet) set_contract_floors();
  if (v >= int(removed_.size())) removed_.resize(P_.size(), 0);
  removed_[v] = 1;
  fixed_[v] = 1;
  vtet_[v] = -1;
  ++st_.contractions;
  return true;
}

bool Improver::contract(int v, int u) {
  Removal r;
  if (!removal(v, r) || !std::binary_search(r.targets.begin(), r.targets.end(), u)) return false;
  std::vector<Tet> fresh;
  std::vector<std::pair<int, Tri>> boundary;
  if (contraction(r, u, fresh, boundary) == -HUGE_VAL) return false;
  return apply_contraction(r, fresh, boundary);
}

bool Improver::contract_vertex(int v, double floor_sine) {
  Removal& r = contract_removal_;
  if (!removal(v, r)) return false;
  if (!std::isnan(floor_sine)) {
    // coarsen()'s floor (improve_coarsen.cpp): the star may get worse, not
    // below min(its worst, floor_sine).
    r.floor = std::min(r.worst_old, floor_sine);
    r.coarsen = true;
  }
  // The best accepted target: the largest worst min-sine of the new tets,
  // the first in target order among equals. The phase's time (issue 14):
  // the min-sine rule's bound of every target first (contraction_bound:
  // the worst that accept() computes, bit for bit, for a target it accepts),
  // then the other checks on the targets from the largest bound down, the
  // first accepted being the best; no check's outcome depends on which
  // targets were judged before (each was judged in turn to the end).
  std::vector<ContractCandidate>& candidates = contract_candidates_;
  candidates.clear();
  for (std::size_t i = 0; i < r.targets.size(); ++i) {
    int rule = 0;
    const double w = contraction_bound(r, r.targets[i], rule);
    if (w != -HUGE_VAL) candidates.push_back({w, r.targets[i], rule});
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const ContractCandidate& a, const ContractCandidate& b) { return a.worst > b.worst; });
  std::vector<Tet>& fresh = contract_fresh_;
  std::vector<std::pair<int, Tri>>& boundary = contract_boundary_;
  for (const ContractCandidate& c : candidates)
    if (contraction_rest(r, c.u, c.rule, fresh, boundary) != -HUGE_VAL) return apply_contraction(r, fresh, boundary);
  return false;
}

std::size_t Improver::contract_pass() {
  const double below = std::sin(kContractBelowDeg * geometry::kPi / 180);
  std::size_t n = 0;
  // The relaxed rule from the second pass on: in the first, the mesh's
  // worst is still that of PUMP's output, so tets the other operations would
  // raise far above it could be traded for ones just above it.
  if (kContractRelaxed && ++contract_passes_ > 1) set_contract_floors();
  std::vector<int> list;
  for (std::size_t t = 0; t < tets_.size(); ++t)
    if (alive(int(t)) && q_[t] < below) list.push_back(int(t));
  // The order of a stable sort by q_ (the list's tets are in increasing
  // order and their q_ below `below`, so none is NaN): ties by index.
  std::sort(list.begin(), list.end(), [&](int a, int b) { return q_[a] < q_[b] || (q_[a] == q_[b] && a < b); });
  for (int t : list) {
    if (!poll()) break;
    if (!alive(t) || !(q_[t] < below)) continue;
    const Tet T = tets_[t];
    for (int v : T) {
      // Retried only after a change touched v's star.
      if (v >= int(contract_tried_.size())) contract_tried_.resize(P_.size(), -1);
      if (contract_tried_[v] >= 0 && v < int(vtime_.size()) && vtime_[v] <= contract_tried_[v]) continue;
      if (contract_vertex(v)) {
        ++n;
        break;  // t is gone
      }
      contract_tried_[v] = clock_;
    }
  }
  contract_floor_ = std::numeric_limits<double>::quiet_NaN();
  return n;
}

void Improver::drop_removed() {
  if (st_.contractions == 0) return;
  TetMesh& m = r_.mesh;
  std::vector<int> id(P_.size(), -1);
  int n = 0;
  for (std::size_t v = 0; v < P_.size(); ++v)
    if (!removed(int(v))) {
      id[v] = n;
      P_[n] = P_[v];
      if (v < m.weights.size()) m.weights[n] = m.weights[v];
      if (v < r_.nearest_neighbour.size()) r_.nearest_neighbour[n] = r_.nearest_neighbour[v];
      if (v < r_.input_vertex.size()) r_.input_vertex[n] = r_.input_vertex[v];
      ++n;
    }
  P_.resize(n);
  if (m.weights.size() > std::size_t(n)) m.weights.resize(n);
  if (r_.nearest_neighbour.size() > std::size_t(n)) r_.nearest_neighbour.resize(n);
  if (r_.input_vertex.size() > std::size_t(n)) r_.input_vertex.resize(n);
  for (auto& T : m.tets)
    for (int& x : T) x = id[x];
  std::size_t kept = 0;
  for (std::size_t b = 0; b < m.boundary.size(); ++b) {
    if (m.boundary[b][0] < 0) continue;  // deleted by a contraction
    Tri t = m.boundary[b];
    for (int& x : t) x = id[x];
    m.boundary[kept] = t;
    if (b < m.boundary_facet.size()) m.boundary_facet[kept] = m.boundary_facet[b];
    ++kept;
  }
  m.boundary.resize(kept);
  if (m.boundary_facet.size() > kept) m.boundary_facet.resize(kept);
}

}  // namespace wqmesh::mesher
