// SPDX-License-Identifier: GPL-3.0-or-later
// wqmesh: the statistics of a run are recountable from what it writes
// (issue 14, item 3). For each model the test meshes it, writes the Medit
// mesh and the statistics JSON, reads both back (read_medit, parse_json) and
// recounts every class and statistic with its own brute-force code (long
// double circumcenters and dihedral angles, every protecting ball looked at
// for every tet; no call of the core's quality or classification code), by
// the definition in core/src/mesher/classify.h. The counts must be equal.
// A decision within rounding of its threshold (|R/l - rho0|, a distance
// against a ball's radius, a dihedral angle against a bin's edge; 1e-9
// relative, more where the circumcenter itself is ill-conditioned, as for
// the flat tets whose four points are cocircular to rounding) may go either
// way in two different computations: such tets are counted as unsure, and a
// count may then differ by at most the unsure tets of its kind.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "geometry.h"
#include "mesher/classify.h"
#include "mesher/improve.h"
#include "wqmesh/json_reader.h"
#include "wqmesh/mesh_reader.h"
#include "wqmesh/wqmesh.h"

namespace wqmesh {
namespace {

using L3 = std::array<long double, 3>;

L3 sub(const Point3& a, const Point3& b) {
  return {{(long double)a[0] - b[0], (long double)a[1] - b[1], (long double)a[2] - b[2]}};
}
long double dot(const L3& a, const L3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
L3 cross(const L3& a, const L3& b) {
  return {{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}};
}

/// Relative width of a decision that counts as within rounding.
constexpr long double kTol = 1e-9L;
/// The rounding of one double operation (the core computes in double).
constexpr long double kEps = 1.2e-16L;

/// -1 below the threshold, +1 above, 0 within `tol` (absolute).
int side(long double x, long double threshold, long double tol) {
  if (std::fabs(x - threshold) <= tol) return 0;
  return x > threshold ? 1 : -1;
}

struct Ball {
  Point3 c;
  double r;
};

/// The counts of a recount. A tet whose decision is within rounding is
/// counted by the recount's side, and also in the matching `*_unsure`: the
/// split between skinny and sliver (R/l against rho0), being bad at all
/// (skinny or sliver or neither), near or not, the bins.
struct Recount {
  std::size_t skinny = 0, slivers = 0, near = 0, violations = 0;
  std::size_t split_unsure = 0, bad_unsure = 0, near_unsure = 0, bins_unsure = 0;
  std::array<std::size_t, 3> radius_edge_bins{}, dihedral_bins{};
  long double min_dihedral = 180;
  std::set<std::size_t> violation_tets, unsure_tets;
};

Recount recount(const TetMesh& m, const std::vector<Ball>& balls, double rho0, double theta) {
  // L_v: the shortest edge at v in the mesh.
  std::vector<long double> shortest(m.vertices.size(), std::numeric_limits<long double>::infinity());
  for (const auto& t : m.tets)
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) {
        const L3 e = sub(m.vertices[t[i]], m.vertices[t[j]]);
        const long double len = std::sqrt(dot(e, e));
        shortest[t[i]] = std::min(shortest[t[i]], len);
        shortest[t[j]] = std::min(shortest[t[j]], len);
      }
  Recount out;
  for (std::size_t ti = 0; ti < m.tets.size(); ++ti) {
    const auto& t = m.tets[ti];
    std::array<Point3, 4> p;
    for (int k = 0; k < 4; ++k) p[k] = m.vertices[t[k]];
    // Circumcenter: a + (|u|^2 v x w + |v|^2 w x u + |w|^2 u x v) / (2 u . v x w).
    const L3 u = sub(p[1], p[0]), v = sub(p[2], p[0]), w = sub(p[3], p[0]);
    const L3 vw = cross(v, w), wu = cross(w, u), uv = cross(u, v);
    const long double den = 2 * dot(u, vw);  // 12 times the signed volume
    L3 z{}, x{};
    for (int k = 0; k < 3; ++k) {
      x[k] = (dot(u, u) * vw[k] + dot(v, v) * wu[k] + dot(w, w) * uv[k]) / den;
      z[k] = p[0][k] + x[k];
    }
    const long double R = den == 0 ? std::numeric_limits<long double>::infinity() : std::sqrt(dot(x, x));
    long double l = std::numeric_limits<long double>::infinity(), lmax = 0;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) {
        const L3 e = sub(p[i], p[j]);
        l = std::min(l, std::sqrt(dot(e, e)));
        lmax = std::max(lmax, std::sqrt(dot(e, e)));
      }
    const long double rho = R / l;
    // The relative rounding of the circumcenter (and so of R) in double: the
    // volume's, eps * lmax^3 / (6 |vol|). A flat tet (four points cocircular
    // to rounding) has no defined circumcenter: its R/l is whatever rounding
    // makes it.
    const long double rel = std::max(kTol, den == 0 ? std::numeric_limits<long double>::infinity()
                                                    : 64 * kEps * lmax * lmax * lmax / std::fabs(den / 2));
    // Dihedral angle at edge ij: between the faces ijk and ijl.
    long double min_dihedral = 180;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) {
        int k = 0;
        while (k == i || k == j) ++k;
        const int o = 6 - i - j - k;
        const L3 e = sub(p[j], p[i]);
        const L3 n1 = cross(e, sub(p[k], p[i])), n2 = cross(e, sub(p[o], p[i]));
        const long double a = std::sqrt(dot(n1, n1) * dot(n2, n2));
        const long double c = a == 0 ? 1 : std::max(-1.0L, std::min(1.0L, dot(n1, n2) / a));
        min_dihedral = std::min(min_dihedral, std::acos(c) * 180 / 3.14159265358979323846264338327950288L);
      }
    out.min_dihedral = std::min(out.min_dihedral, min_dihedral);
    // Classes.
    const int s_rho = side(rho, rho0, rel * rho0);
    const int s_theta = side(min_dihedral, theta, kTol * std::max(1.0, theta));
    const bool skinny = s_rho > 0, sliver = !skinny && s_theta < 0;
    // Bad (skinny or sliver) for sure: a dihedral angle surely below theta,
    // or R/l surely above rho0; good for sure: neither, surely.
    const bool bad_sure = s_theta < 0 || s_rho > 0 || (s_rho < 0 && s_theta > 0);
    const bool split_sure = s_rho != 0;
    bool near = false, near_sure = true;
    if (skinny || sliver || !bad_sure) {
      bool unsure = false;
      for (const Ball& b : balls) {
        const long double r2 = (long double)b.r * b.r;
        // (a) the circumcenter on or inside the ball.
        if (den != 0) {
          L3 d{};
          for (int k = 0; k < 3; ++k) d[k] = z[k] - b.c[k];
          const long double d2 = dot(d, d);
          const long double tol = kTol * (r2 + d2) + 4 * rel * R * (std::sqrt(d2) + R);
          const int s = side(d2, r2, tol);
          near = near || s < 0;
          unsure = unsure || s == 0;
        }
        // (b) a vertex v with |v - c|^2 <= (2r)^2 + L_v^2 / 9.
        for (int k = 0; k < 4; ++k) {
          const L3 d = sub(p[k], b.c);
          const long double bound = 4 * r2 + shortest[t[k]] * shortest[t[k]] / 9;
          const int s = side(dot(d, d), bound, kTol * (bound + dot(d, d)));
          near = near || s < 0;
          unsure = unsure || s == 0;
        }
      }
      near_sure = near || !unsure;
    }
    // Table 2's bins: R/l in [0.6, 1.4], (1.4, 2.2], > 2.2; smallest
    // dihedral in [0, 3), [3, 5), [5, 10).
    const int radius_edge_bin = rho <= 1.4L ? 0 : rho <= 2.2L ? 1 : 2;
    bool bins_sure = side(rho, 1.4L, rel * 1.4L) != 0 && side(rho, 2.2L, rel * 2.2L) != 0;
    const int dihedral_bin = min_dihedral < 3 ? 0 : min_dihedral < 5 ? 1 : min_dihedral < 10 ? 2 : -1;
    for (long double edge : {3.0L, 5.0L, 10.0L}) bins_sure = bins_sure && side(min_dihedral, edge, kTol * edge) != 0;

    ++out.radius_edge_bins[radius_edge_bin];
    if (dihedral_bin >= 0) ++out.dihedral_bins[dihedral_bin];
    out.bins_unsure += !bins_sure;
    out.skinny += skinny;
    out.slivers += sliver;
    out.split_unsure += (skinny || sliver || !bad_sure) && !split_sure;
    out.bad_unsure += !bad_sure;
    out.near_unsure += !near_sure;
    if (!bad_sure || !near_sure) out.unsure_tets.insert(ti);
    if (skinny || sliver) {
      out.near += near;
      out.violations += !near;
      if (!near) out.violation_tets.insert(ti);
    }
  }
  return out;
}

std::size_t count_of(const JsonValue& stats, const std::string& key) {
  const JsonValue* v = stats.find(key);
  EXPECT_TRUE(v != nullptr && v->kind == JsonValue::Kind::number) << "stats key " << key;
  return v == nullptr ? 0 : static_cast<std::size_t>(v->number);
}

/// |a - b| <= slack, as a test failure naming `what`.
void expect_within(std::size_t a, std::size_t b, std::size_t slack, const std::string& what) {
  EXPECT_LE(a > b ? a - b : b - a, slack) << what << ": stats " << a << ", recount " << b;
}

struct Totals {
  std::size_t tets = 0, bad = 0, near = 0, unsure = 0, split_unsure = 0;
};

/// Meshes `path` with `options`, recounts, and keeps the statistics in `out`.
void check_model(const std::filesystem::path& path, Totals& totals, const Options& options = {},
                 JsonValue* out = nullptr) {
  SCOPED_TRACE(path.string());
  const Polyhedron in = Polyhedron::read_file(path.string(), options);
  ASSERT_TRUE(in.valid()) << in.error_message();
  const Result r = mesh(in, options);
  ASSERT_TRUE(r.conforming());
  std::ostringstream medit;
  r.write(medit, OutputFormat::medit);
  const std::string text = medit.str();
  const TetMesh written = read_medit(text.data(), text.size());
  const JsonValue stats = parse_json(r.stats_json());
  if (out != nullptr) *out = stats;

  std::vector<Ball> balls;
  const JsonValue* jb = stats.find("protecting_balls");
  ASSERT_TRUE(jb != nullptr && jb->kind == JsonValue::Kind::array);
  for (const JsonValue& b : jb->array) {
    const JsonValue* c = b.find("center");
    const JsonValue* rad = b.find("radius");
    ASSERT_TRUE(c != nullptr && c->array.size() == 3 && rad != nullptr);
    balls.push_back({{{c->array[0].number, c->array[1].number, c->array[2].number}}, rad->number});
  }
  ASSERT_EQ(balls.size(), r.raw().protecting_balls.size());
  const JsonValue* opts = stats.find("options");
  ASSERT_TRUE(opts != nullptr && opts->find("rho0") != nullptr && opts->find("theta_deg") != nullptr);
  const double rho0 = opts->find("rho0")->number, theta = opts->find("theta_deg")->number;

  const Recount rc = recount(written, balls, rho0, theta);
  ASSERT_EQ(count_of(stats, "tets"), written.tets.size());
  // Skinny against sliver may go either way where R/l is within rounding of
  // rho0 (flat tets); being bad, and near, only where those decisions are.
  const std::size_t bad_slack = rc.bad_unsure + rc.near_unsure;
  expect_within(count_of(stats, "skinny"), rc.skinny, rc.split_unsure + rc.bad_unsure, "skinny");
  expect_within(count_of(stats, "slivers"), rc.slivers, rc.split_unsure + rc.bad_unsure, "slivers");
  expect_within(count_of(stats, "skinny") + count_of(stats, "slivers"), rc.skinny + rc.slivers, rc.bad_unsure,
                "skinny + slivers");
  expect_within(count_of(stats, "near_small_angle"), rc.near, bad_slack, "near_small_angle");
  expect_within(count_of(stats, "violations"), rc.violations, bad_slack, "violations");
  const JsonValue* share = stats.find("near_small_angle_share");
  ASSERT_TRUE(share != nullptr);
  EXPECT_DOUBLE_EQ(share->number,
                   written.tets.empty() ? 0.0 : double(count_of(stats, "near_small_angle")) / written.tets.size());
  // The violations listed (all of them: fewer than the list's cap here).
  std::set<std::size_t> listed;
  for (const JsonValue& v : stats.find("violation_tets")->array)
    listed.insert(static_cast<std::size_t>(v.find("tet")->number));
  for (std::size_t t : listed)
    EXPECT_TRUE(rc.violation_tets.count(t) || rc.unsure_tets.count(t)) << "listed violation " << t;
  for (std::size_t t : rc.violation_tets)
    EXPECT_TRUE(listed.count(t) || rc.unsure_tets.count(t)) << "recounted violation " << t << " not listed";
  // Table 2's bins and the smallest dihedral angle.
  const char* rb[3] = {"0.6-1.4", "1.4-2.2", ">2.2"};
  const char* db[3] = {"0-3", "3-5", "5-10"};
  for (int k = 0; k < 3; ++k) {
    expect_within(count_of(*stats.find("radius_edge_bins"), rb[k]), rc.radius_edge_bins[k], rc.bins_unsure,
                  std::string("radius_edge_bins ") + rb[k]);
    expect_within(count_of(*stats.find("dihedral_bins"), db[k]), rc.dihedral_bins[k], rc.bins_unsure,
                  std::string("dihedral_bins ") + db[k]);
  }
  EXPECT_NEAR(stats.find("min_dihedral_deg")->number, double(rc.min_dihedral), 1e-9 * std::max(1.0L, rc.min_dihedral));
  totals.tets += written.tets.size();
  totals.bad += rc.skinny + rc.slivers;
  totals.near += rc.near;
  totals.unsure += bad_slack;
  totals.split_unsure += rc.split_unsure;
  std::cout << "[ recount  ] " << path.filename().string() << ": tets " << written.tets.size() << ", skinny "
            << rc.skinny << ", slivers " << rc.slivers << ", near " << rc.near << ", violations " << rc.violations
            << "; within rounding: skinny/sliver " << rc.split_unsure << ", bad " << rc.bad_unsure << ", near "
            << rc.near_unsure << ", bins " << rc.bins_unsure << "\n";
}

std::vector<std::filesystem::path> models() {
  std::vector<std::filesystem::path> out;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(WQMESH_EXAMPLE_MODELS, ec))
    if (e.path().extension() == ".off") out.push_back(e.path());
  const std::string shared = WQMESH_SHARED_MODELS;
  if (!shared.empty())
    for (const char* name : {"20mm-xyz-cube.stl", "part.off", "slit-1.off", "wedge-1.off"})
      if (std::filesystem::exists(std::filesystem::path(shared) / name))
        out.push_back(std::filesystem::path(shared) / name);
  std::sort(out.begin(), out.end());
  return out;
}

TEST(Recount, StatsEqualARecountFromTheWrittenMeshAndBalls) {
  const auto files = models();
  ASSERT_FALSE(files.empty()) << "no models in " << WQMESH_EXAMPLE_MODELS;
  Totals totals;
  for (const auto& f : files) check_model(f, totals);
  // The recount has something to recount: the models have tets near small
  // angles (the example models are made for it), and almost every decision
  // is clear of its threshold.
  EXPECT_GT(totals.near, 0u);
  EXPECT_LE(totals.unsure, totals.bad / 100 + 1);
  EXPECT_LE(totals.split_unsure, totals.bad / 20 + 1);
}

// The class counts the improvement phase reports for the mesh before it are
// those of the same run without it (--no-improve), whose statistics are
// recountable from its own written mesh.
TEST(Recount, TheCountsBeforeTheImprovementAreThoseOfTheRunWithoutIt) {
  std::vector<std::filesystem::path> files;
  for (const auto& f : models())
    if (f.filename() != "part.off" && f.filename() != "wedge-1.off") files.push_back(f);  // time
  Totals totals;
  Options plain;
  plain.set("improve", 0);
  for (const auto& f : files) {
    SCOPED_TRACE(f.string());
    JsonValue with, without;
    check_model(f, totals, Options(), &with);
    check_model(f, totals, plain, &without);
    const JsonValue* im = with.find("improve");
    ASSERT_TRUE(im != nullptr && im->find("ran") != nullptr);
    if (!im->find("ran")->boolean) continue;
    for (const char* k : {"skinny", "slivers", "near_small_angle", "violations", "tets"})
      EXPECT_EQ(count_of(*im, std::string(k) + "_before"), count_of(without, k)) << k;
    EXPECT_EQ(im->find("near_small_angle_share_before")->number, without.find("near_small_angle_share")->number);
    EXPECT_EQ(im->find("min_dihedral_before")->number, without.find("min_dihedral_deg")->number);
  }
}

// ---- the definition on hand-made tets (classify_mesh, the core's code) ----

/// One tet: the square (0,0,0) (1,0,0) (1,1,0) (0,1,0) with (1,1,0) lifted
/// by `h` (a sliver for small h: R/l about 0.71, a dihedral angle near 0).
TetMesh sliver(double h) {
  TetMesh m;
  m.vertices = {{{0, 0, 0}}, {{1, 0, 0}}, {{1, 1, h}}, {{0, 1, 0}}};
  m.tets = {{{0, 1, 2, 3}}};
  return m;
}

TEST(Recount, ASliverIsNearOnlyWhenAVertexReachesTwiceABall) {
  const TetMesh m = sliver(0.01);
  // No ball: a violation.
  MeshClasses c = classify_mesh(m, {}, 2.2, 3);
  EXPECT_EQ(c.slivers, 1u);
  EXPECT_EQ(c.skinny, 0u);
  EXPECT_EQ(c.violations, 1u);
  ASSERT_EQ(c.tet_class.size(), 1u);
  EXPECT_EQ(c.tet_class[0], TetClass::violation);
  // A ball of radius 0.5 at distance 1.2 from vertex 0 (and farther from the
  // others): 1.44 > (2r)^2 = 1, but L_0 = 1 gives 1 + 1/9 = 1.11 < 1.44 too:
  // still a violation. At distance 1.05: 1.1025 <= 1.11, near by (b) only
  // through L_v^2/9.
  const ProtectingBall far{{{-1.2, 0, 0}}, 0.5, true};
  EXPECT_EQ(classify_mesh(m, {far}, 2.2, 3).violations, 1u);
  const ProtectingBall reach{{{-1.05, 0, 0}}, 0.5, true};
  c = classify_mesh(m, {reach}, 2.2, 3);
  EXPECT_EQ(c.near_small_angle, 1u);
  EXPECT_EQ(c.violations, 0u);
  EXPECT_EQ(c.tet_class[0], TetClass::sliver_near);
  // Not a sliver when theta is below its smallest dihedral angle.
  EXPECT_EQ(classify_mesh(m, {}, 2.2, 0.01).slivers, 0u);
}

TEST(Recount, ASkinnyTetIsNearWhenItsCircumcenterIsInABall) {
  // A needle: R/l large; its circumcenter far from every vertex.
  TetMesh m;
  m.vertices = {{{0, 0, 0}}, {{0.05, 0, 0}}, {{0, 1, 0}}, {{0, 0, 1}}};
  m.tets = {{{0, 1, 2, 3}}};
  const TetQuality q = tet_quality(m.vertices[0], m.vertices[1], m.vertices[2], m.vertices[3]);
  ASSERT_GT(q.radius_edge, 2.2);
  const Point3 z{{0.025, 0.5, 0.5}};            // the circumcenter
  const ProtectingBall around{z, 0.01, false};  // around it, far from the vertices' reach
  MeshClasses c = classify_mesh(m, {around}, 2.2, 3);
  EXPECT_EQ(c.skinny, 1u);
  EXPECT_EQ(c.tet_class[0], TetClass::skinny_near);
  const ProtectingBall beside{{{0.025, 0.5, 0.52}}, 0.01, false};  // z outside it, vertices far
  EXPECT_EQ(classify_mesh(m, {beside}, 2.2, 3).tet_class[0], TetClass::violation);
  // Weights are not looked at: the classes are those of the geometry.
  m.weights = {0.001, 0, 0, 0};
  EXPECT_EQ(classify_mesh(m, {beside}, 2.2, 3).tet_class[0], TetClass::violation);
}

// ---- TetClassifier (classify.h): one per-tet test for the statistics and
// the improvement phase's guard ----

/// shape() from the four points (with its cheap estimates) and shape() from
/// tet_quality's measures, which classify_tets uses: equal on tet abcd.
void expect_same_shape(const mesher::TetClassifier& c, const Point3& a, const Point3& b, const Point3& p,
                       const Point3& d) {
  const TetQuality q = tet_quality(a, b, p, d);
  EXPECT_EQ(int(c.shape(a, b, p, d, mesher::min_sine(a, b, p, d))), int(c.shape(q.radius_edge, q.min_dihedral_deg)))
      << "R/l " << q.radius_edge << ", min dihedral " << q.min_dihedral_deg;
}

TEST(Recount, TheClassifiersShapeFromPointsIsTetQualitysOnEveryTet) {
  const mesher::ProtectingBalls none(Box{{{0, 0, 0}}, {{1, 1, 1}}});
  const mesher::TetClassifier c(none, 2.2, 3);
  std::size_t tets = 0;
  for (const auto& f : models()) {
    if (f.filename() == "part.off") continue;  // time
    SCOPED_TRACE(f.string());
    Options plain;
    plain.set("improve", 0);  // the PUMP output has slivers and skinny tets
    for (const Options& o : {Options(), plain}) {
      const Result r = mesh(Polyhedron::read_file(f.string()), o);
      const TetMesh& m = r.raw().mesh;
      for (const auto& t : m.tets)
        expect_same_shape(c, m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]], m.vertices[t[3]]);
      tets += m.tets.size();
    }
  }
  EXPECT_GT(tets, 0u);
  // At the thresholds, where the estimates are within rounding: tets of
  // random shapes whose last point is moved along a line until R/l is rho0,
  // or the smallest dihedral angle theta, to the last bits (bisection), then
  // a few ulps on either side.
  const auto solve = [](auto measure, double lo, double hi, double target) {
    for (int i = 0; i < 100 && lo != hi; ++i) {
      const double mid = 0.5 * (lo + hi);
      (measure(mid) > target ? lo : hi) = mid;
    }
    return lo;
  };
  std::set<int> shapes;
  std::uint64_t seed = 12345;
  const auto uniform = [&] {
    seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
    return double(seed >> 11) / 9007199254740992.0;
  };
  for (int trial = 0; trial < 400; ++trial) {
    const bool skinny_side = trial % 2 == 0;
    const Point3 a{{uniform(), uniform(), uniform()}}, b{{uniform(), uniform(), uniform()}},
        p{{uniform(), uniform(), uniform()}};
    // d(s) = d0 plus s along abp's normal, positive for s > 0: d0 the
    // centroid of abp (R/l falls from infinity as d rises), or for the angle
    // the antipode of a on abp's circumcircle (four cocircular points: a
    // sliver, whose smallest dihedral angle grows as d rises).
    const Point3 n = geometry::cross(geometry::sub(b, a), geometry::sub(p, a));
    double r2;
    const Point3 cc = geometry::circumcenter(a, b, p, r2);
    const Point3 d0 = skinny_side
                          ? Point3{{(a[0] + b[0] + p[0]) / 3, (a[1] + b[1] + p[1]) / 3, (a[2] + b[2] + p[2]) / 3}}
                          : geometry::sub(geometry::mul(cc, 2), a);
    const auto d = [&](double s) { return geometry::add(d0, geometry::mul(n, s)); };
    const auto measure = [&](double s) {
      const TetQuality q = tet_quality(a, b, p, d(s));
      return skinny_side ? q.radius_edge : -q.min_dihedral_deg;
    };
    const double target = skinny_side ? 2.2 : -3.0;
    // From nearly flat (a sliver, R/l large) to about as high as abp is wide.
    const double lo = 1e-9, hi = std::sqrt(geometry::dist2(a, b) / geometry::dot(n, n));
    if (!(measure(lo) > target) || measure(hi) > target) continue;  // no crossing on this line
    const double s0 = solve(measure, lo, hi, target);
    for (double x = s0, y = s0, k = 0; k < 16; ++k, x = std::nextafter(x, 1.0), y = std::nextafter(y, 0.0))
      for (double z : {x, y}) {
        expect_same_shape(c, a, b, p, d(z));
        shapes.insert(int(c.shape(a, b, p, d(z), mesher::min_sine(a, b, p, d(z)))));
      }
  }
  // Both sides of both thresholds were met: good, skinny and sliver.
  EXPECT_EQ(shapes.size(), 3u);
  // Flat: four coplanar points (R/l infinite by tet_quality).
  expect_same_shape(c, {{0, 0, 0}}, {{1, 0, 0}}, {{1, 1, 0}}, {{0, 1, 0}});
}

TEST(Recount, JsonReaderReadsWhatTheWriterWritesAndNamesTheDefect) {
  JsonWriter w(false);
  w.begin_object().field("a", 0.1).field("b", std::string("x\"\n")).key("c").begin_array().value(true).null();
  w.value(-2.5e-300).end_array().end_object();
  const JsonValue v = parse_json(w.str());
  EXPECT_EQ(v.find("a")->number, 0.1);
  EXPECT_EQ(v.find("b")->string, "x\"\n");
  ASSERT_EQ(v.find("c")->array.size(), 3u);
  EXPECT_TRUE(v.find("c")->array[0].boolean);
  EXPECT_EQ(v.find("c")->array[1].kind, JsonValue::Kind::null);
  EXPECT_EQ(v.find("c")->array[2].number, -2.5e-300);
  EXPECT_EQ(v.find("missing"), nullptr);
  for (const char* bad : {"{\"a\": 1", "[1,]", "{\"a\" 1}", "01", "\"abc", "[1] 2", "nul"}) {
    try {
      parse_json(bad);
      ADD_FAILURE() << "parsed: " << bad;
    } catch (const InputError& e) {
      EXPECT_EQ(e.kind(), InputErrorKind::syntax) << bad;
      EXPECT_NE(std::string(e.what()).find("at byte"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(parse_json("  "), InputError);
  EXPECT_THROW(parse_json(std::string(300, '[') + std::string(300, ']')), InputError);
}

}  // namespace
}  // namespace wqmesh
