// Tests of the public facade (wqmesh/wqmesh.h) and of the stable names of its
// closed value sets (wqmesh/names.h): the facade gives the same mesh as the
// lower-level calls, keeps the PLC with its own analysis (the bounding box of
// the mesh options' margin, section 2), validates every option, reports
// progress in phase order (section 4.3) and cancels, and writes each format.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>

#include <unistd.h>

#include "wqmesh/wqmesh.h"

namespace wqmesh {
namespace {

namespace fs = std::filesystem;

std::string example(const std::string& name) { return std::string(WQMESH_EXAMPLE_MODELS) + "/" + name; }

template <class E>
void expect_round_trip(const std::vector<E>& all, std::optional<E> (*from)(const std::string&), const char* what) {
  std::set<std::string> names;
  for (E e : all) {
    const std::string name = to_string(e);
    EXPECT_NE(name, "unknown") << what;
    EXPECT_TRUE(names.insert(name).second) << what << ": " << name << " twice";
    ASSERT_TRUE(from(name).has_value()) << what << ": " << name;
    EXPECT_EQ(*from(name), e) << what << ": " << name;
  }
  EXPECT_FALSE(from("no such name").has_value()) << what;
}

TEST(Names, EveryValueHasOneStableNameThatReadsBack) {
  expect_round_trip(all_stop_reasons(), &stop_reason_from_string, "StopReason");
  expect_round_trip(all_mesh_phases(), &mesh_phase_from_string, "MeshPhase");
  expect_round_trip(all_error_kinds(), &error_kind_from_string, "InputErrorKind");
  expect_round_trip(all_tet_classes(), &tet_class_from_string, "TetClass");
  expect_round_trip(all_output_formats(), &output_format_from_string, "OutputFormat");
}

TEST(Names, TheStringsOfTheJsonAndTheJavaScriptPackageAreKept) {
  // MeshStats.stopped, Phase and the classes in wasm/index.d.ts.
  EXPECT_STREQ(to_string(StopReason::done), "");
  EXPECT_STREQ(to_string(StopReason::limit), "limit");
  EXPECT_STREQ(to_string(StopReason::cancelled), "cancelled");
  EXPECT_STREQ(to_string(StopReason::stalled), "stalled");
  std::string phases;
  for (MeshPhase p : all_mesh_phases()) phases += std::string(to_string(p)) + " ";
  EXPECT_EQ(phases, "initialize conform refine pump extract improve ");
  EXPECT_STREQ(to_string(InputErrorKind::out_of_range), "out_of_range");
  EXPECT_EQ(static_cast<int>(TetClass::violation), 3);
}

TEST(Names, TheListOfErrorKindsHoldsEveryEnumerator) {
  // all_error_kinds() is read off error_kind_name: from io, in declaration
  // order, up to out_of_range, the last enumerator today (error.h).
  const auto& all = all_error_kinds();
  ASSERT_FALSE(all.empty());
  EXPECT_EQ(all.front(), InputErrorKind::io);
  EXPECT_EQ(all.back(), InputErrorKind::out_of_range);
  for (std::size_t i = 0; i < all.size(); ++i) EXPECT_EQ(static_cast<std::size_t>(all[i]), i);
  EXPECT_STREQ(error_kind_name(static_cast<InputErrorKind>(all.size())), "unknown");
}

TEST(Facade, VersionIsTheCMakeProjectVersion) {
  EXPECT_STREQ(version(), WQMESH_VERSION);
  EXPECT_TRUE(std::regex_match(version(), std::regex("[0-9]+\\.[0-9]+\\.[0-9]+")));
  EXPECT_EQ(std::to_string(WQMESH_VERSION_MAJOR) + "." + std::to_string(WQMESH_VERSION_MINOR) + "." +
                std::to_string(WQMESH_VERSION_PATCH),
            std::string(version()));
}

TEST(Facade, OptionsAreValidatedByTheTable) {
  Options o;
  EXPECT_EQ(o.get("rho"), 2.2);
  o.set("rho", 3).set("pump", 0).set("boxMargin", 1.5);
  EXPECT_EQ(o.mesh().rho0, 3);
  EXPECT_FALSE(o.mesh().pump);
  // The margin of B flows from the mesh options into the analysis.
  EXPECT_EQ(o.mesh().box_margin, 1.5);
  EXPECT_EQ(o.analysis().box_margin, 1.5);
  EXPECT_THROW(o.set("rho", 0.5), std::invalid_argument);
  EXPECT_THROW(o.set("rho", std::nan("")), std::invalid_argument);
  EXPECT_THROW(o.set("pump", 2), std::invalid_argument);
  EXPECT_THROW(o.set("maxVertices", 100.5), std::invalid_argument);
  EXPECT_THROW(o.set("noSuchOption", 1), std::invalid_argument);
  EXPECT_THROW(o.get("noSuchOption"), std::invalid_argument);
  EXPECT_EQ(o.mesh().rho0, 3) << "a refused value changes nothing";
  const std::string error = o.try_set(*find_option("sliverAngle"), 91, "--sliver-angle");
  EXPECT_NE(error.find("--sliver-angle must be a number in [0, 90]"), std::string::npos) << error;
  EXPECT_EQ(o.mesh().theta_deg, 3);
}

TEST(Facade, BadInputIsAnInvalidPolyhedronWithItsKind) {
  const std::string garbage = "hello";
  const Polyhedron a = Polyhedron::read_bytes(garbage.data(), garbage.size());
  EXPECT_FALSE(a.valid());
  ASSERT_TRUE(a.error_kind().has_value());
  EXPECT_EQ(*a.error_kind(), InputErrorKind::truncated);
  EXPECT_NE(a.report_json().find("\"valid\": false"), std::string::npos);
  const Polyhedron missing = Polyhedron::read_file(example("no_such_model.off"));
  EXPECT_EQ(missing.error_kind(), InputErrorKind::io);
  EXPECT_NE(missing.error_message().find("no_such_model.off"), std::string::npos);
  const Polyhedron folder = Polyhedron::read_file(WQMESH_EXAMPLE_MODELS);
  EXPECT_EQ(folder.error_kind(), InputErrorKind::io);
  InputLimits small;
  small.max_bytes = 10;
  const Polyhedron big = Polyhedron::read_file(example("spike.off"), {}, small);
  EXPECT_EQ(big.error_kind(), InputErrorKind::too_large);
  EXPECT_THROW(mesh(a), std::invalid_argument);
}

TEST(Facade, MeshesAsTheLowerLevelCallsDo) {
  const Polyhedron in = Polyhedron::read_file(example("spike.off"));
  ASSERT_TRUE(in.valid()) << in.error_message();
  EXPECT_FALSE(in.error_kind().has_value());
  EXPECT_EQ(in.format(), "OFF");
  const Result r = mesh(in);
  const MeshResult direct = mesh_polyhedron(in.plc(), in.analysis());
  EXPECT_EQ(r.stop_reason(), StopReason::done);
  EXPECT_TRUE(r.conforming());
  EXPECT_EQ(r.mesh().vertices, direct.mesh.vertices);
  EXPECT_EQ(r.mesh().tets, direct.mesh.tets);
  EXPECT_EQ(r.mesh().weights, direct.mesh.weights);
  EXPECT_EQ(r.stats().inverted, 0u);
  EXPECT_GT(r.stats().volume, 0);
  EXPECT_GE(r.time_s(), in.read_seconds());
  const std::string stats = r.stats_json(-1, false);
  EXPECT_NE(stats.find("\"stopped\":\"\""), std::string::npos) << stats;
  EXPECT_NE(stats.find("\"tets\":" + std::to_string(r.mesh().tets.size())), std::string::npos) << stats;
}

TEST(Facade, TheBoxMarginOfTheOptionsIsTheAnalysisOfTheMesh) {
  // Read with one margin and meshed with another: the mesh is that of the
  // PLC analysed with the second (B is part of the PLC, section 2), the same
  // as reading with the second margin in the first place.
  Options wide;
  wide.set("boxMargin", 1.0);
  const Polyhedron narrow_in = Polyhedron::read_file(example("spike.off"));
  const Polyhedron wide_in = Polyhedron::read_file(example("spike.off"), wide);
  ASSERT_TRUE(narrow_in.valid() && wide_in.valid());
  EXPECT_EQ(wide_in.analysis().box_margin, 1.0);
  EXPECT_NE(wide_in.analysis().bounding_box.hi, narrow_in.analysis().bounding_box.hi);
  const Result a = mesh(narrow_in, wide);
  const Result b = mesh(wide_in, wide);
  AnalysisOptions ao;
  ao.box_margin = 1.0;
  MeshOptions mo;
  mo.box_margin = 1.0;
  const MeshResult direct = mesh_polyhedron(narrow_in.plc(), analyze(narrow_in.plc(), ao), mo);
  EXPECT_EQ(a.mesh().vertices, b.mesh().vertices);
  EXPECT_EQ(a.mesh().tets, b.mesh().tets);
  EXPECT_EQ(a.mesh().vertices, direct.mesh.vertices);
  EXPECT_EQ(a.mesh().tets, direct.mesh.tets);
}

TEST(Facade, ProgressComesInPhaseOrderAndCancels) {
  const Polyhedron in = Polyhedron::read_file(example("spike.off"));
  ASSERT_TRUE(in.valid());
  std::vector<MeshPhase> seen;
  const Result r = mesh(in, {}, [&](const MeshProgress& p) {
    EXPECT_GE(p.fraction, 0);
    EXPECT_LE(p.fraction, 1);
    if (seen.empty() || seen.back() != p.phase) seen.push_back(p.phase);
    return true;
  });
  ASSERT_FALSE(seen.empty());
  for (std::size_t i = 1; i < seen.size(); ++i) EXPECT_LT(seen[i - 1], seen[i]) << "phases out of order";
  EXPECT_EQ(seen.front(), MeshPhase::initialize);
  EXPECT_EQ(r.stop_reason(), StopReason::done);
  std::size_t calls = 0;
  const Result cancelled = mesh(in, {}, [&](const MeshProgress&) { return ++calls < 2; });
  EXPECT_EQ(cancelled.stop_reason(), StopReason::cancelled);
  Options few;
  few.set("maxVertices", 8);
  EXPECT_EQ(mesh(in, few).stop_reason(), StopReason::limit);
}

TEST(Facade, WritesEveryFormat) {
  const Polyhedron in = Polyhedron::read_file(example("spike.off"));
  ASSERT_TRUE(in.valid());
  const Result r = mesh(in);
  const std::string tets = std::to_string(r.mesh().tets.size());
  std::ostringstream medit, vtu, node, ele, face, edge;
  r.write(medit, OutputFormat::medit);
  EXPECT_EQ(medit.str().rfind("MeshVersionFormatted 2", 0), 0u);
  EXPECT_NE(medit.str().find("Tetrahedra\n" + tets + "\n"), std::string::npos);
  r.write(vtu, OutputFormat::vtu);
  EXPECT_NE(vtu.str().find("NumberOfCells=\"" + tets + "\""), std::string::npos);
  EXPECT_NE(vtu.str().find("Name=\"class\""), std::string::npos);
  EXPECT_NE(vtu.str().find("Name=\"weight\""), std::string::npos);
  std::ostringstream unused;
  EXPECT_THROW(r.write(unused, OutputFormat::tetgen), std::invalid_argument);
  r.write_tetgen(node, ele, face, edge);
  EXPECT_EQ(ele.str().rfind(tets + " 4 0", 0), 0u) << ele.str().substr(0, 40);
  EXPECT_EQ(Result::format_of_path("a.vtu"), OutputFormat::vtu);
  EXPECT_EQ(Result::format_of_path("a.ele"), OutputFormat::tetgen);
  EXPECT_FALSE(Result::format_of_path("a.obj").has_value());
  EXPECT_THROW(r.write_file("a.obj"), std::invalid_argument);
  const fs::path dir = fs::temp_directory_path() / ("wqmesh_facade_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  r.write_file((dir / "spike.ele").string());
  for (const char* ext : {".node", ".ele", ".face", ".edge"})
    EXPECT_TRUE(fs::exists(dir / (std::string("spike") + ext)));
  EXPECT_THROW(r.write_file((dir / "no_such_folder" / "x.mesh").string()), std::runtime_error);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace wqmesh
