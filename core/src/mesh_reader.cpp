// SPDX-License-Identifier: GPL-3.0-or-later
// wqmesh: reading tetrahedral meshes (Medit .mesh, TetGen .node/.ele); see
// wqmesh/mesh_reader.h.
#include "wqmesh/mesh_reader.h"
#include "wqmesh/quality.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "reader_detect.h"

namespace wqmesh {

namespace {

/// Whitespace-separated tokens of a text buffer, `#` comments skipped, with
/// the 1-based line of the last token read. `where` names the file in errors
/// ("" for Medit, "node" or "ele" for TetGen).
class Tokens {
 public:
  Tokens(const char* data, std::size_t size, std::string where) : data_(data), size_(size), where_(std::move(where)) {}

  /// The next token, or false at the end of the data.
  bool next(std::string& token) {
    for (;;) {
      while (pos_ < size_ && std::isspace(static_cast<unsigned char>(data_[pos_]))) {
        if (data_[pos_] == '\n') ++line_;
        ++pos_;
      }
      if (pos_ < size_ && data_[pos_] == '#') {
        while (pos_ < size_ && data_[pos_] != '\n') ++pos_;
        continue;
      }
      break;
    }
    if (pos_ >= size_) return false;
    const std::size_t start = pos_;
    while (pos_ < size_ && !std::isspace(static_cast<unsigned char>(data_[pos_])) && data_[pos_] != '#') ++pos_;
    token.assign(data_ + start, pos_ - start);
    token_line_ = line_;
    return true;
  }

  /// The next token, which must exist; `what` says what was expected.
  std::string need(const std::string& what) {
    std::string t;
    if (!next(t)) fail(InputErrorKind::truncated, "the data ends where " + what + " was expected");
    return t;
  }

  double need_double(const std::string& what) {
    const std::string t = need(what);
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(t.c_str(), &end);
    if (end == t.c_str() || *end != '\0')
      fail(InputErrorKind::syntax, "expected " + what + " (a number), got '" + t + "'");
    if (!std::isfinite(v)) fail(InputErrorKind::non_finite, what + " is not finite: '" + t + "'");
    return v;
  }

  long long need_integer(const std::string& what) {
    const std::string t = need(what);
    char* end = nullptr;
    errno = 0;
    const long long v = std::strtoll(t.c_str(), &end, 10);
    if (end == t.c_str() || *end != '\0' || errno == ERANGE)
      fail(InputErrorKind::syntax, "expected " + what + " (a whole number), got '" + t + "'");
    return v;
  }

  /// A count of entries of at least `tokens_per_entry` tokens each: a count
  /// that cannot fit in the rest of the data is reported as truncated before
  /// any memory is reserved for it.
  std::size_t need_count(const std::string& what, std::size_t tokens_per_entry) {
    const long long n = need_integer(what);
    if (n < 0) fail(InputErrorKind::syntax, what + " is negative (" + std::to_string(n) + ")");
    // Each token takes at least one character and one separator.
    const std::size_t room = (size_ - pos_) / (2 * std::max<std::size_t>(tokens_per_entry, 1)) + 1;
    if (static_cast<unsigned long long>(n) > room)
      fail(InputErrorKind::truncated,
           what + " is " + std::to_string(n) + " but the data left holds at most " + std::to_string(room) + " entries");
    return static_cast<std::size_t>(n);
  }

  [[noreturn]] void fail(InputErrorKind kind, const std::string& message) const {
    std::string at = where_.empty() ? "line " : where_ + " line ";
    throw InputError(kind, at + std::to_string(token_line_) + ": " + message);
  }

  long line() const { return token_line_; }

 private:
  const char* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
  long line_ = 1, token_line_ = 1;
  std::string where_;
};

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

/// Medit sections that are read and skipped: tokens per entry.
int skipped_section_tokens(const std::string& keyword) {
  static const struct {
    const char* name;
    int tokens;
  } kSections[] = {
      {"edges", 3},
      {"quadrilaterals", 5},
      {"hexahedra", 9},
      {"prisms", 7},
      {"pyramids", 6},
      {"corners", 1},
      {"ridges", 1},
      {"requiredvertices", 1},
      {"requirededges", 1},
      {"requiredtriangles", 1},
      {"requiredquadrilaterals", 1},
      {"requiredtetrahedra", 1},
      {"normals", 3},
      {"tangents", 3},
      {"normalatvertices", 2},
      {"tangentatvertices", 2},
      {"normalattrianglevertices", 3},
      {"normalatquadrilateralvertices", 3},
      {"tangentatedgevertices", 3},
  };
  for (const auto& s : kSections)
    if (keyword == s.name) return s.tokens;
  return -1;
}

void check_indices(const TetMesh& mesh, const std::vector<long>& tet_line, const std::vector<long>& tri_line,
                   const std::string& where) {
  const long long n = static_cast<long long>(mesh.vertices.size());
  auto bad = [&](const char* what, std::size_t i, long long index, long line) {
    throw InputError(InputErrorKind::bad_index, (where.empty() ? "line " : where + " line ") + std::to_string(line) +
                                                    ": " + what + " " + std::to_string(i + 1) + " refers to vertex " +
                                                    std::to_string(index + 1) + " (1-based) but there are " +
                                                    std::to_string(n) + " vertices");
  };
  for (std::size_t i = 0; i < mesh.tets.size(); ++i)
    for (int v : mesh.tets[i])
      if (v < 0 || v >= n) bad("tetrahedron", i, v, tet_line[i]);
  for (std::size_t i = 0; i < mesh.boundary.size(); ++i)
    for (int v : mesh.boundary[i])
      if (v < 0 || v >= n) bad("triangle", i, v, tri_line[i]);
}

/// An index read from a file as an int, with `base` subtracted; values beyond
/// int become -1 (reported by check_indices).
int to_index(long long value, long long base) {
  const long long v = value - base;
  return (v < 0 || v > 2147483647LL) ? -1 : static_cast<int>(v);
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

TetMesh read_medit(const char* data, std::size_t size) {
  if (data == nullptr || size == 0) throw InputError(InputErrorKind::empty, "the mesh file is empty");
  if (std::memchr(data, '\0', std::min<std::size_t>(size, 256)) != nullptr)
    throw InputError(InputErrorKind::syntax, "binary data: only ASCII Medit (.mesh) is read, not binary .meshb");
  Tokens in(data, size, "");
  TetMesh mesh;
  std::vector<long> tet_line, tri_line;
  bool any_keyword = false;
  std::string token;
  while (in.next(token)) {
    const std::string keyword = lower(token);
    if (keyword == "end") break;
    any_keyword = true;
    if (keyword == "meshversionformatted") {
      const long long v = in.need_integer("the MeshVersionFormatted value");
      if (v < 1 || v > 4) in.fail(InputErrorKind::syntax, "unknown MeshVersionFormatted " + std::to_string(v));
    } else if (keyword == "dimension") {
      const long long d = in.need_integer("the Dimension value");
      if (d != 3) in.fail(InputErrorKind::syntax, "Dimension " + std::to_string(d) + ": only 3 is read");
    } else if (keyword == "vertices") {
      const std::size_t n = in.need_count("the Vertices count", 4);
      mesh.vertices.reserve(mesh.vertices.size() + n);
      for (std::size_t i = 0; i < n; ++i) {
        Point3 p;
        for (double& c : p) c = in.need_double("a vertex coordinate");
        in.need_integer("a vertex reference");
        mesh.vertices.push_back(p);
      }
    } else if (keyword == "tetrahedra") {
      const std::size_t n = in.need_count("the Tetrahedra count", 5);
      mesh.tets.reserve(mesh.tets.size() + n);
      for (std::size_t i = 0; i < n; ++i) {
        std::array<int, 4> t;
        for (int& v : t) v = to_index(in.need_integer("a tetrahedron's vertex index"), 1);
        tet_line.push_back(in.line());
        in.need_integer("a tetrahedron reference");
        mesh.tets.push_back(t);
      }
    } else if (keyword == "triangles") {
      const std::size_t n = in.need_count("the Triangles count", 4);
      for (std::size_t i = 0; i < n; ++i) {
        std::array<int, 3> t;
        for (int& v : t) v = to_index(in.need_integer("a triangle's vertex index"), 1);
        tri_line.push_back(in.line());
        const long long ref = in.need_integer("a triangle reference");
        mesh.boundary.push_back(t);
        mesh.boundary_facet.push_back(ref >= 1 && ref <= 2147483647LL ? static_cast<int>(ref - 1) : -1);
      }
    } else {
      const int k = skipped_section_tokens(keyword);
      if (k < 0) in.fail(InputErrorKind::syntax, "unknown Medit keyword '" + token + "'");
      const std::size_t n = in.need_count("the " + token + " count", static_cast<std::size_t>(k));
      for (std::size_t i = 0; i < n * static_cast<std::size_t>(k); ++i) in.need("an entry of " + token);
    }
  }
  if (!any_keyword) throw InputError(InputErrorKind::empty, "the mesh file holds no keyword");
  if (mesh.vertices.empty()) throw InputError(InputErrorKind::empty, "the mesh has no Vertices");
  if (mesh.tets.empty()) throw InputError(InputErrorKind::empty, "the mesh has no Tetrahedra");
  check_indices(mesh, tet_line, tri_line, "");
  return mesh;
}

TetMesh read_tetgen(const char* node, std::size_t node_size, const char* ele, std::size_t ele_size) {
  if (node == nullptr || node_size == 0) throw InputError(InputErrorKind::empty, "the .node file is empty");
  if (ele == nullptr || ele_size == 0) throw InputError(InputErrorKind::empty, "the .ele file is empty");
  TetMesh mesh;
  long long base = 0;
  {
    Tokens in(node, node_size, "node");
    const long long n = in.need_integer("the number of points");
    const long long dim = in.need_integer("the dimension");
    if (dim != 3) in.fail(InputErrorKind::syntax, "dimension " + std::to_string(dim) + ": only 3 is read");
    const long long attributes = in.need_integer("the number of point attributes");
    const long long markers = in.need_integer("the number of boundary markers (0 or 1)");
    if (attributes < 0 || attributes > 1000)
      in.fail(InputErrorKind::syntax, "bad number of attributes " + std::to_string(attributes));
    if (markers != 0 && markers != 1)
      in.fail(InputErrorKind::syntax, "the number of boundary markers must be 0 or 1, not " + std::to_string(markers));
    if (n <= 0) in.fail(InputErrorKind::empty, "the .node file declares no points");
    const std::size_t per = static_cast<std::size_t>(4 + attributes + markers);
    if (static_cast<unsigned long long>(n) > node_size / (2 * per) + 1)
      in.fail(InputErrorKind::truncated,
              "the .node file declares " + std::to_string(n) + " points but cannot hold that many");
    mesh.vertices.reserve(static_cast<std::size_t>(n));
    for (long long i = 0; i < n; ++i) {
      const long long index = in.need_integer("a point index");
      if (i == 0) {
        base = index;
        if (base != 0 && base != 1)
          in.fail(InputErrorKind::syntax, "the first point index must be 0 or 1, not " + std::to_string(base));
      } else if (index != base + i) {
        in.fail(InputErrorKind::syntax,
                "expected point index " + std::to_string(base + i) + ", got " + std::to_string(index));
      }
      Point3 p;
      for (double& c : p) c = in.need_double("a point coordinate");
      for (long long a = 0; a < attributes; ++a) in.need_double("a point attribute");
      if (markers) in.need_integer("a point boundary marker");
      mesh.vertices.push_back(p);
    }
  }
  std::vector<long> tet_line;
  {
    Tokens in(ele, ele_size, "ele");
    const long long m = in.need_integer("the number of tetrahedra");
    const long long k = in.need_integer("the nodes per tetrahedron");
    if (k != 4 && k != 10)
      in.fail(InputErrorKind::syntax, "nodes per tetrahedron must be 4 or 10, not " + std::to_string(k));
    const long long attributes = in.need_integer("the number of tetrahedron attributes");
    if (attributes < 0 || attributes > 1000)
      in.fail(InputErrorKind::syntax, "bad number of attributes " + std::to_string(attributes));
    if (m <= 0) in.fail(InputErrorKind::empty, "the .ele file declares no tetrahedra");
    const std::size_t per = static_cast<std::size_t>(1 + k + attributes);
    if (static_cast<unsigned long long>(m) > ele_size / (2 * per) + 1)
      in.fail(InputErrorKind::truncated,
              "the .ele file declares " + std::to_string(m) + " tetrahedra but cannot hold that many");
    mesh.tets.reserve(static_cast<std::size_t>(m));
    tet_line.reserve(static_cast<std::size_t>(m));
    for (long long i = 0; i < m; ++i) {
      in.need_integer("a tetrahedron index");
      std::array<int, 4> t;
      for (int& v : t) v = to_index(in.need_integer("a tetrahedron's node index"), base);
      tet_line.push_back(in.line());
      for (long long j = 4; j < k; ++j) in.need_integer("a tetrahedron's node index");
      for (long long a = 0; a < attributes; ++a) in.need_double("a tetrahedron attribute");
      mesh.tets.push_back(t);
    }
  }
  check_indices(mesh, tet_line, {}, "ele");
  return mesh;
}

TetMesh read_tet_mesh_file(const std::string& path) {
  try {
    if (ends_with(path, ".mesh")) {
      const std::string bytes = read_file_bytes(path);
      return read_medit(bytes.data(), bytes.size());
    }
    std::string base;
    if (ends_with(path, ".ele") || ends_with(path, ".node")) {
      base = path.substr(0, path.rfind('.'));
    } else if (std::error_code ec; std::filesystem::is_regular_file(path + ".ele", ec)) {
      base = path;
    } else {
      throw InputError(InputErrorKind::syntax,
                       "unknown mesh format: the name must end in .mesh (Medit) or .ele/.node (TetGen)");
    }
    const std::string node = read_file_bytes(base + ".node");
    const std::string ele = read_file_bytes(base + ".ele");
    return read_tetgen(node.data(), node.size(), ele.data(), ele.size());
  } catch (const InputError& e) {
    throw InputError(e.kind(), path + ": " + e.what());
  }
}

bool orient_tets_by_majority(TetMesh& mesh) {
  std::size_t negative = 0, positive = 0;
  for (const std::array<int, 4>& t : mesh.tets) {
    const Point3 &a = mesh.vertices.at(t[0]), &b = mesh.vertices.at(t[1]), &c = mesh.vertices.at(t[2]),
                 &d = mesh.vertices.at(t[3]);
    // The exact sign: a double determinant overflows at 1e103 and rounds
    // to the wrong sign on flat tets.
    const int v = tet_orientation(a, b, c, d);
    if (v < 0)
      ++negative;
    else if (v > 0)
      ++positive;
  }
  if (negative <= positive) return false;
  for (std::array<int, 4>& t : mesh.tets) std::swap(t[2], t[3]);
  return true;
}

std::size_t used_vertex_count(const TetMesh& mesh) {
  std::vector<char> used(mesh.vertices.size(), 0);
  std::size_t n = 0;
  for (const std::array<int, 4>& t : mesh.tets)
    for (int v : t)
      if (v >= 0 && static_cast<std::size_t>(v) < used.size() && !used[v]) {
        used[v] = 1;
        ++n;
      }
  return n;
}

}  // namespace wqmesh
