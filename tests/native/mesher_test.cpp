// Tests of the mesher (WQMESH, paper section 4.3): invariants checked on the
// output mesh itself (orientation, volume, conformity to the input, the weight
// bound, the regular triangulation), the classes of tets, PUMP, the options,
// and the rules on tiny inputs where the right point is known by hand.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <unordered_set>

#include "mesh_invariants.h"
#include "mesher/extract.h"
#include "mesher/mesher.h"
#include "mesher/phases.h"
#include "mesher/pump.h"
#include "wqmesh/analysis.h"
#include "wqmesh/input.h"
#include "wqmesh/mesher.h"
#include "wqmesh/report.h"

namespace wqmesh {
namespace {

namespace fs = std::filesystem;
using mesher::cross;
using mesher::dot;
using mesher::sub;

using invariants::diag;
using invariants::expect_invariants;
using invariants::facet_area;
using invariants::from_off;
using invariants::Input;
using invariants::load;
using invariants::orient;

std::vector<std::string> models(const std::string& dir, const std::set<std::string>& names) {
  std::vector<std::string> out;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return out;
  for (const std::string& n : names)
    if (fs::exists(dir + "/" + n)) out.push_back(dir + "/" + n);
  return out;
}

// A model on which every rule acts: the 20mm cube from ../shared/models, or
// when that folder is absent, an example model; "" when neither is there.
TEST(Mesher, ExampleModelsMeetEveryInvariant) {
  const auto files = models(WQMESH_EXAMPLE_MODELS,
                            {"box.off", "bracket.off", "edge_facet.off", "slit.off", "spike.off", "thin_wedge.off"});
  if (files.empty()) GTEST_SKIP() << "no example models";
  for (const std::string& f : files) {
    const Input in = load(f);
    const MeshResult r = mesh_polyhedron(in.plc, in.analysis);
    expect_invariants(f, in, r);
    EXPECT_EQ(r.violations, 0u) << f;
  }
}

TEST(Mesher, SharedSmallModelsMeetEveryInvariant) {
  const auto files = models(WQMESH_SHARED_MODELS, {"wedge.off", "slit-1.off", "extrusion.off", "schonhardt.off",
                                                   "example012.stl", "20mm-xyz-cube.stl"});
  if (files.empty()) GTEST_SKIP() << "../shared/models is absent";
  for (const std::string& f : files) {
    const Input in = load(f);
    const MeshResult r = mesh_polyhedron(in.plc, in.analysis);
    expect_invariants(f, in, r);
    std::printf("[ mesher   ] %s: %zu vertices, %zu tets, slivers %zu (QMESH %zu), skinny %zu, violations %zu\n",
                fs::path(f).filename().c_str(), r.mesh.vertices.size(), r.mesh.tets.size(), r.slivers,
                r.slivers_before_pump, r.skinny, r.violations);
  }
}

// The larger shared models, one test each (ctest runs them side by side; the
// sanitizer build leaves the MesherLarge suite out). Each must finish without
// reaching the default vertex limit and meet every invariant, with no
// violation left (issue 14: every skinny tet and sliver near a small angle).
void mesh_large(const std::string& name) {
  const auto files = models(WQMESH_SHARED_MODELS, {name});
  if (files.empty()) GTEST_SKIP() << "../shared/models is absent";
  const Input in = load(files[0]);
  const MeshResult r = mesh_polyhedron(in.plc, in.analysis);
  EXPECT_EQ(r.stopped, "") << r.stop_message;
  expect_invariants(files[0], in, r);
  EXPECT_EQ(r.violations, 0u);
  std::printf("[ mesher   ] %s: %zu vertices, %zu tets, slivers %zu (QMESH %zu), skinny %zu, violations %zu\n",
              name.c_str(), r.mesh.vertices.size(), r.mesh.tets.size(), r.slivers, r.slivers_before_pump, r.skinny,
              r.violations);
}
TEST(MesherLarge, PartMeetsEveryInvariant) { mesh_large("part.off"); }
TEST(MesherLarge, AnchorMeetsEveryInvariant) { mesh_large("anchor.off"); }
TEST(MesherLarge, Wedge1MeetsEveryInvariant) { mesh_large("wedge-1.off"); }
TEST(MesherLarge, FandiskMeetsEveryInvariant) { mesh_large("fandisk.off"); }

// step.off: two edges meet at 1.7e-5 degrees over a length of about 2000
// times the vertex ball radius; a conforming mesh needs millions of vertices
// there, so the run stops at once and says which edges.
TEST(MesherLarge, StepStopsAtOnceNamingItsNeedleEdges) {
  const auto files = models(WQMESH_SHARED_MODELS, {"step.off"});
  if (files.empty()) GTEST_SKIP() << "../shared/models is absent";
  const Input in = load(files[0]);
  const MeshResult r = mesh_polyhedron(in.plc, in.analysis);
  EXPECT_EQ(r.stopped, "limit");
  EXPECT_NE(r.stop_message.find("meet at vertex"), std::string::npos) << r.stop_message;
  EXPECT_TRUE(r.mesh.tets.empty());
}

// Meshes the OFF text `off`, a polyhedron with no angle under 90 degrees
// (no sharp element, so no protecting ball and nothing near a small angle),
// and checks every invariant and that no tet is a violation.
void expect_no_ball_and_no_violation(const char* name, const char* off) {
  const Input in = from_off(off);
  const MeshResult r = mesh_polyhedron(in.plc, in.analysis);
  expect_invariants(name, in, r);
  EXPECT_TRUE(r.protecting_balls.empty());
  EXPECT_EQ(r.violations, 0u);
  EXPECT_EQ(r.near_small_angle, 0u);
  EXPECT_EQ(r.sharp_elements, 0u);
}

TEST(Mesher, BoxHasNoProtectingBallAndNoViolation) {
  expect_no_ball_and_no_violation("box",
                                  "OFF\n8 6 0\n0 0 0\n2 0 0\n2 1 0\n0 1 0\n0 0 1\n2 0 1\n2 1 1\n0 1 1\n"
                                  "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7\n");
}

TEST(Mesher, LShapedBlockHasNoViolation) {
  expect_no_ball_and_no_violation(
      "L-block",
      "OFF\n12 8 0\n0 0 0\n2 0 0\n2 1 0\n1 1 0\n1 2 0\n0 2 0\n0 0 1\n2 0 1\n2 1 1\n1 1 1\n1 2 1\n0 2 1\n"
      "6 0 5 4 3 2 1\n6 6 7 8 9 10 11\n4 0 1 7 6\n4 1 2 8 7\n4 2 3 9 8\n4 3 4 10 9\n4 4 5 11 10\n4 5 0 6 11\n");
}

TEST(Mesher, ProvenRhoLeavesNoSkinnyViolation) {
  // rho0 = 3.5 > 2/(1 - tan(pi/8)): skinny tets lie near small angles.
  const auto files = models(WQMESH_EXAMPLE_MODELS, {"thin_wedge.off", "spike.off", "slit.off"});
  if (files.empty()) GTEST_SKIP() << "no example models";
  MeshOptions o;
  o.rho0 = 3.5;
  for (const std::string& f : files) {
    const Input in = load(f);
    const MeshResult r = mesh_polyhedron(in.plc, in.analysis, o);
    expect_invariants(f, in, r);
    for (std::size_t i = 0; i < r.mesh.tets.size(); ++i)
      if (r.quality[i].radius_edge > o.rho0) EXPECT_NE(r.tet_class[i], TetClass::violation) << f;
  }
}

std::size_t sliver_violations(const MeshResult& r, double rho0) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < r.mesh.tets.size(); ++i)
    n += r.tet_class[i] == TetClass::violation && r.quality[i].radius_edge <= rho0;
  return n;
}

// PUMP works, named for what holds. "PUMP leaves strictly fewer slivers than QMESH" does
// not hold on every model: rule 7 and PUMP skip a vertex whose weighted copy
// encroaches the two-times expansion of a protecting ball (section 4.3), so
// where every QMESH sliver is near a small input angle (wedge.off: 22 before
// and 22 after) PUMP cannot remove any, by design. What the paper promises,
// and what this checks, is about the slivers away from small angles: where
// QMESH alone (no rule 7, no PUMP) leaves some, WQMESH leaves strictly fewer
// slivers, and nowhere does it leave more, or more away from small angles.
TEST(Mesher, PumpLeavesStrictlyFewerSliversWhereQmeshLeavesSomeAwayFromSmallAngles) {
  std::vector<std::string> files =
      models(WQMESH_SHARED_MODELS, {"20mm-xyz-cube.stl", "slit-1.off", "example012.stl", "wedge.off"});
  const std::vector<std::string> examples = models(WQMESH_EXAMPLE_MODELS, {"edge_facet.off", "slit.off", "spike.off"});
  ASSERT_EQ(examples.size(), 3u) << "examples/models is incomplete";
  for (const auto& f : examples) files.push_back(f);
  std::size_t improved = 0, pumped = 0;
  for (const std::string& f : files) {
    const Input in = load(f);
    // PUMP against QMESH, both without the improvement phase after them.
    MeshOptions qmesh, wqmesh;
    qmesh.pump = false;
    qmesh.improve = wqmesh.improve = false;
    const MeshResult before = mesh_polyhedron(in.plc, in.analysis, qmesh);
    const MeshResult after = mesh_polyhedron(in.plc, in.analysis, wqmesh);
    expect_invariants(f + ", QMESH", in, before);
    expect_invariants(f + ", WQMESH", in, after);
    const std::size_t away = sliver_violations(before, qmesh.rho0);
    std::printf("[ pump     ] %s: QMESH %zu slivers (%zu away from small angles), WQMESH %zu (%zu)\n",
                fs::path(f).filename().c_str(), before.slivers, away, after.slivers,
                sliver_violations(after, qmesh.rho0));
    EXPECT_LE(after.slivers, before.slivers) << f;
    EXPECT_LE(sliver_violations(after, qmesh.rho0), away) << f;
    if (away > 0) {
      EXPECT_LT(after.slivers, before.slivers) << f;
      ++improved;
      // Rule 7's insertions alone may remove them (spike.off).
      pumped += after.pumped_vertices > 0;
    }
  }
  // The promise is tested, not vacuous, on the 20mm cube: QMESH leaves
  // slivers away from small angles there, and PUMP weights vertices. (Since
  // SOS splits off the middle, issue 14, spike.off, slit.off and slit-1 have
  // none left: without ../shared/models only the bounds above are checked.)
  if (!models(WQMESH_SHARED_MODELS, {"20mm-xyz-cube.stl"}).empty()) {
    EXPECT_GE(improved, 1u);
    EXPECT_GE(pumped, 1u);
  }
}

TEST(Mesher, SameInputSameMesh) {
  const auto files = models(WQMESH_EXAMPLE_MODELS, {"edge_facet.off"});
  if (files.empty()) GTEST_SKIP() << "no example models";
  const Input in = load(files[0]);
  const MeshResult a = mesh_polyhedron(in.plc, in.analysis);
  const MeshResult b = mesh_polyhedron(in.plc, in.analysis);
  EXPECT_EQ(a.mesh.vertices, b.mesh.vertices);
  EXPECT_EQ(a.mesh.tets, b.mesh.tets);
  EXPECT_EQ(a.mesh.weights, b.mesh.weights);
}

TEST(Mesher, VertexLimitAndCancelStopTheRun) {
  const auto files = models(WQMESH_EXAMPLE_MODELS, {"thin_wedge.off"});
  if (files.empty()) GTEST_SKIP() << "no example models";
  const Input in = load(files[0]);
  MeshOptions o;
  o.max_vertices = 60;
  const MeshResult limited = mesh_polyhedron(in.plc, in.analysis, o);
  EXPECT_EQ(limited.stopped, "limit");
  std::size_t calls = 0;
  const MeshResult cancelled = mesh_polyhedron(in.plc, in.analysis, {}, [&](const Progress& p) {
    EXPECT_GE(p.fraction, 0);
    EXPECT_LE(p.fraction, 1);
    return ++calls < 2;
  });
  EXPECT_EQ(cancelled.stopped, "cancelled");
  EXPECT_GE(calls, 2u);
}

// Two edges at 1e-7 rad need millions of vertices along them (each subsegment
// is split until about 2 d sin t long, d its distance from the vertex): the
// run stops at once with "limit" and names the two edges, and a budget above
// the estimate lets it start.
TEST(Mesher, HopelessAngleStopsAtOnceNamingTheEdges) {
  const Input in = from_off(
      "OFF\n4 4 0\n0 0 0\n1 0 0\n1 1e-7 0\n0.5 0 0.5\n"
      "3 0 2 1\n3 0 1 3\n3 1 2 3\n3 2 0 3\n");
  const PointEstimate need = estimate_edge_points(in.plc, in.analysis);
  EXPECT_EQ(need.vertex, 0);
  EXPECT_NEAR(need.degrees, 1e-7 * 180 / geometry::kPi, 1e-12);
  EXPECT_GT(need.points, 1e6);
  EXPECT_LT(need.points, 1e7);
  const MeshResult r = mesh_polyhedron(in.plc, in.analysis);
  EXPECT_EQ(r.stopped, "limit");
  EXPECT_NE(r.stop_message.find("meet at vertex 0"), std::string::npos) << r.stop_message;
  EXPECT_TRUE(r.mesh.tets.empty());
  // A model without acute edge-edge angles estimates nothing.
  const auto box = models(WQMESH_EXAMPLE_MODELS, {"box.off"});
  if (!box.empty()) {
    const Input b = load(box[0]);
    EXPECT_EQ(estimate_edge_points(b.plc, b.analysis).points, 0);
  }
}

TEST(Mesher, MaxSizeBoundsTheCircumradius) {
  const auto files = models(WQMESH_EXAMPLE_MODELS, {"box.off"});
  if (files.empty()) GTEST_SKIP() << "no example models";
  const Input in = load(files[0]);
  MeshOptions o;
  o.max_size = 0.25;
  const MeshResult r = mesh_polyhedron(in.plc, in.analysis, o);
  expect_invariants("box, max_size", in, r);
  for (const TetQuality& q : r.quality) EXPECT_LE(q.radius, o.max_size * (1 + 1e-9));
}

TEST(Mesher, MaxSizeHoldsNextToSharpEdges) {
  // Rule 6 refuses circumcenters inside protecting balls, so the sharp
  // subsegments are split down to 2/3 max_size first: then every tet has a
  // circumradius within max_size, except one whose circumcenter lies in a
  // vertex ball, within that ball's radius f(u)/4. PUMP is off: the bound is
  // on the Delaunay triangulation REFINE leaves. Flat tets with their four
  // vertices on a vertex ball's sphere have that sphere as circumsphere, but
  // computed in floating point their circumcenter lands anywhere: they are
  // counted apart.
  const auto files = models(WQMESH_EXAMPLE_MODELS, {"thin_wedge.off"});
  if (files.empty()) GTEST_SKIP() << "no example models";
  const Input in = load(files[0]);
  MeshOptions o;
  o.pump = false;
  o.max_size = 0.2;
  const MeshResult r = mesh_polyhedron(in.plc, in.analysis, o);
  expect_invariants("thin_wedge, max_size", in, r);
  const auto on_sphere = [](const Point3& p, const ProtectingBall& b) {
    return std::abs(std::sqrt(mesher::dist2(p, b.center)) - b.radius) <= 1e-9 * b.radius;
  };
  std::size_t in_segment_ball = 0, on_ball_sphere = 0;
  for (const auto& t : r.mesh.tets) {
    bool flat_on_sphere = false;
    for (const ProtectingBall& b : r.protecting_balls)
      if (b.vertex_ball && std::all_of(t.begin(), t.end(), [&](int v) { return on_sphere(r.mesh.vertices[v], b); }))
        flat_on_sphere = true;
    if (flat_on_sphere) {
      ++on_ball_sphere;
      continue;
    }
    double r2;
    const Point3 z = mesher::circumcenter(r.mesh.vertices[t[0]], r.mesh.vertices[t[1]], r.mesh.vertices[t[2]],
                                          r.mesh.vertices[t[3]], r2);
    double bound = o.max_size;
    bool in_ball = false;
    for (const ProtectingBall& b : r.protecting_balls)
      if (mesher::dist2(z, b.center) <= b.radius * b.radius) {
        if (b.vertex_ball) bound = std::max(bound, b.radius);
        in_ball = true;
      }
    if (in_ball && bound == o.max_size) ++in_segment_ball;
    EXPECT_LE(std::sqrt(r2), bound * (1 + 1e-9)) << "circumcenter " << z[0] << " " << z[1] << " " << z[2];
  }
  // The case the split is for occurs: tets centred in subsegment balls.
  EXPECT_GT(in_segment_ball, 0u);
  EXPECT_LT(on_ball_sphere, r.mesh.tets.size() / 20);
}

// ---- rules on tiny inputs ------------------------------------------------------

// A thin wedge: a triangular prism whose edge along z has a dihedral angle of
// atan(0.2) ~ 11.3 degrees.
const char* kWedge =
    "OFF\n6 5 0\n0 0 0\n1 0 0\n1 0.2 0\n0 0 1\n1 0 1\n1 0.2 1\n"
    "3 0 2 1\n3 3 4 5\n4 0 1 4 3\n4 1 2 5 4\n4 2 0 3 5\n";

// The mesher's state on an input; the members outlive the Mesher, which
// refers to them.
struct Stage {
  Input in;
  mesher::Domain dom;
  MeshOptions options;
  ProgressCallback none;
  mesher::Mesher m;
  /// Before INITIALIZE, with the options o.
  Stage(const Input& input, const MeshOptions& o)
      : in(input), dom(in.plc, in.analysis), options(o), m(dom, options, none) {}
  /// After INITIALIZE (and CONFORM when asked), with the default options.
  Stage(const Input& input, bool conformed) : Stage(input, MeshOptions{}) {
    m.initialize();
    if (conformed) m.conform();
  }
};

// INITIALIZE's vertex count is known before it runs (section 4.1), so a vertex
// limit below it is refused at once with the reason, and a limit just above it
// stops the next phase within one insertion step of the limit.
TEST(MesherRules, InitializeCountIsKnownAndALimitBelowItIsRefused) {
  const auto files = models(WQMESH_EXAMPLE_MODELS, {"slit.off", "spike.off", "thin_wedge.off", "edge_facet.off"});
  if (files.empty()) GTEST_SKIP() << "no example models";
  std::size_t with_sos = 0;
  for (const auto& file : files) {
    SCOPED_TRACE(file);
    const Input in = load(file);
    Stage st(in, false);
    const std::size_t n = st.dom.initialize_points();
    ASSERT_FALSE(in.analysis.sharp_vertices.empty());
    EXPECT_EQ(n, st.m.vertices().size());
    std::size_t ball_points = 0;
    for (int u : in.analysis.sharp_vertices) ball_points += st.dom.vertex_edges[u].size();
    with_sos += n > st.dom.p.vertices.size() + ball_points;
    MeshOptions o;
    o.max_vertices = n - 1;
    const MeshResult refused = mesh_polyhedron(in.plc, in.analysis, o);
    EXPECT_EQ(refused.stopped, "limit");
    EXPECT_NE(refused.stop_message.find("INITIALIZE alone inserts " + std::to_string(n) + " vertices"),
              std::string::npos)
        << refused.stop_message;
    EXPECT_TRUE(refused.mesh.tets.empty());
    EXPECT_TRUE(refused.phases.empty());
    o.max_vertices = n + 3;
    const MeshResult limited = mesh_polyhedron(in.plc, in.analysis, o);
    EXPECT_EQ(limited.stopped, "limit");
    EXPECT_NE(limited.stop_message.find("reached in conform"), std::string::npos) << limited.stop_message;
    EXPECT_GE(limited.all_vertices, o.max_vertices);
    EXPECT_LE(limited.all_vertices, o.max_vertices + 64);
  }
  EXPECT_GE(with_sos, 1u) << "no model here has a sector of pi or more at a sharp vertex";
}

TEST(MesherRules, InitializePutsBallPointsAtQuarterLfsOnEveryEdgeOfASharpVertex) {
  Stage st(from_off(kWedge), false);
  const Input& in = st.in;
  const mesher::Domain& dom = st.dom;
  mesher::Mesher& m = st.m;
  ASSERT_FALSE(in.analysis.sharp_vertices.empty());
  for (std::size_t i = 0; i < in.analysis.sharp_vertices.size(); ++i) {
    const int u = in.analysis.sharp_vertices[i];
    const double r = in.analysis.lfs[i] / 4;
    for (const PlcEdge& e : in.plc.edges) {
      if (e.a != u && e.b != u) continue;
      const int w = e.a == u ? e.b : e.a;
      const Point3 dir = sub(in.plc.vertices[w], in.plc.vertices[u]);
      const Point3 expected = mesher::add(in.plc.vertices[u], mesher::mul(dir, r / std::sqrt(dot(dir, dir))));
      bool found = false;
      for (int v = 0; v < m.triangulation().number_of_vertices(); ++v)
        if (mesher::dist2(m.triangulation().point(v), expected) < 1e-24) found = true;
      EXPECT_TRUE(found) << "no ball point of vertex " << u << " on its edge to " << w;
    }
  }
  // The subsegments from a sharp vertex to its ball points are protected.
  const int np = static_cast<int>(dom.p.vertices.size());
  std::size_t protected_count = 0;
  for (const auto& [k, s] : m.subcomplex().subsegments()) {
    if (s.edge < 0) continue;
    const bool from_sharp_vertex = (s.a < np && dom.sharp_vertex[s.a] && m.vertices()[s.b].ball == s.a) ||
                                   (s.b < np && dom.sharp_vertex[s.b] && m.vertices()[s.a].ball == s.b);
    EXPECT_EQ(s.in_ball, from_sharp_vertex) << s.a << "-" << s.b;
    protected_count += s.in_ball;
  }
  std::size_t expected = 0;
  for (int u : in.analysis.sharp_vertices) expected += dom.vertex_edges[u].size();
  EXPECT_EQ(protected_count, expected);
}

TEST(MesherRules, SplitePutsTheMidpointOrTheSosPoint) {
  Stage st(from_off(kWedge), false);
  const Input& in = st.in;
  const mesher::Domain& dom = st.dom;
  mesher::Mesher& m = st.m;
  // A point just beside the midpoint of a non-protected subsegment
  // encroaches it: ENCROACH returns that midpoint (section 4.3, case 2).
  for (const auto& [k, s] : m.subcomplex().subsegments()) {
    if (s.in_ball || s.sector >= 0) continue;
    const Point3 a = m.triangulation().point(s.a), b = m.triangulation().point(s.b);
    const Point3 mid = mesher::midpoint(a, b);
    Point3 off = cross(sub(b, a), Point3{{0.3, 0.5, 0.7}});
    off = mesher::mul(off, 1e-3 * std::sqrt(mesher::dist2(a, b)) / std::sqrt(dot(off, off)));
    const mesher::Insertion ins = m.subcomplex().encroach(mesher::add(mid, off), s.a);
    EXPECT_TRUE(ins.has_segment);
    EXPECT_EQ(ins.on, mesher::On::edge);
    EXPECT_EQ(ins.p, mid);
    break;
  }
  // A shield subsegment is split at its SOS point: on the sphere of the
  // vertex ball, on the arc off its middle (Sector::sos_direction, issue 14).
  for (const auto& [k, s] : m.subcomplex().subsegments()) {
    if (s.sector < 0) continue;
    const Point3 a = m.triangulation().point(s.a), b = m.triangulation().point(s.b);
    const Point3 mid = mesher::midpoint(a, b);
    const mesher::Insertion ins = m.subcomplex().encroach(mid, s.a);
    ASSERT_TRUE(ins.has_segment);
    const int u = m.vertices()[s.a].ball;
    ASSERT_GE(u, 0);
    EXPECT_GT(dom.sos_asymmetry[u], 0);
    invariants::expect_sos_point(ins.p, a, b, dom.p.vertices[u], dom.ball_radius[u], dom.sos_asymmetry[u], 1e-12);
    break;
  }
}

TEST(MesherRules, EncroachAgreesWithABruteForceSearch) {
  // ENCROACH(c) (section 4.3) returns c when c encroaches no subsegment (on or
  // inside its diametric ball) and no subfacet (strictly inside); otherwise a
  // point splitting a feature. Checked against every feature, on a grid of c.
  Stage st(from_off(kWedge), true);
  const Input& in = st.in;
  const mesher::Domain& dom = st.dom;
  mesher::Mesher& m = st.m;
  ASSERT_TRUE(m.subcomplex().conforms());
  const auto& tri = m.triangulation();
  const std::vector<mesher::Subfacet> facets = m.subcomplex().subfacets();
  int free_points = 0, split_points = 0;
  for (int i = 1; i < 8; ++i)
    for (int j = 1; j < 8; ++j)
      for (int k = 1; k < 8; ++k) {
        Point3 c;
        const int ijk[3] = {i, j, k};
        for (int a = 0; a < 3; ++a) c[a] = dom.box.lo[a] + (dom.box.hi[a] - dom.box.lo[a]) * (ijk[a] + 0.137) / 8.0;
        bool encroaches = false;
        for (const auto& [key, sg] : m.subcomplex().subsegments()) {
          if (sg.in_ball) continue;
          const Point3 a = tri.point(sg.a), b = tri.point(sg.b);
          if (mesher::dist2(c, mesher::midpoint(a, b)) <= 0.25 * mesher::dist2(a, b)) encroaches = true;
        }
        for (const mesher::Subfacet& h : facets) {
          double r2;
          const Point3 cc = mesher::circumcenter(tri.point(h.v[0]), tri.point(h.v[1]), tri.point(h.v[2]), r2);
          if (mesher::dist2(c, cc) < r2) encroaches = true;
        }
        const mesher::Insertion ins = m.subcomplex().encroach(c, 0);
        if (encroaches) {
          ++split_points;
          EXPECT_NE(ins.on, mesher::On::free) << "c encroaches a feature but ENCROACH returned it";
        } else {
          ++free_points;
          EXPECT_EQ(ins.on, mesher::On::free);
          EXPECT_EQ(ins.p, c);
        }
      }
  EXPECT_GT(free_points, 0);
  EXPECT_GT(split_points, 0);
  std::size_t vertex_balls = 0;
  for (const ProtectingBall& b : m.balls().all()) vertex_balls += b.vertex_ball;
  EXPECT_EQ(vertex_balls, in.analysis.sharp_vertices.size());
}

TEST(MesherRules, SharpSubsegmentsGetDoubledDiametricBalls) {
  Stage st(from_off(kWedge), true);
  const Input& in = st.in;
  const mesher::Domain& dom = st.dom;
  mesher::Mesher& m = st.m;
  std::size_t sharp = 0;
  for (const auto& [k, s] : m.subcomplex().subsegments()) {
    if (!s.sharp) continue;
    ++sharp;
    const Point3 a = m.triangulation().point(s.a), b = m.triangulation().point(s.b);
    bool found = false;
    for (const ProtectingBall& ball : m.balls().all())
      if (!ball.vertex_ball && ball.center == mesher::midpoint(a, b) &&
          std::fabs(ball.radius - std::sqrt(mesher::dist2(a, b))) < 1e-15 * ball.radius)
        found = true;
    EXPECT_TRUE(found);
  }
  EXPECT_GT(sharp, 0u);
}

}  // namespace
}  // namespace wqmesh

namespace wqmesh {
namespace {

// The options of REFINE without rule 7 (pump off): plenty of slivers left
// for PUMP.
MeshOptions without_rule7() {
  MeshOptions o;
  o.pump = false;
  return o;
}

// INITIALIZE, CONFORM and REFINE on st's mesher, then PUMP's prepare.
mesher::Pump prepared_pump(Stage& st) {
  st.m.initialize();
  st.m.conform();
  st.m.refine();
  mesher::Pump pump = st.m.make_pump();
  pump.prepare();
  return pump;
}

// PUMP's angle key (Pump::angle_key: the pseudo-angle of the cosine and
// sine, made with +, -, *, / and sqrt only, so that native and wasm order
// the candidates alike): known values, increasing with the angle, and the
// pseudo-angle of libm's cosine and sine within rounding.
TEST(MesherPump, AngleKeyIsThePseudoAngleAndIncreases) {
  EXPECT_EQ(mesher::Pump::angle_key(0), 0);
  EXPECT_NEAR(mesher::Pump::angle_key(45), 0.5, 1e-15);
  EXPECT_NEAR(mesher::Pump::angle_key(90), 1, 1e-15);
  EXPECT_NEAR(mesher::Pump::angle_key(180), 2, 1e-15);
  double last = -1;
  for (int i = 0; i <= 3600; ++i) {
    const double deg = i / 20.0, x = std::cos(deg * M_PI / 180), y = std::sin(deg * M_PI / 180);
    const double key = mesher::Pump::angle_key(deg);
    EXPECT_GT(key, last) << deg;
    last = key;
    EXPECT_NEAR(key, x >= 0 ? y / (x + y) : 1 - x / (y - x), 1e-12) << deg;
  }
}

// The candidates' keys are those of the smallest dihedral angle of an inside
// tet at the vertex (tet_min_dihedral_deg's angle, within rounding), at
// most theta's, worst first.
TEST(MesherPump, CandidatesKeysAreTheirTetsSmallestAngles) {
  const std::vector<std::string> files =
      models(WQMESH_EXAMPLE_MODELS, {"slit.off", "edge_facet.off", "thin_wedge.off"});
  if (files.empty()) GTEST_SKIP() << "no model";
  std::size_t checked = 0;
  for (const std::string& file : files) {
    SCOPED_TRACE(file);
    Stage st(load(file), without_rule7());
    mesher::Pump pump = prepared_pump(st);
    const auto cand = pump.candidates();
    EXPECT_TRUE(std::is_sorted(cand.begin(), cand.end()));
    const RegularTriangulation& tri = st.m.triangulation();
    std::vector<Tet> star;
    for (const auto& [key, v] : cand) {
      EXPECT_LE(key, mesher::Pump::angle_key(st.options.theta_deg));
      tri.incident_cells(v, star);
      double nearest = 1;
      for (const Tet& t : star) {
        if (std::count(t.begin(), t.end(), kInfinite)) continue;
        const double deg = tet_min_dihedral_deg(tri.point(t[0]), tri.point(t[1]), tri.point(t[2]), tri.point(t[3]));
        nearest = std::min(nearest, std::fabs(mesher::Pump::angle_key(deg) - key));
      }
      EXPECT_LT(nearest, 1e-9) << "vertex " << v;
      ++checked;
    }
  }
  EXPECT_GT(checked, 0u);
}

TEST(MesherPump, ChosenWeightIsAsGoodAsABruteForceSearchOfTheInterval) {
  // PUMP searches [0, N(v)^2/9] at the critical weights where the star of v
  // changes; a fine grid over the interval must find nothing better.
  // The first model whose REFINE (without rule 7) leaves slivers to pump:
  // the small example models first (the sanitizer build has no shared ones).
  std::vector<std::string> files = models(WQMESH_EXAMPLE_MODELS, {"slit.off", "edge_facet.off", "thin_wedge.off"});
  for (const std::string& f : models(WQMESH_SHARED_MODELS, {"20mm-xyz-cube.stl"})) files.push_back(f);
  if (files.empty()) GTEST_SKIP() << "no model";
  for (const std::string& file : files) {
    Stage st(load(file), without_rule7());
    mesher::Mesher& m = st.m;
    mesher::Pump pump = prepared_pump(st);
    const auto cand = pump.candidates();
    if (cand.empty()) continue;
    int tried = 0, improved = 0;
    std::set<int> seen;
    for (const auto& [angle, v] : cand) {
      if (!seen.insert(v).second) continue;
      if (++tried > 12) break;
      const double wmax = pump.weight_bound(v);
      const mesher::Pump::Features f = pump.features_around(v);
      double brute = pump.evaluate(v, 0, f);
      for (int i = 1; i <= 400; ++i) brute = std::max(brute, pump.evaluate(v, wmax * i / 400.0, f));
      pump.evaluate(v, 0, f);
      const mesher::Pump::Choice c = pump.pump_vertex(v);
      EXPECT_GE(c.quality, brute - 1e-9) << "vertex " << v;
      EXPECT_GE(c.weight, 0);
      EXPECT_LE(c.weight, wmax);
      EXPECT_DOUBLE_EQ(m.triangulation().weight(v), c.weight);
      improved += c.quality > c.base;
      pump.evaluate(v, 0, f);  // leave the mesh as it was for the next vertex
    }
    EXPECT_GT(improved, 0) << file;
    return;
  }
  FAIL() << "no model leaves a sliver for PUMP after REFINE";
}

}  // namespace
}  // namespace wqmesh

namespace wqmesh {
namespace {

TEST(MesherRules, Rule6LeavesTetsOnAVertexBallSphereAlone) {
  // Four vertices on the sphere of one vertex ball: their circumsphere is that
  // sphere, its center u lies in the ball and rule 6 refuses it. Computed in
  // floating point, the circumcenter of such a nearly flat tet lands far from
  // u; it must not be inserted (thin_wedge at max_size 0.2 once inserted it,
  // and the tet stayed, its real circumsphere being empty).
  const auto files = models(WQMESH_EXAMPLE_MODELS, {"thin_wedge.off"});
  if (files.empty()) GTEST_SKIP() << "no example models";
  MeshOptions o;
  o.pump = false;
  o.max_size = 0.2;
  Stage st(load(files[0]), o);
  mesher::Mesher& m = st.m;
  std::set<std::array<double, 3>> rule6;
  m.inserter().observer = [&](const mesher::Insertion& ins, int rule, int id) {
    if (id >= 0 && rule == 6 && ins.on == mesher::On::free) rule6.insert(ins.p);
  };
  m.initialize();
  m.conform();
  m.refine();
  ASSERT_FALSE(rule6.empty());
  std::size_t on_sphere = 0;
  for (const Tet& t : m.triangulation().finite_cells()) {
    const int u = m.vertices()[t[0]].ball;
    if (u < 0 || m.vertices()[t[1]].ball != u || m.vertices()[t[2]].ball != u || m.vertices()[t[3]].ball != u) continue;
    ++on_sphere;
    const auto& tri = m.triangulation();
    double r2;
    const Point3 z = mesher::circumcenter(tri.point(t[0]), tri.point(t[1]), tri.point(t[2]), tri.point(t[3]), r2);
    EXPECT_EQ(rule6.count(z), 0u) << "rule 6 inserted the circumcenter of a tet on the sphere of vertex " << u;
  }
  // Since SOS splits off the middle (issue 14), no four points of a sphere
  // are coplanar, so its center u lies in their circumsphere: no such tet.
  EXPECT_EQ(on_sphere, 0u);
}

// The squared distances from p to the vertices of `tri` other than `skip`
// (those with |dot(v - origin, n)| <= tol only, when n is not zero), sorted.
// The brute-force oracle of the rules' points: a circumcenter is the point at
// equal distance from the vertices of its simplex.
template <class Tri>
std::vector<double> sorted_dist2(const Tri& tri, const Point3& p, int skip, const Point3& origin = {{0, 0, 0}},
                                 const Point3& n = {{0, 0, 0}}, double tol = 0) {
  std::vector<double> d;
  const bool plane = n[0] != 0 || n[1] != 0 || n[2] != 0;
  for (int v = 0; v < tri.number_of_vertices(); ++v) {
    if (v == skip) continue;
    const Point3& q = tri.point(v);
    if (plane && std::fabs(dot(sub(q, origin), n)) > tol) continue;
    d.push_back(mesher::dist2(p, q));
  }
  std::sort(d.begin(), d.end());
  return d;
}

// True when `d` (sorted) holds k values equal within a relative 1e-7.
bool has_k_equal(const std::vector<double>& d, std::size_t k) {
  for (std::size_t i = 0; i + k - 1 < d.size(); ++i)
    if (d[i + k - 1] - d[i] <= 1e-7 * d[i + k - 1]) return true;
  return false;
}

TEST(MesherRules, EveryRuleInsertsThePointThePaperNames) {
  // Watches every insertion of CONFORM and REFINE (section 4.3) and checks
  // each point against the procedure of the rule that put it, with a
  // brute-force oracle (distances to every vertex) rather than the mesher's
  // own geometry. Every rule calls one of three: SPLITE, the midpoint of a
  // subsegment (or, for a shield subsegment, the SOS point on the arc of its
  // vertex ball, a little off its arc's middle); SPLITF, the circumcenter of a
  // subfacet: in its facet, at equal distance from three vertices of that
  // facet's plane, and encroaching no subsegment; ENCROACH(z) of rule 6,
  // which inserts z itself when it is free: the circumcenter of a Delaunay
  // tet (REFINE has no weights yet), so at least four vertices at the same
  // smallest distance, outside every protecting ball. edge_facet.off and
  // slit.off together make every rule 1-7 insert (rule 3 twice on the one,
  // rule 7 four times on the other); the 20 mm cube, when ../shared/models
  // is there, adds thousands of rule-6 points.
  std::vector<std::string> files = models(WQMESH_EXAMPLE_MODELS, {"edge_facet.off", "slit.off"});
  ASSERT_EQ(files.size(), 2u) << "examples/models/edge_facet.off or slit.off is missing";
  std::array<int, 8> examples_seen{};
  for (const auto& f : models(WQMESH_SHARED_MODELS, {"20mm-xyz-cube.stl"})) files.push_back(f);
  for (const std::string& file : files) {
    SCOPED_TRACE(file);
    Stage st(load(file), MeshOptions{});
    const Input& in = st.in;
    const mesher::Domain& dom = st.dom;
    mesher::Mesher& m = st.m;
    std::array<int, 8> seen{};
    std::size_t circumcenters = 0, subfacet_centers = 0;
    m.inserter().observer = [&](const mesher::Insertion& ins, int rule, int id) {
      if (id < 0) return;
      ++seen[rule];
      const auto& tri = m.triangulation();
      if (ins.has_segment) {
        const int a = int(ins.split_segment >> 32), b = int(ins.split_segment & 0xFFFFFFFFu);
        if (ins.sector >= 0) {
          const int u = m.vertices()[a].ball;
          ASSERT_GE(u, 0);
          invariants::expect_sos_point(ins.p, tri.point(a), tri.point(b), dom.p.vertices[u], dom.ball_radius[u],
                                       dom.sos_asymmetry[u], 1e-9);
        } else {
          EXPECT_EQ(ins.p, mesher::midpoint(tri.point(a), tri.point(b)));
        }
        return;
      }
      // Not a subsegment split: the point encroaches no subsegment.
      for (const auto& [k, s] : m.subcomplex().subsegments()) {
        if (s.in_ball || s.a == id || s.b == id) continue;
        const Point3 pa = tri.point(s.a), pb = tri.point(s.b);
        EXPECT_GT(mesher::dist2(ins.p, mesher::midpoint(pa, pb)), 0.25 * mesher::dist2(pa, pb))
            << "rule " << rule << " put a point that encroaches a subsegment";
      }
      if (ins.on == mesher::On::facet) {
        EXPECT_TRUE(dom.inside_facet(ins.element, ins.p)) << "rule " << rule;
        const auto& fr = dom.frames[ins.element];
        const double tol = 1e-9 * diag(in.plc);
        EXPECT_LE(std::fabs(dot(sub(ins.p, fr.origin), fr.n)), tol);
        // SPLITF: the circumcenter of a subfacet of this facet.
        EXPECT_TRUE(has_k_equal(sorted_dist2(tri, ins.p, id, fr.origin, fr.n, tol), 3))
            << "rule " << rule << ": no three vertices of the facet's plane at equal distance from the point";
        ++subfacet_centers;
      }
      if (rule == 6 && ins.on == mesher::On::free) {
        for (const ProtectingBall& b : m.balls().all())
          EXPECT_GT(mesher::dist2(ins.p, b.center), b.radius * b.radius) << "rule 6 inside a protecting ball";
        // z, the circumcenter of a tet of Del V: its circumball was empty,
        // so its four vertices are the nearest, at the same distance.
        const std::vector<double> d = sorted_dist2(tri, ins.p, id);
        ASSERT_GE(d.size(), 4u);
        EXPECT_LE(d[3] - d[0], 1e-7 * d[3]) << "rule 6 put a point that is not a circumcenter of Del V";
        ++circumcenters;
      }
    };
    m.initialize();
    m.conform();
    m.refine();
    EXPECT_TRUE(m.subcomplex().conforms());
    if (file.find(WQMESH_EXAMPLE_MODELS) == 0)
      for (int rule = 0; rule < 8; ++rule) examples_seen[rule] += seen[rule];
    EXPECT_GT(circumcenters, 0u);
    EXPECT_GT(subfacet_centers, 0u);
    std::printf("[ rules    ] %s: points by rule 0..7:", fs::path(file).filename().c_str());
    for (int n : seen) std::printf(" %d", n);
    std::printf("\n");
  }
  for (int rule = 1; rule <= 7; ++rule) EXPECT_GT(examples_seen[rule], 0) << "rule " << rule << " inserted nothing";
}

}  // namespace
}  // namespace wqmesh

namespace wqmesh {
namespace {

// The speed work of issue 15 keeps the meshes: the sliver count before PUMP
// (count_qmesh_slivers, without building the mesh) is extract()'s count, the
// scan it hands to PUMP gives PUMP the candidates of PUMP's own scan, and
// labels said to be order-free are the same for the cells in another order.
TEST(MesherSpeed, SliverCountAndHandedScanAgreeWithTheFullOnes) {
  std::vector<std::string> files =
      models(WQMESH_EXAMPLE_MODELS, {"edge_facet.off", "slit.off", "thin_wedge.off", "bracket.off"});
  ASSERT_FALSE(files.empty()) << "examples/models is missing";
  for (const auto& f : models(WQMESH_SHARED_MODELS, {"20mm-xyz-cube.stl", "slit-1.off"})) files.push_back(f);
  int order_free_models = 0;
  for (const std::string& file : files) {
    SCOPED_TRACE(file);
    MeshOptions o;
    o.pump = false;  // no rule 7: slivers left to count
    Stage st(load(file), o);
    const mesher::Domain& dom = st.dom;
    mesher::Mesher& m = st.m;
    m.initialize();
    m.conform();
    m.refine();
    RegularTriangulation::CellGraph scan;
    std::vector<char> scan_labels;
    std::vector<double> nn;
    mesher::Extract x(dom, o, m.triangulation(), m.vertices(), m.subcomplex(), m.balls(), nn, m.meter());
    bool in_cells = false;
    const std::size_t counted = x.count_qmesh_slivers(scan, scan_labels, in_cells);
    // The labels it leaves: in the cells' label bytes (cell_graph's order),
    // or the scan's.
    std::vector<char> left = scan_labels;
    if (in_cells) {
      EXPECT_TRUE(scan.cells.empty());
      left.clear();
      m.triangulation().visit_labels([&](const Tet&, char& label) {
        left.push_back(label == RegularTriangulation::kExcludedOdd ? char(0) : label);
      });
    }
    // The scan count_qmesh_slivers hands on is PUMP's own.
    mesher::Pump handed = m.make_pump();
    if (in_cells)
      handed.use_cell_labels();
    else
      handed.use_scan(scan, scan_labels);
    handed.prepare();
    mesher::Pump own = m.make_pump();
    own.prepare();
    EXPECT_EQ(handed.candidates(), own.candidates());
    EXPECT_EQ(counted, m.extract().slivers);
    const RegularTriangulation::CellGraph g = m.triangulation().cell_graph();
    bool order_free = false;
    const std::vector<char> labels = mesher::interior_labels(dom, m.subcomplex(), g, m.meter(), false, &order_free);
    EXPECT_EQ(labels, left);
    // Labels in the cells only where they are free of the order; else the
    // scan hands on its cells without their neighbours (PUMP reads only the
    // cells): the same triangulation's own graph, in the same order.
    if (in_cells) {
      EXPECT_TRUE(order_free);
    } else {
      EXPECT_TRUE(scan.neighbor.empty());
      EXPECT_EQ(g.cells, scan.cells);
    }
    // Labels in reversed cell order.
    RegularTriangulation::CellGraph r;
    const int n = static_cast<int>(g.cells.size());
    for (int i = n - 1; i >= 0; --i) {
      r.cells.push_back(g.cells[i]);
      std::array<int, 4> nb = g.neighbor[i];
      for (int& c : nb) c = n - 1 - c;
      r.neighbor.push_back(nb);
    }
    const std::vector<char> reversed = mesher::interior_labels(dom, m.subcomplex(), r, m.meter());
    if (order_free) {
      ++order_free_models;
      for (int i = 0; i < n; ++i) ASSERT_EQ(labels[i], reversed[n - 1 - i]) << "cell " << i;
    }
  }
  EXPECT_GT(order_free_models, 0);
}

// Runs INITIALIZE, CONFORM and REFINE on m, calling check() after CONFORM
// and after REFINE and, when after_insertions, after every insertion of a
// vertex; returns how many insertions it saw (0 unless after_insertions).
std::size_t conform_and_refine_checking(mesher::Mesher& m, const std::function<void()>& check, bool after_insertions) {
  std::size_t insertions = 0;
  if (after_insertions)
    m.inserter().observer = [&](const mesher::Insertion&, int, int id) {
      if (id < 0) return;
      ++insertions;
      check();
    };
  m.initialize();
  m.conform();
  check();
  m.refine();
  check();
  return insertions;
}

// A fresh Mesher with default options for each of files (which must not be
// empty), given to body.
void for_each_model(const std::vector<std::string>& files, const std::function<void(mesher::Mesher&)>& body) {
  ASSERT_FALSE(files.empty()) << "examples/models is missing";
  for (const std::string& file : files) {
    SCOPED_TRACE(file);
    Stage st(load(file), MeshOptions{});
    body(st.m);
  }
}

// Calls f(s, fresh) for every subsegment s that holds the record of a test,
// fresh a copy of s without its cell hint (so that a test of it walks).
void for_each_tested_subsegment(mesher::Mesher& m,
                                const std::function<void(const mesher::Subsegment&, mesher::Subsegment&)>& f) {
  for (const auto& [k, s] : m.subcomplex().subsegments()) {
    if (s.tested_at == 0) continue;
    mesher::Subsegment fresh = s;
    fresh.cell = nullptr;
    f(s, fresh);
  }
}

// The record of the rule 1/4 test a subsegment keeps (Subsegment::
// tested_at, queued_at, encroached; issue 15) is reused only when no
// insertion queued the subsegment since the test: then it must be what the
// test says now. Checked against a fresh segment_encroached of every
// subsegment after every insertion of CONFORM and REFINE.
TEST(MesherSpeed, KeptSubsegmentTestsAgreeWithAFreshTest) {
  std::vector<std::string> files = models(WQMESH_EXAMPLE_MODELS, {"slit.off", "thin_wedge.off"});
  for (const auto& f : models(WQMESH_SHARED_MODELS, {"20mm-xyz-cube.stl"})) files.push_back(f);
  for_each_model(files, [](mesher::Mesher& m) {
    std::size_t kept = 0;
    auto check = [&] {
      for_each_tested_subsegment(m, [&](const mesher::Subsegment& s, mesher::Subsegment& fresh) {
        if (s.tested_at < s.queued_at) return;  // tested again when next popped
        ++kept;
        ASSERT_EQ(s.encroached, m.subcomplex().segment_encroached(fresh)) << "subsegment " << s.a << "-" << s.b;
      });
    };
    EXPECT_GT(conform_and_refine_checking(m, check, true), 0u);
    EXPECT_GT(kept, 0u);
  });
}

// Subcomplex::segment_encroached_update (issue 15) answers from a
// subsegment's record of its last test and of the vertices that queued it
// since (Subsegment::ball_entered): it must say what a fresh full test says,
// for every subsegment with a record (stale ones included), after every
// insertion of CONFORM and REFINE.
TEST(MesherSpeed, UpdatedSubsegmentTestsAgreeWithAFreshTest) {
  for_each_model(models(WQMESH_EXAMPLE_MODELS, {"slit.off", "thin_wedge.off"}), [](mesher::Mesher& m) {
    std::size_t updated = 0;
    auto check = [&] {
      const int n = m.triangulation().number_of_vertices();
      for_each_tested_subsegment(m, [&](const mesher::Subsegment& s, mesher::Subsegment& fresh) {
        // The short way is taken (a record saying "not encroached", no
        // vertex that queued it since counting for it): counted, so that the
        // test cannot pass without it.
        updated += !s.encroached && !s.in_ball && !s.ball_entered;
        mesher::Subsegment kept = s;
        ASSERT_EQ(m.subcomplex().segment_encroached_update(kept), m.subcomplex().segment_encroached(fresh))
            << "subsegment " << s.a << "-" << s.b << " tested at " << s.tested_at << " of " << n;
      });
    };
    EXPECT_GT(conform_and_refine_checking(m, check, true), 0u);
    EXPECT_GT(updated, 0u);
  });
}

// mesher::nearest_neighbours (one pass over the cells; issue 15) gives every
// vertex the N(v) of nearest_neighbour's star walk, bit for bit, after
// CONFORM and after REFINE.
TEST(MesherSpeed, NearestNeighboursOfAllVerticesAgreeWithEachVertexsWalk) {
  for_each_model(models(WQMESH_EXAMPLE_MODELS, {"slit.off", "thin_wedge.off"}), [](mesher::Mesher& m) {
    auto check = [&] {
      const RegularTriangulation& tri = m.triangulation();
      std::vector<double> all;
      ASSERT_TRUE(mesher::nearest_neighbours(tri, all));
      ASSERT_EQ(all.size(), std::size_t(tri.number_of_vertices()));
      ASSERT_EQ(all.size(), m.vertices().size());
      for (int v = 0; v < tri.number_of_vertices(); ++v) {
        ASSERT_EQ(all[v], mesher::nearest_neighbour(tri, v)) << "vertex " << v;
        ASSERT_TRUE(std::isfinite(all[v]) && all[v] > 0) << "vertex " << v;
      }
    };
    conform_and_refine_checking(m, check, false);
  });
}

// Rule 3's records (Conform::rule3_pass, issue 15) skip the test of a sharp
// subsegment whose midpoint's conflict cells no insertion touched since its
// last test found nothing: after CONFORM every record that would skip now
// must agree with a fresh test, which finds nothing to split.
TEST(MesherSpeed, Rule3RecordsAgreeWithAFreshTest) {
  std::vector<std::string> files = models(WQMESH_EXAMPLE_MODELS, {"slit.off", "thin_wedge.off", "spike.off"});
  for (const auto& f : models(WQMESH_SHARED_MODELS, {"20mm-xyz-cube.stl", "wedge-1.off", "part.off"}))
    files.push_back(f);
  ASSERT_FALSE(files.empty()) << "examples/models is missing";
  std::size_t skipped = 0;
  for (const std::string& file : files) {
    SCOPED_TRACE(file);
    Stage st(load(file), MeshOptions{});
    mesher::Mesher& m = st.m;
    m.initialize();
    mesher::Conform c = m.make_conform();
    c.run();
    EXPECT_TRUE(c.rule3_records_hold());
    skipped += c.rule3_skipped();
    EXPECT_TRUE(m.subcomplex().conforms());
  }
  EXPECT_GT(skipped, 0u);  // some test was skipped: the records were used
}

// The byte per vertex behind Subcomplex::on_p (issue 15) says what the
// vertex's own record says, for every vertex, after every phase of a run.
TEST(MesherSpeed, KeptOnPMarksAgreeWithTheVertexRecords) {
  std::vector<std::string> files = models(WQMESH_EXAMPLE_MODELS, {"slit.off", "thin_wedge.off"});
  ASSERT_FALSE(files.empty()) << "examples/models is missing";
  for (const std::string& file : files) {
    SCOPED_TRACE(file);
    Stage st(load(file), MeshOptions{});
    mesher::Mesher& m = st.m;
    std::size_t on = 0, free = 0;
    auto check = [&] {
      const auto& verts = m.vertices();
      for (int v = 0; v < static_cast<int>(verts.size()); ++v) {
        const bool expected = verts[v].on != mesher::On::free;
        ASSERT_EQ(m.subcomplex().on_p(v), expected) << "vertex " << v;
        ++(expected ? on : free);
      }
      EXPECT_FALSE(m.subcomplex().on_p(kInfinite));
    };
    m.initialize();
    check();
    m.conform();
    check();
    m.refine();
    check();
    m.pump();
    check();
    EXPECT_GT(on, 0u);
    EXPECT_GT(free, 0u);
  }
}

// The upkeep of a free insertion in REFINE reads the features it may have
// to split from the insertion's cavity (Queues::enqueue_from_cavity, issue
// 15, step 6), not from the new vertex's ring. What that relies on, checked
// after every insertion: a subsegment or subfacet that needs a split of rule
// 4 or 5 after a free insertion of rule 6 and did not before it (encroached,
// or a guarded subfacet gone from Del V) is an edge or triangle of a cell of
// the cavity (RegularTriangulation::last_cavity); and the cavity is known for
// every such insertion. The features needing a split are found afresh, from
// every subsegment and subfacet.
TEST(MesherSpeed, FreeInsertionsChangeOnlyTheFeaturesOfTheirCavity) {
  const std::vector<std::string> files =
      models(WQMESH_EXAMPLE_MODELS, {"slit.off", "thin_wedge.off", "spike.off", "edge_facet.off"});
  ASSERT_FALSE(files.empty()) << "examples/models is missing";
  std::size_t free_insertions = 0, new_needs = 0, cavity_features = 0;
  for (const std::string& file : files) {
    SCOPED_TRACE(file);
    Stage st(load(file), MeshOptions{});
    mesher::Mesher& m = st.m;
    const mesher::Subcomplex& sub = m.subcomplex();
    auto needing = [&] {
      std::set<std::vector<int>> out;  // {a, b} or {facet, a, b, c}, sorted vertices
      for (const auto& [k, s] : sub.subsegments()) {
        mesher::Subsegment fresh = s;
        fresh.cell = nullptr;
        if (sub.segment_encroached(fresh)) out.insert({std::min(s.a, s.b), std::max(s.a, s.b)});
      }
      for (const mesher::Subfacet& h : sub.subfacets())
        if (sub.guarded(h) ? !sub.subfacet_present(h) : sub.subfacet_encroached(h)) {
          const mesher::Tri t = mesher::sorted(h.v);
          out.insert({h.facet, t[0], t[1], t[2]});
        }
      return out;
    };
    std::set<std::vector<int>> before;
    m.inserter().observer = [&](const mesher::Insertion& ins, int rule, int id) {
      if (id < 0) return;
      const std::set<std::vector<int>> now = needing();
      if (rule == 6 && ins.on == mesher::On::free) {
        ++free_insertions;
        const std::vector<Tet>* cavity = m.triangulation().last_cavity();
        ASSERT_NE(cavity, nullptr) << "insertion " << id;
        std::set<std::vector<int>> edges, tris;
        for (Tet c : *cavity) {
          std::sort(c.begin(), c.end());
          for (int i = 0; i < 4; ++i)
            for (int j = i + 1; j < 4; ++j) edges.insert({c[i], c[j]});
          for (int k = 0; k < 4; ++k) {
            std::vector<int> t;
            for (int i = 0; i < 4; ++i)
              if (i != k) t.push_back(c[i]);
            tris.insert(t);
          }
        }
        for (const std::vector<int>& f : now) {
          if (before.count(f)) continue;
          ++new_needs;
          if (f.size() == 2)
            EXPECT_TRUE(edges.count(f)) << "subsegment " << f[0] << "-" << f[1] << " after insertion " << id;
          else
            EXPECT_TRUE(tris.count({f[1], f[2], f[3]}))
                << "subfacet " << f[1] << " " << f[2] << " " << f[3] << " after insertion " << id;
        }
        for (const auto& [k, s] : sub.subsegments())
          if (edges.count({std::min(s.a, s.b), std::max(s.a, s.b)})) ++cavity_features;
      }
      before = now;
    };
    m.initialize();
    before = needing();
    m.conform();
    m.refine();
  }
  EXPECT_GT(free_insertions, 100u);
  EXPECT_GT(cavity_features, 0u);  // the cavities do reach the boundary
  std::cout << "free insertions " << free_insertions << ", features needing a split after one " << new_needs
            << ", subsegments among the cavities' edges " << cavity_features << "\n";
}

}  // namespace
}  // namespace wqmesh
