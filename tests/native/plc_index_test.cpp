// wqmesh: the PLC index (core/src/plc_index.h) against brute force over the
// PLC, and its reuse: the mesher's domain made from the index analyze built
// is the domain built anew, bit for bit, also on a PLC analyze scales.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "geometry.h"
#include "mesh_invariants.h"
#include "mesher/domain.h"
#include "plc_index.h"
#include "scaling.h"
#include "wqmesh/analysis.h"

namespace wqmesh {
namespace {

using namespace geometry;

const char* const kModels[] = {"box.off", "bracket.off", "edge_facet.off", "slit.off", "spike.off", "thin_wedge.off"};

invariants::Input model(const std::string& name) {
  return invariants::load(std::string(WQMESH_EXAMPLE_MODELS) + "/" + name);
}

/// The PLC analyze runs on, whose index it keeps: plc normalised
/// (scaling.h).
PLC analysed(const PLC& plc) {
  const Normalisation n = normalisation(plc);
  return n.exponent != 0 || n.translated() ? normalised_plc(plc, n) : plc;
}

/// The index's incidence and frames, checked against the PLC itself.
void expect_index_of(const PLC& plc, const PlcIndex& index) {
  const std::size_t nv = plc.vertices.size();
  ASSERT_EQ(index.vertex_edges.size(), nv);
  ASSERT_EQ(index.vertex_facets.size(), nv);
  ASSERT_EQ(index.vertex_corners.size(), nv);
  ASSERT_EQ(index.frames.size(), plc.facets.size());
  EXPECT_TRUE(index.built_from(plc));
  for (std::size_t v = 0; v < nv; ++v) {
    std::vector<int> edges, facets;
    for (std::size_t e = 0; e < plc.edges.size(); ++e)
      if (plc.edges[e].a == static_cast<int>(v) || plc.edges[e].b == static_cast<int>(v))
        edges.push_back(static_cast<int>(e));
    for (std::size_t f = 0; f < plc.facets.size(); ++f)
      for (const auto& loop : plc.facets[f].loops)
        if (std::count(loop.begin(), loop.end(), static_cast<int>(v)) && !std::count(facets.begin(), facets.end(), f))
          facets.push_back(static_cast<int>(f));
    EXPECT_EQ(index.vertex_edges[v], edges) << "vertex " << v;
    EXPECT_EQ(index.vertex_facets[v], facets) << "vertex " << v;
    ASSERT_EQ(index.vertex_corners[v].size(), facets.size());
    for (std::size_t i = 0; i < facets.size(); ++i) {
      const PlcIndex::Corner& c = index.vertex_corners[v][i];
      EXPECT_EQ(c.facet, facets[i]);
      const auto& loops = plc.facets[c.facet].loops;
      ASSERT_LT(c.loop, static_cast<int>(loops.size()));
      ASSERT_LT(c.position, static_cast<int>(loops[c.loop].size()));
      EXPECT_EQ(loops[c.loop][c.position], static_cast<int>(v)) << "the corner is where v is";
      for (int l = 0; l <= c.loop; ++l)  // and its first place
        for (int r = 0; r < (l == c.loop ? c.position : static_cast<int>(loops[l].size())); ++r)
          EXPECT_NE(loops[l][r], static_cast<int>(v));
      EXPECT_TRUE(index.facet_has_vertex(c.facet, static_cast<int>(v)));
    }
  }
  double extent = 0;
  for (const Point3& p : plc.vertices)
    for (double x : p) extent = std::max(extent, std::fabs(x));
  for (std::size_t f = 0; f < plc.facets.size(); ++f) {
    const PlcIndex::Frame& fr = index.frames[f];
    const auto& facet = plc.facets[f];
    EXPECT_NEAR(norm(fr.n), 1, 1e-14);
    EXPECT_NEAR(norm(fr.plane_n), 1, 1e-14);
    EXPECT_NEAR(norm(fr.e1), 1, 1e-14);
    EXPECT_NEAR(dot(fr.n, fr.plane_n), 1, 1e-12) << "two roundings of one normal";
    EXPECT_GT(dot(fr.n, facet.normal), 1 - 1e-9) << "the outward normal of the builder, facet " << f;
    EXPECT_NEAR(dot(fr.e1, fr.n), 0, 1e-14);
    const Point3 e2 = cross(fr.n, fr.e1);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(fr.e2[k], e2[k]);
    EXPECT_EQ(fr.origin, plc.vertices[facet.loops[0][0]]);
    ASSERT_EQ(fr.loops.size(), facet.loops.size());
    for (std::size_t l = 0; l < facet.loops.size(); ++l) {
      ASSERT_EQ(fr.loops[l].size(), facet.loops[l].size());
      for (std::size_t r = 0; r < facet.loops[l].size(); ++r) {
        const Point3& p = plc.vertices[facet.loops[l][r]];
        EXPECT_LE(std::fabs(dot(sub(p, fr.origin), fr.n)), 1e-12 * extent) << "planar, facet " << f;
        EXPECT_EQ(fr.loops[l][r], index.to2d(static_cast<int>(f), p));
        // In the frame, distances are those in space.
        const std::array<double, 2> q = fr.loops[l][r];
        EXPECT_NEAR(std::hypot(q[0], q[1]), norm(sub(p, fr.origin)), 1e-12 * extent);
      }
    }
    // Far outside along e1: outside the facet.
    EXPECT_FALSE(index.inside_facet(static_cast<int>(f), add(fr.origin, mul(fr.e1, 1e3 * (extent + 1)))));
  }
}

TEST(PlcIndex, IncidenceAndFramesMatchThePlc) {
  for (const char* name : kModels) {
    SCOPED_TRACE(name);
    const auto in = model(name);
    ASSERT_TRUE(in.analysis.index) << "analyze keeps its index";
    expect_index_of(analysed(in.plc), *in.analysis.index);
    expect_index_of(in.plc, PlcIndex(in.plc));
  }
}

TEST(PlcIndex, InsideFacetOnTheBox) {
  // box.off's facets are convex: each loop's centroid is inside its facet,
  // and so is every point a little inside from a corner towards it.
  const auto in = model("box.off");
  const PLC plc = analysed(in.plc);
  const PlcIndex& index = *in.analysis.index;
  for (std::size_t f = 0; f < plc.facets.size(); ++f) {
    const auto& loop = plc.facets[f].loops[0];
    Point3 c{{0, 0, 0}};
    for (int v : loop) c = add(c, plc.vertices[v]);
    c = mul(c, 1.0 / loop.size());
    EXPECT_TRUE(index.inside_facet(static_cast<int>(f), c)) << "facet " << f;
    for (int v : loop)
      EXPECT_TRUE(index.inside_facet(static_cast<int>(f), add(plc.vertices[v], mul(sub(c, plc.vertices[v]), 0.01))));
    // The centroid moved off the plane projects inside still.
    EXPECT_TRUE(index.inside_facet(static_cast<int>(f), add(c, index.frames[f].n)));
  }
}

/// Every field of the index part of two domains, bit for bit.
void expect_same_index(const PlcIndex& a, const PlcIndex& b) {
  EXPECT_EQ(a.vertex_edges, b.vertex_edges);
  EXPECT_EQ(a.vertex_facets, b.vertex_facets);
  ASSERT_EQ(a.vertex_corners.size(), b.vertex_corners.size());
  for (std::size_t v = 0; v < a.vertex_corners.size(); ++v) {
    ASSERT_EQ(a.vertex_corners[v].size(), b.vertex_corners[v].size());
    for (std::size_t i = 0; i < a.vertex_corners[v].size(); ++i) {
      EXPECT_EQ(a.vertex_corners[v][i].facet, b.vertex_corners[v][i].facet);
      EXPECT_EQ(a.vertex_corners[v][i].loop, b.vertex_corners[v][i].loop);
      EXPECT_EQ(a.vertex_corners[v][i].position, b.vertex_corners[v][i].position);
    }
  }
  ASSERT_EQ(a.frames.size(), b.frames.size());
  for (std::size_t f = 0; f < a.frames.size(); ++f) {
    EXPECT_EQ(a.frames[f].origin, b.frames[f].origin);
    EXPECT_EQ(a.frames[f].e1, b.frames[f].e1);
    EXPECT_EQ(a.frames[f].e2, b.frames[f].e2);
    EXPECT_EQ(a.frames[f].n, b.frames[f].n);
    EXPECT_EQ(a.frames[f].area, b.frames[f].area);
    EXPECT_EQ(a.frames[f].plane_n, b.frames[f].plane_n);
    EXPECT_EQ(a.frames[f].loops, b.frames[f].loops);
  }
}

TEST(PlcIndex, TheDomainReusesTheAnalysisIndexBitForBit) {
  // Scaled by powers of two (exact), and moved far from the origin (the
  // normalisation translates it).
  for (const auto& [scale, offset] : {std::pair{1.0, 0.0}, {0x1p40, 0.0}, {0x1p-30, 0.0}, {1.0, 1e6}}) {
    for (const char* name : kModels) {
      SCOPED_TRACE(std::string(name) + " scaled by " + std::to_string(scale) + " moved by " + std::to_string(offset));
      invariants::Input in = model(name);
      for (Point3& p : in.plc.vertices)
        for (double& x : p) x = x * scale + offset;
      const Analysis analysis = analyze(in.plc);
      ASSERT_TRUE(analysis.index);
      // What mesh_polyhedron hands the domain: the PLC and analysis
      // normalised (scaling.h), the index shared.
      const Normalisation n = normalisation(in.plc);
      const int E = n.exponent;
      if (scale != 1.0) EXPECT_NE(E, 0);
      const PLC plc = E != 0 || n.translated() ? normalised_plc(in.plc, n) : in.plc;
      Analysis a = analysis;
      analysis_to_normalised(a, n);
      EXPECT_TRUE(a.index->built_from(plc)) << "the index is of the PLC the mesher meshes";
      EXPECT_EQ(n.translated(), offset != 0);
      EXPECT_EQ(a.index->built_from(in.plc), E == 0 && !n.translated());
      const mesher::Domain reused(plc, a);
      Analysis bare = a;
      bare.index.reset();
      const mesher::Domain anew(plc, bare);
      expect_same_index(reused, anew);
      expect_index_of(reused.p, reused);
      EXPECT_EQ(reused.indexed_facets, plc.facets.size() + 6) << "B's facets are indexed too";
    }
  }
}

TEST(PlcIndex, AnIndexOfAnotherPlcIsNotUsed) {
  const auto in = model("slit.off");
  PLC moved = in.plc;  // the same PLC twice as large (exact): another PLC
  for (Point3& p : moved.vertices)
    for (double& x : p) x *= 2;
  EXPECT_FALSE(in.analysis.index->built_from(moved));
  const mesher::Domain d(moved, in.analysis);
  expect_index_of(d.p, d);
}

}  // namespace
}  // namespace wqmesh
