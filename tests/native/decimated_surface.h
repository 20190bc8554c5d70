// Generated test inputs: closed surfaces triangulated finely (a sphere, a
// torus, blended blobs), decimated by random half-edge collapses down to a
// few hundred vertices and perturbed, as decimated scans are: long thin
// triangles, vertices of high valence, small input angles, and every triangle
// tilted its own way (no two adjacent triangles coplanar, so every triangle
// is a facet of its own). Deterministic: the same Config gives the same
// surface on every platform (std::mt19937_64 and only + - * / sqrt on
// doubles; no std:: distribution, whose output the standard leaves open).
// Also the helpers other generated inputs share: subdivision on the unit
// sphere, OFF text.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iterator>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "geometry.h"
#include "wqmesh/types.h"

namespace wqmesh::testing {

enum class Shape { sphere, torus, blobs };

struct DecimationConfig {
  Shape shape = Shape::sphere;
  std::uint64_t seed = 1;
  int target_vertices = 500;  ///< collapse until this many vertices remain
  /// Each vertex moves by up to this fraction of the mean edge length after
  /// decimation (in each coordinate).
  double perturbation = 0.05;
  /// A collapse is refused when it turns a triangle's normal by more than
  /// this (cosine of the largest turn), so that the surface stays embedded.
  double min_normal_cos = 0.3;
};

inline const char* shape_name(Shape s) { return s == Shape::sphere ? "sphere" : s == Shape::torus ? "torus" : "blobs"; }

inline std::string describe(const DecimationConfig& c) {
  char text[160];
  std::snprintf(text, sizeof text, "%s seed %llu, %d vertices, perturbation %g, normal cos %g", shape_name(c.shape),
                static_cast<unsigned long long>(c.seed), c.target_vertices, c.perturbation, c.min_normal_cos);
  return text;
}

struct TriSurface {
  std::vector<Point3> points;
  std::vector<std::array<int, 3>> faces;  ///< counter-clockwise seen from outside
};

/// p / |p| (|p| = sqrt(p.p), then each coordinate divided by it).
inline Point3 on_unit_sphere(const Point3& p) {
  const double l = std::sqrt(geometry::dot(p, p));
  return Point3{{p[0] / l, p[1] / l, p[2] / l}};
}

/// `s` (a triangulated polyhedron around the origin, faces counter-clockwise
/// seen from outside) with its points moved to the unit sphere, then
/// subdivided `levels` times: each triangle into four, each edge's midpoint
/// (p + q) / 2 moved to the sphere. This exact arithmetic makes the regression
/// seeds of regression_test.cpp (icosphere) the surfaces that crashed the old
/// code; the fuzz target's octasphere uses it too.
inline TriSurface subdivided_on_unit_sphere(TriSurface s, int levels) {
  for (Point3& p : s.points) p = on_unit_sphere(p);
  for (int k = 0; k < levels; ++k) {
    std::map<std::pair<int, int>, int> middle;
    auto mid = [&](int a, int b) {
      const std::pair<int, int> key{std::min(a, b), std::max(a, b)};
      const auto it = middle.find(key);
      if (it != middle.end()) return it->second;
      const Point3 &p = s.points[a], &q = s.points[b];
      s.points.push_back(on_unit_sphere({{(p[0] + q[0]) / 2, (p[1] + q[1]) / 2, (p[2] + q[2]) / 2}}));
      return middle[key] = static_cast<int>(s.points.size()) - 1;
    };
    std::vector<std::array<int, 3>> faces;
    for (const auto& f : s.faces) {
      const int a = f[0], b = f[1], c = f[2];
      const int ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
      faces.push_back({{a, ab, ca}});
      faces.push_back({{b, bc, ab}});
      faces.push_back({{c, ca, bc}});
      faces.push_back({{ab, bc, ca}});
    }
    s.faces = faces;
  }
  return s;
}

/// An OFF file of `points` and `faces` (each a sequence of vertex indices,
/// any number of them): coordinates with 17 significant digits, so that they
/// read back exactly.
template <class Faces>
std::string to_off(const std::vector<Point3>& points, const Faces& faces) {
  std::ostringstream out;
  out << "OFF\n" << points.size() << " " << faces.size() << " 0\n";
  char buf[96];
  for (const Point3& p : points) {
    std::snprintf(buf, sizeof buf, "%.17g %.17g %.17g\n", p[0], p[1], p[2]);
    out << buf;
  }
  for (const auto& f : faces) {
    out << f.size();
    for (int v : f) out << " " << v;
    out << "\n";
  }
  return out.str();
}

/// The icosahedron subdivided `levels` times, on the unit sphere.
inline TriSurface icosphere(int levels) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  TriSurface s;
  s.points = {{{-1, t, 0}},  {{1, t, 0}},  {{-1, -t, 0}}, {{1, -t, 0}}, {{0, -1, t}},  {{0, 1, t}},
              {{0, -1, -t}}, {{0, 1, -t}}, {{t, 0, -1}},  {{t, 0, 1}},  {{-t, 0, -1}}, {{-t, 0, 1}}};
  s.faces = {{{0, 11, 5}},  {{0, 5, 1}},  {{0, 1, 7}},  {{0, 7, 10}}, {{0, 10, 11}}, {{1, 5, 9}}, {{5, 11, 4}},
             {{11, 10, 2}}, {{10, 7, 6}}, {{7, 1, 8}},  {{3, 9, 4}},  {{3, 4, 2}},   {{3, 2, 6}}, {{3, 6, 8}},
             {{3, 8, 9}},   {{4, 9, 5}},  {{2, 4, 11}}, {{6, 2, 10}}, {{8, 6, 7}},   {{9, 8, 1}}};
  return subdivided_on_unit_sphere(s, levels);
}

namespace detail {

/// A uniform double in [0, 1) from the top 53 bits.
inline double uniform(std::mt19937_64& rng) { return double(rng() >> 11) * (1.0 / 9007199254740992.0); }

/// A torus (radii 1 and 0.4) on an n x m grid.
inline TriSurface torus(int n, int m) {
  TriSurface s;
  const double pi = geometry::kPi;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const double u = 2 * pi * i / n, v = 2 * pi * j / m;
      const double r = 1 + 0.4 * std::cos(v);
      s.points.push_back({{r * std::cos(u), r * std::sin(u), 0.4 * std::sin(v)}});
    }
  auto id = [&](int i, int j) { return ((i + n) % n) * m + (j + m) % m; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      s.faces.push_back({{id(i, j), id(i + 1, j), id(i + 1, j + 1)}});
      s.faces.push_back({{id(i, j), id(i + 1, j + 1), id(i, j + 1)}});
    }
  return s;
}

/// The unit sphere pushed out by a sum of Gaussian bumps (blended blobs).
inline TriSurface blobs(std::mt19937_64& rng) {
  TriSurface s = icosphere(5);
  std::vector<std::pair<Point3, double>> bumps;
  for (int k = 0; k < 5; ++k) {
    Point3 c{{2 * uniform(rng) - 1, 2 * uniform(rng) - 1, 2 * uniform(rng) - 1}};
    const double l = std::sqrt(geometry::dot(c, c));
    if (l == 0) continue;
    for (double& x : c) x /= l;
    bumps.push_back({c, 0.3 + 0.6 * uniform(rng)});
  }
  for (Point3& p : s.points) {
    double r = 1;
    for (const auto& [c, a] : bumps) {
      const Point3 d = geometry::sub(p, c);
      r += a * std::exp(-geometry::dot(d, d) / 0.25);
    }
    for (double& x : p) x *= r;
  }
  return s;
}

}  // namespace detail

/// The decimated, perturbed surface of `c`.
inline TriSurface decimated_surface(const DecimationConfig& c) {
  using namespace detail;
  std::mt19937_64 rng(c.seed * 0x9E3779B97F4A7C15ull + static_cast<std::uint64_t>(c.shape));
  TriSurface s = c.shape == Shape::sphere ? icosphere(5) : c.shape == Shape::torus ? torus(120, 48) : blobs(rng);
  const int nv = static_cast<int>(s.points.size());
  std::vector<std::vector<int>> vf(nv);  // faces at each vertex
  std::vector<char> face_alive(s.faces.size(), 1), vertex_alive(nv, 1);
  for (int f = 0; f < static_cast<int>(s.faces.size()); ++f)
    for (int v : s.faces[f]) vf[v].push_back(f);
  auto neighbours = [&](int v) {
    std::vector<int> out;
    for (int f : vf[v])
      for (int x : s.faces[f])
        if (x != v) out.push_back(x);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  };
  auto normal = [&](const std::array<int, 3>& t) {
    return geometry::cross(geometry::sub(s.points[t[1]], s.points[t[0]]),
                           geometry::sub(s.points[t[2]], s.points[t[0]]));
  };
  // Half-edge collapse a -> b: a disappears, its triangles take b instead.
  auto try_collapse = [&](int a, int b) {
    const std::vector<int> na = neighbours(a), nb = neighbours(b);
    std::vector<int> common;
    std::set_intersection(na.begin(), na.end(), nb.begin(), nb.end(), std::back_inserter(common));
    if (common.size() != 2) return false;  // the link condition
    for (int x : common)
      if (neighbours(x).size() <= 3) return false;
    if (nb.size() + na.size() > 40) return false;
    for (int f : vf[a]) {
      std::array<int, 3> t = s.faces[f];
      if (t[0] == b || t[1] == b || t[2] == b) continue;
      const Point3 n0 = normal(t);
      for (int& x : t)
        if (x == a) x = b;
      const Point3 n1 = normal(t);
      const double l0 = std::sqrt(geometry::dot(n0, n0)), l1 = std::sqrt(geometry::dot(n1, n1));
      if (!(l1 > 1e-9 * l0) || geometry::dot(n0, n1) < c.min_normal_cos * l0 * l1) return false;
    }
    for (int f : vf[a]) {
      std::array<int, 3>& t = s.faces[f];
      if (t[0] == b || t[1] == b || t[2] == b) {
        face_alive[f] = 0;
        for (int x : t) {
          auto& l = vf[x];
          if (x != a) l.erase(std::remove(l.begin(), l.end(), f), l.end());
        }
        continue;
      }
      for (int& x : t)
        if (x == a) x = b;
      vf[b].push_back(f);
    }
    vf[a].clear();
    vertex_alive[a] = 0;
    return true;
  };
  int alive = nv, misses = 0;
  while (alive > c.target_vertices && misses < 100000) {
    // A random triangle and one of its edges, collapsed either way.
    const int f = static_cast<int>(rng() % s.faces.size());
    if (!face_alive[f]) continue;
    const int k = static_cast<int>(rng() % 3);
    int a = s.faces[f][k], b = s.faces[f][(k + 1) % 3];
    if (rng() & 1) std::swap(a, b);
    if (try_collapse(a, b))
      --alive;
    else
      ++misses;
  }
  // Compact, then perturb by a fraction of the mean edge length.
  TriSurface out;
  std::vector<int> index(nv, -1);
  for (int v = 0; v < nv; ++v)
    if (vertex_alive[v]) {
      index[v] = static_cast<int>(out.points.size());
      out.points.push_back(s.points[v]);
    }
  double total = 0;
  std::size_t edges = 0;
  for (std::size_t f = 0; f < s.faces.size(); ++f) {
    if (!face_alive[f]) continue;
    const auto& t = s.faces[f];
    out.faces.push_back({{index[t[0]], index[t[1]], index[t[2]]}});
    for (int i = 0; i < 3; ++i) {
      const Point3 d = geometry::sub(s.points[t[i]], s.points[t[(i + 1) % 3]]);
      total += std::sqrt(geometry::dot(d, d));
      ++edges;
    }
  }
  const double h = c.perturbation * (edges ? total / edges : 0);
  for (Point3& p : out.points)
    for (double& x : p) x += h * (2 * uniform(rng) - 1);
  return out;
}

inline std::string to_off(const TriSurface& s) { return to_off(s.points, s.faces); }

}  // namespace wqmesh::testing
