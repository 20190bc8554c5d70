// wqmesh: small helpers the native tests share (one copy each): reading a
// whole file, a two-tet mesh fixture for the writers and readers, and the
// faces of a prism in OFF.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <fstream>
#include <sstream>
#include <string>
#include <utility>

#include "wqmesh/quality.h"
#include "wqmesh/types.h"

namespace wqmesh::testing {

/// The bytes of the file at `path`; empty when it cannot be read.
inline std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Two positively oriented tets sharing the face 1 2 3, with coordinates that
/// need 17 significant digits, and their 6 boundary triangles (one of them in
/// an unknown facet, -1).
inline TetMesh two_tets() {
  TetMesh m;
  m.vertices = {{{0, 0, 0}}, {{1.0 / 3.0, 0, 0}}, {{0, 0.1 + 0.2, 1e-300}}, {{-2.5e17, 0, 1}}, {{1, 1, 1.0 / 7.0}}};
  m.tets = {{{0, 1, 2, 3}}, {{1, 2, 3, 4}}};
  for (auto& t : m.tets) {
    const TetQuality q = tet_quality(m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]], m.vertices[t[3]]);
    if (q.volume < 0) std::swap(t[0], t[1]);
  }
  m.boundary = {{{0, 2, 1}}, {{0, 1, 3}}, {{0, 3, 2}}, {{1, 2, 4}}, {{2, 3, 4}}, {{3, 1, 4}}};
  m.boundary_facet = {0, 1, 2, 3, -1, 5};
  return m;
}

/// The face lines of an OFF prism over a polygon of n corners: the bottom
/// 0..n-1 (counter-clockwise seen from above, so written reversed to face
/// down), the top n..2n-1 above it, and the n side quads, all outwards.
inline std::string prism_faces_off(int n) {
  std::string s = std::to_string(n);
  for (int k = n - 1; k >= 0; --k) s += " " + std::to_string(k);
  s += "\n" + std::to_string(n);
  for (int k = 0; k < n; ++k) s += " " + std::to_string(n + k);
  s += "\n";
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    s += "4 " + std::to_string(i) + " " + std::to_string(j) + " " + std::to_string(n + j) + " " +
         std::to_string(n + i) + "\n";
  }
  return s;
}

}  // namespace wqmesh::testing
