// wqmesh: the O(1) records REFINE's per-insertion upkeep reads instead of
// look-ups (issue 15): each checked against the look-up it stands in for.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "mesh_invariants.h"
#include "mesher/mesher.h"

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

}  // namespace
}  // namespace wqmesh
