// wqmesh: the check report's coordinates of the sharp elements.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>
#include <vector>

#include "test_support.h"
#include "wqmesh/report.h"

namespace {

// The numbers of the JSON array that follows `"key":` in `json`, in order
// (brackets and commas skipped), up to the array's closing bracket.
std::vector<double> numbers_of(const std::string& json, const std::string& key) {
  std::vector<double> out;
  std::size_t i = json.find("\"" + key + "\"");
  if (i == std::string::npos) return out;
  i = json.find('[', i);
  int depth = 0;
  for (; i < json.size(); ++i) {
    const char c = json[i];
    if (c == '[')
      ++depth;
    else if (c == ']') {
      if (--depth == 0) break;
    } else if (c == '-' || c == '.' || (c >= '0' && c <= '9')) {
      char* end = nullptr;
      out.push_back(std::strtod(json.c_str() + i, &end));
      i = static_cast<std::size_t>(end - json.c_str()) - 1;
    }
  }
  return out;
}

}  // namespace

// spike.off has sharp vertices (its tip), thin_wedge.off sharp edges too.
TEST(Report, SharpPointsAreThePlcCoordinatesOfTheSharpElements) {
  std::size_t sharp_vertices = 0, sharp_edges = 0;
  for (const char* name : {"spike.off", "thin_wedge.off"}) {
    const std::string bytes = wqmesh::testing::read_file(std::string(WQMESH_EXAMPLE_MODELS) + "/" + name);
    ASSERT_FALSE(bytes.empty()) << "examples/models/" << name << " is missing";
    const wqmesh::CheckResult r = wqmesh::check_polyhedron(bytes.data(), bytes.size());
    ASSERT_TRUE(r.valid) << name << ": " << r.error;
    sharp_vertices += r.analysis.sharp_vertices.size();
    sharp_edges += r.analysis.sharp_edges.size();
    for (bool pretty : {true, false}) {
      const std::string json = wqmesh::check_json(r, pretty);
      const std::vector<double> v = numbers_of(json, "sharp_vertex_points");
      ASSERT_EQ(v.size(), 3 * r.analysis.sharp_vertices.size()) << name;
      for (std::size_t i = 0; i < r.analysis.sharp_vertices.size(); ++i)
        for (int k = 0; k < 3; ++k) EXPECT_EQ(v[3 * i + k], r.plc.vertices[r.analysis.sharp_vertices[i]][k]) << name;
      const std::vector<double> e = numbers_of(json, "sharp_edge_points");
      ASSERT_EQ(e.size(), 6 * r.analysis.sharp_edges.size()) << name;
      for (std::size_t i = 0; i < r.analysis.sharp_edges.size(); ++i) {
        const wqmesh::PlcEdge& edge = r.plc.edges[r.analysis.sharp_edges[i]];
        for (int k = 0; k < 3; ++k) {
          EXPECT_EQ(e[6 * i + k], r.plc.vertices[edge.a][k]) << name;
          EXPECT_EQ(e[6 * i + 3 + k], r.plc.vertices[edge.b][k]) << name;
        }
      }
    }
  }
  EXPECT_GT(sharp_vertices, 0u);
  EXPECT_GT(sharp_edges, 0u);
}
