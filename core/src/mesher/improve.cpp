// wqmesh: the improvement phase after PUMP (beyond the paper; see improve.h
// for the contract and Klingner and Shewchuk's Stellar for the operations).
// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesher/improve.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include "cgal_types.h"
#include "geometry.h"
#include "mesher/classify.h"
#include "wqmesh/quality.h"

namespace wqmesh::mesher {

using geometry::cross;
using geometry::dot;
using geometry::norm;
using geometry::sub;

namespace {

// The faces of a positively oriented tet (v0, v1, v2, v3), outward: face k
// is opposite vertex k.
constexpr int kOutward[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
// The edges of a tet and, for edge e, the two other vertices.
constexpr int kEdge[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};

using Tri = std::array<int, 3>;

/// The rotation of an oriented triangle that starts at its smallest vertex
/// (same orientation, canonical).
Tri rotated(const Tri& f) {
  const int m = f[0] < f[1] ? (f[0] < f[2] ? 0 : 2) : (f[1] < f[2] ? 1 : 2);
  return {{f[m], f[(m + 1) % 3], f[(m + 2) % 3]}};
}
Tri reversed(const Tri& f) { return rotated({{f[0], f[2], f[1]}}); }

/// The squared length of the shortest edge of tet T at its vertex T[i].
double shortest_edge2_at(const std::vector<Point3>& P, const std::array<int, 4>& T, int i) {
  double m = HUGE_VAL;
  for (int j = 0; j < 4; ++j)
    if (j != i) m = std::min(m, geometry::dist2(P[T[i]], P[T[j]]));
  return m;
}

Tri outward_face(const std::array<int, 4>& t, int k) {
  return rotated({{t[kOutward[k][0]], t[kOutward[k][1]], t[kOutward[k][2]]}});
}

bool positive(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  return CGAL::orientation(cgal::to_cgal(a), cgal::to_cgal(b), cgal::to_cgal(c), cgal::to_cgal(d)) == CGAL::POSITIVE;
}

/// R/l and R of tet abcd (infinite when it is flat).
void radius_edge(const Point3& a, const Point3& b, const Point3& c, const Point3& d, double& rl, double& R) {
  double r2;
  geometry::circumcenter(a, b, c, d, r2);
  const double l2 = std::min({geometry::dist2(a, b), geometry::dist2(a, c), geometry::dist2(a, d),
                              geometry::dist2(b, c), geometry::dist2(b, d), geometry::dist2(c, d)});
  R = std::sqrt(r2);
  rl = l2 > 0 ? std::sqrt(r2 / l2) : HUGE_VAL;
}

}  // namespace

namespace {

/// min_sine()'s arithmetic; with kStopInverted, a determinant at most 0
/// returns 0 (min_sine_if_positive()).
template <bool kStopInverted>
double min_sine_of(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  const Point3 u = sub(b, a), v = sub(c, a), w = sub(d, a), x = sub(c, b), y = sub(d, b), z = sub(d, c);
  const Point3 m1 = cross(v, w);
  const double D = dot(u, m1);  // 6 V
  if (kStopInverted && D <= 0) return 0;
  // Squared area normals; one square root at the end.
  const double n0 = dot(cross(x, y), cross(x, y)), n1 = dot(m1, m1), n2 = dot(cross(u, w), cross(u, w)),
               n3 = dot(cross(u, v), cross(u, v));
  const double p23 = n2 * n3, p13 = n1 * n3, p12 = n1 * n2, p03 = n0 * n3, p02 = n0 * n2, p01 = n0 * n1;
  if (!(p23 > 0 && p13 > 0 && p12 > 0 && p03 > 0 && p02 > 0 && p01 > 0)) return D < 0 ? -1 : 0;
  // Edge ij lies on the faces opposite the two other vertices k and l.
  const double s2 =
      std::min({dot(u, u) / p23, dot(v, v) / p13, dot(w, w) / p12, dot(x, x) / p03, dot(y, y) / p02, dot(z, z) / p01});
  return D * std::sqrt(s2);
}

}  // namespace

double min_sine(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  return min_sine_of<false>(a, b, c, d);
}

double min_sine_if_positive(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  return min_sine_of<true>(a, b, c, d);
}

Improver::Improver(MeshResult& r, double rho, double max_size, const std::function<bool()>& keep_going)
    : r_(r), rho_(rho), max_size_(max_size), keep_going_(keep_going), P_(r.mesh.vertices) {
  const TetMesh& m = r.mesh;
  tets_ = m.tets;
  initial_tets_ = tets_.size();
  q_.resize(tets_.size());
  for (std::size_t t = 0; t < tets_.size(); ++t) {
    const Tet& T = tets_[t];
    q_[t] = min_sine(P_[T[0]], P_[T[1]], P_[T[2]], P_[T[3]]);
  }
  bnd_ = m.boundary;
  tried_.assign(tets_.size(), -1);
  insert_tried_.assign(tets_.size(), -1);
  vtime_.assign(P_.size(), 0);
  smoothed_.assign(P_.size(), -1);
  vtet_.assign(P_.size(), -1);
  fixed_.assign(P_.size(), 0);
  for (const auto& b : bnd_)
    for (int v : b) fixed_[v] = 1;
  for (std::size_t v = 0; v < P_.size() && v < r.input_vertex.size(); ++v)
    if (r.input_vertex[v] >= 0) fixed_[v] = 1;
  // Face adjacency: each oriented face meets its reverse in the neighbour.
  // Face i is face k of tet t for i = 4 t + k, boundary triangle b for i =
  // 4 T + b (T tets); its key is its vertices sorted (unoriented).
  const std::size_t tet_faces = 4 * tets_.size(), nfaces = tet_faces + bnd_.size();
  const auto face_key = [&](std::size_t i) {
    Tri f = i < tet_faces ? Tri{{tets_[i / 4][kOutward[i % 4][0]], tets_[i / 4][kOutward[i % 4][1]],
                                 tets_[i / 4][kOutward[i % 4][2]]}}
                          : bnd_[i - tet_faces];
    std::sort(f.begin(), f.end());
    return f;
  };
  for (std::size_t t = 0; t < tets_.size(); ++t)
    for (int k = 0; k < 4; ++k) vtet_[tets_[t][k]] = int(t);
  // The faces in the order of a stable sort by key. The phase's time (issue
  // 14; the same order): below 2^21 vertices a sorted face packs into 63
  // bits, and (packed key, index) pairs sort to that order at once; the keys
  // are made from the tets as they are packed (no array of faces).
  const bool packed = P_.size() < (std::size_t(1) << 21);
  std::vector<std::pair<std::uint64_t, int>> order(nfaces);
  std::vector<Tri> keys;  // above 2^21 vertices: the keys, sorted stably
  if (packed) {
    for (std::size_t i = 0; i < nfaces; ++i) {
      const Tri f = face_key(i);
      order[i] = {std::uint64_t(f[0]) << 42 | std::uint64_t(f[1]) << 21 | std::uint64_t(f[2]), int(i)};
    }
    std::sort(order.begin(), order.end());
  } else {
    keys.resize(nfaces);
    for (std::size_t i = 0; i < nfaces; ++i) keys[i] = face_key(i), order[i] = {0, int(i)};
    std::stable_sort(order.begin(), order.end(),
                     [&keys](const std::pair<std::uint64_t, int>& a, const std::pair<std::uint64_t, int>& b) {
                       return keys[std::size_t(a.second)] < keys[std::size_t(b.second)];
                     });
  }
  // The tet of face i (its slot: i % 4), or -1 - b for boundary triangle b.
  const auto face_tet = [&](int i) {
    return std::size_t(i) < tet_faces ? i / 4 : -1 - int(std::size_t(i) - tet_faces);
  };
  // A face with neither a neighbour nor a boundary triangle (a mesh that is
  // not closed) gets the code -1 - bnd_.size(), which names no triangle: it
  // is never flipped and its vertices never move.
  const int kOpen = -1 - int(bnd_.size());
  nb_.assign(tets_.size(), {{kOpen, kOpen, kOpen, kOpen}});
  for (std::size_t i = 0; i + 1 < nfaces; ++i) {
    const int a = order[i].second, b = order[i + 1].second;
    if (packed ? order[i].first != order[i + 1].first : keys[std::size_t(a)] != keys[std::size_t(b)]) continue;
    const int ta = face_tet(a), tb = face_tet(b);
    if (ta >= 0) nb_[ta][a % 4] = tb;
    if (tb >= 0) nb_[tb][b % 4] = ta;
    ++i;
  }
  for (std::size_t t = 0; t < tets_.size(); ++t)
    for (int k = 0; k < 4; ++k)
      if (nb_[t][k] == kOpen)
        for (int j = 0; j < 3; ++j) fixed_[tets_[t][kOutward[k][j]]] = 1;
  init_slides();
}

void Improver::set_classes(const ProtectingBalls* balls, double theta_deg) {
  balls_ = balls;
  classifier_.reset();
  L2_.clear();
  shape_.clear();
  bad_at_.clear();
  if (balls == nullptr) return;
  classifier_ = std::make_unique<TetClassifier>(*balls, rho_, theta_deg);
  L2_.assign(P_.size(), HUGE_VAL);
  bad_at_.assign(P_.size(), 0);
  l2_at_.assign(P_.size(), 0);
  class_.clear();
  class_at_.clear();
  shape_.assign(tets_.size(), TetClassifier::Shape::good);
  std::vector<int> live;
  for (std::size_t t = 0; t < tets_.size(); ++t)
    if (alive(int(t))) live.push_back(int(t));
  learn(live);
}

void Improver::touch(const Tet& T) {
  for (int v : T) {
    if (v >= int(vtime_.size())) vtime_.resize(v + 1, 0), smoothed_.resize(v + 1, -1);
    vtime_[v] = clock_;
  }
}

bool Improver::fresh_since(std::int64_t at, const Tet& T) const {
  if (at < 0) return true;
  for (int v : T)
    if (v >= int(vtime_.size()) || vtime_[v] > at) return true;
  return false;
}

bool Improver::poll() {
  if (cancelled_) return false;
  if (keep_going_ && !keep_going_()) cancelled_ = true;
  return !cancelled_;
}

bool Improver::has(int t, int v) const {
  const Tet& T = tets_[t];
  return T[0] == v || T[1] == v || T[2] == v || T[3] == v;
}

int Improver::slot(int t, int v) const {
  const Tet& T = tets_[t];
  for (int k = 0; k < 4; ++k)
    if (T[k] == v) return k;
  return -1;
}

double Improver::worst() const {
  double w = HUGE_VAL;
  for (std::size_t t = 0; t < tets_.size(); ++t)
    if (alive(int(t))) w = std::min(w, q_[t]);
  return w;
}

void Improver::star(int v, std::vector<int>& out, std::vector<int>* outer) const {
  out.clear();
  if (outer) outer->clear();
  const int s = v < int(vtet_.size()) ? vtet_[v] : -1;
  if (s < 0 || !alive(s) || !has(s, v)) return;
  star_marks_.reset(tets_.size());
  star_marks_.put(s);
  out.push_back(s);
  for (std::size_t i = 0; i < out.size(); ++i) {
    const int t = out[i];
    for (int k = 0; k < 4; ++k) {
      if (tets_[t][k] == v) continue;  // the face opposite v does not hold v
      const int n = nb_[t][k];
      if (n >= 0 && !star_marks_.has(n)) {
        star_marks_.put(n);
        out.push_back(n);
      } else if (n < 0 && outer) {
        outer->push_back(n);
      }
    }
  }
}

bool Improver::ring(int t, int a, int b, std::vector<int>& ts, std::vector<int>& vs) const {
  // The tets around edge ab in order, with ring vertices r_i such that
  // (a, b, r_i, r_i+1) is positive; false when the ring meets the boundary
  // or is longer than kMaxRing.
  const int i = slot(t, a), j = slot(t, b);
  int k = -1, l = -1;
  for (int s = 0; s < 4; ++s)
    if (s != i && s != j) (k < 0 ? k : l) = s;
  // (a, b, c, d) is an even permutation of t's order iff (i, j, k, l) is.
  int perm[4] = {i, j, k, l}, inv = 0;
  for (int x = 0; x < 4; ++x)
    for (int y = x + 1; y < 4; ++y) inv += perm[x] > perm[y];
  int c = tets_[t][k], d = tets_[t][l];
  if (inv % 2) std::swap(c, d);
  ts.assign(1, t);
  vs.assign({c, d});
  int cur = t, prev = c, last = d;
  for (;;) {
    const int n = nb_[cur][slot(cur, prev)];
    if (n < 0) return false;
    if (n == t) break;
    int e = -1;
    for (int s = 0; s < 4; ++s) {
      const int v = tets_[n][s];
      if (v != a && v != b && v != last) e = v;
    }
    ts.push_back(n);
    vs.push_back(e);
    if (int(ts.size()) > kMaxRing) return false;
    prev = last;
    last = e;
    cur = n;
  }
  vs.pop_back();  // the last one is c again
  return vs.size() == ts.size();
}

TetClass Improver::tet_class(int t) const {
  if (!classifier_ || !alive(t)) return TetClass::good;
  const Tet& T = tets_[t];
  if (class_.size() < tets_.size()) class_.resize(tets_.size(), -1), class_at_.resize(tets_.size(), 0);
  const std::int64_t at = class_at_[t];
  if (class_[t] >= 0 && l2_at_[T[0]] <= at && l2_at_[T[1]] <= at && l2_at_[T[2]] <= at && l2_at_[T[3]] <= at) {
    return TetClass(class_[t]);
  }
  const TetClass c = classifier_->classify(shape_[t], P_[T[0]], P_[T[1]], P_[T[2]], P_[T[3]],
                                           {{L2_[T[0]], L2_[T[1]], L2_[T[2]], L2_[T[3]]}});
  class_[t] = static_cast<signed char>(c);
  class_at_[t] = l2_clock_;
  return c;
}

double Improver::shortest_at(int v, const std::vector<int>& skip) const {
  std::vector<int>& S = shortest_star_;
  star(v, S);
  set_marks_.reset(tets_.size());
  for (int t : skip) set_marks_.put(t);
  double l2 = HUGE_VAL;
  for (int t : S)
    if (!set_marks_.has(t))
      for (int u : tets_[t])
        if (u != v) l2 = std::min(l2, geometry::dist2(P_[u], P_[v]));
  return l2;
}

void Improver::forget(const std::vector<int>& ids) {
  if (!classifier_) return;
  forgot_marks_.reset(P_.size());
  forgot_l2_.clear();
  forgot_ = true;
  for (int t : ids) {
    const Tet& T = tets_[t];
    if (shape_[t] != TetClassifier::Shape::good)
      for (int v : T) --bad_at_[v];
    for (int i = 0; i < 4; ++i) {
      const double m = shortest_edge2_at(P_, T, i);
      const int at = forgot_marks_.get(T[i]);
      if (at < 0) {
        forgot_marks_.put(T[i], int(forgot_l2_.size()));
        forgot_l2_.push_back(m);
      } else {
        forgot_l2_[at] = std::min(forgot_l2_[at], m);
      }
    }
  }
}

void Improver::learn(const std::vector<int>& ids, int moved, const Point3& from, bool judged) {
  if (!classifier_) return;
  if (shape_.size() < tets_.size()) shape_.resize(tets_.size(), TetClassifier::Shape::good);
  if (L2_.size() < P_.size())
    L2_.resize(P_.size(), HUGE_VAL), bad_at_.resize(P_.size(), 0), l2_at_.resize(P_.size(), 0);
  // The vertices of ids in the order met (learn_marks_: v -> its index;
  // the phase's time, issue 14: they were sorted, and searched below; each
  // vertex's L_v is its own, so their order changes no value).
  std::vector<int>& verts = learn_verts_;
  verts.clear();
  learn_marks_.reset(P_.size());
  for (int t : ids) {
    const Tet& T = tets_[t];
    shape_[t] = classifier_->shape(P_[T[0]], P_[T[1]], P_[T[2]], P_[T[3]], q_[t]);
    if (t < int(class_.size())) class_[t] = -1;  // its shape or points changed
    for (int v : T) {
      bad_at_[v] += shape_[t] != TetClassifier::Shape::good;
      if (!learn_marks_.has(v)) {
        learn_marks_.put(v, int(verts.size()));
        verts.push_back(v);
      }
    }
  }
  const bool forgot = forgot_;
  forgot_ = false;
  if (moved < 0) {
    if (!forgot) {
      for (int v : verts) set_l2(v, shortest_at(v));
      return;
    }
    // After replace() of a change its accept() just judged: classes_change()
    // computed L_v after it for every vertex of the new tets (after_, found
    // through vert_marks_), by the rules below and one more (when L_v is an
    // old edge's, v's edges outside `old` are at least L_v: a new edge at
    // most L_v is L_v after); each is the minimum over v's new star, as
    // shortest_at() gives it (the phase's time, issue 14: the star walks of
    // the vertices whose L_v was an old edge's).
    if (judged && std::all_of(verts.begin(), verts.end(), [&](int v) { return vert_marks_.has(v); })) {
      for (int v : verts) {
        set_l2(v, after_[std::size_t(vert_marks_.get(v))].second);
      }
      return;
    }
    // After replace() (forget(old), then learn(new); improve.h, "The
    // phase's time on large meshes"): v's shortest edge on the new tets.
    std::vector<double>& fresh = learn_fresh_;
    fresh.assign(verts.size(), HUGE_VAL);
    for (int t : ids) {
      const Tet& T = tets_[t];
      for (int i = 0; i < 4; ++i) {
        double& m = fresh[std::size_t(learn_marks_.get(T[i]))];
        m = std::min(m, shortest_edge2_at(P_, T, i));
      }
    }
    for (std::size_t i = 0; i < verts.size(); ++i) {
      const int v = verts[i], at = forgot_marks_.get(v);
      if (at >= 0 && L2_[v] < forgot_l2_[at])
        set_l2(v, std::min(L2_[v], fresh[i]));  // its shortest edge lies outside the old tets: it stays
      else
        set_l2(v, shortest_at(v));
    }
    return;
  }
  // Only `moved` changed place (ids is its star): an edge at u != moved
  // other than (u, moved) is as it was, so when L_u was shorter than the old
  // (u, moved) it is another edge's and stays unless the new (u, moved) is
  // shorter; else u's star is read again. The same values as shortest_at().
  for (int u : verts) {
    if (u == moved) continue;
    const double was = geometry::dist2(from, P_[u]);
    set_l2(u, L2_[u] < was ? std::min(L2_[u], geometry::dist2(P_[moved], P_[u])) : shortest_at(u));
  }
  double l2 = HUGE_VAL;
  for (int t : ids)
    for (int u : tets_[t])
      if (u != moved) l2 = std::min(l2, geometry::dist2(P_[u], P_[moved]));
  set_l2(moved, l2);
}

void Improver::classes_before(const std::vector<int>& old, ClassesBefore& b) const {
  b.violations = 0;
  b.verts.clear();
  b.bad_used = 0;
  b.slot.reset(P_.size());
  if (!classifier_) {
    b.inside.clear(), b.bad_inside.clear(), b.outside.clear(), b.outside_known.clear(), b.bad_list.clear();
    return;
  }
  // The phase's time (issue 14): the vertices in the order met, found
  // through b.slot (they were sorted and searched; no value depends on
  // their order).
  for (int t : old)
    for (int v : tets_[t])
      if (!b.slot.has(v)) {
        b.slot.put(v, int(b.verts.size()));
        b.verts.push_back(v);
      }
  const std::size_t n = b.verts.size();
  b.inside.assign(n, HUGE_VAL);
  b.bad_inside.assign(n, 0);
  b.outside.assign(n, HUGE_VAL);
  b.outside_known.assign(n, 0);
  b.bad_list.assign(n, -1);
  // Each vertex's minimum over old's tets in the order of old (as the
  // linear list of before did: the same values).
  for (int t : old) {
    b.violations += tet_class(t) == TetClass::violation;
    const Tet& T = tets_[t];
    const bool bad = shape_[t] != TetClassifier::Shape::good;
    for (int i = 0; i < 4; ++i) {
      const int at = b.index(T[i]);
      b.inside[at] = std::min(b.inside[at], shortest_edge2_at(P_, T, i));
      b.bad_inside[at] += bad;
    }
  }
}

int Improver::classes_change(const std::vector<int>& old, const ClassesBefore& before, const std::vector<Tet>& fresh,
                             const std::vector<double>* fresh_q) const {
  if (!classifier_) return 0;
  const auto cur = [&](int v) { return v < int(L2_.size()) ? L2_[v] : HUGE_VAL; };
  // L_v^2 after the change at each vertex of the new tets: the shorter of
  // its new edges and of its edges outside `old` (those stay). When its L_v
  // now is shorter than every old edge at it, that edge lies outside `old`.
  std::vector<std::pair<int, double>>& after = after_;  // (v, L_v^2 after)
  after.clear();
  vert_marks_.reset(P_.size());  // v -> its index in after
  for (const Tet& T : fresh)
    for (int i = 0; i < 4; ++i) {
      const double m = shortest_edge2_at(P_, T, i);
      const int at = vert_marks_.get(T[i]);
      if (at < 0) {
        vert_marks_.put(T[i], int(after.size()));
        after.push_back({T[i], m});
      } else {
        after[at].second = std::min(after[at].second, m);
      }
    }
  std::vector<std::pair<int, int>>& changed = changed_;  // vertices whose L_v changes, with their index in before
  changed.clear();
  for (auto& [v, l2] : after) {
    const int at = before.index(v);
    const double inside = at < 0 ? HUGE_VAL : before.inside[at];
    double outside = cur(v);
    // When L_v now is not shorter than every old edge at v, it is an old
    // edge's (L_v = min(inside, outside) at the points `before` was taken
    // at, and the edges outside `old` do not move), so v's edges outside
    // `old` are at least L_v: when its shortest new edge is at most L_v, that
    // is L_v after, and v's star need not be read (the same value).
    if (!(outside < inside) && !(l2 <= outside)) {
      if (at >= 0 && before.outside_known[at]) {
        outside = before.outside[at];
      } else {
        outside = shortest_at(v, old);
        if (at >= 0) before.outside[at] = outside, before.outside_known[at] = 1;
      }
    }
    l2 = std::min(l2, outside);
    if (l2 != cur(v)) changed.push_back({v, at});
  }
  const auto l2_after = [&](int v) {
    const int at = v < int(P_.size()) ? vert_marks_.get(v) : -1;
    return at < 0 ? cur(v) : after[at].second;
  };
  int violations = 0;
  for (std::size_t i = 0; i < fresh.size(); ++i) {
    const Tet& T = fresh[i];
    const double q = fresh_q ? (*fresh_q)[i] : min_sine(P_[T[0]], P_[T[1]], P_[T[2]], P_[T[3]]);
    Point3 center;  // the shape's circumcenter, for near()
    const TetClassifier::Shape sh = classifier_->shape(P_[T[0]], P_[T[1]], P_[T[2]], P_[T[3]], q, center);
    if (sh == TetClassifier::Shape::good) continue;
    violations += classifier_->classify(sh, P_[T[0]], P_[T[1]], P_[T[2]], P_[T[3]],
                                        {{l2_after(T[0]), l2_after(T[1]), l2_after(T[2]), l2_after(T[3])}},
                                        &center) == TetClass::violation;
  }
  // The tets outside `old` of a bad shape at a vertex whose L_v changes.
  int allowed = before.violations;
  set_marks_.reset(tets_.size());
  for (int t : old) set_marks_.put(t, 1);
  for (const auto& [v, at] : changed) {
    const int bad_inside = at < 0 ? 0 : before.bad_inside[at];
    if (v >= int(bad_at_.size()) || bad_at_[v] - bad_inside <= 0) continue;
    // v's tets of a bad shape outside old, in star order (kept in `before`:
    // shapes and stars do not change while the same change is judged again).
    const std::vector<int>* bad = &bad_scratch_;
    if (at >= 0 && before.bad_list[at] >= 0) {
      bad = &before.bad_lists[std::size_t(before.bad_list[at])];
    } else {
      std::vector<int>* list = &bad_scratch_;
      if (at >= 0) {
        if (before.bad_used == before.bad_lists.size()) before.bad_lists.emplace_back();
        before.bad_list[at] = int(before.bad_used);
        list = &before.bad_lists[before.bad_used++];
      }
      list->clear();
      star(v, change_star_);
      for (int t : change_star_)
        if (shape_[t] != TetClassifier::Shape::good && set_marks_.get(t) != 1) list->push_back(t);
      bad = list;
    }
    for (int t : *bad) {
      // old's tets are marked 1, the tets seen 2.
      if (set_marks_.get(t) >= 1) continue;
      set_marks_.put(t, 2);
      const Tet& T = tets_[t];
      allowed += tet_class(t) == TetClass::violation;
      violations += classifier_->classify(shape_[t], P_[T[0]], P_[T[1]], P_[T[2]], P_[T[3]],
                                          {{l2_after(T[0]), l2_after(T[1]), l2_after(T[2]), l2_after(T[3])}}) ==
                    TetClass::violation;
    }
  }
  return violations - allowed;
}

bool Improver::beats(double worst_new, double worst_old) const {
  if (polishing_ && polish_dihedral_) return worst_new >= polish_sine_floor_;  // accept() judges the angle
  return worst_new > worst_old || (fixing_ && worst_new >= fix_min_ && worst_new > fix_floor_);
}

bool Improver::admissible(const Tet& T, double size_cap) const {
  if (polishing_ && !polish_admits(T)) return false;  // polish()'s floor (improve_polish.cpp)
  if (size_cap <= 0) return true;
  double rl, R;
  radius_edge(P_[T[0]], P_[T[1]], P_[T[2]], P_[T[3]], rl, R);
  return R <= size_cap;
}

bool Improver::accept(const std::vector<int>& old, const std::vector<Tet>& fresh, double& worst_new,
                      double floor) const {
  double size_cap = max_size_;
  if (polishing_ && !polish_room(old.size(), fresh.size())) return false;  // improve_polish.cpp
  const double worst_old = std::isnan(floor) ? worst_of(old) : floor;
  worst_new = HUGE_VAL;
  std::vector<double>& fresh_q = accept_q_;
  fresh_q.clear();
  // The phase's time (issue 14): where the rule refuses a new worst of 0 it
  // refuses every value at most 0 (beats() only grows with worst_new), so an
  // inverted new tet's min-sine need not be finished (fresh_q and worst_new
  // matter only when the change passes).
  const bool zero_refused = !beats(0, worst_old);
  for (const Tet& T : fresh) {
    fresh_q.push_back(zero_refused ? min_sine_if_positive(P_[T[0]], P_[T[1]], P_[T[2]], P_[T[3]])
                                   : min_sine(P_[T[0]], P_[T[1]], P_[T[2]], P_[T[3]]));
    worst_new = std::min(worst_new, fresh_q.back());
    if (!beats(worst_new, worst_old)) return false;
  }
  for (const Tet& T : fresh)
    if (!positive(P_[T[0]], P_[T[1]], P_[T[2]], P_[T[3]])) return false;
  for (int t : old) {
    if (max_size_ > 0) {
      const Tet& T = tets_[t];
      double rl, R;
      radius_edge(P_[T[0]], P_[T[1]], P_[T[2]], P_[T[3]], rl, R);
      size_cap = std::max(size_cap, R);
    }
  }
  for (const Tet& T : fresh)
    if (!admissible(T, size_cap)) return false;
  if (polishing_ && polish_dihedral_ && !polish_lowers_cosine(old, fresh)) return false;  // improve_polish.cpp
  classes_before(old, accept_before_);
  const int change = classes_change(old, accept_before_, fresh, &fresh_q);
  return fixing_ ? change < 0 : change <= 0;
}

bool Improver::replace(const std::vector<int>& old, const std::vector<Tet>& fresh,
                       const std::vector<std::pair<int, std::array<int, 3>>>& boundary, int vanishing, bool judged) {
  // The outer faces of the old set, outward, with what lies beyond each.
  std::vector<ReplaceOuter>& outer = replace_outer_;
  outer.clear();
  set_marks_.reset(tets_.size());
  for (int t : old) set_marks_.put(t);
  for (int t : old)
    for (int k = 0; k < 4; ++k) {
      const int n = nb_[t][k];
      if (n >= 0 && set_marks_.has(n)) continue;
      int s = -1;
      if (n >= 0)
        for (int j = 0; j < 4; ++j)
          if (nb_[n][j] == t) s = j;
      outer.push_back({outward_face(tets_[t], k), n, s, false});
    }
  for (const auto& [b, tri] : boundary)
    for (ReplaceOuter& o : outer)
      if (o.beyond == -1 - b) {
        if (tri[0] < 0)
          o.used = true;  // deleted (a contraction): nothing new faces it
        else
          o.key = rotated(tri);
      }
  // A boundary triangle with a new index (insert_boundary's fan) is an outer
  // face of its own.
  for (const auto& [b, tri] : boundary)
    if (b >= int(bnd_.size())) outer.push_back({rotated(tri), -1 - b, -1, false});
  // Every vertex of the old set stays in the new one (but `vanishing`). The
  // phase's time (issue 14): the new tets' vertices are marked once (each
  // old vertex was looked for in every new tet, quadratic in a star's size).
  replace_marks_.reset(P_.size());
  for (const Tet& T : fresh)
    for (int v : T) replace_marks_.put(v);
  for (int t : old)
    for (int v : tets_[t])
      if (v != vanishing && !replace_marks_.has(v)) return false;
  // Match the new faces: in pairs of opposite orientation, or to an outer
  // face of the same orientation; each outer face exactly once (the last
  // unused one of that key, as the linear search of before took; the outer
  // faces are looked up by key in `by_key`, sorted by key, then index).
  std::vector<ReplaceFace>& faces = replace_faces_;
  faces.clear();
  for (std::size_t i = 0; i < fresh.size(); ++i)
    for (int k = 0; k < 4; ++k) {
      ReplaceFace f{outward_face(fresh[i], k), {}, int(i), k};
      f.sorted = f.key;
      std::sort(f.sorted.begin(), f.sorted.end());
      faces.push_back(f);
    }
  // The new faces by their sorted vertices (faces of one key next to each
  // other; which comes first among them changes nothing below). The
  // phase's time (issue 14): below 2^21 vertices by the key packed into 63
  // bits, as the constructor sorts the faces.
  std::vector<std::pair<std::uint64_t, int>>& by_sorted = replace_sorted_;
  by_sorted.resize(faces.size());
  if (P_.size() < (std::size_t(1) << 21)) {
    for (std::size_t x = 0; x < faces.size(); ++x) {
      const Tri& f = faces[x].sorted;
      by_sorted[x] = {std::uint64_t(f[0]) << 42 | std::uint64_t(f[1]) << 21 | std::uint64_t(f[2]), int(x)};
    }
    std::sort(by_sorted.begin(), by_sorted.end());
  } else {
    std::sort(faces.begin(), faces.end(),
              [](const ReplaceFace& a, const ReplaceFace& b) { return a.sorted < b.sorted; });
    for (std::size_t x = 0; x < faces.size(); ++x) by_sorted[x] = {0, int(x)};
  }
  const auto face = [&](std::size_t x) -> const ReplaceFace& { return faces[std::size_t(by_sorted[x].second)]; };
  std::vector<int>& by_key = replace_by_key_;
  by_key.resize(outer.size());
  for (std::size_t o = 0; o < outer.size(); ++o) by_key[o] = int(o);
  std::sort(by_key.begin(), by_key.end(),
            [&outer](int a, int b) { return outer[a].key < outer[b].key || (outer[a].key == outer[b].key && a < b); });
  std::vector<Tet>& link = replace_link_;  // >= 0: new tet index; < 0: -1 - outer index
  link.assign(fresh.size(), {{0, 0, 0, 0}});
  for (std::size_t x = 0; x < faces.size();) {
    std::size_t y = x + 1;
    while (y < faces.size() && face(y).sorted == face(x).sorted) ++y;
    if (y - x == 2) {
      const ReplaceFace &f = face(x), &g = face(x + 1);
      if (g.key != reversed(f.key)) return false;
      link[f.i][f.k] = g.i;
      link[g.i][g.k] = f.i;
    } else if (y - x == 1) {
      const Tri& key = face(x).key;
      auto it = std::upper_bound(by_key.begin(), by_key.end(), key,
                                 [&outer](const Tri& k, int o) { return k < outer[o].key; });
      int found = -1;
      while (it != by_key.begin() && outer[*(it - 1)].key == key) {
        --it;
        if (!outer[*it].used) {
          found = *it;
          break;
        }
      }
      if (found < 0) return false;
      outer[found].used = true;
      link[face(x).i][face(x).k] = -1 - found;
    } else {
      return false;
    }
    x = y;
  }
  for (const ReplaceOuter& o : outer)
    if (!o.used) return false;
  // Commit.
  forget(old);
  for (const auto& [b, tri] : boundary) {
    if (b >= int(bnd_.size())) bnd_.resize(b + 1);
    bnd_[b] = tri;
  }
  // free_slots_ is a min-heap: a new tet takes the smallest free slot.
  for (int t : old) {
    tets_[t][0] = -1;
    free_slots_.push_back(t);
    std::push_heap(free_slots_.begin(), free_slots_.end(), std::greater<int>());
  }
  std::vector<int>& id = replace_id_;
  id.resize(fresh.size());
  for (std::size_t i = 0; i < fresh.size(); ++i) {
    if (!free_slots_.empty()) {
      std::pop_heap(free_slots_.begin(), free_slots_.end(), std::greater<int>());
      id[i] = free_slots_.back();
      free_slots_.pop_back();
    } else {
      id[i] = int(tets_.size());
      tets_.push_back({});
      nb_.push_back({});
      q_.push_back(0);
      tried_.push_back(-1);
      insert_tried_.push_back(-1);
    }
    const Tet& T = fresh[i];
    tets_[id[i]] = T;
    // A judged change: accept() has computed each new tet's min-sine at these
    // points (accept_q_, in fresh's order; the same values).
    q_[id[i]] =
        judged && accept_q_.size() == fresh.size() ? accept_q_[i] : min_sine(P_[T[0]], P_[T[1]], P_[T[2]], P_[T[3]]);
    forget_dihedral(id[i]);
    for (int v : T) vtet_[v] = id[i];
  }
  ++clock_;
  for (std::size_t i = 0; i < fresh.size(); ++i) {
    touch(fresh[i]);
    tried_[id[i]] = insert_tried_[id[i]] = -1;
  }
  for (std::size_t i = 0; i < fresh.size(); ++i)
    for (int k = 0; k < 4; ++k) {
      const int l = link[i][k];
      if (l >= 0) {
        nb_[id[i]][k] = id[l];
      } else {
        const ReplaceOuter& o = outer[-1 - l];
        nb_[id[i]][k] = o.beyond;
        if (o.beyond >= 0) nb_[o.beyond][o.beyond_slot] = id[i];
      }
    }
  learn(id, -1, {}, judged);
  return true;
}

bool Improver::flip23(int t, int k) {
  const int n = nb_[t][k];
  if (n < 0) return false;
  const int d = tets_[t][k];
  int e = -1;
  for (int j = 0; j < 4; ++j)
    if (nb_[n][j] == t) e = tets_[n][j];
  if (e < 0) return false;
  // (x, y, z, d) positive: the reverse of t's outward face opposite d.
  const Tri f = reversed(outward_face(tets_[t], k));
  std::vector<Tet>& fresh = op_fresh_;
  fresh.assign({{{f[0], f[1], e, d}}, {{f[1], f[2], e, d}}, {{f[2], f[0], e, d}}});
  std::vector<int>& old = op_old_;
  old.assign({t, n});
  double w;
  if (!accept(old, fresh, w) || !replace(old, fresh, {}, -1, true)) return false;
  ++st_.flips23;
  return true;
}

bool Improver::remove_edge(int t, int i, int j) {
  const int a = tets_[t][i], b = tets_[t][j];
  std::vector<int>&ts = op_old_, &rv = ring_verts_;
  if (!ring(t, a, b, ts, rv)) return false;
  const int m = int(rv.size());
  // Triangles (r_i, r_j, r_k), i < j < k, become the tets (r_i, r_j, r_k, b)
  // and (r_k, r_j, r_i, a); the dynamic programme (Klincsek's, as Shewchuk's
  // edge removal uses it) maximises the worst of them over the
  // triangulations of the ring's polygon.
  const double worst_old = worst_of(ts);
  // The phase's time (issue 14; the same meshes): outside fix_violations a
  // triangulation is taken only when its worst beats worst_old, and the
  // programme keeps, per sub-polygon, the first cut of the strictly largest
  // value, so an option whose value is at most worst_old (`prune`) decides
  // nothing the outcome depends on: it is skipped, and tri() stops after the
  // first of its two tets when that one is no better. Each entry whose value
  // beats worst_old stays what it was (by induction on the length), every
  // other stays at most worst_old; the cuts followed from an accepted
  // triangulation are those of before.
  const double prune = fixing_ ? -HUGE_VAL : worst_old;
  // A tet whose min-sine is at most 0 <= prune gives an option at most
  // prune, decided by any value at most prune (min_sine_if_positive).
  const bool zero_pruned = prune >= 0;
  const auto sine = [&](const Point3& p, const Point3& q, const Point3& r, const Point3& s) {
    return zero_pruned ? min_sine_if_positive(p, q, r, s) : min_sine(p, q, r, s);
  };
  auto tri = [&](int x, int y, int z) {
    const Point3 &p = P_[rv[x]], &q = P_[rv[y]], &r = P_[rv[z]];
    const double first = sine(p, q, r, P_[b]);
    if (first <= prune) return first;
    return std::min(first, sine(r, q, p, P_[a]));
  };
  double best[kMaxRing][kMaxRing];
  int cut[kMaxRing][kMaxRing];
  for (int len = 1; len < m; ++len)
    for (int x = 0; x + len < m; ++x) {
      const int z = x + len;
      if (len == 1) {
        best[x][z] = HUGE_VAL;
        continue;
      }
      best[x][z] = -HUGE_VAL;
      for (int y = x + 1; y < z; ++y) {
        const double sub = std::min(best[x][y], best[y][z]);
        if (sub <= prune) continue;
        const double v = std::min(sub, tri(x, y, z));
        if (v > best[x][z]) {
          best[x][z] = v;
          cut[x][z] = y;
        }
      }
    }
  if (!beats(best[0][m - 1], worst_old)) return false;
  std::vector<Tet> fresh;
  std::vector<std::pair<int, int>> todo = {{0, m - 1}};
  while (!todo.empty()) {
    const auto [x, z] = todo.back();
    todo.pop_back();
    if (z - x < 2) continue;
    const int y = cut[x][z];
    fresh.push_back({{rv[x], rv[y], rv[z], b}});
    fresh.push_back({{rv[z], rv[y], rv[x], a}});
    todo.push_back({x, y});
    todo.push_back({y, z});
  }
  double w;
  if (!accept(ts, fresh, w) || !replace(ts, fresh, {}, -1, true)) return false;
  if (m == 3)
    ++st_.flips32;
  else if (m == 4)
    ++st_.flips44;
  else
    ++st_.edge_removals;
  return true;
}

bool Improver::flip22(int t, int i, int j) {
  const int a0 = tets_[t][i], b0 = tets_[t][j];
  int k = -1, l = -1;
  for (int s = 0; s < 4; ++s)
    if (s != i && s != j) (k < 0 ? k : l) = s;
  // One of t's two faces at the edge is a boundary triangle, the other
  // interior, leading to t2, whose other face at the edge is boundary too.
  if (nb_[t][k] >= 0) std::swap(k, l);
  if (nb_[t][k] >= 0 || nb_[t][l] < 0) return false;
  const int t2 = nb_[t][l];
  const int c = tets_[t][k];  // opposite the boundary face (a, b, d); on the shared face (a, b, c)
  const int d = tets_[t][l];  // opposite the shared face
  const int e = [&] {
    for (int s = 0; s < 4; ++s)
      if (nb_[t2][s] == t) return tets_[t2][s];
    return -1;
  }();
  const int k2 = slot(t2, c);
  if (e < 0 || k2 < 0 || nb_[t2][k2] >= 0) return false;
  const int b1 = -1 - nb_[t][k], b2 = -1 - nb_[t2][k2];
  if (b1 >= int(bnd_.size()) || b2 >= int(bnd_.size())) return false;
  const int f1 = r_.mesh.boundary_facet[b1], f2 = r_.mesh.boundary_facet[b2];
  if (f1 < 0 || f1 != f2) return false;
  // Outward, t's boundary face is (a, b, d) for (a, b, c, d) positive.
  const Tri B1 = outward_face(tets_[t], k);
  // Rotate so that B1 = (a, b, d): a, b the edge, d the apex.
  Tri o = B1;
  while (o[2] != d) o = {{o[1], o[2], o[0]}};
  const int a = o[0], b = o[1];
  // The boundary cycle a -> e -> b -> d: new triangles (a, e, d), (e, b, d);
  // the tets with apex c inside: (x, z, y, c) for each outward (x, y, z).
  const Tri n1{{a, e, d}}, n2{{e, b, d}};
  std::vector<Tet>& fresh = op_fresh_;
  fresh.assign({{{a, d, e, c}}, {{e, d, b, c}}});
  std::vector<int>& old = op_old_;
  old.assign({t, t2});
  // The phase's time (issue 14; the same outcome): the min-sine rule that
  // accept() applies, before the exact coplanarity test (costly on the
  // exactly coplanar points it is there for); each refuses on its own.
  if (!beats(worst_min_sine(fresh), worst_of(old))) return false;
  if (CGAL::orientation(cgal::to_cgal(P_[a0]), cgal::to_cgal(P_[b0]), cgal::to_cgal(P_[d]), cgal::to_cgal(P_[e])) !=
      CGAL::COPLANAR)
    return false;
  double w;
  if (!accept(old, fresh, w) || !replace(old, fresh, {{b1, n1}, {b2, n2}}, -1, true)) return false;
  ++st_.flips22;
  return true;
}

double Improver::ascend(int v, const std::vector<Tet>& tets, double current, double lmin,
                        const std::function<bool()>& valid, int axes) {
  auto quality_at = [&](const Tet& T, const Point3& x) {
    Point3 p[4];
    for (int k = 0; k < 4; ++k) p[k] = T[k] == v ? x : P_[T[k]];
    return min_sine(p[0], p[1], p[2], p[3]);
  };
  // q[i]: tet i's quality at P_[v]; order: the tets by it, worst first.
  std::vector<double>&q = ascend_q_, &qx = ascend_qx_;
  std::vector<int>& order = ascend_order_;
  q.assign(tets.size(), 0);
  qx.assign(tets.size(), 0);
  order.assign(tets.size(), 0);
  for (std::size_t i = 0; i < tets.size(); ++i) q[i] = quality_at(tets[i], P_[v]);
  // The worst at x if it beats `current` (qx then holds every tet's
  // quality), else some value <= current: the scan stops at the first tet
  // that does not beat it, worst first (std::min skips a NaN, as before).
  // An inverted tet at x ends the scan when current >= 0: its
  // min_sine_if_positive() is at most 0 <= current (the phase's time, issue
  // 14; qx is read only when every tet beats current, so exact then).
  auto worst_at = [&](const Point3& x) {
    double w = HUGE_VAL;
    const bool zero_fails = current >= 0;
    for (int i : order) {
      const Tet& T = tets[i];
      Point3 p[4];
      for (int k = 0; k < 4; ++k) p[k] = T[k] == v ? x : P_[T[k]];
      w = std::min(
          w, qx[i] = zero_fails ? min_sine_if_positive(p[0], p[1], p[2], p[3]) : min_sine(p[0], p[1], p[2], p[3]));
      if (w <= current) return w;
    }
    return w;
  };
  for (int step = 0; step < kSmoothSteps; ++step) {
    // The gradient of each nearly worst tet (central differences); the
    // direction is the sum of their unit gradients (nonsmooth ascent).
    const double h = 1e-7 * lmin;
    Point3 dir{{0, 0, 0}};
    for (std::size_t i = 0; i < tets.size(); ++i) {
      if (q[i] > current + 1e-3) continue;
      const Tet& T = tets[i];
      Point3 g;
      for (int c = 0; c < 3; ++c) {
        g[c] = 0;  // an exact 0: the coordinate stays (boundary slides)
        if (!(axes >> c & 1)) continue;
        Point3 p = P_[v], m = P_[v];
        p[c] += h;
        m[c] -= h;
        g[c] = (quality_at(T, p) - quality_at(T, m)) / (2 * h);
      }
      dir = geometry::add(dir, geometry::unit(g));
    }
    if (!(norm(dir) > 0)) break;
    dir = geometry::unit(dir);
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = int(i);
    std::sort(order.begin(), order.end(), [&](int a, int b) {
      const double qa = std::isnan(q[a]) ? HUGE_VAL : q[a], qb = std::isnan(q[b]) ? HUGE_VAL : q[b];
      return qa < qb || (qa == qb && a < b);
    });
    bool better = false;
    for (double alpha = 0.2 * lmin; alpha > 1e-4 * lmin; alpha *= 0.5) {
      const Point3 x = geometry::add(P_[v], geometry::mul(dir, alpha));
      const double w = worst_at(x);
      if (!(w > current)) continue;
      // w > current: worst_at() computed every tet's min-sine at x (qx),
      // which smooth()'s valid() reads instead of computing them again.
      valid_q_ = &qx;
      const bool moved = move_if_valid(v, x, valid);
      valid_q_ = nullptr;
      if (!moved) continue;
      current = w;
      q.swap(qx);
      better = true;
      break;
    }
    if (!better) break;
  }
  return current;
}

bool Improver::move_if_valid(int v, const Point3& x, const std::function<bool()>& valid) {
  const Point3 keep = P_[v];
  P_[v] = x;
  if (valid()) return true;
  P_[v] = keep;
  return false;
}

Improver::MeshWorst Improver::mesh_worst() const {
  MeshWorst w{HUGE_VAL, 180};
  int first = -1;  // a tet of the smallest min-sine
  for (std::size_t t = 0; t < tets_.size(); ++t)
    if (alive(int(t))) {
      w.sine = std::min(w.sine, q_[t]);
      if (first < 0 || q_[t] < q_[first]) first = int(t);
    }
  if (first < 0) return w;
  // The phase's time (issue 14): the smallest dihedral(t) over the live
  // tets, from the tet of the smallest min-sine on; a tet whose min-sine
  // shows its angle above the smallest so far (sine_above) cannot lower it
  // and is not measured. The same minimum (std::min skips a NaN, as before).
  w.dihedral_deg = std::min(w.dihedral_deg, dihedral(first));
  double sine = sine_above(w.dihedral_deg);
  for (std::size_t t = 0; t < tets_.size(); ++t)
    if (alive(int(t)) && !dihedral_above(int(t), w.dihedral_deg, sine)) {
      const double d = std::min(w.dihedral_deg, dihedral(int(t)));
      if (d < w.dihedral_deg) w.dihedral_deg = d, sine = sine_above(d);
    }
  return w;
}

double Improver::sine_above(double deg) {
  if (!(deg < 60)) return HUGE_VAL;
  return std::sin(std::max(deg, 0.0) * (1 + 1e-6) * geometry::kPi / 180) * (1 + 1e-6) + 1e-12;
}

double Improver::dihedral(int t) const {
  if (dih_.size() < tets_.size()) dih_.resize(tets_.size(), std::numeric_limits<double>::quiet_NaN());
  if (std::isnan(dih_[t])) {
    const Tet& T = tets_[t];
    dih_[t] = tet_min_dihedral_deg(P_[T[0]], P_[T[1]], P_[T[2]], P_[T[3]]);
  }
  return dih_[t];
}

double Improver::worst_of(const std::vector<int>& live) const {
  double worst = HUGE_VAL;
  for (int t : live) worst = std::min(worst, q_[t]);
  return worst;
}

double Improver::worst_min_sine(const std::vector<Tet>& fresh) const {
  double worst = HUGE_VAL;
  for (const Tet& T : fresh) worst = std::min(worst, min_sine(P_[T[0]], P_[T[1]], P_[T[2]], P_[T[3]]));
  return worst;
}

double Improver::ascend_new_point(int p_id, const std::vector<Tet>& fresh, double start, int axes) {
  const Point3 p = P_[p_id];
  double lmin = HUGE_VAL;
  const double current = start;
  for (const Tet& T : fresh)
    for (int k = 0; k < 3; ++k) lmin = std::min(lmin, geometry::dist2(P_[T[k]], p));
  lmin = std::sqrt(lmin);
  if (!(lmin > 0)) return current;
  return ascend(
      p_id, fresh, current, lmin,
      [&] {
        for (const Tet& T : fresh)
          if (!positive(P_[T[0]], P_[T[1]], P_[T[2]], P_[T[3]])) return false;
        return true;
      },
      axes);
}

bool Improver::smooth(int v) {
  const int axes = movable_axes(v);
  if (axes == 0) return false;
  std::vector<int>& S = smooth_star_;
  star(v, S);
  if (S.empty()) return false;
  double worst_old = HUGE_VAL, size_cap = max_size_, lmin = HUGE_VAL;
  ClassesBefore& before = smooth_before_;
  classes_before(S, before);  // before v moves
  std::vector<Tet>& tets = smooth_tets_;
  tets.clear();
  for (int t : S) {
    worst_old = std::min(worst_old, q_[t]);
    const Tet& T = tets_[t];
    tets.push_back(T);
    if (max_size_ > 0) {
      double rl, R;
      radius_edge(P_[T[0]], P_[T[1]], P_[T[2]], P_[T[3]], rl, R);
      size_cap = std::max(size_cap, R);
    }
    for (int u : T)
      if (u != v) lmin = std::min(lmin, geometry::dist2(P_[u], P_[v]));
  }
  lmin = std::sqrt(lmin);
  if (!(lmin > 0)) return false;
  // Each step: every tet of the star positive (exact), within max_size, and
  // no more violations than before among the tets whose class can change.
  // The answer does not depend on the order of the tets, so the one that
  // failed the last call is tried first.
  std::size_t hard = 0;
  const auto valid = [&] {
    for (std::size_t n = 0; n < tets.size(); ++n) {
      const std::size_t i = n == 0 ? hard : n <= hard ? n - 1 : n;
      const Tet& T = tets[i];
      if (!positive(P_[T[0]], P_[T[1]], P_[T[2]], P_[T[3]]) || !admissible(T, size_cap)) {
        hard = i;
        return false;
      }
    }
    return classes_change(S, before, tets, valid_q_) <= 0;
  };
  const Point3 from = P_[v];
  if (polishing_ && polish_dihedral_) {
    // polish()'s smoothing: on the star's smallest dihedral angle
    // (improve_dihedral.cpp), under the same guards (valid()).
    if (!ascend_dihedral(v, tets, lmin, valid, axes)) return false;
  } else {
    double w = ascend(v, tets, worst_old, lmin, valid, axes & 7);
    if (axes & kPlaneSlide) w = ascend_in_plane(v, tets, w, lmin, valid);  // improve_boundary.cpp
    if (!(w > worst_old)) return false;
  }
  forget(S);
  for (int t : S) {
    const Tet& T = tets_[t];
    q_[t] = min_sine(P_[T[0]], P_[T[1]], P_[T[2]], P_[T[3]]);
    forget_dihedral(t);
  }
  learn(S, v, from);
  // improve_contract.cpp's promise: a vertex on or inside a vertex ball's
  // sphere is never removed. The move can take v onto or into one (the
  // ascent knows no balls), so whether it lies on one is read anew.
  if (v < int(ball_point_.size())) ball_point_[v] = -1;
  ++clock_;
  for (int t : S) touch(tets_[t]);
  ++st_.smoothed;
  st_.slid += fixed_[v] != 0;
  return true;
}

bool Improver::insert(int t) {
  if (!alive(t)) return false;
  const Tet T0 = tets_[t];
  double r2;
  const Point3 cc = geometry::circumcenter(P_[T0[0]], P_[T0[1]], P_[T0[2]], P_[T0[3]], r2);
  Point3 g{{0, 0, 0}};
  for (int v : T0) g = geometry::add(g, geometry::mul(P_[v], 0.25));
  std::vector<Point3>& candidates = insert_candidates_;
  candidates.clear();
  if (std::isfinite(r2)) candidates.push_back(cc);
  candidates.push_back(g);
  // Beyond Stellar's choice: for each face of t, the apex of a regular tet on
  // it, on t's side (where the bad dihedral angle is at a boundary edge, the
  // point that makes a good tet on the boundary face).
  for (int k = 0; k < 4; ++k) {
    const Tri f = outward_face(T0, k);
    const Point3 &x = P_[f[0]], &y = P_[f[1]], &z = P_[f[2]];
    const Point3 n = geometry::unit(cross(sub(y, x), sub(z, x)));  // outward of t: into t is -n
    const double l = (norm(sub(y, x)) + norm(sub(z, y)) + norm(sub(x, z))) / 3;
    Point3 c{{(x[0] + y[0] + z[0]) / 3, (x[1] + y[1] + z[1]) / 3, (x[2] + y[2] + z[2]) / 3}};
    candidates.push_back(geometry::add(c, geometry::mul(n, -std::sqrt(2.0 / 3) * l)));
  }
  double best = -HUGE_VAL;
  std::vector<int>&best_old = insert_old_[1], &cav = insert_old_[0];
  std::vector<Tet>&best_fresh = insert_fresh_[1], &fresh = insert_fresh_[0];
  std::vector<char>& known = insert_known_;
  best_old.clear();
  best_fresh.clear();
  Point3 best_p{};
  const int p_id = int(P_.size());
  for (const Point3& p : candidates) {
    // Walk from t to the tet that holds p (double orientation; the exact
    // test comes with the new tets); give up at the boundary.
    int cur = t;
    for (int steps = 0; steps < 64 && cur >= 0; ++steps) {
      int next = -1;
      for (int k = 0; k < 4 && next < 0; ++k) {
        const Tri f = outward_face(tets_[cur], k);
        // p beyond face k: (x, z, y, p) is not positive.
        const Point3 &x = P_[f[0]], &y = P_[f[1]], &z = P_[f[2]];
        if (dot(sub(z, x), cross(sub(y, x), sub(p, x))) < 0) next = k;
      }
      if (next < 0) break;
      cur = nb_[cur][next];
    }
    if (cur < 0) continue;
    // The cavity: tets whose circumsphere holds p, grown from cur, then
    // grown further until every outer face sees p (star-shaped).
    sphere_cavity(cur, p, cav);
    P_.push_back(p);
    bool ok = false;
    // Each round scans the outer faces in order for the first that p does
    // not see; a face found positive stays so (its tet and p do not change),
    // so it is not tested again (known[4 i + k]: face k of cav[i]).
    known.clear();
    cav_marks_.reset(tets_.size());
    for (int x : cav) cav_marks_.put(x);
    for (int round = 0; round < kMaxCavity; ++round) {
      fresh.clear();
      known.resize(4 * cav.size(), 0);
      int grow = -2;
      for (std::size_t i = 0; i < cav.size() && grow == -2; ++i)
        for (int k = 0; k < 4; ++k) {
          const int n = nb_[cav[i]][k];
          if (n >= 0 && cav_marks_.has(n)) continue;
          const Tri f = outward_face(tets_[cav[i]], k);
          const Tet nt{{f[0], f[2], f[1], p_id}};
          if (!known[4 * i + k]) {
            if (!positive(P_[nt[0]], P_[nt[1]], P_[nt[2]], P_[nt[3]])) {
              grow = n;
              break;
            }
            known[4 * i + k] = 1;
          }
          fresh.push_back(nt);
        }
      if (grow == -2) {
        ok = true;
        break;
      }
      if (grow < 0 || int(cav.size()) >= kMaxCavity) break;
      cav.push_back(grow);
      cav_marks_.put(grow);
    }
    if (ok && cav_marks_.has(t)) {
      // Beyond Stellar's rule as written: the new point is first placed by
      // the smoothing ascent on its own star (the cavity stays), then the
      // insertion is judged.
      const double placed = ascend_new_point(p_id, fresh, worst_min_sine(fresh));
      vtet_.push_back(-1);
      double w;
      // placed is what accept() computes as the new worst, bit for bit
      // (ascend_new_point): outside fix_violations a candidate that does not
      // beat the cavity's worst is refused there; spare it (as
      // insert_boundary does; the same meshes).
      const bool hopeless = !fixing_ && !(placed > worst_of(cav));
      if (placed > best && !hopeless && accept(cav, fresh, w) && w > best) {
        best = w;
        best_old = cav;
        best_fresh = fresh;
        best_p = P_[p_id];
      }
      vtet_.pop_back();
    }
    P_.pop_back();
  }
  return !best_fresh.empty() && add_point(best_p, best_old, best_fresh, {}, -1);
}

bool Improver::improve_tet(int t) {
  if (!alive(t)) return false;
  for (const auto& e : kEdge)
    if (alive(t) && remove_edge(t, e[0], e[1])) return true;
  for (int k = 0; k < 4; ++k)
    if (alive(t) && nb_[t][k] >= 0 && flip23(t, k)) return true;
  for (int k = 0; k < 4; ++k)
    if (alive(t) && nb_[t][k] >= 0 && remove_faces(t, k)) return true;
  for (const auto& e : kEdge)
    if (alive(t) && flip22(t, e[0], e[1])) return true;
  return false;
}

std::size_t Improver::fix_violations() {
  if (!classifier_) return 0;
  std::vector<int> list;
  for (std::size_t t = 0; t < tets_.size(); ++t)
    if (alive(int(t)) && shape_[t] != TetClassifier::Shape::good && tet_class(int(t)) == TetClass::violation)
      list.push_back(int(t));
  if (list.empty()) return 0;
  const MeshWorst worst = mesh_worst();
  fix_floor_ = std::max(worst.sine, std::sin(worst.dihedral_deg * geometry::kPi / 180));
  // One attempt on violation t under the current fix_min_: flips, the
  // insertion of a Steiner point, then the removal of one of its Steiner
  // vertices (a skinny tet's short edge; contract_vertex() under the same
  // rule and guards).
  const auto attempt = [&](int t) {
    if (improve_tet(t) || insert(t)) return true;
    const Tet T = tets_[t];
    for (int v : T)
      if (contract_vertex(v)) return true;
    return false;
  };
  const double target = std::sin(kImproveTargetDeg * geometry::kPi / 180);
  const double second = std::sin(kFixSecondDeg * geometry::kPi / 180);
  std::size_t n = 0;
  fixing_ = true;
  for (int t : list) {
    if (!poll()) break;
    if (!alive(t) || tet_class(t) != TetClass::violation) continue;
    if (t < int(fix_tried_.size()) && !fresh_since(fix_tried_[t], tets_[t])) continue;
    // The second rule only where the first leaves the violation (each
    // refused attempt changes nothing, so t is still the same violation).
    fix_min_ = target;
    if (attempt(t)) {
      ++n;
      continue;
    }
    fix_min_ = second;
    if (attempt(t)) {
      ++n;
      continue;
    }
    if (fix_tried_.size() < tets_.size()) fix_tried_.resize(tets_.size(), -1);
    fix_tried_[t] = clock_;
  }
  fixing_ = false;
  return n;
}

Improver::QualityMeasures Improver::quality_measures() const {
  QualityMeasures m;
  // The phase's time (issue 14): a tet whose min-sine shows its smallest
  // dihedral angle above both kQualityCountDeg and the smallest so far
  // (sine_above) changes neither measure and is not measured; the smallest
  // starts at the tet of the smallest min-sine. The same measures.
  int first = -1;
  for (std::size_t t = 0; t < tets_.size(); ++t)
    if (alive(int(t)) && (first < 0 || q_[t] < q_[first])) first = int(t);
  if (first < 0) return m;
  m.smallest_dihedral_deg = std::min(m.smallest_dihedral_deg, dihedral(first));
  double above = std::max(m.smallest_dihedral_deg, kQualityCountDeg), sine = sine_above(above);
  for (std::size_t t = 0; t < tets_.size(); ++t)
    if (alive(int(t)) && !dihedral_above(int(t), above, sine)) {
      const double d = dihedral(int(t));
      m.smallest_dihedral_deg = std::min(m.smallest_dihedral_deg, d);
      m.under_count_deg += d < kQualityCountDeg;
      if (std::max(m.smallest_dihedral_deg, kQualityCountDeg) < above)
        above = std::max(m.smallest_dihedral_deg, kQualityCountDeg), sine = sine_above(above);
    }
  return m;
}

bool Improver::pass_improves(const QualityMeasures& before, const QualityMeasures& after) {
  return after.smallest_dihedral_deg > before.smallest_dihedral_deg || after.under_count_deg < before.under_count_deg;
}

bool Improver::pass_extends(const QualityMeasures& before, const QualityMeasures& after) {
  if (!(after.smallest_dihedral_deg < kExtraPassBelowDeg)) return false;
  return after.smallest_dihedral_deg > kExtraPassRise * before.smallest_dihedral_deg ||
         double(after.under_count_deg) < (1 - kExtraPassCut) * double(before.under_count_deg);
}

bool Improver::run() {
  const double target = std::sin(kImproveTargetDeg * geometry::kPi / 180);
  const double insert_below = std::sin(kInsertBelowDeg * geometry::kPi / 180);
  auto bad_tets = [&](double below) {
    std::vector<int> list;
    for (std::size_t t = 0; t < tets_.size(); ++t)
      if (alive(int(t)) && q_[t] < below) list.push_back(int(t));
    // The order of a stable sort by q_ (the list's tets are in increasing
    // order and their q_ below `below`, so none is NaN): ties by index.
    std::sort(list.begin(), list.end(), [&](int a, int b) { return q_[a] < q_[b] || (q_[a] == q_[b] && a < b); });
    return list;
  };
  auto flips = [&]() {
    std::size_t n = 0;
    for (int t : bad_tets(target)) {
      if (!poll()) return n;
      if (!alive(t) || !(q_[t] < target) || !fresh_since(tried_[t], tets_[t])) continue;
      if (improve_tet(t))
        ++n;
      else
        tried_[t] = clock_;
    }
    return n;
  };
  // Smoothing: the free vertices of the bad tets, each only after its star
  // changed.
  auto smoothing = [&]() {
    std::size_t n = 0;
    std::vector<int> verts;
    for (int t : bad_tets(target))
      for (int v : tets_[t])
        if (movable_axes(v)) verts.push_back(v);
    std::sort(verts.begin(), verts.end());
    verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
    for (int v : verts) {
      if (!poll()) break;
      if (smoothed_[v] >= 0 && vtime_[v] <= smoothed_[v]) continue;  // its star has not changed
      if (smooth(v))
        ++n;
      else
        smoothed_[v] = clock_;
    }
    return n;
  };
  // Insertion where a sliver is left, then smoothing of the new vertex.
  auto insertion = [&]() {
    std::size_t n = 0;
    for (int t : bad_tets(insert_below)) {
      if (!poll()) break;
      if (!alive(t) || !(q_[t] < insert_below) || !fresh_since(insert_tried_[t], tets_[t])) continue;
      if (!insert(t) && !insert_boundary(t)) {
        insert_tried_[t] = clock_;
        continue;
      }
      ++n;
      const int v = int(P_.size()) - 1;
      n += smooth(v);
    }
    return n;
  };
  // Beyond the paper, a choice for the phase's time (issue 14; figures of
  // 2026-12-03 in BENCHMARKS.md, "Session 11, h1"): a pass is contraction,
  // flips, smoothing, contraction, and insertion only in a pass that follows
  // a stalled one (pass_improves()). Contraction first removes the most tets
  // under 5 degrees for the least work and leaves fewer tets to flip and
  // smooth; insertion is the dearest operation (on wedge and wedge-1 half
  // of the phase's time when it ran in every pass) and, tried while the
  // cheaper operations still make progress, it left as many tets under 5
  // degrees or more (wedge 97 either way, wedge-1 161 against 144).
  // Beyond the paper, a choice (kImproveExtraPasses; BENCHMARKS.md,
  // "Session 14 (2026-12-04), h1"): the last regular pass also inserts when
  // the pass before it raised the smallest angle (the worst tets still
  // move, so no input angle holds them: on wedge and wedge-1 it has not
  // risen since the first pass, and insertion there cost wedge-1's phase
  // 13% for 144 -> 139 tets under 5 degrees), and extra passes, insertion
  // included, follow while pass_extends() holds (mpi.off: 0.0158 -> 0.0557
  // degrees in 10 passes).
  QualityMeasures before = quality_measures();
  bool insert_next = false, rose = false;
  for (int pass = 0; pass < kImprovePasses + kImproveExtraPasses; ++pass) {
    const bool inserting = insert_next || pass >= kImprovePasses || (pass == kImprovePasses - 1 && rose);
    std::size_t changed = contract_pass();  // improve_contract.cpp
    changed += flips();
    changed += smoothing();
    if (inserting) changed += insertion();
    changed += contract_pass();
    changed += fix_violations();
    if (cancelled_) return false;
    st_.passes = pass + 1;
    // A pass that changes nothing or does not improve the measures stalls:
    // the next one adds insertion; a stalled pass with insertion ends the
    // phase. From the last regular pass on, the next pass is an extra one
    // only when this one extends.
    const QualityMeasures after = changed == 0 ? before : quality_measures();
    pass_records_.push_back({before, after, inserting});
    const bool stalled = changed == 0 || !pass_improves(before, after);
    if (stalled && inserting) break;
    if (pass >= kImprovePasses - 1 && !pass_extends(before, after)) break;
    insert_next = stalled;
    rose = after.smallest_dihedral_deg > before.smallest_dihedral_deg;
    before = after;
  }
  if (coarsen_on_) coarsen();                // improve_coarsen.cpp (when the passes reach kImproveTargetDeg)
  st_.polished = polish_on_ ? polish() : 0;  // improve_polish.cpp (off unless MeshOptions::polish)
  return !cancelled_;
}

void Improver::finish() {
  TetMesh& m = r_.mesh;
  m.tets.clear();
  for (std::size_t t = 0; t < tets_.size(); ++t)
    if (alive(int(t))) m.tets.push_back(tets_[t]);
  m.boundary = bnd_;
  // N(v) of an inserted vertex: its shortest edge.
  for (int v : inserted_) {
    std::vector<int> S;
    star(v, S);
    double l2 = HUGE_VAL;
    for (int t : S)
      for (int u : tets_[t])
        if (u != v) l2 = std::min(l2, geometry::dist2(P_[u], P_[v]));
    r_.nearest_neighbour[v] = std::sqrt(l2);
  }
  drop_removed();
  ImproveStats& s = r_.improve;
  const ImproveStats keep = s;
  s = st_;
  s.ran = true;
  s.min_dihedral_before = keep.min_dihedral_before;
  s.min_dihedral_after = keep.min_dihedral_after;
  s.slivers_before = keep.slivers_before;
  s.skinny_before = keep.skinny_before;
  s.near_small_angle_before = keep.near_small_angle_before;
  s.violations_before = keep.violations_before;
  s.tets_before = keep.tets_before;
}

namespace {

double smallest_dihedral(const std::vector<TetQuality>& quality) {
  double m = 180;
  for (const TetQuality& q : quality) m = std::min(m, q.min_dihedral_deg);
  return quality.empty() ? 0 : m;
}

}  // namespace

bool improve_phase(MeshResult& r, const ProtectingBalls& balls, const MeshOptions& opt,
                   const ProgressCallback& progress) {
  ImproveStats& s = r.improve;
  s = ImproveStats();
  // Dihedral angles do not depend on the weights: the extraction's weighted
  // qualities give the smallest angle before.
  s.min_dihedral_before = smallest_dihedral(r.quality);
  s.slivers_before = r.slivers;
  s.skinny_before = r.skinny;
  s.near_small_angle_before = r.near_small_angle;
  s.violations_before = r.violations;
  s.tets_before = r.mesh.tets.size();
  // The measures are stale once the mesh changes and classify_tets below
  // makes them anew: freed now, so that they are not held beside the phase's
  // own arrays (issue 15, the peak memory).
  std::vector<TetQuality>().swap(r.quality);
  std::size_t calls = 0, tried = 0;
  const auto report = [&] {
    Progress p;
    p.phase = "improve";
    p.vertices = r.mesh.vertices.size();
    p.steps = tried;
    p.fraction = 0.95;
    return progress(p);
  };
  if (progress && !report()) return false;
  const std::function<bool()> keep_going = [&] {
    ++tried;
    if (!progress || ++calls < kImprovePoll) return true;
    calls = 0;
    return report();
  };
  bool done = false;
  {  // the Improver's arrays are freed before the classes are made
    Improver im(r, opt.rho0, opt.max_size, keep_going);
    im.set_classes(&balls, opt.theta_deg);
    im.set_polish(opt.polish);  // MeshOptions::polish
    done = im.run();
    im.finish();
  }
  if (!done) return false;
  // The classes again, on the improved mesh (h5's classify_tets).
  if (!classify_tets(r, balls, opt, keep_going)) return false;
  s.min_dihedral_after = smallest_dihedral(r.quality);
  return true;
}

}  // namespace wqmesh::mesher
