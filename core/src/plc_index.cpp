// wqmesh: the index of a PLC, built once (see plc_index.h).
// SPDX-License-Identifier: GPL-3.0-or-later
#include "plc_index.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "geometry.h"

namespace wqmesh {

using namespace geometry;

void PlcIndex::extend(const PLC& plc) {
  const std::size_t nv = plc.vertices.size();
  vertex_edges.resize(nv);
  vertex_facets.resize(nv);
  vertex_corners.resize(nv);
  for (std::size_t e = indexed_edges; e < plc.edges.size(); ++e) {
    vertex_edges[plc.edges[e].a].push_back(static_cast<int>(e));
    vertex_edges[plc.edges[e].b].push_back(static_cast<int>(e));
  }
  // Facets in increasing order, so each vertex's list is sorted, and all the
  // corners of one facet at a vertex come one after the other: the first one
  // (by loop, then position) is kept.
  for (std::size_t f = indexed_facets; f < plc.facets.size(); ++f) {
    const auto& loops = plc.facets[f].loops;
    for (std::size_t l = 0; l < loops.size(); ++l)
      for (std::size_t r = 0; r < loops[l].size(); ++r) {
        const int v = loops[l][r];
        if (!vertex_facets[v].empty() && vertex_facets[v].back() == static_cast<int>(f)) continue;
        vertex_facets[v].push_back(static_cast<int>(f));
        vertex_corners[v].push_back({static_cast<int>(f), static_cast<int>(l), static_cast<int>(r)});
      }
  }

  frames.resize(plc.facets.size());
  for (std::size_t f = indexed_facets; f < plc.facets.size(); ++f) {
    Frame& fr = frames[f];
    const auto& facet = plc.facets[f];
    if (!facet.loops.empty() && facet.loops[0].size() >= 3) {
      const auto& loop = facet.loops[0];
      fr.origin = plc.vertices[loop[0]];
      // Newell's normal of the outer loop (robust for non-convex facets).
      fr.n = unit(newell_normal(plc.vertices, loop));
      fr.e1 = unit(sub(plc.vertices[loop[1]], fr.origin));
      fr.e1 = unit(sub(fr.e1, mul(fr.n, dot(fr.e1, fr.n))));
      fr.e2 = cross(fr.n, fr.e1);
      fr.area = fan_area_vector(plc.vertices, loop);
      const double len = std::sqrt(dot(fr.area, fr.area));
      if (len > 0)
        for (int k = 0; k < 3; ++k) fr.plane_n[k] = fr.area[k] / len;
    }
    for (const auto& l : facet.loops) {
      fr.loops.emplace_back();
      for (int v : l) fr.loops.back().push_back(to2d(static_cast<int>(f), plc.vertices[v]));
    }
  }
  indexed_vertices = nv;
  indexed_edges = plc.edges.size();
  indexed_facets = plc.facets.size();
  fingerprint_ = fingerprint(plc);
}

std::array<double, 2> PlcIndex::to2d(int f, const Point3& x) const {
  const Frame& fr = frames[f];
  const Point3 d = sub(x, fr.origin);
  return {{dot(d, fr.e1), dot(d, fr.e2)}};
}

bool PlcIndex::inside_facet(int f, const Point3& x) const {
  const std::array<double, 2> q = to2d(f, x);
  bool inside = false;
  for (const auto& loop : frames[f].loops) {
    const std::size_t n = loop.size();
    for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
      const auto &a = loop[i], &b = loop[j];
      if ((a[1] > q[1]) != (b[1] > q[1])) {
        const double x_cross = a[0] + (q[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1]);
        if (q[0] < x_cross) inside = !inside;
      }
    }
  }
  return inside;
}

bool PlcIndex::facet_has_vertex(int f, int v) const {
  return std::binary_search(vertex_facets[v].begin(), vertex_facets[v].end(), f);
}

std::uint64_t PlcIndex::fingerprint(const PLC& plc) {
  // FNV-1a over 64-bit words (the same on every platform).
  std::uint64_t h = 14695981039346656037ull;
  auto mix = [&h](std::uint64_t w) {
    for (int i = 0; i < 8; ++i, w >>= 8) h = (h ^ (w & 0xff)) * 1099511628211ull;
  };
  mix(plc.vertices.size());
  for (const Point3& p : plc.vertices)
    for (double x : p) {
      std::uint64_t bits;
      std::memcpy(&bits, &x, sizeof bits);
      mix(bits);
    }
  mix(plc.edges.size());
  for (const PlcEdge& e : plc.edges) mix(static_cast<std::uint64_t>(e.a) << 32 ^ static_cast<std::uint32_t>(e.b));
  mix(plc.facets.size());
  for (const PlcFacet& f : plc.facets) {
    mix(f.loops.size());
    for (const auto& loop : f.loops) {
      mix(loop.size());
      for (int v : loop) mix(static_cast<std::uint32_t>(v));
    }
  }
  return h;
}

bool PlcIndex::built_from(const PLC& plc) const {
  return indexed_vertices == plc.vertices.size() && indexed_edges == plc.edges.size() &&
         indexed_facets == plc.facets.size() && fingerprint_ == fingerprint(plc);
}

}  // namespace wqmesh
