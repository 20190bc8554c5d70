// SPDX-License-Identifier: GPL-3.0-or-later
// wqmesh: the readers and build_plc over every model of the test folders
// (WQMESH_SHARED_MODELS, WQMESH_EXAMPLE_MODELS): valid models give a PLC that
// satisfies the contract of types.h (paper, section 2); the broken ones listed
// last in SOURCES.md are rejected with an error naming a real defect; and no
// prefix or byte-flipped copy of any model makes the code do anything but
// return or throw InputError.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "test_support.h"
#include "wqmesh/input.h"

namespace wqmesh {

int expect_valid_plc(const PLC& plc);  // plc_test.cpp

namespace {

namespace fs = std::filesystem;

std::vector<fs::path> models_in(const std::string& dir) {
  std::vector<fs::path> out;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return out;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    std::string ext = entry.path().extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (entry.is_regular_file() && (ext == ".off" || ext == ".stl")) out.push_back(entry.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

/// The file names of the last `n` rows of the table in SOURCES.md: the models
/// that are broken on purpose.
std::set<std::string> broken_models(const std::string& dir, std::size_t n) {
  std::ifstream in(dir + "/SOURCES.md");
  std::vector<std::string> rows;
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("| ", 0) != 0) continue;
    const std::string name = line.substr(2, line.find(" |", 2) - 2);
    if (name.size() > 4 && (name.find(".off") != std::string::npos || name.find(".stl") != std::string::npos))
      rows.push_back(name);
  }
  std::set<std::string> out;
  for (std::size_t i = rows.size() > n ? rows.size() - n : 0; i < rows.size(); ++i) out.insert(rows[i]);
  return out;
}

/// The defects SOURCES.md documents for the broken models.
std::set<std::string> documented_defects(const std::string& name) {
  static const std::map<std::string, std::set<std::string>> known = {
      {"cubes.off", {"non_manifold_edge", "non_manifold_vertex"}},
      {"cube-ouvert.off", {"open_boundary"}},
      {"self_intersecting.off", {"open_boundary", "self_intersection", "too_few_faces"}},
      {"issue1580-zero-area-triangle.stl", {"degenerate_face"}},
      {"bad-stl-pcbvicebar.stl", {"self_intersection"}},
  };
  auto it = known.find(name);
  if (it != known.end()) return it->second;
  return {"degenerate_face", "duplicate_face",    "open_boundary", "non_manifold_edge", "non_manifold_vertex",
          "not_orientable",  "self_intersection", "zero_volume",   "too_few_faces"};
}

void check_folder(const std::string& dir, bool has_sources) {
  const auto files = models_in(dir);
  if (files.empty()) GTEST_SKIP() << "no models in " << dir;
  const std::set<std::string> broken = has_sources ? broken_models(dir, 5) : std::set<std::string>{};
  if (has_sources) EXPECT_EQ(broken.size(), 5u) << "cannot read the table of " << dir << "/SOURCES.md";
  for (const auto& path : files) {
    const std::string name = path.filename().string();
    SCOPED_TRACE(name);
    const bool must_fail = broken.count(name) > 0 || name.rfind("bad-", 0) == 0;
    try {
      const PolygonSoup soup = read_polyhedron_file(path.string());
      Warnings warnings;
      MergeReport report;
      const PLC plc = build_plc(soup, warnings, &report);
      EXPECT_FALSE(must_fail) << name << " is broken but was accepted";
      if (!must_fail) {
        expect_valid_plc(plc);
        EXPECT_EQ(report.facets, plc.facets.size());
        EXPECT_EQ(report.edges, plc.edges.size());
        EXPECT_EQ(report.faces_read, soup.faces.size());
        std::size_t holes = 0;
        for (const auto& f : plc.facets) holes += f.loops.size() - 1;
        std::cout << "[ model    ] " << name << ": " << plc.vertices.size() << " vertices, " << plc.edges.size()
                  << " edges, " << plc.facets.size() << " facets (" << holes << " holes), " << warnings.size()
                  << " warnings\n";
      }
    } catch (const InputError& e) {
      EXPECT_TRUE(must_fail) << name << " rejected: " << e.what();
      if (must_fail) {
        EXPECT_EQ(documented_defects(name).count(error_kind_name(e.kind())), 1u)
            << name << ": " << error_kind_name(e.kind()) << ": " << e.what();
        std::cout << "[ rejected ] " << name << ": " << error_kind_name(e.kind()) << ": " << e.what() << "\n";
      }
    }
  }
}

TEST(Models, SharedModels) { check_folder(WQMESH_SHARED_MODELS, true); }
TEST(Models, ExampleModels) { check_folder(WQMESH_EXAMPLE_MODELS, false); }

/// Reads and builds; anything but success or InputError fails the test.
void must_not_crash(const std::string& bytes, const std::string& what) {
  try {
    const PolygonSoup soup = read_polyhedron(bytes.data(), bytes.size());
    Warnings w;
    build_plc(soup, w);
  } catch (const InputError&) {
  } catch (const std::exception& e) {
    ADD_FAILURE() << what << ": " << e.what();
  } catch (...) {
    ADD_FAILURE() << what << ": unknown exception";
  }
}

void fuzz_folder(const std::string& dir) {
  const auto files = models_in(dir);
  if (files.empty()) GTEST_SKIP() << "no models in " << dir;
  std::mt19937 rng(20051);
  for (const auto& path : files) {
    const std::string bytes = testing::read_file(path.string());
    const std::string name = path.filename().string();
    // Prefixes: all of them for small files, about 300 for large ones.
    const std::size_t step = std::max<std::size_t>(1, bytes.size() / 300);
    for (std::size_t len = 0; len < bytes.size(); len += step)
      must_not_crash(bytes.substr(0, len), name + " cut at " + std::to_string(len));
    // Random byte flips: fewer on large files (each build costs more).
    const int trials = static_cast<int>(std::clamp<std::size_t>(400000 / (bytes.size() + 1), 3, 100));
    for (int t = 0; t < trials; ++t) {
      std::string b = bytes;
      const int flips = 1 + static_cast<int>(rng() % 4);
      for (int k = 0; k < flips && !b.empty(); ++k) b[rng() % b.size()] = static_cast<char>(rng() & 0xff);
      must_not_crash(b, name + " flip trial " + std::to_string(t));
    }
  }
}

TEST(Models, SharedModelsTruncatedAndFlippedNeverCrash) { fuzz_folder(WQMESH_SHARED_MODELS); }
TEST(Models, ExampleModelsTruncatedAndFlippedNeverCrash) { fuzz_folder(WQMESH_EXAMPLE_MODELS); }

}  // namespace
}  // namespace wqmesh
