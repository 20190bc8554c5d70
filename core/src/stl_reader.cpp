// SPDX-License-Identifier: GPL-3.0-or-later
// wqmesh: reading ASCII and binary STL into a polygon soup (see input.h).
// STL repeats the coordinates of every corner; corners with identical
// coordinates (exact equality of the doubles) become one point, so that the
// soup has the shared vertices of the PLC of the paper, section 2.
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>
#include <unordered_map>

#include "hashing.h"
#include "reader_detect.h"
#include "wqmesh/input.h"

namespace wqmesh {
namespace {

/// Gives identical corners one index.
class CornerMerger {
 public:
  explicit CornerMerger(PolygonSoup& soup) : soup_(soup) {}
  int index(Point3 p) {
    for (double& x : p) x += 0.0;  // -0 and +0 are equal coordinates
    auto it = map_.find(p);
    if (it != map_.end()) return it->second;
    const int i = static_cast<int>(soup_.points.size());
    soup_.points.push_back(p);
    map_.emplace(p, i);
    return i;
  }

 private:
  PolygonSoup& soup_;
  std::unordered_map<Point3, int, PointHash> map_;
};

std::uint32_t read_u32(const unsigned char* b) {
  return std::uint32_t(b[0]) | (std::uint32_t(b[1]) << 8) | (std::uint32_t(b[2]) << 16) | (std::uint32_t(b[3]) << 24);
}

float read_f32(const unsigned char* b) {
  const std::uint32_t u = read_u32(b);
  float f;
  std::memcpy(&f, &u, sizeof f);
  return f;
}

PolygonSoup read_binary(const unsigned char* data, std::size_t size, std::uint64_t n, const InputLimits& limits) {
  if (n > limits.max_faces)
    throw InputError(InputErrorKind::too_large, "binary STL: " + std::to_string(n) + " triangles exceed the limit of " +
                                                    std::to_string(limits.max_faces));
  if (n == 0) throw InputError(InputErrorKind::empty, "binary STL: the header declares no triangles");
  (void)size;  // == 84 + 50 n: read_stl decides binary by that alone
  PolygonSoup soup;
  soup.format = "STL-binary";
  CornerMerger merger(soup);
  soup.faces.reserve(static_cast<std::size_t>(n));
  for (std::uint64_t t = 0; t < n; ++t) {
    const unsigned char* rec = data + 84 + 50 * t;
    std::vector<int> face(3);
    for (int c = 0; c < 3; ++c) {
      Point3 p;
      for (int k = 0; k < 3; ++k) {
        p[k] = static_cast<double>(read_f32(rec + 12 + 12 * c + 4 * k));
        if (!std::isfinite(p[k]))
          throw InputError(InputErrorKind::non_finite, "binary STL: triangle " + std::to_string(t) + ", corner " +
                                                           std::to_string(c) + " has a non-finite coordinate");
      }
      face[c] = merger.index(p);
    }
    soup.faces.push_back(std::move(face));
    soup.face_line.push_back(0);
  }
  if (soup.points.size() > limits.max_points)
    throw InputError(InputErrorKind::too_large, "binary STL: too many distinct points");
  return soup;
}

/// Whitespace tokens of ASCII STL with their 1-based lines (a line ends in
/// LF, CRLF or a lone CR); a UTF-8 byte order mark at the start is skipped.
class StlScanner {
 public:
  StlScanner(const char* data, std::size_t size) : p_(data + utf8_bom_length(data, size)), end_(data + size) {}
  bool next(std::string& token, long& line) {
    while (p_ < end_ && std::isspace(static_cast<unsigned char>(*p_))) {
      if (*p_ == '\n' || (*p_ == '\r' && (p_ + 1 == end_ || p_[1] != '\n'))) ++line_;
      ++p_;
    }
    if (p_ >= end_) return false;
    const char* s = p_;
    while (p_ < end_ && !std::isspace(static_cast<unsigned char>(*p_))) ++p_;
    token.assign(s, p_);
    line = line_;
    return true;
  }
  long line() const { return line_; }

 private:
  const char* p_;
  const char* end_;
  long line_ = 1;
};

bool same_word(const std::string& t, const char* word) {
  const std::size_t n = std::strlen(word);
  if (t.size() != n) return false;
  for (std::size_t i = 0; i < n; ++i)
    if (std::tolower(static_cast<unsigned char>(t[i])) != word[i]) return false;
  return true;
}

PolygonSoup read_ascii(const char* data, std::size_t size, const InputLimits& limits) {
  StlScanner in(data, size);
  std::string tok;
  long line = 1;
  auto fail = [&](InputErrorKind kind, long at, const std::string& what) {
    throw InputError(kind, "ASCII STL line " + std::to_string(at) + ": " + what);
  };
  auto need = [&](const char* what) {
    if (!in.next(tok, line)) fail(InputErrorKind::truncated, in.line(), std::string("the file ends before ") + what);
  };
  auto expect = [&](const char* word) {
    need((std::string("'") + word + "'").c_str());
    if (!same_word(tok, word))
      fail(InputErrorKind::syntax, line, std::string("expected '") + word + "', found '" + escape_bytes(tok) + "'");
  };
  auto number = [&](const char* what, double& x) {
    need(what);
    char* stop = nullptr;
    x = std::strtod(tok.c_str(), &stop);
    if (tok.empty() || stop != tok.c_str() + tok.size())
      fail(InputErrorKind::syntax, line, std::string("bad ") + what + " '" + escape_bytes(tok) + "'");
  };

  PolygonSoup soup;
  soup.format = "STL-ascii";
  CornerMerger merger(soup);
  if (!in.next(tok, line)) throw InputError(InputErrorKind::empty, "STL: the file is empty");
  if (!same_word(tok, "solid"))
    fail(InputErrorKind::syntax, line, "expected 'solid' (or a binary STL), found '" + escape_bytes(tok) + "'");
  // The solid's name: the rest of its line, up to a `facet` or `endsolid`
  // keyword (some writers put a whole STL on one line).
  auto skip_name = [&] {
    const long solid_line = line;
    for (;;) {
      StlScanner ahead = in;
      std::string t;
      long l = 0;
      if (!ahead.next(t, l) || l != solid_line || same_word(t, "facet") || same_word(t, "endsolid")) return;
      in = ahead;
    }
  };
  skip_name();
  bool in_solid = true;
  for (;;) {
    if (!in.next(tok, line)) {
      if (in_solid) fail(InputErrorKind::truncated, in.line(), "the file ends before 'endsolid'");
      break;
    }
    if (!in_solid) {  // several solids may follow one another
      if (!same_word(tok, "solid"))
        fail(InputErrorKind::syntax, line, "expected 'solid', found '" + escape_bytes(tok) + "'");
      skip_name();
      in_solid = true;
      continue;
    }
    if (same_word(tok, "endsolid")) {
      // The name after endsolid, on the same line.
      const long end_line = line;
      for (;;) {
        StlScanner ahead = in;
        std::string t;
        long l = 0;
        if (!ahead.next(t, l) || l != end_line || same_word(t, "solid")) break;
        in = ahead;
      }
      in_solid = false;
      continue;
    }
    if (!same_word(tok, "facet"))
      fail(InputErrorKind::syntax, line, "expected 'facet' or 'endsolid', found '" + escape_bytes(tok) + "'");
    const long facet_line = line;
    expect("normal");
    // The normal is not used: its three components may be anything
    // ("nan", "-1.#IND" ...).
    for (int k = 0; k < 3; ++k) need("a normal coordinate");
    expect("outer");
    expect("loop");
    // Exactly three vertices: an STL facet is a triangle.
    std::vector<int> face;
    for (;;) {
      need("'endloop'");
      if (same_word(tok, "endloop")) break;
      if (!same_word(tok, "vertex"))
        fail(InputErrorKind::syntax, line, "expected 'vertex' or 'endloop', found '" + escape_bytes(tok) + "'");
      if (face.size() == 3)
        fail(
            InputErrorKind::syntax, line,
            "triangle " + std::to_string(soup.faces.size()) + " has a fourth 'vertex': an STL facet has exactly three");
      Point3 p;
      for (int k = 0; k < 3; ++k) {
        number("vertex coordinate", p[k]);
        if (!std::isfinite(p[k]))
          fail(InputErrorKind::non_finite, line,
               "corner " + std::to_string(face.size()) + " of triangle " + std::to_string(soup.faces.size()) +
                   " has a non-finite coordinate '" + escape_bytes(tok) + "'");
      }
      face.push_back(merger.index(p));
    }
    if (face.size() < 3)
      fail(InputErrorKind::syntax, line,
           "triangle " + std::to_string(soup.faces.size()) + " has only " + std::to_string(face.size()) + " vertices");
    expect("endfacet");
    if (soup.faces.size() >= limits.max_faces)
      fail(InputErrorKind::too_large, line, "more than " + std::to_string(limits.max_faces) + " triangles");
    if (soup.points.size() > limits.max_points)
      fail(InputErrorKind::too_large, line, "more than " + std::to_string(limits.max_points) + " points");
    soup.faces.push_back(std::move(face));
    soup.face_line.push_back(facet_line);
  }
  if (soup.faces.empty()) throw InputError(InputErrorKind::empty, "ASCII STL: no triangles");
  return soup;
}

}  // namespace

PolygonSoup read_stl(const char* data, std::size_t size, const InputLimits& limits) {
  if (size > limits.max_bytes)
    throw InputError(InputErrorKind::too_large,
                     "STL: " + std::to_string(size) + " bytes exceed the limit of " + std::to_string(limits.max_bytes));
  if (size == 0) throw InputError(InputErrorKind::empty, "STL: the file is empty");
  const auto* bytes = reinterpret_cast<const unsigned char*>(data);
  // Binary iff the size matches the triangle count of the header exactly
  // (see input.h: no text has such a size); ASCII iff it starts with solid.
  if (size >= 84 && binary_stl_size(data) == size) return read_binary(bytes, size, read_u32(bytes + 80), limits);
  if (starts_with_solid(data, size)) return read_ascii(data, size, limits);
  throw_unknown_format(data, size, "an STL file");
}

}  // namespace wqmesh
