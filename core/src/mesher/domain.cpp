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

bool Sector::holds(const Point3& da, const Point3& db, const Point3& d) const {
  const bool after_a = dot(cross(da, d), n) >= 0, before_b = dot(cross(d, db), n) >= 0;
  // Below pi the arc is where both hold; from pi on, where d is not strictly
  // inside the complement, the arc below pi from db to da.
  return below_pi(da, db) ? after_a && before_b : after_a || before_b;
}

// ---- the SOS split point (section 4.1; beyond the paper) ------------------------
// The paper splits a shield arc at its middle. Where the input is symmetric
// that puts four points of a vertex ball's sphere on one small circle: a
// mirror of the input, or the rotation about a sharp edge (which acts on the
// edge's two facets as a mirror does), maps the sector of a facet onto the
// sector of another and reverses its turn (a mirror reverses the facets'
// loops: the e1 end of one is the eb end of the other). Two mirror pairs of
// points are coplanar (their chords are parallel), so the ball points of two
// such sectors' far edges and the two arcs' midpoints lie on a circle, and
// rounding makes their tet flat (20 mm cube, example012, extrusion, fandisk,
// wedge-1, thin_wedge, spike, edge_facet: smallest dihedral angles of 1e-13
// to 1e-15 degrees).
// So SOS splits the arc from direction a counter-clockwise to b (a on the
// e1 side) at the direction unit(m + delta (b - a)), m the arc's middle. For
// an arc of angle theta, |a + b| = 2 cos(theta/2) and |b - a| = 2 sin(theta/2),
// and m = unit(a + b) = unit(cross(b - a, n)) in exact arithmetic; each is
// taken where it is well conditioned (a + b for arcs below 2 pi/3). b - a is
// the tangent at m toward b, so the point lies on the arc, turned from the
// middle toward b by omega = atan(2 delta sin(theta/2)): at delta = 0 it is
// the paper's point, the midpoint of the chord ab pushed onto the sphere.
// For theta up to pi (every arc after INITIALIZE), omega / theta lies between
// 0.636 delta ((2/pi) delta, less 2e-5 of it: atan x >= x - x^3/3) and
// delta. Measured as an angle from e1 (for the argument only; the code has
// no angles), the point is
// (ta + tb)/2 + omega; as a function of delta it increases (induction: its
// ends do or stay put, and d omega / d theta lies in [0, delta], below 1/2)
// at least at the rate d omega / d delta = 2 sin(theta/2) / (1 + 4 delta^2
// sin^2(theta/2)). So where the paper's point has a mirror partner, ours
// misses the partner's mirror image by at least 2 omega: there are no mirror
// pairs, and four points of one sphere are not coplanar by far more than
// rounding. Four non-coplanar points of the sphere have it as circumsphere,
// which holds u: they make no tet of Del V at all.
// delta is small where the sphere's points of two facets lie close: at a
// sharp edge of dihedral angle a, a point of one facet off the mirror image
// of a point of the other by d lies inside the diametric balls of the other
// facet's subfacets unless d is below about a^2 times the arc, and each such
// encroachment splits another arc (wedge-1, a = 1 degree: 6 732 tets at
// delta = 3e-5, 24 211 at 3e-3, 63 537 at 1e-2, with the split at the angle
// fraction 1/2 + delta). So delta = min(pi/1000, a^2/64), a the smallest
// input angle at u (edge-edge, edge-facet, dihedral) in radians.
// Why the paper's lemmas still hold: the point still lies on the arc of the
// boundary of u's ball in F between a and b, so the ball stays empty, the new
// shield subsegments are chords of the arc, and the shield subfacets'
// diametric balls still lie in the ball and the shield subsegments'
// diametric balls (4.1). Each new arc is at least 1/2 - delta >= 0.4968 of
// the old one instead of 1/2, so the distance from the split point to the
// arc's ends, and the bounds on neighbour radii the termination proofs draw
// from it (Lemma 5.1, from [8]), change by a factor of at least 0.993; the
// packing argument is unchanged. INITIALIZE splits a sector of angle pi or
// more until every arc is below pi (initial_splits: twice when the span is
// within 2 omega <= 4 delta <= 0.004 pi of 2 pi, where the middle needed one
// split); those points, like the paper's, have no predecessor (5.1) and lie
// Omega(r) apart.
Point3 Sector::sos_direction(const Point3& da, const Point3& db) const {
  const Point3 chord = sub(db, da);
  const bool narrow = below_pi(da, db) && dot(da, db) >= -0.5;  // theta below 2 pi/3
  const Point3 m = unit(narrow ? add(da, db) : cross(chord, n));
  return unit(add(m, mul(chord, delta)));
}

int Sector::initial_splits() const {
  // The arc from e1 to the last split point is the larger piece, the one
  // split next; two splits leave every arc below pi (see above).
  int splits = 0;
  for (Point3 b = eb; splits < 2 && !below_pi(e1, b); b = sos_direction(e1, b)) ++splits;
  return splits;
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
  Sector s;
  s.u = u;
  s.facet = f;
  s.center = p.vertices[u];
  s.n = frames[f].n;
  s.r = ball_radius[u];
  s.delta = sos_asymmetry[u];
  // The directions of the edges to next and prev in the facet's plane.
  const auto in_plane = [&](int w) {
    const Point3 d = sub(p.vertices[w], s.center);
    return unit(sub(d, mul(s.n, dot(d, s.n))));
  };
  s.e1 = in_plane(next);
  s.eb = in_plane(prev);
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
