// SPDX-License-Identifier: GPL-3.0-or-later
// wqmesh: validating a polygon soup and building its PLC (paper, section 2:
// a closed 2-manifold made of vertices, edges and planar facets that intersect
// properly). See build_plc in input.h for the steps; every geometric decision
// (collinear, coplanar, planar, orientation, intersection) is exact.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <map>
#include <numeric>
#include <set>
#include <tuple>
#include <unordered_map>

#include "cgal_types.h"
#include "exact.h"
#include "geometry.h"
#include "hashing.h"
#include "validation.h"
#include "wqmesh/input.h"

namespace wqmesh {
namespace {

using cgal::to_cgal;

/// Union-find with path halving.
struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

using validation::coords;

/// A half-edge of the triangulated surface: triangle t, its side k going from
/// corner k to corner k+1.
struct HalfEdge {
  int lo, hi;  // the edge's vertices, lo < hi
  int t, k;
};

/// The state of one build: the soup after merging, its triangles and their
/// adjacency, and the names used in messages.
class Builder {
 public:
  Builder(const PolygonSoup& soup, Warnings& warnings) : soup_(soup), warnings_(warnings) {}

  PLC run(MergeReport& rep);

 private:
  // --- names for messages ---------------------------------------------------
  std::string face_name(int f) const {
    std::string s = "face " + std::to_string(f);
    if (f < static_cast<int>(soup_.face_line.size()) && soup_.face_line[f] > 0)
      s += " (line " + std::to_string(soup_.face_line[f]) + ")";
    return s;
  }
  std::string tri_name(int t) const { return face_name(tri_face_[t]); }
  /// A merged vertex named by its first index in the file and coordinates.
  std::string vertex_name(int v) const { return "vertex " + std::to_string(first_index_[v]) + " " + coords(pts_[v]); }
  std::string edge_name(int a, int b) const { return "edge from " + vertex_name(a) + " to " + vertex_name(b); }
  [[noreturn]] void fail(InputErrorKind kind, const std::string& what) const { throw InputError(kind, what); }

  void check_and_merge_points();
  void check_faces();
  void triangulate();
  void build_adjacency();
  void check_vertex_fans();
  void orient();
  void orient_outwards();
  std::vector<PlcFacet> merge_coplanar();
  PLC finish(std::vector<PlcFacet> facets);

  const PolygonSoup& soup_;
  Warnings& warnings_;
  MergeReport rep_;

  std::vector<Point3> pts_;              // merged, used points
  std::vector<int> first_index_;         // merged point -> first soup index
  std::vector<std::vector<int>> faces_;  // soup faces on merged points
  std::vector<std::array<int, 3>> tris_;
  std::vector<int> tri_face_;             // triangle -> soup face
  std::vector<std::array<int, 3>> nbr_;   // triangle across side k (k -> k+1)
  std::vector<std::vector<int>> shells_;  // connected components (triangles)
  std::vector<char> reversed_;            // triangle reversed from the input
};

void Builder::check_and_merge_points() {
  const auto& P = soup_.points;
  if (P.empty()) fail(InputErrorKind::empty, "the input has no points");
  if (soup_.faces.empty()) fail(InputErrorKind::empty, "the input has no faces");
  for (std::size_t i = 0; i < P.size(); ++i)
    for (double x : P[i])
      if (!std::isfinite(x))
        fail(InputErrorKind::non_finite, "point " + std::to_string(i) + " has a non-finite coordinate " + coords(P[i]));
  for (std::size_t f = 0; f < soup_.faces.size(); ++f) {
    const auto& face = soup_.faces[f];
    for (int v : face)
      if (v < 0 || static_cast<std::size_t>(v) >= P.size())
        fail(InputErrorKind::bad_index, face_name(static_cast<int>(f)) + " refers to point " + std::to_string(v) +
                                            ", but there are " + std::to_string(P.size()) + " points");
    if (face.size() < 3)
      fail(InputErrorKind::degenerate_face,
           face_name(static_cast<int>(f)) + " has only " + std::to_string(face.size()) + " vertices");
  }
  // Merge identical points (exact equality; -0 == +0) among the used ones.
  std::vector<char> used(P.size(), 0);
  for (const auto& face : soup_.faces)
    for (int v : face) used[v] = 1;
  std::vector<int> remap(P.size(), -1);
  std::unordered_map<Point3, int, PointHash> seen;
  std::size_t unused = 0, merged = 0;
  for (std::size_t i = 0; i < P.size(); ++i) {
    if (!used[i]) {
      ++unused;
      continue;
    }
    Point3 p = P[i];
    for (double& x : p) x += 0.0;
    auto [it, fresh] = seen.emplace(p, static_cast<int>(pts_.size()));
    if (fresh) {
      pts_.push_back(P[i]);
      first_index_.push_back(static_cast<int>(i));
    } else {
      ++merged;
    }
    remap[i] = it->second;
  }
  if (unused > 0) warnings_.push_back(std::to_string(unused) + " point(s) used by no face were dropped");
  if (merged > 0)
    warnings_.push_back(std::to_string(merged) +
                        " point(s) with the coordinates of an earlier point were merged into it");
  faces_.resize(soup_.faces.size());
  for (std::size_t f = 0; f < soup_.faces.size(); ++f)
    for (int v : soup_.faces[f]) faces_[f].push_back(remap[v]);
  rep_.points_read = P.size();
  rep_.vertices = pts_.size();
  rep_.faces_read = soup_.faces.size();
}

void Builder::check_faces() {
  // A repeated vertex (after merging) makes a face degenerate.
  for (std::size_t f = 0; f < faces_.size(); ++f) {
    std::vector<int> s = faces_[f];
    std::sort(s.begin(), s.end());
    auto d = std::adjacent_find(s.begin(), s.end());
    if (d != s.end())
      fail(InputErrorKind::degenerate_face, face_name(static_cast<int>(f)) + " uses " + vertex_name(*d) + " twice");
  }
  // Duplicate faces: the same vertex set.
  std::unordered_map<std::string, int> sets;
  for (std::size_t f = 0; f < faces_.size(); ++f) {
    std::vector<int> s = faces_[f];
    std::sort(s.begin(), s.end());
    std::string key(reinterpret_cast<const char*>(s.data()), s.size() * sizeof(int));
    auto [it, fresh] = sets.emplace(std::move(key), static_cast<int>(f));
    if (!fresh)
      fail(InputErrorKind::duplicate_face,
           face_name(it->second) + " and " + face_name(static_cast<int>(f)) + " have the same vertices");
  }
  std::set<std::pair<int, int>> edges;
  for (const auto& face : faces_)
    for (std::size_t i = 0; i < face.size(); ++i) {
      const int a = face[i], b = face[(i + 1) % face.size()];
      edges.emplace(std::min(a, b), std::max(a, b));
    }
  rep_.edges_before = edges.size();
}

void Builder::triangulate() {
  std::vector<int> split;
  for (std::size_t f = 0; f < faces_.size(); ++f) {
    const auto& face = faces_[f];
    const int n = static_cast<int>(face.size());
    // Three vertices not on one line, exactly; none means zero area.
    int c = -1;
    const auto p0 = to_cgal(pts_[face[0]]), p1 = to_cgal(pts_[face[1]]);
    for (int i = 2; i < n && c < 0; ++i)
      if (!CGAL::collinear(p0, p1, to_cgal(pts_[face[i]]))) c = i;
    if (c < 0)
      fail(InputErrorKind::degenerate_face,
           face_name(static_cast<int>(f)) + " has zero area: its vertices are collinear, e.g. " + vertex_name(face[0]) +
               ", " + vertex_name(face[1]) + ", " + vertex_name(face[2]));
    if (n == 3) {
      tris_.push_back({face[0], face[1], face[2]});
      tri_face_.push_back(static_cast<int>(f));
      continue;
    }
    bool planar = true;
    const auto pc = to_cgal(pts_[face[c]]);
    for (int i = 2; i < n && planar; ++i)
      if (i != c && CGAL::orientation(p0, p1, pc, to_cgal(pts_[face[i]])) != CGAL::COPLANAR) planar = false;
    std::vector<std::array<int, 3>> out;
    if (!validation::triangulate_polygon(pts_, face, out))
      fail(InputErrorKind::self_intersection,
           face_name(static_cast<int>(f)) + " is a polygon whose boundary crosses itself");
    // A planar polygon's triangles are merged back into one facet later; a
    // non-planar one keeps them as facets of their own.
    if (!planar) split.push_back(static_cast<int>(f));
    for (const auto& t : out) {
      tris_.push_back(t);
      tri_face_.push_back(static_cast<int>(f));
    }
  }
  rep_.faces_split = split.size();
  if (!split.empty()) {
    std::string list;
    for (std::size_t i = 0; i < split.size() && i < 5; ++i) list += (i ? ", " : "") + face_name(split[i]);
    if (split.size() > 5) list += ", ...";
    warnings_.push_back(std::to_string(split.size()) + " non-planar polygon(s) were split into triangles: " + list);
  }
}

void Builder::build_adjacency() {
  std::vector<HalfEdge> hes;
  hes.reserve(tris_.size() * 3);
  for (std::size_t t = 0; t < tris_.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = tris_[t][k], b = tris_[t][(k + 1) % 3];
      hes.push_back({std::min(a, b), std::max(a, b), static_cast<int>(t), k});
    }
  std::sort(hes.begin(), hes.end(), [](const HalfEdge& x, const HalfEdge& y) {
    return std::tie(x.lo, x.hi, x.t, x.k) < std::tie(y.lo, y.hi, y.t, y.k);
  });
  nbr_.assign(tris_.size(), {{-1, -1, -1}});
  std::vector<std::pair<std::size_t, std::size_t>> groups;
  for (std::size_t i = 0; i < hes.size();) {
    std::size_t j = i;
    while (j < hes.size() && hes[j].lo == hes[i].lo && hes[j].hi == hes[i].hi) ++j;
    groups.emplace_back(i, j);
    i = j;
  }
  auto faces_of = [&](std::size_t i, std::size_t j) {
    std::string s;
    for (std::size_t k = i; k < j && k < i + 6; ++k) s += (k > i ? ", " : "") + tri_name(hes[k].t);
    if (j - i > 6) s += ", ...";
    return s;
  };
  for (auto [i, j] : groups)
    if (j - i > 2)
      fail(InputErrorKind::non_manifold_edge, "non-manifold " + edge_name(hes[i].lo, hes[i].hi) + ": it is in " +
                                                  std::to_string(j - i) + " faces: " + faces_of(i, j));
  for (auto [i, j] : groups)
    if (j - i == 1)
      fail(InputErrorKind::open_boundary,
           "open boundary: the " + edge_name(hes[i].lo, hes[i].hi) + " is in only one face, " + tri_name(hes[i].t));
  if (faces_.size() < 4)
    fail(InputErrorKind::too_few_faces,
         "only " + std::to_string(faces_.size()) + " faces: a polyhedron needs at least 4");
  for (auto [i, j] : groups) {
    (void)j;
    nbr_[hes[i].t][hes[i].k] = hes[i + 1].t;
    nbr_[hes[i + 1].t][hes[i + 1].k] = hes[i].t;
  }
}

/// Index of corner v in triangle t.
int corner_of(const std::array<int, 3>& t, int v) { return t[0] == v ? 0 : t[1] == v ? 1 : 2; }

void Builder::check_vertex_fans() {
  // Corners around a vertex joined across its edges: one fan means one class.
  UnionFind uf(tris_.size() * 3);
  for (std::size_t t = 0; t < tris_.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int s = nbr_[t][k];
      for (int v : {tris_[t][k], tris_[t][(k + 1) % 3]})
        uf.unite(static_cast<int>(3 * t) + corner_of(tris_[t], v), 3 * s + corner_of(tris_[s], v));
    }
  std::vector<int> root(pts_.size(), -1);
  for (std::size_t t = 0; t < tris_.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int v = tris_[t][k];
      const int r = uf.find(static_cast<int>(3 * t + k));
      if (root[v] < 0) {
        root[v] = r;
      } else if (root[v] != r) {
        fail(InputErrorKind::non_manifold_vertex,
             "non-manifold " + vertex_name(v) + ": the faces around it form more than one fan (e.g. " +
                 tri_name(root[v] / 3) + " and " + tri_name(static_cast<int>(t)) + " are not connected around it)");
      }
    }
}

void Builder::orient() {
  // Breadth-first over edge adjacency: a neighbour must traverse the common
  // edge the other way.
  const std::size_t n = tris_.size();
  std::vector<int> flip(n, -1);
  std::vector<int> queue;
  for (std::size_t s = 0; s < n; ++s) {
    if (flip[s] >= 0) continue;
    flip[s] = 0;
    queue.assign(1, static_cast<int>(s));
    for (std::size_t qi = 0; qi < queue.size(); ++qi) {
      const int t = queue[qi];
      for (int k = 0; k < 3; ++k) {
        const int a = tris_[t][k], b = tris_[t][(k + 1) % 3];
        const int o = nbr_[t][k];
        const int j = corner_of(tris_[o], a);
        const bool same_way = tris_[o][(j + 1) % 3] == b;  // also a -> b
        const int want = flip[t] ^ (same_way ? 1 : 0);
        if (flip[o] < 0) {
          flip[o] = want;
          queue.push_back(o);
        } else if (flip[o] != want) {
          fail(InputErrorKind::not_orientable, "the surface is not orientable: no orientation of " + tri_name(t) +
                                                   " and " + tri_name(o) + " agrees along the " + edge_name(a, b));
        }
      }
    }
    shells_.push_back(queue);
    // Keep the orientation of the majority of this component's triangles.
    std::size_t flipped = 0;
    for (int t : queue) flipped += static_cast<std::size_t>(flip[t]);
    if (2 * flipped > queue.size())
      for (int t : queue) flip[t] ^= 1;
  }
  std::vector<char> face_flipped(faces_.size(), 0);
  reversed_.assign(n, 0);
  for (std::size_t t = 0; t < n; ++t)
    if (flip[t]) {
      std::swap(tris_[t][1], tris_[t][2]);
      face_flipped[tri_face_[t]] = 1;
      reversed_[t] = 1;
    }
  // Sides changed: neighbours of side k are now those of the reversed side.
  for (std::size_t t = 0; t < n; ++t)
    if (flip[t]) nbr_[t] = {nbr_[t][2], nbr_[t][1], nbr_[t][0]};
  const auto count = static_cast<std::size_t>(std::count(face_flipped.begin(), face_flipped.end(), 1));
  if (count > 0)
    warnings_.push_back(std::to_string(count) + " face(s) were reversed to orient the surface consistently");
}

/// Winding number of the closed triangulated shell `tris` around p (not on
/// it), from the solid angles of its triangles (van Oosterom and Strackee).
/// Rounded arithmetic: only its distance from 0 matters (0 outside, +-1 inside).
/// Coordinates are multiplied by `scale` first, a power of two that keeps
/// their differences and products finite (validation::power_of_two_scale of
/// the largest coordinate).
double winding_number(const std::vector<Point3>& pts, const std::vector<std::array<int, 3>>& all,
                      const std::vector<int>& tris, const Point3& p, double scale) {
  double total = 0;
  for (int t : tris) {
    double v[3][3], len[3];
    for (int c = 0; c < 3; ++c) {
      for (int k = 0; k < 3; ++k) v[c][k] = pts[all[t][c]][k] * scale - p[k] * scale;
      len[c] = std::sqrt(v[c][0] * v[c][0] + v[c][1] * v[c][1] + v[c][2] * v[c][2]);
    }
    auto dot3 = [](const double* x, const double* y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; };
    const double det = v[0][0] * (v[1][1] * v[2][2] - v[1][2] * v[2][1]) -
                       v[0][1] * (v[1][0] * v[2][2] - v[1][2] * v[2][0]) +
                       v[0][2] * (v[1][0] * v[2][1] - v[1][1] * v[2][0]);
    const double den =
        len[0] * len[1] * len[2] + dot3(v[0], v[1]) * len[2] + dot3(v[0], v[2]) * len[1] + dot3(v[1], v[2]) * len[0];
    total += 2 * std::atan2(det, den);
  }
  return total / (4 * geometry::kPi);
}

void Builder::orient_outwards() {
  // The exact sign of six times the volume enclosed by each shell: the sum
  // over its triangles of det(p0 - o, p1 - o, p2 - o), o a vertex.
  const std::size_t k = shells_.size();
  std::vector<int> sign(k);
  for (std::size_t c = 0; c < k; ++c) {
    const auto& shell = shells_[c];
    const Point3 o = pts_[tris_[shell[0]][0]];
    sign[c] = exact::sign([&](auto z) {
      using NT = decltype(z);
      NT sum = z;
      for (int t : shell) {
        NT a[3], b[3], d[3];
        for (int i = 0; i < 3; ++i) {
          a[i] = NT(pts_[tris_[t][0]][i]) - NT(o[i]);
          b[i] = NT(pts_[tris_[t][1]][i]) - NT(o[i]);
          d[i] = NT(pts_[tris_[t][2]][i]) - NT(o[i]);
        }
        sum = sum + a[0] * (b[1] * d[2] - b[2] * d[1]) - a[1] * (b[0] * d[2] - b[2] * d[0]) +
              a[2] * (b[0] * d[1] - b[1] * d[0]);
      }
      return sum;
    });
    if (sign[c] == 0)
      fail(InputErrorKind::zero_volume, "the closed surface through " + tri_name(shell[0]) + " encloses zero volume");
  }
  // A shell inside an odd number of others bounds a cavity: it must face
  // inwards (negative volume); the others outwards. Shells do not intersect
  // (checked before), so one vertex tells whether a shell is inside another.
  std::vector<std::array<double, 6>> box(k);
  for (std::size_t c = 0; c < k; ++c) {
    box[c] = {HUGE_VAL, HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (int t : shells_[c])
      for (int v : tris_[t])
        for (int i = 0; i < 3; ++i) {
          box[c][i] = std::min(box[c][i], pts_[v][i]);
          box[c][3 + i] = std::max(box[c][3 + i], pts_[v][i]);
        }
  }
  double big = 0;
  for (const Point3& q : pts_)
    for (double x : q) big = std::max(big, std::fabs(x));
  const double scale = validation::power_of_two_scale(big);
  std::size_t flipped = 0;
  bool outer_inwards = false;
  for (std::size_t c = 0; c < k; ++c) {
    int depth = 0;
    const Point3& p = pts_[tris_[shells_[c][0]][0]];
    for (std::size_t d = 0; d < k && k > 1; ++d) {
      if (d == c) continue;
      bool in_box = true;
      for (int i = 0; i < 3; ++i) in_box &= box[d][i] <= p[i] && p[i] <= box[d][3 + i];
      if (in_box && std::fabs(winding_number(pts_, tris_, shells_[d], p, scale)) > 0.5) ++depth;
    }
    const int want = depth % 2 == 0 ? 1 : -1;
    if (sign[c] == want) continue;
    if (depth == 0) outer_inwards = true;
    for (int t : shells_[c]) {
      std::swap(tris_[t][1], tris_[t][2]);
      nbr_[t] = {nbr_[t][2], nbr_[t][1], nbr_[t][0]};
      reversed_[t] ^= 1;
      ++flipped;
    }
  }
  if (flipped > 0) {
    warnings_.push_back(outer_inwards && k == 1 ? "the surface was oriented inwards; all faces were reversed"
                                                : std::to_string(flipped) +
                                                      " triangle(s) of closed surfaces oriented the wrong way "
                                                      "(inwards, or outwards around a cavity) were reversed");
  }
  // Input faces that now run the other way (their triangles turn together).
  std::vector<char> face_reversed(faces_.size(), 0);
  for (std::size_t t = 0; t < tris_.size(); ++t)
    if (reversed_[t]) face_reversed[tri_face_[t]] = 1;
  rep_.faces_flipped = static_cast<std::size_t>(std::count(face_reversed.begin(), face_reversed.end(), 1));
}

std::vector<PlcFacet> Builder::merge_coplanar() {
  const std::size_t n = tris_.size();
  UnionFind uf(n);
  for (std::size_t t = 0; t < n; ++t)
    for (int k = 0; k < 3; ++k) {
      const int o = nbr_[t][k];
      if (o < static_cast<int>(t)) continue;
      const auto& T = tris_[t];
      int w = -1;
      for (int v : tris_[o])
        if (v != T[0] && v != T[1] && v != T[2]) w = v;
      // Consistently oriented and not folded (checked before): coplanar
      // neighbours face the same way.
      if (CGAL::orientation(to_cgal(pts_[T[0]]), to_cgal(pts_[T[1]]), to_cgal(pts_[T[2]]), to_cgal(pts_[w])) ==
          CGAL::COPLANAR)
        uf.unite(static_cast<int>(t), o);
    }
  std::vector<int> facet_of(n, -1);
  std::vector<PlcFacet> facets;
  std::vector<std::vector<int>> members;
  for (std::size_t t = 0; t < n; ++t) {
    const int r = uf.find(static_cast<int>(t));
    if (facet_of[r] < 0) {
      facet_of[r] = static_cast<int>(facets.size());
      facets.emplace_back();
      members.emplace_back();
    }
    facet_of[t] = facet_of[r];
    members[facet_of[t]].push_back(static_cast<int>(t));
  }
  // Trace the boundary of every facet: the sides whose neighbour lies in
  // another facet, in the orientation of the triangles (outer loop
  // counter-clockwise from outside, holes clockwise).
  std::vector<std::array<char, 3>> done(n, {{0, 0, 0}});
  for (std::size_t f = 0; f < facets.size(); ++f) {
    PlcFacet& F = facets[f];
    std::vector<std::array<int, 3>> tris;
    for (int t : members[f]) {
      F.source_faces.push_back(tri_face_[t]);
      tris.push_back(tris_[t]);
    }
    std::sort(F.source_faces.begin(), F.source_faces.end());
    F.source_faces.erase(std::unique(F.source_faces.begin(), F.source_faces.end()), F.source_faces.end());
    F.normal = validation::unit_area_vector(pts_, tris);
    for (int t0 : members[f])
      for (int k0 = 0; k0 < 3; ++k0) {
        if (done[t0][k0] || facet_of[nbr_[t0][k0]] == static_cast<int>(f)) continue;
        std::vector<int> loop;
        int t = t0, k = k0;
        std::size_t guard = 0;
        while (!done[t][k]) {
          done[t][k] = 1;
          loop.push_back(tris_[t][k]);
          // From the end v of side k, turn around v inside the facet until a
          // side leaves it.
          const int v = tris_[t][(k + 1) % 3];
          int tt = t, kk = (k + 1) % 3;
          while (facet_of[nbr_[tt][kk]] == static_cast<int>(f)) {
            const int o = nbr_[tt][kk];
            kk = corner_of(tris_[o], v);  // side v -> next in o
            tt = o;
            if (++guard > 4 * n + 8)
              fail(InputErrorKind::non_manifold_vertex, "cannot trace the boundary around " + vertex_name(v));
          }
          t = tt;
          k = kk;
        }
        if (loop.size() < 3)
          fail(InputErrorKind::self_intersection,
               "a facet boundary made of coplanar faces around " + tri_name(t0) + " has fewer than 3 vertices");
        F.loops.push_back(std::move(loop));
      }
    // The lexicographically smallest vertex of a planar region is on its outer
    // boundary.
    std::size_t outer = 0;
    const Point3* best = nullptr;
    for (std::size_t l = 0; l < F.loops.size(); ++l)
      for (int v : F.loops[l])
        if (!best || pts_[v] < *best) {
          best = &pts_[v];
          outer = l;
        }
    if (outer != 0) std::swap(F.loops[0], F.loops[outer]);
  }
  return facets;
}

PLC Builder::finish(std::vector<PlcFacet> facets) {
  // PLC edges are the loop sides; neighbours of every vertex along them.
  std::vector<std::vector<int>> adj(pts_.size());
  for (const auto& F : facets)
    for (const auto& loop : F.loops)
      for (std::size_t i = 0; i < loop.size(); ++i) {
        const int a = loop[i], b = loop[(i + 1) % loop.size()];
        adj[a].push_back(b);
        adj[b].push_back(a);
      }
  // A vertex with exactly two edges whose other ends are exactly collinear
  // with it lies inside the edge they form: remove it.
  std::vector<char> drop(pts_.size(), 0);
  std::size_t in_edge = 0;
  for (std::size_t v = 0; v < pts_.size(); ++v) {
    auto& a = adj[v];
    std::sort(a.begin(), a.end());
    a.erase(std::unique(a.begin(), a.end()), a.end());
    if (a.size() == 2 && CGAL::collinear(to_cgal(pts_[a[0]]), to_cgal(pts_[v]), to_cgal(pts_[a[1]]))) {
      drop[v] = 1;
      ++in_edge;
    }
  }
  std::vector<int> newid(pts_.size(), -1);
  PLC plc;
  for (auto& F : facets)
    for (auto& loop : F.loops) {
      loop.erase(std::remove_if(loop.begin(), loop.end(), [&](int v) { return drop[v] != 0; }), loop.end());
      for (int v : loop) newid[v] = 0;
    }
  for (std::size_t v = 0; v < pts_.size(); ++v)
    if (newid[v] == 0) {
      newid[v] = static_cast<int>(plc.vertices.size());
      plc.vertices.push_back(pts_[v]);
    }
  std::map<std::pair<int, int>, int> edge_index;
  for (std::size_t f = 0; f < facets.size(); ++f)
    for (auto& loop : facets[f].loops) {
      for (int& v : loop) v = newid[v];
      for (std::size_t i = 0; i < loop.size(); ++i) {
        const int a = loop[i], b = loop[(i + 1) % loop.size()];
        auto [it, fresh] =
            edge_index.emplace(std::make_pair(std::min(a, b), std::max(a, b)), static_cast<int>(plc.edges.size()));
        if (fresh) {
          PlcEdge e;
          e.a = std::min(a, b);
          e.b = std::max(a, b);
          plc.edges.push_back(e);
        }
        PlcEdge& e = plc.edges[it->second];
        // facets[0] runs a -> b (a < b) in its loop, facets[1] runs b -> a.
        int& slot = e.facets[a < b ? 0 : 1];
        if (slot >= 0)
          fail(InputErrorKind::self_intersection, "the edge from " + coords(plc.vertices[e.a]) + " to " +
                                                      coords(plc.vertices[e.b]) +
                                                      " is traversed twice the same way by the facet boundaries");
        slot = static_cast<int>(f);
      }
    }
  for (const auto& e : plc.edges)
    if (e.facets[0] < 0 || e.facets[1] < 0)
      fail(InputErrorKind::open_boundary, "the edge from " + coords(plc.vertices[e.a]) + " to " +
                                              coords(plc.vertices[e.b]) + " bounds only one facet");
  plc.facets = std::move(facets);
  rep_.facets = plc.facets.size();
  rep_.edges = plc.edges.size();
  rep_.vertices_removed = pts_.size() - plc.vertices.size();
  if (rep_.vertices_removed > 0)
    warnings_.push_back(std::to_string(rep_.vertices_removed) + " vertex(es) inside a facet or an edge were removed (" +
                        std::to_string(in_edge) + " inside an edge)");
  return plc;
}

PLC Builder::run(MergeReport& rep) {
  check_and_merge_points();
  check_faces();
  triangulate();
  build_adjacency();
  check_vertex_fans();
  orient();
  validation::check_self_intersections(pts_, tris_, [&](int t) { return tri_name(t); });
  orient_outwards();
  PLC plc = finish(merge_coplanar());
  rep = rep_;
  return plc;
}

}  // namespace

PLC build_plc(const PolygonSoup& soup, Warnings& warnings, MergeReport* report) {
  Builder b(soup, warnings);
  MergeReport rep;
  PLC plc = b.run(rep);
  if (report) *report = rep;
  return plc;
}

}  // namespace wqmesh
