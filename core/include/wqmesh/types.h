// wqmesh: basic geometric types shared by every module.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace wqmesh {

/// A point or vector of R^3 in double precision. Input coordinates are kept
/// bit-exact from the file; every exact decision is made on these doubles.
using Point3 = std::array<double, 3>;

/// A polygon soup as read from a file, before any validation or merging.
/// Contract: `faces[i]` holds indices into `points` (not yet checked);
/// `face_line[i]` is the 1-based line of the file on which face i is declared
/// for text formats, or 0 for binary ones.
struct PolygonSoup {
  std::vector<Point3> points;
  std::vector<std::vector<int>> faces;
  std::vector<long> face_line;
  /// "OFF", "STL-ascii" or "STL-binary".
  std::string format;
};

/// An input edge of the PLC (paper, section 2): a closed segment between two
/// vertices, with a < b, shared by exactly two facets of the closed 2-manifold.
struct PlcEdge {
  int a = -1, b = -1;
  std::array<int, 2> facets{{-1, -1}};
};

/// A planar polygonal facet of the PLC (paper, section 2), possibly with holes.
/// Contract: `loops[0]` is the outer boundary, counter-clockwise when seen from
/// outside the polyhedron (so its normal points outwards); `loops[1..]` are
/// holes, clockwise from outside. Every loop edge is an input edge (after
/// collinear chains are joined), and every loop vertex is an input vertex.
struct PlcFacet {
  std::vector<std::vector<int>> loops;
  /// Unit outward normal, rounded (decisions use exact predicates on vertices).
  Point3 normal{{0, 0, 0}};
  /// Indices of the input faces (of the PolygonSoup) merged into this facet.
  std::vector<int> source_faces;
};

/// A piecewise linear complex bounding a polyhedron (paper, section 2): the
/// result of reading, validating and merging an input surface.
/// Contract: a closed, oriented (outward) 2-manifold without self-intersection;
/// no two facets sharing an edge are coplanar; no vertex lies in the interior of
/// an edge or a facet.
struct PLC {
  std::vector<Point3> vertices;
  std::vector<PlcEdge> edges;
  std::vector<PlcFacet> facets;
};

/// A tetrahedral mesh, possibly weighted (a weight is a squared radius, as in
/// CGAL's Regular_triangulation_3). Contract: `tets` are positively oriented
/// (orient3d(v0,v1,v2,v3) > 0 in the right-handed sense, i.e. signed volume > 0);
/// `weights` is empty (all zero) or has one entry per vertex.
struct TetMesh {
  std::vector<Point3> vertices;
  std::vector<double> weights;
  std::vector<std::array<int, 4>> tets;
  /// Boundary triangles, oriented outwards, with the input facet each lies in
  /// (`boundary_facet[i]`, -1 where unknown).
  std::vector<std::array<int, 3>> boundary;
  std::vector<int> boundary_facet;
};

}  // namespace wqmesh
