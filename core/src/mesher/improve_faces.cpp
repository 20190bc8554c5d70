// wqmesh: multi-face removal in the improvement phase (beyond the paper:
// Klingner and Shewchuk, "Aggressive Tetrahedral Mesh Improvement", IMR 2007,
// after de Cougny and Shephard; the inverse of edge removal). See improve.h,
// "Multi-face removal", for the contract.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <algorithm>
#include <cmath>

#include "mesher/improve.h"

namespace wqmesh::mesher {

namespace {

// The face of a positively oriented tet (v0, v1, v2, v3) opposite vertex k,
// oriented so that (face, v_k) is positive (the reverse of the outward face).
constexpr int kInward[4][3] = {{1, 3, 2}, {0, 2, 3}, {0, 3, 1}, {0, 1, 2}};

}  // namespace

int Improver::other_vertex(int t, int x, int y, int z) const {
  for (int v : tets_[t])
    if (v != x && v != y && v != z) return v;
  return -1;
}

bool Improver::sandwiched(const Sandwich& face, int e, int a, int b, std::array<int, 3>& u, int& na, int& nb) const {
  const int p = face.u[e], q = face.u[(e + 1) % 3], r = face.u[(e + 2) % 3];
  na = nb_[face.ta][slot(face.ta, r)];
  nb = nb_[face.tb][slot(face.tb, r)];
  const int w = na >= 0 ? other_vertex(na, p, q, a) : -1;
  if (nb < 0 || w < 0 || w == b || other_vertex(nb, p, q, b) != w) return false;
  // Oriented with a on its positive side, it must read (q, p, w).
  const int s = slot(na, a);
  u = {{tets_[na][kInward[s][0]], tets_[na][kInward[s][1]], tets_[na][kInward[s][2]]}};
  while (u[2] != w) u = {{u[1], u[2], u[0]}};
  return u[0] == q && u[1] == p;
}

void Improver::grow_sandwich(std::vector<Sandwich>& faces, int f, int back, int a, int b) const {
  // Edge e of face (u0, u1, u2) runs from u_e to u_(e+1); the face beyond it
  // shares the edge reversed. Which faces join does not depend on any
  // min-sine, so the tree is grown before the programme runs on it.
  for (int e = 0; e < 3; ++e) {
    faces[f].child[e] = -1;
    if (e == back) continue;
    std::array<int, 3> u;
    int na, nb;
    if (int(faces.size()) < kMaxSandwich && sandwiched(faces[f], e, a, b, u, na, nb)) {
      std::array<int, 3> key = u;
      std::sort(key.begin(), key.end());
      bool seen = false;
      for (const Sandwich& g : faces) seen = seen || g.key == key;
      if (!seen) {
        const int child = int(faces.size());
        faces[f].child[e] = child;
        faces.push_back({u, key, na, nb, {{-1, -1, -1}}, {{-1, -1, -1}}, 0});
        grow_sandwich(faces, child, 0, a, b);
      }
    }
  }
}

double Improver::sandwich_value(std::vector<Sandwich>& faces, int f, int back, int a, int b, double bound) {
  // The bound (beyond Shewchuk's programme; the phase's time, issue 14): by
  // induction on the subtree, sandwich_value(f, bound) is V(f) when V(f) >
  // bound, else some value <= bound. At edge e the child is asked with
  // max(bound, stop): when it answers a value c <= max(bound, stop), either
  // stop >= bound and the child's V <= stop, so the edge stops (as without
  // the bound) and max(stop, c) = stop is exact; or stop < bound and
  // max(stop, V of the child) <= bound, so V(f) <= bound as the early return
  // says. So a face whose V beats its bound is computed exactly, and every
  // face chosen from it beats its own bound.
  double value = HUGE_VAL;
  for (int e = 0; e < 3; ++e) {
    faces[f].next[e] = -1;
    if (e == back) continue;
    const int p = faces[f].u[e], q = faces[f].u[(e + 1) % 3];
    // Stopping here leaves the edge on the polygon's boundary: the new tet
    // (p, q, b, a) around the new edge ab.
    const double stop = min_sine(P_[p], P_[q], P_[b], P_[a]);
    const int child = faces[f].child[e];
    const double cont = child >= 0 ? sandwich_value(faces, child, 0, a, b, std::max(bound, stop)) : -HUGE_VAL;
    // Continue only when strictly better: fewer tets on a tie.
    faces[f].next[e] = cont > stop ? child : -1;
    value = std::min(value, std::max(stop, cont));
    if (value <= bound) break;
  }
  faces[f].value = value;
  return value;
}

bool Improver::remove_faces_choice(int t, int k, bool bound, std::vector<int>& old, std::vector<Tet>& fresh) {
  old.clear();
  fresh.clear();
  const int n = nb_[t][k];
  if (n < 0) return false;
  const int a = tets_[t][k];
  const std::array<int, 3> u0 = {{tets_[t][kInward[k][0]], tets_[t][kInward[k][1]], tets_[t][kInward[k][2]]}};
  const int b = other_vertex(n, u0[0], u0[1], u0[2]);
  if (b < 0) return false;
  std::array<int, 3> key = u0;
  std::sort(key.begin(), key.end());
  std::vector<Sandwich>& faces = sandwich_faces_;
  faces.assign(1, {u0, key, t, n, {{-1, -1, -1}}, {{-1, -1, -1}}, 0});
  grow_sandwich(faces, 0, -1, a, b);
  // Without a face beyond the root, the tree is the root alone, two old
  // tets (the 2-3 flip, refused below), so no min-sine is computed.
  if (faces.size() < 2) return false;
  // Any choice's old tets are among the tree's: their worst is at least
  // `least`, so a programme whose worst is at most `least` is refused below
  // whichever faces it would choose, and the bound `least` decides nothing
  // that is kept (sandwich_value). Without `bound`: the full programme.
  double least = -HUGE_VAL;
  if (bound) {
    least = HUGE_VAL;
    for (const Sandwich& g : faces) least = std::min({least, q_[g.ta], q_[g.tb]});
  }
  const double value = sandwich_value(faces, 0, -1, a, b, least);
  if (!(value > least)) return false;
  // The chosen faces (a tree from the root) and the polygon's boundary
  // edges, each giving the new tet (p, q, b, a).
  std::vector<int> todo = {0};
  double worst_old = HUGE_VAL;
  while (!todo.empty()) {
    const int f = todo.back();
    todo.pop_back();
    old.push_back(faces[f].ta);
    old.push_back(faces[f].tb);
    worst_old = std::min({worst_old, q_[faces[f].ta], q_[faces[f].tb]});
    for (int e = 0; e < 3; ++e) {
      if (f != 0 && e == 0) continue;  // the edge to the parent
      if (faces[f].next[e] >= 0) {
        todo.push_back(faces[f].next[e]);
      } else {
        fresh.push_back({{faces[f].u[e], faces[f].u[(e + 1) % 3], b, a}});
      }
    }
  }
  // One face is the 2-3 flip (flip23); the dynamic programme's worst must
  // beat the old set's.
  if (old.size() < 4 || !(value > worst_old)) {
    old.clear();
    fresh.clear();
    return false;
  }
  return true;
}

bool Improver::remove_faces(int t, int k) {
  std::vector<int>& old = faces_old_;
  std::vector<Tet>& fresh = faces_fresh_;
  if (!remove_faces_choice(t, k, true, old, fresh)) return false;
  double w;
  if (!accept(old, fresh, w) || !replace(old, fresh, {}, -1, true)) return false;
  ++st_.multi_face_removals;
  return true;
}

}  // namespace wqmesh::mesher
