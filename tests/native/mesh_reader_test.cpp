// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of the mesh reader (Medit .mesh, TetGen .node/.ele): meshes written
// by output.h's writers read back to the same vertices (bit-exact), tets and
// boundary; other meshers' variants (comments, extra sections, 1-based TetGen
// numbering, attributes, markers, 10-node tets) read; broken files give
// typed errors that name the line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "test_support.h"
#include "wqmesh/mesh_reader.h"
#include "wqmesh/mesher.h"
#include "wqmesh/output.h"
#include "wqmesh/quality.h"
#include "wqmesh/report.h"

namespace wqmesh {
namespace {

using testing::two_tets;

void expect_same_tets(const TetMesh& a, const TetMesh& b) {
  ASSERT_EQ(a.vertices.size(), b.vertices.size());
  for (std::size_t i = 0; i < a.vertices.size(); ++i)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(a.vertices[i][k], b.vertices[i][k]) << "vertex " << i;
  ASSERT_EQ(a.tets.size(), b.tets.size());
  for (std::size_t i = 0; i < a.tets.size(); ++i) EXPECT_EQ(a.tets[i], b.tets[i]) << "tet " << i;
}

TetMesh medit(const std::string& text) { return read_medit(text.data(), text.size()); }

/// The InputError of reading `text` as Medit; fails the test if none.
InputError medit_error(const std::string& text) {
  try {
    medit(text);
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no error for:\n" << text;
  return InputError(InputErrorKind::io, "");
}

InputError tetgen_error(const std::string& node, const std::string& ele) {
  try {
    read_tetgen(node.data(), node.size(), ele.data(), ele.size());
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no error for:\n" << node << "\n" << ele;
  return InputError(InputErrorKind::io, "");
}

TEST(MeshReader, MeditRoundTrip) {
  const TetMesh m = two_tets();
  std::ostringstream out;
  write_medit(out, m);
  const TetMesh r = medit(out.str());
  expect_same_tets(m, r);
  EXPECT_EQ(r.boundary, m.boundary);
  EXPECT_EQ(r.boundary_facet, m.boundary_facet);
  EXPECT_TRUE(r.weights.empty());
}

TEST(MeshReader, TetgenRoundTrip) {
  const TetMesh m = two_tets();
  std::ostringstream node, ele, face;
  write_tetgen(node, ele, face, m);
  const std::string n = node.str(), e = ele.str();
  const TetMesh r = read_tetgen(n.data(), n.size(), e.data(), e.size());
  expect_same_tets(m, r);
}

TEST(MeshReader, MesherOutputRoundTripsThroughFiles) {
  const std::string model = std::string(WQMESH_EXAMPLE_MODELS) + "/spike.off";
  std::ifstream in(model, std::ios::binary);
  ASSERT_TRUE(in) << model;
  std::ostringstream bytes;
  bytes << in.rdbuf();
  const std::string data = bytes.str();
  const CheckResult input = check_polyhedron(data.data(), data.size());
  ASSERT_TRUE(input.valid) << input.error;
  const MeshResult result = mesh_polyhedron(input.plc, input.analysis);
  ASSERT_TRUE(result.conforming);

  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "wqmesh_mesh_reader_test";
  std::filesystem::create_directories(dir);
  const std::string medit_path = (dir / "spike.mesh").string(), base = (dir / "spike").string();
  {
    std::ofstream f(medit_path, std::ios::binary);
    write_medit(f, result.mesh);
  }
  write_tetgen(base, result.mesh);

  for (const std::string& path : {medit_path, base + ".ele", base + ".node", base}) {
    SCOPED_TRACE(path);
    TetMesh r = read_tet_mesh_file(path);
    expect_same_tets(result.mesh, r);
    EXPECT_FALSE(orient_tets_by_majority(r));  // the mesher's tets are positive
    EXPECT_EQ(used_vertex_count(r), r.vertices.size());
    const MeshStats s = mesh_stats(r, mesh_quality(r));
    EXPECT_EQ(s.inverted, 0u);
    EXPECT_NEAR(s.volume, plc_volume(input.plc), 1e-9 * plc_volume(input.plc));
  }
  std::filesystem::remove_all(dir);
}

TEST(MeshReader, MeditVariantsOfOtherWriters) {
  // Lower-case keywords, counts on the keyword's line, comments, sections
  // that are skipped, no End, and a vertex no tet uses.
  const TetMesh r = medit(
      "# written by someone else\n"
      "MeshVersionFormatted 1\n"
      "Dimension\n3\n"
      "vertices 5\n"
      "0 0 0 1\n1 0 0 1\n0 1 0 1\n0 0 1 1  # a comment\n9 9 9 0\n"
      "Edges\n1\n1 2 3\n"
      "Corners 2\n1\n2\n"
      "Triangles 1\n1 3 2 7\n"
      "NormalAtVertices 1\n1 1\n"
      "Normals 1\n0 0 1\n"
      "Tetrahedra 1\n1 2 3 4 1\n");
  ASSERT_EQ(r.vertices.size(), 5u);
  ASSERT_EQ(r.tets.size(), 1u);
  EXPECT_EQ(r.tets[0], (std::array<int, 4>{{0, 1, 2, 3}}));
  ASSERT_EQ(r.boundary.size(), 1u);
  EXPECT_EQ(r.boundary_facet[0], 6);
  EXPECT_EQ(used_vertex_count(r), 4u);
}

TEST(MeshReader, TetgenVariants) {
  // 1-based numbering, attributes and markers, a 10-node tet with an attribute.
  const std::string node = "# TetGen\n4 3 1 1\n1 0 0 0 5.5 1\n2 1 0 0 5.5 1\n3 0 1 0 5.5 1\n4 0 0 1 5.5 0\n";
  const std::string ele = "1 10 1\n1 1 3 2 4 1 1 1 1 1 1 0.25\n";
  const TetMesh r = read_tetgen(node.data(), node.size(), ele.data(), ele.size());
  ASSERT_EQ(r.vertices.size(), 4u);
  EXPECT_EQ(r.vertices[3], (Point3{{0, 0, 1}}));
  ASSERT_EQ(r.tets.size(), 1u);
  EXPECT_EQ(r.tets[0], (std::array<int, 4>{{0, 2, 1, 3}}));
}

TEST(MeshReader, OrientByMajority) {
  TetMesh m = two_tets();
  for (auto& t : m.tets) std::swap(t[0], t[1]);  // both negative now
  EXPECT_TRUE(orient_tets_by_majority(m));
  for (const auto& t : m.tets)
    EXPECT_GT(tet_quality(m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]], m.vertices[t[3]]).volume, 0);
  EXPECT_FALSE(orient_tets_by_majority(m));
}

TEST(MeshReader, MeditErrorsAreTypedAndNameTheLine) {
  EXPECT_EQ(medit_error("").kind(), InputErrorKind::empty);
  EXPECT_EQ(medit_error("# nothing\n").kind(), InputErrorKind::empty);
  EXPECT_EQ(medit_error(std::string("\x01\0\0\0\x02\0\0\0", 8)).kind(), InputErrorKind::syntax);

  InputError e = medit_error("MeshVersionFormatted 2\nDimension 3\nVertices 1\n0 0 0 0\nFrobs 3\n");
  EXPECT_EQ(e.kind(), InputErrorKind::syntax);
  EXPECT_NE(std::string(e.what()).find("line 5"), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("Frobs"), std::string::npos) << e.what();

  e = medit_error("Dimension 2\n");
  EXPECT_EQ(e.kind(), InputErrorKind::syntax);
  EXPECT_NE(std::string(e.what()).find("Dimension 2"), std::string::npos) << e.what();

  e = medit_error("Vertices 4\n0 0 0 0\n1 0 0 0\n0 1 x 0\n0 0 1 0\n");
  EXPECT_EQ(e.kind(), InputErrorKind::syntax);
  EXPECT_NE(std::string(e.what()).find("line 4"), std::string::npos) << e.what();

  e = medit_error("Vertices 4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\nTetrahedra 2\n1 2 3 4 1\n");
  EXPECT_EQ(e.kind(), InputErrorKind::truncated);

  e = medit_error("Vertices 4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\nTetrahedra 1000000000\n1 2 3 4 1\n");
  EXPECT_EQ(e.kind(), InputErrorKind::truncated);

  e = medit_error("Vertices 4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\nTetrahedra 1\n1 2 3 5 1\n");
  EXPECT_EQ(e.kind(), InputErrorKind::bad_index);
  EXPECT_NE(std::string(e.what()).find("line 7"), std::string::npos) << e.what();

  e = medit_error("Vertices 4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\nTetrahedra 1\n0 1 2 3 1\n");
  EXPECT_EQ(e.kind(), InputErrorKind::bad_index);

  EXPECT_EQ(medit_error("Vertices 1\n0 0 inf 0\nTetrahedra 0\n").kind(), InputErrorKind::non_finite);
  EXPECT_EQ(medit_error("Vertices 4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\nEnd\n").kind(), InputErrorKind::empty);
}

TEST(MeshReader, TetgenErrorsAreTypedAndNameTheFile) {
  const std::string node = "4 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n";
  InputError e = tetgen_error(node, "1 4 0\n0 0 1 2 4\n");
  EXPECT_EQ(e.kind(), InputErrorKind::bad_index);
  EXPECT_NE(std::string(e.what()).find("ele line 2"), std::string::npos) << e.what();

  e = tetgen_error("4 2 0 0\n", "1 4 0\n0 0 1 2 3\n");
  EXPECT_EQ(e.kind(), InputErrorKind::syntax);
  EXPECT_NE(std::string(e.what()).find("node line 1"), std::string::npos) << e.what();

  e = tetgen_error("4 3 0 0\n0 0 0 0\n1 1 0 0\n5 0 1 0\n3 0 0 1\n", "1 4 0\n0 0 1 2 3\n");
  EXPECT_EQ(e.kind(), InputErrorKind::syntax);

  EXPECT_EQ(tetgen_error(node, "2 4 0\n0 0 1 2 3\n").kind(), InputErrorKind::truncated);
  EXPECT_EQ(tetgen_error(node, "1 6 0\n0 0 1 2 3 0 0\n").kind(), InputErrorKind::syntax);
  EXPECT_EQ(tetgen_error(node, "").kind(), InputErrorKind::empty);
}

TEST(MeshReader, FileErrors) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "wqmesh_mesh_reader_files";
  std::filesystem::create_directories(dir);
  try {
    read_tet_mesh_file((dir / "missing.mesh").string());
    ADD_FAILURE() << "no error for a missing file";
  } catch (const InputError& e) {
    EXPECT_EQ(e.kind(), InputErrorKind::io);
    EXPECT_NE(std::string(e.what()).find("missing.mesh"), std::string::npos) << e.what();
  }
  { std::ofstream((dir / "only.ele").string()) << "1 4 0\n0 0 1 2 3\n"; }
  try {
    read_tet_mesh_file((dir / "only.ele").string());
    ADD_FAILURE() << "no error for a .ele without its .node";
  } catch (const InputError& e) {
    EXPECT_EQ(e.kind(), InputErrorKind::io);
    EXPECT_NE(std::string(e.what()).find("only.node"), std::string::npos) << e.what();
  }
  try {
    read_tet_mesh_file((dir / "x.vtu").string());
    ADD_FAILURE() << "no error for a .vtu";
  } catch (const InputError& e) {
    EXPECT_EQ(e.kind(), InputErrorKind::syntax);
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace wqmesh
