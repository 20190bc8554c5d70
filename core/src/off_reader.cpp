// SPDX-License-Identifier: GPL-3.0-or-later
// wqmesh: reading ASCII OFF polyhedra into a polygon soup (see input.h). The
// soup is the raw material of the PLC of the paper, section 2; nothing is
// validated here beyond what the format itself requires.
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <string>

#include "reader_detect.h"
#include "wqmesh/input.h"

namespace wqmesh {
namespace {

/// Splits OFF text into whitespace-separated tokens, skipping `#` comments
/// and a UTF-8 byte order mark at the start, and tracks the 1-based line of
/// every token. A line ends in LF, CRLF or a lone CR.
class OffScanner {
 public:
  OffScanner(const char* data, std::size_t size) : p_(data + utf8_bom_length(data, size)), end_(data + size) {}

  /// Moves to the next token; false at the end of the data.
  bool next(std::string& token, long& line) {
    skip_blank(true);
    if (p_ >= end_) return false;
    const char* start = p_;
    while (p_ < end_ && !is_space(*p_) && *p_ != '#') ++p_;
    token.assign(start, p_);
    line = line_;
    return true;
  }

  /// True when another token follows on the current line.
  bool more_on_line() {
    skip_blank(false);
    return p_ < end_ && *p_ != '\n' && *p_ != '\r';
  }

  /// Skips whatever is left on the current line (colours, normals, comments),
  /// up to its line end.
  void skip_line() {
    while (p_ < end_ && *p_ != '\n' && *p_ != '\r') ++p_;
  }

  long line() const { return line_; }

 private:
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }
  /// Skips blanks and comments; crosses line ends only when `cross` is set.
  void skip_blank(bool cross) {
    while (p_ < end_) {
      const char c = *p_;
      if (c == '\n' || c == '\r') {
        if (!cross) return;
        ++line_;
        p_ += (c == '\r' && p_ + 1 < end_ && p_[1] == '\n') ? 2 : 1;  // CRLF is one
      } else if (c == '#') {
        while (p_ < end_ && *p_ != '\n' && *p_ != '\r') ++p_;
      } else if (is_space(c)) {
        ++p_;
      } else {
        return;
      }
    }
  }

  const char* p_;
  const char* end_;
  long line_ = 1;
};

[[noreturn]] void fail(InputErrorKind kind, long line, const std::string& what) {
  throw InputError(kind, "OFF line " + std::to_string(line) + ": " + what);
}

/// Parses a non-negative decimal integer; false if the token is not one.
bool parse_count(const std::string& t, unsigned long long& value) {
  if (t.empty() || t.size() > 18) return false;
  value = 0;
  for (char c : t) {
    if (c < '0' || c > '9') return false;
    value = value * 10 + static_cast<unsigned long long>(c - '0');
  }
  return true;
}

/// Parses a (possibly negative) decimal integer.
bool parse_int(const std::string& t, long long& value) {
  if (t.empty()) return false;
  const bool neg = t[0] == '-';
  const std::string digits = (neg || t[0] == '+') ? t.substr(1) : t;
  unsigned long long u = 0;
  if (!parse_count(digits, u)) return false;
  value = neg ? -static_cast<long long>(u) : static_cast<long long>(u);
  return true;
}

/// Parses a floating point number (decimal, exponent, or nan/inf spelled out).
bool parse_double(const std::string& t, double& value) {
  if (t.empty()) return false;
  char* stop = nullptr;
  errno = 0;
  value = std::strtod(t.c_str(), &stop);
  return stop == t.c_str() + t.size();
}

}  // namespace

/// True when `t` is an OFF header keyword: OFF with optional prefixes
/// ST, C, N (e.g. COFF, NOFF, CNOFF, STCOFF).
bool is_off_keyword(const std::string& t) {
  if (t.size() < 3 || t.compare(t.size() - 3, 3, "OFF") != 0) return false;
  for (std::size_t i = 0; i + 3 < t.size(); ++i)
    if (t[i] != 'S' && t[i] != 'T' && t[i] != 'C' && t[i] != 'N') return false;
  return true;
}

PolygonSoup read_off(const char* data, std::size_t size, const InputLimits& limits) {
  if (size > limits.max_bytes)
    throw InputError(InputErrorKind::too_large,
                     "OFF: " + std::to_string(size) + " bytes exceed the limit of " + std::to_string(limits.max_bytes));
  OffScanner in(data, size);
  std::string tok;
  long line = 1;
  if (!in.next(tok, line)) throw InputError(InputErrorKind::empty, "OFF: the file is empty");
  if (!is_off_keyword(tok))
    fail(InputErrorKind::syntax, line, "expected the OFF header, found '" + escape_bytes(tok) + "'");

  // `what` names what is missing; it is only called when the data has ended.
  auto need = [&](auto what) {
    if (!in.next(tok, line)) fail(InputErrorKind::truncated, in.line(), "the file ends before " + std::string(what()));
  };
  unsigned long long nv = 0, nf = 0, ne = 0;
  need([] { return "the vertex count"; });
  if (!parse_count(tok, nv)) fail(InputErrorKind::syntax, line, "bad vertex count '" + escape_bytes(tok) + "'");
  need([] { return "the face count"; });
  if (!parse_count(tok, nf)) fail(InputErrorKind::syntax, line, "bad face count '" + escape_bytes(tok) + "'");
  if (in.more_on_line()) {
    need([] { return "the edge count"; });
    if (!parse_count(tok, ne)) fail(InputErrorKind::syntax, line, "bad edge count '" + escape_bytes(tok) + "'");
  }
  in.skip_line();
  if (nv > limits.max_points)
    fail(InputErrorKind::too_large, line,
         std::to_string(nv) + " vertices exceed the limit of " + std::to_string(limits.max_points));
  if (nf > limits.max_faces)
    fail(InputErrorKind::too_large, line,
         std::to_string(nf) + " faces exceed the limit of " + std::to_string(limits.max_faces));
  if (nv == 0) fail(InputErrorKind::empty, line, "the header declares no vertices");
  if (nf == 0) fail(InputErrorKind::empty, line, "the header declares no faces");

  PolygonSoup soup;
  soup.format = "OFF";
  // Never trust the counts for allocation: a vertex takes at least 6 bytes.
  soup.points.reserve(static_cast<std::size_t>(std::min<unsigned long long>(nv, size / 6 + 1)));
  for (unsigned long long i = 0; i < nv; ++i) {
    Point3 p{};
    for (int k = 0; k < 3; ++k) {
      need([&] {
        return "coordinate " + std::to_string(k + 1) + " of vertex " + std::to_string(i) + " (" + std::to_string(nv) +
               " declared)";
      });
      if (!parse_double(tok, p[k]))
        fail(InputErrorKind::syntax, line,
             "vertex " + std::to_string(i) + ": bad coordinate '" + escape_bytes(tok) + "'");
      if (!std::isfinite(p[k]))
        fail(InputErrorKind::non_finite, line,
             "vertex " + std::to_string(i) + " has a non-finite coordinate '" + escape_bytes(tok) + "'");
    }
    in.skip_line();  // normals, colours, texture coordinates
    soup.points.push_back(p);
  }
  soup.faces.reserve(static_cast<std::size_t>(std::min<unsigned long long>(nf, size / 8 + 1)));
  soup.face_line.reserve(soup.faces.capacity());
  for (unsigned long long f = 0; f < nf; ++f) {
    need([&] { return "face " + std::to_string(f) + " (" + std::to_string(nf) + " declared)"; });
    const long face_line = line;
    unsigned long long n = 0;
    if (!parse_count(tok, n))
      fail(InputErrorKind::syntax, line,
           "face " + std::to_string(f) + ": bad vertex count '" + escape_bytes(tok) + "'");
    if (n > limits.max_face_size)
      fail(InputErrorKind::too_large, line,
           "face " + std::to_string(f) + " has " + std::to_string(n) + " vertices, beyond the limit of " +
               std::to_string(limits.max_face_size));
    std::vector<int> face;
    face.reserve(static_cast<std::size_t>(std::min<unsigned long long>(n, size)));
    for (unsigned long long k = 0; k < n; ++k) {
      need([&] { return "vertex " + std::to_string(k) + " of face " + std::to_string(f); });
      long long idx = 0;
      if (!parse_int(tok, idx))
        fail(InputErrorKind::syntax, line,
             "face " + std::to_string(f) + ": bad vertex index '" + escape_bytes(tok) + "'");
      if (idx < 0 || static_cast<unsigned long long>(idx) >= nv)
        fail(InputErrorKind::bad_index, line,
             "face " + std::to_string(f) + " refers to vertex " + std::to_string(idx) + ", but there are " +
                 std::to_string(nv) + " vertices");
      face.push_back(static_cast<int>(idx));
    }
    in.skip_line();  // colour values
    soup.faces.push_back(std::move(face));
    soup.face_line.push_back(face_line);
  }
  return soup;
}

}  // namespace wqmesh
