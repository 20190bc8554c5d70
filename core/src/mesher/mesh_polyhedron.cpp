// wqmesh: WQMESH(P) (paper, section 4.3): the four phases in order, then the
// tets inside the polyhedron, their classes and the statistics.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "wqmesh/mesher.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <unordered_map>
#include <unordered_set>

#include "mesher/classify.h"
#include "mesher/improve.h"
#include "mesher/mesher.h"
#include "scaling.h"

namespace wqmesh {

PointEstimate estimate_edge_points(const PLC& plc, const Analysis& analysis) {
  // Two input edges e1, e2 leave the sharp vertex u at angle t. At distance d
  // from u, e2 passes within d sin t of e1, so a subsegment of e1 there of
  // length s > 2 d sin t / (1 - sin t) has e2 through its diametric ball, and
  // once e2 is split as finely, a vertex of e2 in it: rule 1 (SPLITE, section
  // 4.2) splits it. Outside the vertex ball (radius f(u)/4, section 4.1) and up
  // to L, the length of the shorter edge, e1 ends with subsegments of length
  // about 2 d sin t, so about ln(4 L / f(u)) / (2 sin t) vertices; we take
  // a quarter of that, ln(4 L / f(u)) / (8 sin t), as a safe lower estimate.
  PointEstimate best;
  std::vector<double> f(plc.vertices.size(), 0);
  for (std::size_t i = 0; i < analysis.sharp_vertices.size(); ++i) f[analysis.sharp_vertices[i]] = analysis.lfs[i];
  auto length = [&](int e) {
    const Point3& a = plc.vertices[plc.edges[e].a];
    const Point3& b = plc.vertices[plc.edges[e].b];
    return std::sqrt(geometry::dist2(a, b));
  };
  for (const EdgeEdgeAngle& a : analysis.edge_edge) {
    if (!a.acute || f[a.vertex] <= 0) continue;
    const double L = std::min(length(a.edge1), length(a.edge2));
    const double r = f[a.vertex] / 4;
    const double s = std::sin(a.degrees * geometry::kPi / 180);
    if (!(L > r) || !(s > 0)) continue;
    const double n = std::log(L / r) / (8 * s);
    if (n > best.points) best = {n, a.vertex, a.edge1, a.edge2, a.degrees};
  }
  return best;
}

/// WQMESH on a normalised input (see mesh_polyhedron below): coordinates at
/// most 2 in absolute value.
static MeshResult mesh_normalised(const PLC& plc, const Analysis& analysis, const MeshOptions& options,
                                  const ProgressCallback& progress) {
  using clock = std::chrono::steady_clock;
  // Runs that cannot fit the vertex limit are refused before meshing, with
  // the reason, instead of refining for minutes towards the limit.
  auto refuse = [&](const std::string& message) {
    MeshResult r;
    r.stopped = "limit";
    r.stop_message = message;
    r.input_points = plc.vertices.size();
    r.sharp_elements = analysis.sharp_vertices.size() + analysis.sharp_edges.size();
    return r;
  };
  const PointEstimate need = estimate_edge_points(plc, analysis);
  if (need.points > double(options.max_vertices)) {
    const PlcEdge& e1 = plc.edges[need.edge1];
    const PlcEdge& e2 = plc.edges[need.edge2];
    char text[400];
    std::snprintf(text, sizeof text,
                  "the input edges %d (vertices %d-%d) and %d (vertices %d-%d) meet at vertex %d at %.3g degrees: "
                  "a conforming mesh needs at least about %.3g vertices along them, more than the vertex limit %zu",
                  need.edge1, e1.a, e1.b, need.edge2, e2.a, e2.b, need.vertex, need.degrees, need.points,
                  options.max_vertices);
    return refuse(text);
  }
  const mesher::Domain domain(plc, analysis);
  // INITIALIZE's vertex count is known in advance (section 4.1); each later
  // phase stops at the limit by itself.
  const std::size_t initial = domain.initialize_points();
  if (initial > options.max_vertices) {
    char text[300];
    std::snprintf(text, sizeof text,
                  "INITIALIZE alone inserts %zu vertices (the input vertices and the bounding box corners, the "
                  "vertex-ball points and the SOS splits of %zu sharp vertices), more than the vertex limit %zu",
                  initial, analysis.sharp_vertices.size(), options.max_vertices);
    return refuse(text);
  }
  mesher::Mesher m(domain, options, progress);
  std::vector<PhaseStats> phases;
  std::size_t last_count = 0;
  auto run = [&](const char* name, auto&& step) {
    if (m.meter().stopped()) return;
    if (progress) {
      Progress p;
      p.phase = name;
      p.vertices = m.vertices().size();
      if (!progress(p)) {
        m.meter().cancel();
        return;
      }
    }
    const auto t0 = clock::now();
    // A walk past its stated bound (LoopBoundError, triangulation.h) is an
    // internal error: named with the phase, the loop and the vertex.
    try {
      step();
    } catch (const LoopBoundError& e) {
      throw std::runtime_error(std::string("internal error in ") + name + ": " + e.what());
    }
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
  // V is final: PUMP and the extraction need only the list of subfacets,
  // not the facets' planar triangulations (issue 15, the peak memory).
  m.freeze_subcomplex();
  std::size_t slivers_qmesh = 0;
  if (options.pump && !m.meter().stopped()) {
    // Count the inside slivers QMESH would leave (a scan that polls: a
    // cancel during it ends the run), then PUMP.
    slivers_qmesh = m.count_qmesh_slivers();
    run("pump", [&] { m.pump(); });
  }
  MeshResult r;
  // What the statistics need of V, taken now: V is final, and when a mesh
  // is extracted the mesher's large pieces (V's triangulation, the
  // subcomplex, the queues) are freed before the per-tet measures, the
  // classes and the improvement phase are built (issue 15: the peak memory
  // was the extraction's result beside the triangulation). The protecting
  // balls are kept (a copy: the classes and the phase read them).
  const mesher::ProtectingBalls balls = m.balls();
  const std::size_t all_vertices = m.vertices().size();
  const std::array<std::size_t, 8> rule_points = m.inserter().rule_count();
  std::vector<Point3> floor_points;
  if (options.measure_floor)
    for (std::size_t v = 0; v < all_vertices; ++v) floor_points.push_back(m.triangulation().point(static_cast<int>(v)));
  if (m.meter().stop_reason() == "cancelled") {
    // Beyond the paper (issue 10, stops that reach every step): a cancelled
    // run returns at once, without extracting its partial mesh (extraction
    // walks the whole triangulation: about a second at 300,000 tets), so
    // that a cancel takes effect within a bounded amount of work.
    r.stopped = m.meter().stop_reason();
    r.stop_message =
        "cancelled by the caller at " + std::to_string(m.vertices().size()) + " vertices; no mesh was extracted";
    r.protecting_balls = m.balls().all();
  } else {
    const auto t0 = clock::now();
    r = m.extract_mesh();
    m.release();
    mesher::classify_tets(r, balls, options);
    PhaseStats s;
    s.name = "extract";
    s.time_s = std::chrono::duration<double>(clock::now() - t0).count();
    phases.push_back(s);
    // Beyond the paper (issue 14): the improvement phase (improve.h) on a
    // finished, conforming run; then the classes again.
    if (options.improve && r.stopped.empty() && r.conforming) {
      const auto i0 = clock::now();
      const std::size_t before = r.mesh.vertices.size();
      if (!mesher::improve_phase(r, balls, options, progress)) {
        r = MeshResult();
        r.stopped = "cancelled";
        r.stop_message = "cancelled by the caller in the improvement phase; no mesh is returned";
        r.protecting_balls = balls.all();
      }
      PhaseStats p;
      p.name = "improve";
      p.time_s = std::chrono::duration<double>(clock::now() - i0).count();
      p.points_inserted = r.mesh.vertices.size() > before ? r.mesh.vertices.size() - before : 0;
      phases.push_back(p);
    }
  }
  r.phases = phases;
  if (r.stop_message.empty()) r.stop_message = m.meter().stop_message();  // "stalled"
  if (r.stopped == "limit" && r.stop_message.empty()) {
    char text[200];
    std::snprintf(text, sizeof text, "the vertex limit %zu was reached in %s", options.max_vertices,
                  phases.size() >= 2 ? phases[phases.size() - 2].name.c_str() : "initialize");
    r.stop_message = text;
  }
  r.input_points = plc.vertices.size();
  r.sharp_elements = analysis.sharp_vertices.size() + analysis.sharp_edges.size();
  r.points_inserted = all_vertices - domain.p.vertices.size() + r.improve.inserted;
  r.slivers_before_pump = options.pump ? slivers_qmesh : r.improve.ran ? r.improve.slivers_before : r.slivers;
  r.pumped_vertices = m.pumped_vertices();
  r.rule_points = rule_points;
  r.caps_reached = m.meter().caps_reached();
  r.all_vertices = all_vertices + r.improve.inserted;
  if (options.measure_floor) {
    const auto f0 = clock::now();
    RegularTriangulation floor;
    floor.insert_all(floor_points);
    r.delaunay_floor_s = std::chrono::duration<double>(clock::now() - f0).count();
  }
  return r;
}

MeshResult mesh_polyhedron(const PLC& plc, const Analysis& analysis, const MeshOptions& options,
                           const ProgressCallback& progress) {
  // Beyond the paper: the run works on the input normalised (translated when
  // far from the origin, scaled by 2^-E; exact, see scaling.h), so that no
  // formula of the mesher overflows or underflows and a far input is meshed
  // as at the origin, and every output is mapped back (points times 2^E plus
  // the centre, lengths times 2^E, weights 2^2E, volumes 2^3E): the input
  // vertices come out at their exact input coordinates.
  const Normalisation n = normalisation(plc);
  const int E = n.exponent;
  MeshResult r;
  if (E == 0 && !n.translated()) {
    r = mesh_normalised(plc, analysis, options, progress);
  } else {
    const PLC normalised = normalised_plc(plc, n);
    Analysis a = analysis;
    analysis_to_normalised(a, n);
    MeshOptions o = options;
    o.max_size = std::ldexp(options.max_size, -E);
    r = mesh_normalised(normalised, a, o, progress);
    for (Point3& p : r.mesh.vertices) p = input_point(p, n);
    for (double& w : r.mesh.weights) w = std::ldexp(w, 2 * E);
    for (double& d : r.nearest_neighbour) d = std::ldexp(d, E);
    for (ProtectingBall& b : r.protecting_balls) {
      b.center = input_point(b.center, n);
      b.radius = std::ldexp(b.radius, E);
    }
    for (TetQuality& q : r.quality) {
      q.volume = std::ldexp(q.volume, 3 * E);
      q.radius = std::ldexp(q.radius, E);
      q.shortest_edge = std::ldexp(q.shortest_edge, E);
      q.longest_edge = std::ldexp(q.longest_edge, E);
      q.inradius = std::ldexp(q.inradius, E);
    }
  }
  // A valid polyhedron always has interior tets once a run is done: none is
  // a bug (the symptom of a lost inside/outside labelling), not a result.
  if (r.stopped.empty() && r.mesh.tets.empty())
    throw std::runtime_error("internal error: the run finished with no tet inside the polyhedron");
  return r;
}

}  // namespace wqmesh
