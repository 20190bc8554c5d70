// wqmesh: the domain P, the input PLC with the bounding box B (paper, section
// 2), with the input's index (plc_index.h) extended to B, the vertex balls
// and their sectors (section 4.1).
// SPDX-License-Identifier: GPL-3.0-or-later
#include <algorithm>
#include <cmath>
#include <map>

#include "geometry.h"
#include "mesher/domain.h"

namespace wqmesh::mesher {

using namespace geometry;

Point3 Sector::at(double t) const { return add(center, add(mul(e1, r * std::cos(t)), mul(e2, r * std::sin(t)))); }

// ---- the SOS split point (section 4.1; beyond the paper) ------------------------
// The paper splits a shield arc at its middle. Where the input is symmetric
// that puts four points of a vertex ball's sphere on one small circle: a
// mirror of the input, or the rotation about a sharp edge (which acts on the
// edge's two facets as a mirror does), maps the sector [0, span] of a facet
// onto the sector of another and the arc angle t to span - t (a mirror
// reverses the facets' loops: t = 0 of one is t = span of the other). Two
// mirror pairs of points are coplanar (their chords are parallel), so the
// ball points of two such sectors' far edges and the two arcs' midpoints lie
// on a circle, and rounding makes their tet flat (20 mm cube, example012,
// extrusion, fandisk, wedge-1, thin_wedge, spike, edge_facet: smallest
// dihedral angles of 1e-13 to 1e-15 degrees).
// So SOS splits the arc [ta, tb] at ta + phi (tb - ta), phi = 1/2 + delta,
// measured from the sector's t = 0 edge. Every split point's angle, as a
// function of phi, increases with slope at least the length of the arc it
// splits (induction: (1 - phi) ta + phi tb with ta, tb increasing), so where
// the paper's point has a mirror partner, ours misses the partner's mirror
// image by at least 2 delta times that arc: there are no mirror pairs, and
// four points of one sphere are not coplanar by far more than rounding. Four
// non-coplanar points of the sphere have it as circumsphere, which holds u:
// they make no tet of Del V at all.
// delta is small where the sphere's points of two facets lie close: at a
// sharp edge of dihedral angle a, a point of one facet off the mirror image
// of a point of the other by d lies inside the diametric balls of the other
// facet's subfacets unless d is below about a^2 times the arc, and each such
// encroachment splits another arc (wedge-1, a = 1 degree: 6 732 tets at
// delta = 3e-5, 24 211 at 3e-3, 63 537 at 1e-2). So delta = min(pi/1000, a^2/64), a the
// smallest input angle at u (edge-edge, edge-facet, dihedral) in radians.
// Why the paper's lemmas still hold: the point still lies on the arc of the
// boundary of u's ball in F between a and b, so the ball stays empty, the new
// shield subsegments are chords of the arc, and the shield subfacets'
// diametric balls still lie in the ball and the shield subsegments'
// diametric balls (4.1). Each new arc is at least 1 - phi >= 0.4968 of the
// old one instead of 1/2, so the distance from the split point to the arc's
// ends, and the bounds on neighbour radii the termination proofs draw from
// it (Lemma 5.1, from [8]), change by a factor of at least 0.993; the packing
// argument is unchanged. INITIALIZE splits a sector of angle pi or more until
// every arc is below pi (initial_splits: twice above pi/phi, a span within
// 0.013 pi of 2 pi, where the middle needed one split); those points, like
// the paper's, have no predecessor (5.1) and lie Omega(r) apart.
int Sector::initial_splits() const {
  int n = 0;
  // sos_angle(0, t) ends the larger piece [0, phi t], the one split next.
  for (double t = span; t >= kPi; t = sos_angle(0, t)) ++n;
  return n;
}

// ---- P = the input PLC with the bounding box B ----------------------------------

Domain::Domain(const PLC& plc, const Analysis& analysis) : p(plc) {
  // The input's index, built once by analyze (an Analysis made otherwise, or
  // of another PLC, gets it built here), then B's elements added.
  if (analysis.index && analysis.index->built_from(plc))
    static_cast<PlcIndex&>(*this) = *analysis.index;
  else
    extend(plc);
  input_vertices = static_cast<int>(plc.vertices.size());
  input_edges = static_cast<int>(plc.edges.size());
  input_facets = static_cast<int>(plc.facets.size());
  box = analysis.bounding_box;
  input_box = analysis.input_box;

  // B: corners i = x + 2y + 4z; edges join corners differing in one bit;
  // facets are oriented with their normals pointing out of B.
  for (int i = 0; i < 8; ++i)
    p.vertices.push_back(
        {{(i & 1) ? box.hi[0] : box.lo[0], (i & 2) ? box.hi[1] : box.lo[1], (i & 4) ? box.hi[2] : box.lo[2]}});
  const int c0 = input_vertices;
  const int faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  std::map<std::pair<int, int>, int> edge_index;
  for (int f = 0; f < 6; ++f) {
    PlcFacet facet;
    facet.loops.push_back({c0 + faces[f][0], c0 + faces[f][1], c0 + faces[f][2], c0 + faces[f][3]});
    const int axis = f / 2;
    facet.normal = {{0, 0, 0}};
    facet.normal[axis] = (f % 2) ? 1 : -1;
    const int fid = static_cast<int>(p.facets.size());
    for (int k = 0; k < 4; ++k) {
      int a = facet.loops[0][k], b = facet.loops[0][(k + 1) % 4];
      if (a > b) std::swap(a, b);
      auto it = edge_index.find({a, b});
      if (it == edge_index.end()) {
        PlcEdge e;
        e.a = a;
        e.b = b;
        e.facets = {{fid, -1}};
        edge_index[{a, b}] = static_cast<int>(p.edges.size());
        p.edges.push_back(e);
      } else {
        p.edges[it->second].facets[1] = fid;
      }
    }
    p.facets.push_back(facet);
  }

  extend(p);

  const std::size_t nv = p.vertices.size();
  sharp_vertex.assign(nv, 0);
  sharp_edge.assign(p.edges.size(), 0);
  ball_radius.assign(nv, 0);
  for (std::size_t i = 0; i < analysis.sharp_vertices.size(); ++i) {
    const int u = analysis.sharp_vertices[i];
    sharp_vertex[u] = 1;
    ball_radius[u] = analysis.lfs.at(i) / 4;  // section 4.1: radius f(u)/4
  }
  for (int e : analysis.sharp_edges) sharp_edge[e] = 1;
  // The SOS asymmetry per vertex (see Sector::initial_splits above), from the
  // smallest input angle at it.
  std::vector<double> smallest(nv, 90);
  for (const EdgeEdgeAngle& a : analysis.edge_edge) smallest[a.vertex] = std::min(smallest[a.vertex], a.degrees);
  for (const EdgeFacetAngle& a : analysis.edge_facet) smallest[a.vertex] = std::min(smallest[a.vertex], a.degrees);
  for (const DihedralAngle& a : analysis.dihedral)
    for (int v : {p.edges[a.edge].a, p.edges[a.edge].b})
      smallest[v] = std::min({smallest[v], a.internal_degrees, a.external_degrees});
  sos_asymmetry.resize(nv);
  for (std::size_t v = 0; v < nv; ++v) {
    const double a = smallest[v] * kPi / 180;
    sos_asymmetry[v] = std::min(kSosAsymmetry, a * a / 64);
  }
}

Sector Domain::sector(int u, int f, int prev, int next) const {
  const Point3 n = frames[f].n;
  Sector s;
  s.u = u;
  s.facet = f;
  s.center = p.vertices[u];
  s.r = ball_radius[u];
  s.phi = 0.5 + sos_asymmetry[u];
  Point3 d1 = sub(p.vertices[next], s.center);
  d1 = sub(d1, mul(n, dot(d1, n)));
  s.e1 = mul(d1, 1 / std::sqrt(dot(d1, d1)));
  s.e2 = cross(n, s.e1);
  const Point3 d2 = sub(p.vertices[prev], s.center);
  double span = std::atan2(dot(d2, s.e2), dot(d2, s.e1));
  if (span <= 0) span += 2 * kPi;
  s.span = span;
  return s;
}

std::size_t Domain::initialize_points() const {
  std::size_t n = p.vertices.size();
  for (int u = 0; u < static_cast<int>(p.vertices.size()); ++u) {
    if (ball_radius[u] <= 0) continue;
    n += vertex_edges[u].size();
    for_each_corner(u, [&](int f, int prev, int next) { n += sector(u, f, prev, next).initial_splits(); });
  }
  return n;
}

}  // namespace wqmesh::mesher
