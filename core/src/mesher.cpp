// wqmesh: WQMESH(P) (paper, section 4.3): the four phases in order, then the
// tets inside the polyhedron, their classes and the statistics.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "wqmesh/mesher.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <unordered_map>
#include <unordered_set>

#include "mesher_state.h"

namespace wqmesh {

namespace mesher {

MeshResult Mesher::extract() {
  MeshResult r;
  r.stopped = stop_reason_;
  r.conforming = conforms();
  r.protecting_balls = balls_;
  if (nn_.size() != verts_.size()) {
    nn_.resize(verts_.size());
    for (std::size_t v = 0; v < verts_.size(); ++v) nn_[v] = nearest_neighbour(static_cast<int>(v));
  }
  const RegularTriangulation::CellGraph g = tri_.cell_graph();
  const std::vector<char> inside = interior_labels(g);
  // Which input facet each wall triangle lies in.
  std::unordered_map<Tri, int, TriHash> facet_of;
  for (const Subfacet& h : subfacets())
    if (!dom_.is_box_facet(h.facet)) facet_of[sorted(h.v)] = h.facet;

  std::vector<int> new_id(verts_.size(), -1);
  TetMesh& mesh = r.mesh;
  bool weighted = false;
  for (std::size_t v = 0; v < verts_.size(); ++v) weighted = weighted || tri_.weight(int(v)) != 0;
  auto id = [&](int v) {
    if (new_id[v] < 0) {
      new_id[v] = static_cast<int>(mesh.vertices.size());
      mesh.vertices.push_back(tri_.point(v));
      if (weighted) mesh.weights.push_back(tri_.weight(v));
      r.nearest_neighbour.push_back(nn_[v]);
      r.input_vertex.push_back(verts_[v].on == On::vertex && verts_[v].element < dom_.input_vertices
                                   ? verts_[v].element
                                   : -1);
    }
    return new_id[v];
  };
  // Input vertices first, in their order, so that vertex i of the PLC is
  // vertex i of the mesh.
  for (std::size_t v = 0; v < verts_.size(); ++v)
    if (verts_[v].on == On::vertex && verts_[v].element < dom_.input_vertices) id(static_cast<int>(v));
  static const int kOutward[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  for (std::size_t c = 0; c < g.cells.size(); ++c) {
    if (!inside[c]) continue;
    const Tet& t = g.cells[c];
    mesh.tets.push_back({{id(t[0]), id(t[1]), id(t[2]), id(t[3])}});
    for (int k = 0; k < 4; ++k) {
      if (inside[g.neighbor[c][k]]) continue;
      const Tri f{{t[kOutward[k][0]], t[kOutward[k][1]], t[kOutward[k][2]]}};
      mesh.boundary.push_back({{id(f[0]), id(f[1]), id(f[2])}});
      const auto it = facet_of.find(sorted(f));
      mesh.boundary_facet.push_back(it == facet_of.end() ? -1 : it->second);
    }
  }
  r.quality = mesh_quality(mesh);
  // Classes (see TetClass).
  r.tet_class.resize(mesh.tets.size(), TetClass::good);
  for (std::size_t i = 0; i < mesh.tets.size(); ++i) {
    const TetQuality& q = r.quality[i];
    const bool skinny = q.radius_edge > opt_.rho0;
    const bool sliver = !skinny && q.min_dihedral_deg < opt_.theta_deg;
    if (!skinny && !sliver) continue;
    const auto& t = mesh.tets[i];
    double r2;
    const Point3 z = circumcenter(mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]],
                                  mesh.vertices[t[3]], r2);
    bool near = in_protecting_ball(z);
    for (int k = 0; k < 4 && !near; ++k) {
      const double n = r.nearest_neighbour[t[k]];
      near = encroaches_expanded_ball(mesh.vertices[t[k]], n * n / 9);
    }
    r.tet_class[i] = !near ? TetClass::violation : skinny ? TetClass::skinny_near : TetClass::sliver_near;
    r.slivers += sliver;
    r.skinny += skinny;
    r.near_small_angle += near;
    r.violations += !near;
  }
  return r;
}

}  // namespace mesher

MeshResult mesh_polyhedron(const PLC& plc, const Analysis& analysis, const MeshOptions& options,
                           const ProgressCallback& progress) {
  using clock = std::chrono::steady_clock;
  const mesher::Domain domain(plc, analysis);
  mesher::Mesher m(domain, options, progress);
  std::vector<PhaseStats> phases;
  std::size_t last_count = 0;
  auto run = [&](const char* name, auto&& step) {
    if (m.stopped()) return;
    if (progress) {
      Progress p;
      p.phase = name;
      p.vertices = m.vertices().size();
      if (!progress(p)) {
        m.cancel();
        return;
      }
    }
    const auto t0 = clock::now();
    step();
    PhaseStats s;
    s.name = name;
    s.time_s = std::chrono::duration<double>(clock::now() - t0).count();
    s.points_inserted = m.vertices().size() - last_count;
    last_count = m.vertices().size();
    phases.push_back(s);
  };
  run("initialize", [&] { m.initialize(); });
  run("conform", [&] { m.conform(); });
  run("refine", [&] { m.refine(); });
  std::size_t slivers_qmesh = 0;
  if (options.pump && !m.stopped()) {
    // Count the inside slivers QMESH would leave, then PUMP.
    MeshResult before = m.extract();
    slivers_qmesh = before.slivers;
    run("pump", [&] { m.pump(); });
  }
  MeshResult r;
  const auto t0 = clock::now();
  r = m.extract();
  PhaseStats s;
  s.name = "extract";
  s.time_s = std::chrono::duration<double>(clock::now() - t0).count();
  phases.push_back(s);
  r.phases = phases;
  r.input_points = plc.vertices.size();
  r.sharp_elements = analysis.sharp_vertices.size() + analysis.sharp_edges.size();
  r.points_inserted = m.vertices().size() - domain.p.vertices.size();
  r.slivers_before_pump = options.pump ? slivers_qmesh : r.slivers;
  r.pumped_vertices = m.pumped_vertices;
  r.rule_points = m.rule_count;
  r.all_vertices = m.vertices().size();
  if (options.measure_floor) {
    std::vector<Point3> points(m.vertices().size());
    for (std::size_t v = 0; v < points.size(); ++v) points[v] = m.triangulation().point(static_cast<int>(v));
    const auto f0 = clock::now();
    RegularTriangulation floor;
    floor.insert_all(points);
    r.delaunay_floor_s = std::chrono::duration<double>(clock::now() - f0).count();
  }
  return r;
}

}  // namespace wqmesh
