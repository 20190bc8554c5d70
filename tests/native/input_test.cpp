// SPDX-License-Identifier: GPL-3.0-or-later
// wqmesh: tests of the OFF and STL readers (input.h): format variants and
// every error kind, with the line (or triangle) it names.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "expect_input_error.h"
#include "wqmesh/input.h"

namespace wqmesh {
namespace {

PolygonSoup off(const std::string& s) { return read_off(s.data(), s.size()); }
PolygonSoup any(const std::string& s) { return read_polyhedron(s.data(), s.size()); }

/// Runs `f`, expects an InputError of `kind` whose message contains `needle`.
template <class F>
void expect_error(F f, InputErrorKind kind, const std::string& needle) {
  const std::string what = testing::expect_input_error(f, kind);
  EXPECT_NE(what.find(needle), std::string::npos) << "message '" << what << "' lacks '" << needle << "'";
}

const char* kTetOff =
    "OFF\n"
    "4 4 6\n"
    "0 0 0\n"
    "1 0 0\n"
    "0 1 0\n"
    "0 0 1\n"
    "3 0 2 1\n"
    "3 0 1 3\n"
    "3 0 3 2\n"
    "3 1 2 3\n";

/// The soup's structure is consistent with what the text declared.
void expect_tet(const PolygonSoup& s) {
  ASSERT_EQ(s.points.size(), 4u);
  ASSERT_EQ(s.faces.size(), 4u);
  ASSERT_EQ(s.face_line.size(), s.faces.size());
  for (const auto& f : s.faces) {
    ASSERT_EQ(f.size(), 3u);
    for (int v : f) EXPECT_TRUE(v >= 0 && v < 4);
  }
  EXPECT_EQ(s.points[1][0], 1.0);
  EXPECT_EQ(s.points[3][2], 1.0);
}

TEST(InputOff, PlainTetrahedron) {
  const PolygonSoup s = off(kTetOff);
  expect_tet(s);
  EXPECT_EQ(s.format, "OFF");
  EXPECT_EQ(s.face_line[0], 7);
  EXPECT_EQ(s.face_line[3], 10);
  EXPECT_EQ(s.faces[0], (std::vector<int>{0, 2, 1}));
}

TEST(InputOff, HeaderVariantsCommentsAndCounts) {
  // Counts on the header line, comments everywhere, COFF colours, blank lines.
  const std::string text =
      "# a comment before the header\n"
      "COFF 4 4 0 # counts on the header line\n"
      "\n"
      "0 0 0 255 0 0 255\n"
      "1 0 0 255 0 0 255  # trailing comment\n"
      "# a comment line between vertices\n"
      "0 1 0 0 255 0 255\n"
      "0 0 1 0 0 255 255\n"
      "3 0 2 1 0.5 0.5 0.5\n"
      "3 0 1 3 1 0 0 1\n"
      "3 0 3 2\n"
      "3 1 2 3 # a comment after a face\n";
  const PolygonSoup s = off(text);
  expect_tet(s);
  EXPECT_EQ(s.face_line[0], 9);
  EXPECT_EQ(s.face_line[3], 12);
  // NOFF: normals after each vertex are ignored; counts without edge count.
  const std::string noff =
      "NOFF\n4 4\n0 0 0 0 0 -1\n1 0 0 1 0 0\n0 1 0 0 1 0\n0 0 1 0 0 1\n"
      "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  expect_tet(off(noff));
  const std::string cnoff =
      "CNOFF\n4 4 6\n0 0 0 0 0 -1 1 1 1\n1 0 0 1 0 0 1 1 1\n0 1 0 0 1 0 1 1 1\n"
      "0 0 1 0 0 1 1 1 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  expect_tet(off(cnoff));
  // Windows line ends and tabs.
  const std::string crlf =
      "OFF\r\n4\t4\t6\r\n0 0 0\r\n1 0 0\r\n0 1 0\r\n0 0 1\r\n3 0 2 1\r\n3 0 1 3\r\n"
      "3 0 3 2\r\n3 1 2 3\r\n";
  const PolygonSoup w = off(crlf);
  expect_tet(w);
  EXPECT_EQ(w.face_line[0], 7);
}

TEST(InputOff, PolygonsOfAnySize) {
  const std::string text =
      "OFF\n8 6 12\n"
      "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
      "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7\n";
  const PolygonSoup s = off(text);
  ASSERT_EQ(s.faces.size(), 6u);
  for (const auto& f : s.faces) EXPECT_EQ(f.size(), 4u);
  const std::string big = "OFF\n6 1 0\n0 0 0\n1 0 0\n2 1 0\n1 2 0\n0 2 0\n-1 1 0\n6 0 1 2 3 4 5\n";
  const PolygonSoup b = off(big);
  ASSERT_EQ(b.faces.size(), 1u);
  EXPECT_EQ(b.faces[0].size(), 6u);
}

TEST(InputOff, Errors) {
  expect_error([] { off(""); }, InputErrorKind::empty, "empty");
  expect_error([] { off("# only a comment\n"); }, InputErrorKind::empty, "empty");
  expect_error([] { off("OFF\n0 0 0\n"); }, InputErrorKind::empty, "line 2");
  expect_error([] { off("PLY\n4 4 0\n"); }, InputErrorKind::syntax, "line 1");
  expect_error([] { off("OFF\n4 x 0\n"); }, InputErrorKind::syntax, "line 2");
  expect_error([] { off("OFF\n4 4 6\n0 0 0\n1 0 0\n0 1e 0\n"); }, InputErrorKind::syntax, "line 5");
  expect_error([] { off("OFF\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 a 3\n"); }, InputErrorKind::syntax,
               "line 8");
  // Truncated: the file ends before the counts are met.
  expect_error([] { off("OFF\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n"); }, InputErrorKind::truncated,
               "line 9");
  expect_error([] { off("OFF\n4 4 6\n0 0 0\n1 0"); }, InputErrorKind::truncated, "line 4");
  expect_error([] { off("OFF\n4"); }, InputErrorKind::truncated, "line 2");
  // Non-finite coordinates name the vertex and the line.
  expect_error([] { off("OFF\n4 4 6\n0 0 0\n1 nan 0\n0 1 0\n0 0 1\n"); }, InputErrorKind::non_finite,
               "line 4: vertex 1");
  expect_error([] { off("OFF\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 -inf\n"); }, InputErrorKind::non_finite, "vertex 3");
  expect_error([] { off("OFF\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1e999\n"); }, InputErrorKind::non_finite, "line 6");
  // Bad indices name the face and the line.
  expect_error([] { off("OFF\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 4\n"); }, InputErrorKind::bad_index,
               "line 8: face 1");
  expect_error([] { off("OFF\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 -2 1\n"); }, InputErrorKind::bad_index,
               "line 7: face 0");
  // Limits.
  InputLimits small;
  small.max_points = 3;
  const std::string tet = kTetOff;
  expect_error([&] { read_off(tet.data(), tet.size(), small); }, InputErrorKind::too_large, "line 2");
  InputLimits tiny_faces;
  tiny_faces.max_face_size = 2;
  expect_error([&] { read_off(tet.data(), tet.size(), tiny_faces); }, InputErrorKind::too_large, "line 7");
  InputLimits few_bytes;
  few_bytes.max_bytes = 10;
  expect_error([&] { read_off(tet.data(), tet.size(), few_bytes); }, InputErrorKind::too_large, "bytes");
  // A huge count in a tiny file is truncated, not an allocation failure.
  expect_error([] { off("OFF\n4000000 1 0\n0 0 0\n"); }, InputErrorKind::truncated, "line 4");
}

// ---- STL -------------------------------------------------------------------

struct Tri {
  float c[3][3];
};

/// Unit tetrahedron as STL triangles, outward.
std::vector<Tri> tet_tris() {
  const float p[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const int f[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  std::vector<Tri> out(4);
  for (int t = 0; t < 4; ++t)
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) out[t].c[c][k] = p[f[t][c]][k];
  return out;
}

void put_u32(std::string& s, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) s.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
}
void put_f32(std::string& s, float f) {
  std::uint32_t u;
  std::memcpy(&u, &f, 4);
  put_u32(s, u);
}

std::string binary_stl(const std::vector<Tri>& tris, const std::string& header) {
  std::string s = header;
  s.resize(80, ' ');
  put_u32(s, static_cast<std::uint32_t>(tris.size()));
  for (const Tri& t : tris) {
    for (int k = 0; k < 3; ++k) put_f32(s, 0.0f);  // normal, ignored
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) put_f32(s, t.c[c][k]);
    s.push_back(0);
    s.push_back(0);
  }
  return s;
}

std::string ascii_stl(const std::vector<Tri>& tris) {
  std::string s = "solid test\n";
  for (const Tri& t : tris) {
    s += "  facet normal 0 0 0\n    outer loop\n";
    for (int c = 0; c < 3; ++c)
      s += "      vertex " + std::to_string(t.c[c][0]) + " " + std::to_string(t.c[c][1]) + " " +
           std::to_string(t.c[c][2]) + "\n";
    s += "    endloop\n  endfacet\n";
  }
  s += "endsolid test\n";
  return s;
}

/// Corners are merged: 4 distinct points, and each face's corners are the
/// points the triangle names.
void expect_stl_tet(const PolygonSoup& s, const std::vector<Tri>& tris) {
  ASSERT_EQ(s.points.size(), 4u);
  ASSERT_EQ(s.faces.size(), tris.size());
  for (std::size_t t = 0; t < tris.size(); ++t)
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) EXPECT_EQ(s.points[s.faces[t][c]][k], static_cast<double>(tris[t].c[c][k]));
}

TEST(InputStl, AsciiAndBinary) {
  const auto tris = tet_tris();
  const std::string a = ascii_stl(tris);
  PolygonSoup sa = read_stl(a.data(), a.size());
  EXPECT_EQ(sa.format, "STL-ascii");
  expect_stl_tet(sa, tris);
  EXPECT_EQ(sa.face_line[0], 2);
  EXPECT_EQ(sa.face_line[1], 9);
  const std::string b = binary_stl(tris, "made by a test");
  PolygonSoup sb = read_stl(b.data(), b.size());
  EXPECT_EQ(sb.format, "STL-binary");
  expect_stl_tet(sb, tris);
  // A binary file whose header starts with "solid" is still binary.
  const std::string bs = binary_stl(tris, "solid but binary");
  PolygonSoup sbs = read_stl(bs.data(), bs.size());
  EXPECT_EQ(sbs.format, "STL-binary");
  expect_stl_tet(sbs, tris);
  // read_polyhedron decides by content.
  EXPECT_EQ(any(a).format, "STL-ascii");
  EXPECT_EQ(any(bs).format, "STL-binary");
  EXPECT_EQ(any(std::string("# comment\n") + kTetOff).format, "OFF");
  // Upper-case keywords and several solids are accepted.
  std::string upper = a;
  for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  expect_stl_tet(read_stl(upper.data(), upper.size()), tris);
  // A whole STL on one line, two solids, and normals that are not numbers.
  std::string one_line = a;
  for (char& c : one_line)
    if (c == '\n') c = ' ';
  expect_stl_tet(read_stl(one_line.data(), one_line.size()), tris);
  const std::string two = ascii_stl({tris[0], tris[1]}) + ascii_stl({tris[2], tris[3]});
  expect_stl_tet(read_stl(two.data(), two.size()), tris);
  std::string odd_normals = a;
  for (std::size_t at = 0; (at = odd_normals.find("normal 0 0 0", at)) != std::string::npos;)
    odd_normals.replace(at, 12, "normal nan -1.#IND 0");
  expect_stl_tet(read_stl(odd_normals.data(), odd_normals.size()), tris);
}

TEST(InputStl, Errors) {
  const auto tris = tet_tris();
  const std::string a = ascii_stl(tris);
  expect_error([] { read_stl("", 0); }, InputErrorKind::empty, "empty");
  expect_error(
      [] {
        std::string s = "solid x\nendsolid x\n";
        read_stl(s.data(), s.size());
      },
      InputErrorKind::empty, "no triangles");
  // Truncated ASCII: cut in the middle of the second facet.
  const std::string cut = a.substr(0, a.find("vertex", a.find("facet", 20)) + 10);
  expect_error([&] { read_stl(cut.data(), cut.size()); }, InputErrorKind::truncated, "line 11");
  const std::string no_end = a.substr(0, a.find("endsolid"));
  expect_error([&] { read_stl(no_end.data(), no_end.size()); }, InputErrorKind::truncated, "endsolid");
  // Garbled keyword on line 4 and a garbled number on line 5.
  std::string bad = a;
  bad.replace(bad.find("vertex"), 6, "vertx");
  expect_error([&] { read_stl(bad.data(), bad.size()); }, InputErrorKind::syntax, "line 4");
  std::string badnum = "solid s\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0x\n";
  expect_error([&] { read_stl(badnum.data(), badnum.size()); }, InputErrorKind::syntax, "line 5");
  std::string nan = "solid s\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 nan 0\n";
  expect_error([&] { read_stl(nan.data(), nan.size()); }, InputErrorKind::non_finite, "line 5");
  // Binary: cut in the middle of triangle 2 (binary only at 84 + 50 n bytes,
  // so the message says what that size would be); a NaN in triangle 3.
  const std::string b = binary_stl(tris, "bin");
  const std::string bcut = b.substr(0, 84 + 50 * 2 + 20);
  expect_error([&] { read_stl(bcut.data(), bcut.size()); }, InputErrorKind::syntax,
               "not an STL file: it starts with 'bin  ");
  expect_error([&] { read_stl(bcut.data(), bcut.size()); }, InputErrorKind::syntax, "(204 bytes)");
  expect_error([&] { read_stl(bcut.data(), bcut.size()); }, InputErrorKind::syntax,
               "declaring 4 triangles would make it 284 bytes long");
  std::string bnan = b;
  const float q = std::nanf("");
  std::memcpy(&bnan[84 + 50 * 3 + 12 + 4], &q, 4);
  expect_error([&] { read_stl(bnan.data(), bnan.size()); }, InputErrorKind::non_finite, "triangle 3");
  std::string short_header = "abc";
  expect_error([&] { read_stl(short_header.data(), short_header.size()); }, InputErrorKind::truncated, "header");
  InputLimits few;
  few.max_faces = 2;
  expect_error([&] { read_stl(b.data(), b.size(), few); }, InputErrorKind::too_large, "limit");
  expect_error([&] { read_stl(a.data(), a.size(), few); }, InputErrorKind::too_large, "line");
}

// ---- honest readers: byte order marks, line ends, unknown content --------

const char kBom[] = "\xef\xbb\xbf";

/// `text` with every "\n" replaced by `end`.
std::string with_line_ends(const std::string& text, const std::string& end) {
  std::string out;
  for (char c : text) {
    if (c == '\n')
      out += end;
    else
      out += c;
  }
  return out;
}

TEST(InputHonest, ByteOrderMarkIsSkipped) {
  const std::string off_bom = kBom + std::string(kTetOff);
  const PolygonSoup s = off(off_bom);
  expect_tet(s);
  EXPECT_EQ(s.face_line[0], 7);
  EXPECT_EQ(any(off_bom).format, "OFF");
  const auto tris = tet_tris();
  const std::string stl_bom = kBom + ascii_stl(tris);
  expect_stl_tet(read_stl(stl_bom.data(), stl_bom.size()), tris);
  EXPECT_EQ(any(stl_bom).format, "STL-ascii");
  EXPECT_EQ(any(stl_bom).face_line[1], 9);
  // A binary STL whose header happens to start with the same three bytes is
  // still binary (decided by its size).
  const std::string bin = binary_stl(tris, kBom + std::string("binary"));
  EXPECT_EQ(any(bin).format, "STL-binary");
  expect_stl_tet(any(bin), tris);
}

TEST(InputHonest, LineEndsLfCrlfAndCr) {
  const auto tris = tet_tris();
  for (const std::string end : {"\n", "\r\n", "\r"}) {
    SCOPED_TRACE(escape_bytes(end));
    const std::string o = with_line_ends(kTetOff, end);
    const PolygonSoup s = any(o);
    expect_tet(s);
    EXPECT_EQ(s.face_line[0], 7);
    EXPECT_EQ(s.face_line[3], 10);
    const std::string a = with_line_ends(ascii_stl(tris), end);
    const PolygonSoup t = any(a);
    EXPECT_EQ(t.format, "STL-ascii");
    expect_stl_tet(t, tris);
    EXPECT_EQ(t.face_line[1], 9);
    // Lines are still counted right in errors: vertex 1 on line 4.
    std::string bad = with_line_ends("OFF\n4 4 6\n0 0 0\n1 nan 0\n0 1 0\n0 0 1\n", end);
    expect_error([&] { any(bad); }, InputErrorKind::non_finite, "line 4: vertex 1");
    // Comments and colours end at any line end, too.
    const std::string commented = with_line_ends(
        "# comment\nOFF # header\n4 4 6\n0 0 0 # c\n1 0 0\n0 1 0\n0 0 1\n"
        "3 0 2 1 0.5 0.5 0.5\n3 0 1 3\n3 0 3 2\n3 1 2 3\n",
        end);
    expect_tet(any(commented));
  }
}

/// Deterministic bytes (a linear congruential generator).
std::string random_bytes(std::size_t n, std::uint32_t seed) {
  std::string s(n, '\0');
  for (char& c : s) {
    seed = seed * 1664525u + 1013904223u;
    c = static_cast<char>(seed >> 24);
  }
  return s;
}

TEST(InputHonest, NeitherOffNorStl) {
  for (std::uint32_t seed : {1u, 2u, 3u, 12345u}) {
    const std::string r = random_bytes(4096, seed);
    std::uint32_t n;
    std::memcpy(&n, r.data() + 80, 4);  // little-endian machines only
    ASSERT_NE(84 + 50 * std::uint64_t(n), 4096u) << "pick another seed";
    expect_error([&] { any(r); }, InputErrorKind::syntax, "not an OFF or STL file: it starts with '");
    expect_error([&] { any(r); }, InputErrorKind::syntax, "(4096 bytes)");
    expect_error([&] { any(r); }, InputErrorKind::syntax,
                 "would make it " + std::to_string(84 + 50 * std::uint64_t(n)) + " bytes long");
    // What was seen is quoted escaped: the first 24 bytes, then "...".
    expect_error([&] { any(r); }, InputErrorKind::syntax, "'" + escape_bytes(r, 24) + "'");
  }
  expect_error([] { any("PLY\nformat ascii 1.0\n"); }, InputErrorKind::truncated,
               "not an OFF or STL file: it starts with 'PLY\\x0aformat ascii 1.0\\x0a'");
  const std::string text(200, 'x');
  expect_error([&] { any(text); }, InputErrorKind::syntax, "not an OFF or STL file");
  expect_error([] { any(std::string("\0\0\0", 3)); }, InputErrorKind::truncated, "'\\x00\\x00\\x00' (3 bytes)");
}

TEST(InputHonest, MessagesQuoteBytesEscaped) {
  EXPECT_EQ(escape_bytes(std::string("a\0b\n'\\\xff", 7)), "a\\x00b\\x0a\\'\\\\\\xff");
  EXPECT_EQ(escape_bytes(std::string(50, 'z'), 40), std::string(40, 'z') + "...");
  // A NUL inside a number: the whole token is quoted, NUL escaped, so the
  // message cannot end at the NUL and show a valid-looking "1".
  const std::string nul = std::string("OFF\n4 4 6\n0 0 0\n1") + '\0' + "5 0 0\n0 1 0\n0 0 1\n";
  expect_error([&] { any(nul); }, InputErrorKind::syntax, "line 4: vertex 1: bad coordinate '1\\x005'");
  const std::string nul_index = std::string(kTetOff).replace(std::string(kTetOff).find("3 0 1 3"), 7,
                                                             std::string("3 0 1\0"
                                                                         "3",
                                                                         7));
  expect_error([&] { any(nul_index); }, InputErrorKind::syntax, "bad vertex index '1\\x003'");
  const std::string stl_nul =
      std::string("solid s\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1") + '\0' + "7 0 0\n";
  expect_error([&] { any(stl_nul); }, InputErrorKind::syntax, "line 5: bad vertex coordinate '1\\x007'");
  expect_error([] { off("\xef\xbb\xbfPLY\n"); }, InputErrorKind::syntax, "found 'PLY'");
  expect_error(
      [] {
        off("O\x01"
            "FF\n");
      },
      InputErrorKind::syntax, "found 'O\\x01FF'");
}

TEST(InputHonest, FourVertexStlFacetIsASyntaxError) {
  const std::string quad =
      "solid q\n"
      "facet normal 0 0 1\n"
      "outer loop\n"
      "vertex 0 0 0\n"
      "vertex 1 0 0\n"
      "vertex 1 1 0\n"
      "vertex 0 1 0\n"
      "endloop\n"
      "endfacet\n"
      "endsolid q\n";
  expect_error([&] { any(quad); }, InputErrorKind::syntax,
               "ASCII STL line 7: triangle 0 has a fourth 'vertex': an STL facet has exactly three");
  const std::string two =
      "solid q\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\n"
      "endsolid q\n";
  expect_error([&] { any(two); }, InputErrorKind::syntax, "line 6: triangle 0 has only 2 vertices");
}

TEST(InputFile, MissingFileIsIoError) {
  expect_error([] { read_polyhedron_file("/nonexistent/dir/model.off"); }, InputErrorKind::io,
               "/nonexistent/dir/model.off");
  expect_error([] { read_polyhedron_file("/"); }, InputErrorKind::io, "folder");
  EXPECT_STREQ(error_kind_name(InputErrorKind::self_intersection), "self_intersection");
  EXPECT_STREQ(error_kind_name(InputErrorKind::non_manifold_vertex), "non_manifold_vertex");
}

}  // namespace
}  // namespace wqmesh
