// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of the mesh writers (Medit, VTK XML, TetGen) and of stats_json: each
// file is written, parsed back here, and compared with the mesh (coordinates
// bit-exact through round-trip precision, indices, counts, markers).
#include <gtest/gtest.h>

#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "test_support.h"
#include "wqmesh/output.h"
#include "wqmesh/quality.h"

namespace wqmesh {
namespace {

using testing::two_tets;

/// Whitespace-separated tokens of a text.
std::vector<std::string> tokens(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> out;
  for (std::string t; in >> t;) out.push_back(t);
  return out;
}

double to_double(const std::string& s) {
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  EXPECT_EQ(*end, '\0') << s;
  return v;
}

long to_long(const std::string& s) {
  char* end = nullptr;
  const long v = std::strtol(s.c_str(), &end, 10);
  EXPECT_EQ(*end, '\0') << s;
  return v;
}

/// Reads tokens in order, failing the test on a mismatch.
struct Reader {
  std::vector<std::string> t;
  std::size_t i = 0;
  std::string next() {
    if (i >= t.size()) {
      ADD_FAILURE() << "unexpected end of file";
      return "";
    }
    return t[i++];
  }
  void expect(const std::string& s) { EXPECT_EQ(next(), s); }
  double number() { return to_double(next()); }
  long integer() { return to_long(next()); }
  bool done() const { return i == t.size(); }
};

TEST(Output, MeditRoundTrip) {
  const TetMesh m = two_tets();
  std::ostringstream out;
  write_medit(out, m);
  Reader r{tokens(out.str())};
  r.expect("MeshVersionFormatted");
  r.expect("2");
  r.expect("Dimension");
  r.expect("3");
  r.expect("Vertices");
  ASSERT_EQ(r.integer(), 5);
  for (const Point3& p : m.vertices) {
    for (int k = 0; k < 3; ++k) EXPECT_EQ(r.number(), p[k]);  // bit-exact
    EXPECT_EQ(r.integer(), 0);
  }
  r.expect("Tetrahedra");
  ASSERT_EQ(r.integer(), 2);
  for (const auto& t : m.tets) {
    for (int k = 0; k < 4; ++k) EXPECT_EQ(r.integer(), t[k] + 1);  // 1-based
    EXPECT_EQ(r.integer(), 1);
  }
  r.expect("Triangles");
  ASSERT_EQ(r.integer(), 6);
  for (std::size_t i = 0; i < m.boundary.size(); ++i) {
    for (int k = 0; k < 3; ++k) EXPECT_EQ(r.integer(), m.boundary[i][k] + 1);
    EXPECT_EQ(r.integer(), m.boundary_facet[i] + 1);  // facet + 1, 0 if unknown
  }
  r.expect("End");
  EXPECT_TRUE(r.done());
}

TEST(Output, MeditMissingFacetsAndEmptyMesh) {
  TetMesh m = two_tets();
  m.boundary_facet.resize(2);  // the rest unknown: reference 0
  std::ostringstream out;
  write_medit(out, m);
  const std::string s = out.str();
  EXPECT_NE(s.find("\n3 4 5 0\n"), std::string::npos) << s;  // boundary[4], 1-based
  std::ostringstream empty;
  write_medit(empty, TetMesh{});
  EXPECT_EQ(tokens(empty.str()), (std::vector<std::string>{"MeshVersionFormatted", "2", "Dimension", "3", "Vertices",
                                                           "0", "Tetrahedra", "0", "Triangles", "0", "End"}));
}

TEST(Output, TetgenStreamsRoundTrip) {
  const TetMesh m = two_tets();
  std::ostringstream node, ele, face;
  write_tetgen(node, ele, face, m);
  Reader n{tokens(node.str())};
  EXPECT_EQ(n.integer(), 5);
  EXPECT_EQ(n.integer(), 3);
  EXPECT_EQ(n.integer(), 0);
  EXPECT_EQ(n.integer(), 0);
  for (std::size_t i = 0; i < m.vertices.size(); ++i) {
    EXPECT_EQ(n.integer(), static_cast<long>(i));  // 0-based
    for (int k = 0; k < 3; ++k) EXPECT_EQ(n.number(), m.vertices[i][k]);
  }
  EXPECT_TRUE(n.done());
  Reader e{tokens(ele.str())};
  EXPECT_EQ(e.integer(), 2);
  EXPECT_EQ(e.integer(), 4);
  EXPECT_EQ(e.integer(), 0);
  for (std::size_t i = 0; i < m.tets.size(); ++i) {
    EXPECT_EQ(e.integer(), static_cast<long>(i));
    for (int k = 0; k < 4; ++k) EXPECT_EQ(e.integer(), m.tets[i][k]);
  }
  EXPECT_TRUE(e.done());
  Reader f{tokens(face.str())};
  EXPECT_EQ(f.integer(), 6);
  EXPECT_EQ(f.integer(), 1);
  for (std::size_t i = 0; i < m.boundary.size(); ++i) {
    EXPECT_EQ(f.integer(), static_cast<long>(i));
    for (int k = 0; k < 3; ++k) EXPECT_EQ(f.integer(), m.boundary[i][k]);
    EXPECT_EQ(f.integer(), m.boundary_facet[i] + 1);
  }
  EXPECT_TRUE(f.done());
}

TEST(Output, TetgenFilesMatchStreams) {
  namespace fs = std::filesystem;
  const TetMesh m = two_tets();
  const fs::path dir =
      fs::temp_directory_path() /
      ("wqmesh_output_test_" + std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()));
  fs::create_directories(dir);
  const std::string base = (dir / "mesh").string();
  write_tetgen(base, m);
  std::ostringstream node, ele, face;
  write_tetgen(node, ele, face, m);
  EXPECT_EQ(testing::read_file(base + ".node"), node.str());
  EXPECT_EQ(testing::read_file(base + ".ele"), ele.str());
  EXPECT_EQ(testing::read_file(base + ".face"), face.str());
  fs::remove_all(dir);
  EXPECT_THROW(write_tetgen((dir / "no" / "such" / "dir").string(), m), std::runtime_error);
}

/// A minimal XML element tree, enough to check the writer's output.
struct Xml {
  std::string name;
  std::map<std::string, std::string> attrs;
  std::string text;
  std::vector<Xml> children;
  const Xml* child(const std::string& n) const {
    for (const Xml& c : children)
      if (c.name == n) return &c;
    return nullptr;
  }
  /// The DataArray child with attribute Name = n, or the first unnamed one.
  const Xml* array(const std::string& n) const {
    for (const Xml& c : children)
      if (c.name == "DataArray" &&
          (n.empty() ? c.attrs.count("Name") == 0 : c.attrs.count("Name") && c.attrs.at("Name") == n))
        return &c;
    return nullptr;
  }
};

/// Parses a well-formed XML document (declaration, elements, attributes in
/// double quotes, text); throws std::runtime_error on any malformation.
class XmlParser {
 public:
  explicit XmlParser(const std::string& s) : s_(s) {}
  Xml parse() {
    skip_ws();
    if (s_.compare(i_, 5, "<?xml") == 0) {
      const std::size_t e = s_.find("?>", i_);
      if (e == std::string::npos) fail("unterminated declaration");
      i_ = e + 2;
    }
    skip_ws();
    Xml root = element();
    skip_ws();
    if (i_ != s_.size()) fail("content after the root element");
    return root;
  }

 private:
  [[noreturn]] void fail(const std::string& why) {
    throw std::runtime_error("XML: " + why + " at " + std::to_string(i_));
  }
  void skip_ws() {
    while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_;
  }
  std::string name() {
    const std::size_t b = i_;
    while (i_ < s_.size() &&
           (std::isalnum(static_cast<unsigned char>(s_[i_])) || s_[i_] == '_' || s_[i_] == '-' || s_[i_] == ':'))
      ++i_;
    if (b == i_) fail("expected a name");
    return s_.substr(b, i_ - b);
  }
  Xml element() {
    if (i_ >= s_.size() || s_[i_] != '<') fail("expected <");
    ++i_;
    Xml x;
    x.name = name();
    for (;;) {
      skip_ws();
      if (i_ >= s_.size()) fail("unterminated tag");
      if (s_.compare(i_, 2, "/>") == 0) {
        i_ += 2;
        return x;
      }
      if (s_[i_] == '>') {
        ++i_;
        break;
      }
      const std::string key = name();
      if (x.attrs.count(key)) fail("duplicate attribute " + key);
      skip_ws();
      if (i_ >= s_.size() || s_[i_] != '=') fail("expected =");
      ++i_;
      skip_ws();
      if (i_ >= s_.size() || s_[i_] != '"') fail("expected \"");
      const std::size_t e = s_.find('"', i_ + 1);
      if (e == std::string::npos) fail("unterminated attribute");
      x.attrs[key] = s_.substr(i_ + 1, e - i_ - 1);
      i_ = e + 1;
    }
    for (;;) {
      const std::size_t lt = s_.find('<', i_);
      if (lt == std::string::npos) fail("unterminated element " + x.name);
      const std::string text = s_.substr(i_, lt - i_);
      if (text.find('&') != std::string::npos || text.find('>') != std::string::npos)
        fail("unexpected character in text");
      x.text += text;
      i_ = lt;
      if (s_.compare(i_, 2, "</") == 0) {
        i_ += 2;
        if (name() != x.name) fail("mismatched end tag for " + x.name);
        skip_ws();
        if (i_ >= s_.size() || s_[i_] != '>') fail("expected >");
        ++i_;
        return x;
      }
      x.children.push_back(element());
    }
  }
  const std::string& s_;
  std::size_t i_ = 0;
};

std::vector<double> numbers(const Xml* x) {
  std::vector<double> v;
  if (x == nullptr) {
    ADD_FAILURE() << "missing DataArray";
    return v;
  }
  for (const std::string& t : tokens(x->text)) v.push_back(to_double(t));
  return v;
}

TEST(Output, VtuIsWellFormedAndRoundTrips) {
  TetMesh m = two_tets();
  m.weights = {0.0, 0.25, 1.0 / 3.0, 0.1, 2.0};
  const std::vector<TetQuality> q = mesh_quality(m, {}, false);  // unweighted, as the writers pass it
  const std::vector<TetQuality> weighted = mesh_quality(m);
  TetLabels labels;
  labels.tet_class = {0, 3};
  std::ostringstream out;
  write_vtu(out, m, q, &labels);
  Xml root;
  ASSERT_NO_THROW(root = XmlParser(out.str()).parse()) << out.str();
  EXPECT_EQ(root.name, "VTKFile");
  EXPECT_EQ(root.attrs["type"], "UnstructuredGrid");
  const Xml* grid = root.child("UnstructuredGrid");
  ASSERT_NE(grid, nullptr);
  const Xml* piece = grid->child("Piece");
  ASSERT_NE(piece, nullptr);
  EXPECT_EQ(piece->attrs.at("NumberOfPoints"), "5");
  EXPECT_EQ(piece->attrs.at("NumberOfCells"), "2");

  const Xml* points = piece->child("Points");
  ASSERT_NE(points, nullptr);
  ASSERT_NE(points->array(""), nullptr);
  EXPECT_EQ(points->array("")->attrs.at("NumberOfComponents"), "3");
  const std::vector<double> xyz = numbers(points->array(""));
  ASSERT_EQ(xyz.size(), 15u);
  for (std::size_t i = 0; i < 5; ++i)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(xyz[3 * i + k], m.vertices[i][k]);  // bit-exact

  const Xml* cells = piece->child("Cells");
  ASSERT_NE(cells, nullptr);
  const std::vector<double> conn = numbers(cells->array("connectivity"));
  const std::vector<double> offsets = numbers(cells->array("offsets"));
  const std::vector<double> types = numbers(cells->array("types"));
  ASSERT_EQ(conn.size(), 8u);
  for (int t = 0; t < 2; ++t)
    for (int k = 0; k < 4; ++k) EXPECT_EQ(conn[4 * t + k], m.tets[t][k]);
  EXPECT_EQ(offsets, (std::vector<double>{4, 8}));
  EXPECT_EQ(types, (std::vector<double>{10, 10}));

  const Xml* cd = piece->child("CellData");
  ASSERT_NE(cd, nullptr);
  const std::vector<double> md = numbers(cd->array("min_dihedral"));
  const std::vector<double> re = numbers(cd->array("radius_edge"));
  const std::vector<double> ore = numbers(cd->array("orthoradius_edge"));
  const std::vector<double> ar = numbers(cd->array("radius_ratio_R_over_r"));
  const std::vector<double> vol = numbers(cd->array("volume"));
  const std::vector<double> cls = numbers(cd->array("class"));
  ASSERT_EQ(md.size(), 2u);
  ASSERT_EQ(re.size(), 2u);
  ASSERT_EQ(ore.size(), 2u);
  ASSERT_EQ(ar.size(), 2u);
  ASSERT_EQ(vol.size(), 2u);
  for (int t = 0; t < 2; ++t) {
    EXPECT_EQ(md[t], q[t].min_dihedral_deg);
    EXPECT_EQ(re[t], q[t].radius_edge);          // unweighted R/l
    EXPECT_EQ(ore[t], weighted[t].radius_edge);  // with the weights: the orthoradius-edge ratio
    EXPECT_EQ(ar[t], q[t].aspect_ratio);
    EXPECT_EQ(vol[t], q[t].volume);
    EXPECT_GT(vol[t], 0);
  }
  EXPECT_EQ(cls, (std::vector<double>{0, 3}));

  const Xml* pd = piece->child("PointData");
  ASSERT_NE(pd, nullptr);
  EXPECT_EQ(numbers(pd->array("weight")), m.weights);
}

TEST(Output, VtuOptionalArraysAndNonFiniteValues) {
  TetMesh m = two_tets();
  // Unweighted, no quality, no labels: only Points and Cells.
  std::ostringstream plain;
  write_vtu(plain, m, {});
  Xml root = XmlParser(plain.str()).parse();
  const Xml* piece = root.child("UnstructuredGrid")->child("Piece");
  EXPECT_EQ(piece->child("PointData"), nullptr);
  EXPECT_EQ(piece->child("CellData"), nullptr);
  EXPECT_NE(piece->child("Points"), nullptr);

  // A flat tet: R/l and the aspect ratio are infinite, written as DBL_MAX.
  m.vertices[4] = {{0, 0, 1}};
  m.vertices[3] = {{1, 1, 0}};
  m.vertices[2] = {{0, 1, 0}};
  m.vertices[1] = {{1, 0, 0}};
  const std::vector<TetQuality> q = mesh_quality(m);
  ASSERT_EQ(q[0].radius_edge, std::numeric_limits<double>::infinity());
  std::ostringstream flat;
  write_vtu(flat, m, q);
  root = XmlParser(flat.str()).parse();
  const Xml* cd = root.child("UnstructuredGrid")->child("Piece")->child("CellData");
  ASSERT_NE(cd, nullptr);
  EXPECT_EQ(numbers(cd->array("radius_edge"))[0], std::numeric_limits<double>::max());
  EXPECT_EQ(cd->array("class"), nullptr);
  EXPECT_EQ(flat.str().find("inf"), std::string::npos);
  EXPECT_EQ(flat.str().find("nan"), std::string::npos);

  // Size mismatches are rejected.
  std::ostringstream bad;
  EXPECT_THROW(write_vtu(bad, m, {q[0]}), std::invalid_argument);
  TetLabels labels;
  labels.tet_class = {1};
  EXPECT_THROW(write_vtu(bad, m, q, &labels), std::invalid_argument);
}

TEST(Output, StatsJsonHasTable2Bins) {
  MeshStats s;
  s.vertices = 5;
  s.tets = 2;
  s.volume = 0.1;
  s.radius_edge_bins = {{7, 8, 9}};
  s.dihedral_bins = {{1, 2, 3}};
  s.slivers = 4;
  s.min_dihedral_histogram[12] = 11;
  const std::string pretty = stats_json(s);
  for (const char* key : {"\"0.6-1.4\": 7",
                          "\"1.4-2.2\": 8",
                          "\">2.2\": 9",
                          "\"0-3\": 1",
                          "\"3-5\": 2",
                          "\"5-10\": 3",
                          "\"vertices\": 5",
                          "\"tets\": 2",
                          "\"volume\": 0.1",
                          "\"slivers\": 4",
                          "\"radius_edge_bins\"",
                          "\"dihedral_bins\"",
                          "\"min_dihedral_histogram\"",
                          "\"min_face_angle_histogram\"",
                          "\"inverted\"",
                          "\"max_radius_edge\"",
                          "\"max_aspect_ratio\"",
                          "\"min_dihedral_deg\"",
                          "\"max_dihedral_deg\"",
                          "\"min_face_angle_deg\"",
                          "\"radius_edge_below\""})
    EXPECT_NE(pretty.find(key), std::string::npos) << key << "\n" << pretty;
  const std::string compact = stats_json(s, false);
  EXPECT_EQ(compact.find('\n'), std::string::npos);
  EXPECT_NE(compact.find("\"radius_edge_bins\":{\"0.6-1.4\":7,\"1.4-2.2\":8,\">2.2\":9}"), std::string::npos)
      << compact;
  EXPECT_NE(compact.find("\"dihedral_bins\":{\"0-3\":1,\"3-5\":2,\"5-10\":3}"), std::string::npos);
  // The histogram: 90 counts, the 13th is 11.
  const std::size_t h = compact.find("\"min_dihedral_histogram\":[");
  ASSERT_NE(h, std::string::npos);
  const std::size_t b = compact.find('[', h), e = compact.find(']', h);
  std::string list = compact.substr(b + 1, e - b - 1);
  for (char& c : list)
    if (c == ',') c = ' ';
  const std::vector<std::string> counts = tokens(list);
  ASSERT_EQ(counts.size(), 90u);
  EXPECT_EQ(counts[12], "11");
  // An infinite R/l (flat tet) becomes null.
  s.max_radius_edge = std::numeric_limits<double>::infinity();
  EXPECT_NE(stats_json(s, false).find("\"max_radius_edge\":null"), std::string::npos);
}

}  // namespace
}  // namespace wqmesh
