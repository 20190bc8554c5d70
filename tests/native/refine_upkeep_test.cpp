// wqmesh: the O(1) records REFINE's per-insertion upkeep reads instead of
// look-ups (issue 15): each checked against the look-up it stands in for.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "mesh_invariants.h"
#include "mesher/extract.h"
#include "mesher/mesher.h"
#include "mesher/queues.h"

namespace wqmesh {
namespace {

using invariants::Input;
using invariants::load;

std::vector<std::string> example_models(const std::set<std::string>& names) {
  std::vector<std::string> out;
  std::error_code ec;
  if (!std::filesystem::is_directory(WQMESH_EXAMPLE_MODELS, ec)) return out;
  for (const std::string& n : names)
    if (std::filesystem::exists(std::string(WQMESH_EXAMPLE_MODELS) + "/" + n))
      out.push_back(std::string(WQMESH_EXAMPLE_MODELS) + "/" + n);
  return out;
}

/// A mesher on a loaded model, before INITIALIZE.
struct MesherRun {
  Input in;
  mesher::Domain dom;
  MeshOptions options;
  ProgressCallback none;
  mesher::Mesher m;
  explicit MesherRun(const Input& input) : in(input), dom(in.plc, in.analysis), m(dom, options, none) {}
};

// Subcomplex::may_be_subsegment (the record of the other ends of each
// vertex's subsegments) never says "no" to a subsegment: checked for every
// subsegment, both ways, and against the subsegment map for every edge of
// Del V, after every insertion of CONFORM and REFINE and after PUMP. And it
// does say "no" to edges between ends of subsegments that are none (what it
// is for).
TEST(RefineUpkeep, SegmentEndsRecordAgreesWithTheSubsegmentMap) {
  const std::vector<std::string> files = example_models({"slit.off", "thin_wedge.off", "spike.off", "edge_facet.off"});
  ASSERT_FALSE(files.empty()) << "examples/models is missing";
  std::size_t subsegments = 0, refused = 0, checks = 0;
  for (const std::string& file : files) {
    SCOPED_TRACE(file);
    MesherRun run(load(file));
    mesher::Mesher& m = run.m;
    const mesher::Subcomplex& sub = m.subcomplex();
    std::vector<int> adjacent;
    auto check = [&] {
      ++checks;
      for (const auto& [k, s] : sub.subsegments()) {
        ASSERT_TRUE(sub.may_be_subsegment(s.a, s.b)) << s.a << "-" << s.b;
        ASSERT_TRUE(sub.may_be_subsegment(s.b, s.a)) << s.b << "-" << s.a;
        ++subsegments;
      }
      const int n = m.triangulation().number_of_vertices();
      for (int a = 0; a < n; ++a) {
        if (sub.subsegments_at(a).empty()) continue;
        m.triangulation().adjacent_vertices(a, adjacent);
        for (int b : adjacent) {
          if (b < 0 || sub.subsegments_at(b).empty() || sub.may_be_subsegment(a, b)) continue;
          ASSERT_EQ(sub.subsegments().count(mesher::edge_key(a, b)), 0u) << a << "-" << b;
          ++refused;
        }
      }
    };
    m.inserter().observer = [&](const mesher::Insertion&, int, int id) {
      if (id >= 0) check();
    };
    m.initialize();
    check();
    m.conform();
    m.refine();
    m.pump();
    check();
  }
  EXPECT_GT(checks, 100u);
  EXPECT_GT(subsegments, 0u);
  EXPECT_GT(refused, 0u);
}

// Queues::rule5_needs_split, which asks Subcomplex::guarded only of a
// present, encroached subfacet, answers as rule 5 reads (guarded: missing
// from Del V; else encroached, a missing one counted as encroached), for
// every subfacet after every insertion of REFINE; the case that needs
// guarded (present, encroached) and both others do occur.
TEST(RefineUpkeep, Rule5AnswersAsGuardedFirst) {
  const std::vector<std::string> files =
      example_models({"slit.off", "thin_wedge.off", "spike.off", "edge_facet.off", "bracket.off"});
  ASSERT_FALSE(files.empty()) << "examples/models is missing";
  std::size_t missing = 0, encroached = 0, guarded = 0, clear = 0;
  for (const std::string& file : files) {
    SCOPED_TRACE(file);
    MesherRun run(load(file));
    mesher::Mesher& m = run.m;
    const mesher::Subcomplex& sub = m.subcomplex();
    const mesher::Queues queues(m.domain(), m.triangulation(), sub, m.meter());
    bool refine = false;
    m.inserter().observer = [&](const mesher::Insertion&, int rule, int id) {
      refine = refine || rule >= 4;
      if (id < 0 || !refine) return;
      for (const mesher::Subfacet& h : sub.subfacets()) {
        const bool g = sub.guarded(h), present = sub.subfacet_present(h);
        const bool paper = g ? !present : sub.subfacet_encroached(h);
        ASSERT_EQ(queues.rule5_needs_split(h), paper) << h.v[0] << " " << h.v[1] << " " << h.v[2];
        bool gone = false;
        const bool e = sub.subfacet_encroached(h, &gone);
        ASSERT_EQ(gone, !present);
        missing += gone;
        encroached += e && !gone;
        guarded += e && !gone && g;
        clear += !e;
      }
    };
    m.initialize();
    m.conform();
    m.refine();
  }
  EXPECT_GT(missing, 0u);
  EXPECT_GT(encroached, 0u);
  EXPECT_GT(guarded, 0u);
  EXPECT_GT(clear, 0u);
}

// Queues::SliverRecord (rule 7's cells with an angle at theta or less)
// brought up to date from the recorded cells that live on and the stars of
// the vertices inserted since gives the same cells, angles and candidates
// as a read of every cell: compared every few insertions of REFINE, with
// the labels in the cells set by label_cells_in_place as rule 7 sets them.
TEST(RefineUpkeep, SliverRecordKeptFromTheNewStarsIsAReadOfEveryCell) {
  const std::vector<std::string> files = example_models({"slit.off", "thin_wedge.off", "spike.off", "edge_facet.off"});
  ASSERT_FALSE(files.empty()) << "examples/models is missing";
  std::size_t compared = 0, inside = 0, cells = 0;
  using Record = mesher::Queues::SliverRecord;
  const auto sorted_cells = [](const Record& r) {
    std::vector<std::pair<Tet, double>> out;
    for (const Record::Cell& c : r.cells) {
      Tet t = c.t;
      std::sort(t.begin(), t.end());
      out.push_back({t, c.angle});
    }
    std::sort(out.begin(), out.end());
    return out;
  };
  const auto always = [](std::size_t) { return true; };
  for (const std::string& file : files) {
    SCOPED_TRACE(file);
    MesherRun run(load(file));
    mesher::Mesher& m = run.m;
    const double theta = run.options.theta_deg;
    Record kept;
    int insertions = 0;
    m.inserter().observer = [&](const mesher::Insertion&, int rule, int id) {
      if (id < 0 || rule < 4 || ++insertions % 7 != 0) return;
      if (!mesher::label_cells_in_place(m.domain(), m.subcomplex(), m.triangulation(), m.meter(), false)) {
        kept.clear();
        return;
      }
      const bool incremental = kept.valid;
      std::vector<std::pair<double, int>> from_kept, from_all;
      ASSERT_TRUE(kept.update(m.triangulation(), theta, from_kept, always));
      Record fresh;
      ASSERT_TRUE(fresh.update(m.triangulation(), theta, from_all, always));
      if (!incremental) return;
      std::sort(from_kept.begin(), from_kept.end());
      std::sort(from_all.begin(), from_all.end());
      ASSERT_EQ(from_kept, from_all) << "insertion " << id;
      ASSERT_EQ(sorted_cells(kept), sorted_cells(fresh)) << "insertion " << id;
      ++compared;
      inside += from_all.size();
      cells += fresh.cells.size();
    };
    m.initialize();
    m.conform();
    m.refine();
  }
  EXPECT_GT(compared, 20u);
  EXPECT_GT(inside, 0u);  // some recorded cell was inside (a candidate)
  EXPECT_GT(cells, 0u);
}

// Subcomplex::zone_features (ENCROACH's zone kept for the upkeep of its free
// insertion) holds what Queues::enqueue_from_cavity would read from the
// cavity: the subsegments among its edges, in key order, and its triangles
// with every vertex on P that some facet of P holds, sorted, without
// repeats. Checked after every free insertion of rule 6 on four example
// models, against the cavity and the subsegment map; and it is there for
// most of them.
TEST(RefineUpkeep, ZoneKeptByEncroachIsTheCavitysFeatures) {
  const std::vector<std::string> files = example_models({"slit.off", "thin_wedge.off", "spike.off", "edge_facet.off"});
  ASSERT_FALSE(files.empty()) << "examples/models is missing";
  std::size_t free_insertions = 0, kept = 0, segments = 0, triangles = 0;
  for (const std::string& file : files) {
    SCOPED_TRACE(file);
    MesherRun run(load(file));
    mesher::Mesher& m = run.m;
    const mesher::Subcomplex& sub = m.subcomplex();
    std::vector<int> f0, f1, f2;
    m.inserter().observer = [&](const mesher::Insertion& ins, int rule, int id) {
      if (id < 0 || rule != 6 || ins.on != mesher::On::free) return;
      ++free_insertions;
      const std::vector<Tet>* cavity = m.triangulation().last_cavity();
      if (!cavity) return;
      const mesher::Subcomplex::ZoneFeatures* z = sub.zone_features(m.triangulation().point(id), *cavity);
      if (!z) return;
      ++kept;
      std::set<std::uint64_t> edges;
      std::set<mesher::Tri> tris;
      for (const Tet& c : *cavity) {
        for (int i = 0; i < 4; ++i)
          for (int j = i + 1; j < 4; ++j)
            if (c[i] != kInfinite && c[j] != kInfinite && sub.subsegments().count(mesher::edge_key(c[i], c[j])))
              edges.insert(mesher::edge_key(c[i], c[j]));
        for (int k = 0; k < 4; ++k) {
          const mesher::Tri t = mesher::sorted({{c[(k + 1) % 4], c[(k + 2) % 4], c[(k + 3) % 4]}});
          if (!sub.on_p(t[0]) || !sub.on_p(t[1]) || !sub.on_p(t[2])) continue;
          sub.facets_of(t[0], f0);
          sub.facets_of(t[1], f1);
          sub.facets_of(t[2], f2);
          for (int f : f0)
            if (std::count(f1.begin(), f1.end(), f) && std::count(f2.begin(), f2.end(), f)) tris.insert(t);
        }
      }
      std::vector<std::uint64_t> keys;
      for (const mesher::Subsegment* s : z->segments) keys.push_back(mesher::edge_key(s->a, s->b));
      ASSERT_EQ(keys, std::vector<std::uint64_t>(edges.begin(), edges.end())) << "insertion " << id;
      ASSERT_EQ(z->tris, std::vector<mesher::Tri>(tris.begin(), tris.end())) << "insertion " << id;
      segments += keys.size();
      triangles += z->tris.size();
    };
    m.initialize();
    m.conform();
    m.refine();
  }
  EXPECT_GT(free_insertions, 100u);
  EXPECT_GT(kept, free_insertions / 2);
  EXPECT_GT(segments, 0u);
  EXPECT_GT(triangles, 0u);
}

}  // namespace
}  // namespace wqmesh
