// SPDX-License-Identifier: GPL-3.0-or-later
// wqmesh: what the libFuzzer targets of tests/fuzz check on a successful read
// (private to the fuzz targets). A broken contract aborts, which libFuzzer
// reports as a crash with the input that caused it.
#pragma once

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "wqmesh/types.h"

namespace wqmesh::fuzz {

/// Aborts with `what` on stderr when `ok` is false (also with NDEBUG).
inline void require(bool ok, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "wqmesh fuzz: broken contract: %s\n", what);
  std::abort();
}

/// The soup a reader returned keeps the contract of types.h and input.h:
/// one line per face, every face of at least `min_face` indices into
/// `points` (OFF allows faces of 0, 1 or 2 vertices, left to build_plc to
/// reject; an STL facet has 3 or more), and finite coordinates (the readers
/// reject the others).
inline void check_soup(const PolygonSoup& soup, std::size_t min_face) {
  require(soup.face_line.size() == soup.faces.size(), "face_line has one entry per face");
  require(!soup.points.empty() && !soup.faces.empty(), "a soup read without error is not empty");
  for (const auto& face : soup.faces) {
    require(face.size() >= min_face, "every face has at least the vertices the format wants");
    for (int v : face)
      require(v >= 0 && static_cast<std::size_t>(v) < soup.points.size(), "every face index refers to a point");
  }
  for (const Point3& p : soup.points)
    for (double x : p) require(std::isfinite(x), "every coordinate is finite");
}

/// The PLC build_plc returned keeps the cheap part of the contract of
/// types.h: loops of at least 3 vertices on PLC vertices, a unit normal per
/// facet, and every edge between two PLC vertices (a < b) bounding two
/// distinct existing facets.
inline void check_plc(const PLC& plc) {
  const auto nv = plc.vertices.size();
  const auto nf = plc.facets.size();
  require(nv >= 4 && nf >= 4 && plc.edges.size() >= 6, "a polyhedron has 4 vertices, 4 facets, 6 edges");
  for (const PlcFacet& f : plc.facets) {
    require(!f.loops.empty(), "every facet has an outer loop");
    const double len2 = f.normal[0] * f.normal[0] + f.normal[1] * f.normal[1] + f.normal[2] * f.normal[2];
    require(std::fabs(len2 - 1) < 1e-9, "every facet normal has unit length");
    for (const auto& loop : f.loops) {
      require(loop.size() >= 3, "every loop has at least 3 vertices");
      for (int v : loop) require(v >= 0 && static_cast<std::size_t>(v) < nv, "loop vertices exist");
    }
  }
  for (const PlcEdge& e : plc.edges) {
    require(0 <= e.a && e.a < e.b && static_cast<std::size_t>(e.b) < nv, "edge ends exist, a < b");
    for (int f : e.facets) require(f >= 0 && static_cast<std::size_t>(f) < nf, "edge facets exist");
    require(e.facets[0] != e.facets[1], "an edge bounds two different facets");
  }
}

}  // namespace wqmesh::fuzz
