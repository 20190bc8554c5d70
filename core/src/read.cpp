// SPDX-License-Identifier: GPL-3.0-or-later
// wqmesh: reading a polyhedron from bytes or a file, the format decided by
// content (see input.h).
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "reader_detect.h"
#include "wqmesh/input.h"

namespace wqmesh {

std::string escape_bytes(const char* data, std::size_t size, std::size_t max) {
  static const char* hex = "0123456789abcdef";
  std::string out;
  const std::size_t n = std::min(size, max);
  for (std::size_t i = 0; i < n; ++i) {
    const unsigned char c = static_cast<unsigned char>(data[i]);
    if (c == '\\' || c == '\'') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else {
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  if (size > max) out += "...";
  return out;
}

PolygonSoup read_polyhedron(const char* data, std::size_t size, const InputLimits& limits) {
  if (size == 0 || data == nullptr) throw InputError(InputErrorKind::empty, "the input is empty");
  if (size > limits.max_bytes) return read_stl(data, size, limits);  // too_large, by size
  // Binary STL first, by its exact size (no text has it, see read_stl): its
  // free-form header may start with anything, "OFF" or "solid" included.
  if (size >= 84 && binary_stl_size(data) == size) return read_stl(data, size, limits);
  // OFF iff its first token, after a byte order mark, blanks and `#`
  // comments, is an OFF keyword; ASCII STL iff it is `solid`.
  std::size_t i = utf8_bom_length(data, size);
  for (;;) {
    while (i < size && (data[i] == ' ' || data[i] == '\t' || data[i] == '\n' || data[i] == '\r' || data[i] == '\f' ||
                        data[i] == '\v'))
      ++i;
    if (i < size && data[i] == '#') {
      while (i < size && data[i] != '\n' && data[i] != '\r') ++i;
      continue;
    }
    break;
  }
  std::size_t j = i;
  while (j < size && j - i < 16 && data[j] != ' ' && data[j] != '\t' && data[j] != '\n' && data[j] != '\r' &&
         data[j] != '#')
    ++j;
  if (j > i && is_off_keyword(std::string(data + i, j - i))) return read_off(data, size, limits);
  if (starts_with_solid(data, size)) return read_stl(data, size, limits);
  throw_unknown_format(data, size, "an OFF or STL file");
}

std::size_t utf8_bom_length(const char* data, std::size_t size) {
  return size >= 3 && static_cast<unsigned char>(data[0]) == 0xef && static_cast<unsigned char>(data[1]) == 0xbb &&
                 static_cast<unsigned char>(data[2]) == 0xbf
             ? 3
             : 0;
}

std::uint64_t binary_stl_size(const char* data) {
  const auto* b = reinterpret_cast<const unsigned char*>(data + 80);
  const std::uint64_t n =
      std::uint64_t(b[0]) | (std::uint64_t(b[1]) << 8) | (std::uint64_t(b[2]) << 16) | (std::uint64_t(b[3]) << 24);
  return 84 + 50 * n;
}

bool starts_with_solid(const char* data, std::size_t size) {
  std::size_t i = utf8_bom_length(data, size);
  while (i < size && std::isspace(static_cast<unsigned char>(data[i]))) ++i;
  if (size - i < 5) return false;
  for (int k = 0; k < 5; ++k)
    if (std::tolower(static_cast<unsigned char>(data[i + k])) != "solid"[k]) return false;
  return true;
}

void throw_unknown_format(const char* data, std::size_t size, const char* what) {
  std::string seen = "not " + std::string(what) + ": it starts with '" + escape_bytes(data, size, 24) + "' (" +
                     std::to_string(size) + " bytes): no OFF header, no 'solid', and ";
  if (size < 84) throw InputError(InputErrorKind::truncated, seen + "shorter than the 84-byte header of a binary STL");
  const std::uint64_t n = (binary_stl_size(data) - 84) / 50;
  throw InputError(InputErrorKind::syntax, seen + "not a binary STL, whose header declaring " + std::to_string(n) +
                                               " triangles would make it " + std::to_string(84 + 50 * n) +
                                               " bytes long");
}

std::string read_file_bytes(const std::string& path, std::size_t max_bytes) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw InputError(InputErrorKind::io, "cannot read '" + path + "': it is a folder");
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw InputError(InputErrorKind::io, "cannot open '" + path + "': " + std::strerror(errno));
  const std::streamoff end = in.tellg();
  if (end < 0) throw InputError(InputErrorKind::io, "cannot read '" + path + "'");
  if (static_cast<unsigned long long>(end) > max_bytes)
    throw InputError(InputErrorKind::too_large, "'" + path + "' has " + std::to_string(end) +
                                                    " bytes, beyond the limit of " + std::to_string(max_bytes));
  std::string bytes(static_cast<std::size_t>(end), '\0');
  in.seekg(0);
  if (end > 0 && !in.read(&bytes[0], end)) throw InputError(InputErrorKind::io, "cannot read '" + path + "'");
  return bytes;
}

PolygonSoup read_polyhedron_file(const std::string& path, const InputLimits& limits) {
  const std::string bytes = read_file_bytes(path, limits.max_bytes);
  try {
    return read_polyhedron(bytes.data(), bytes.size(), limits);
  } catch (const InputError& e) {
    throw InputError(e.kind(), path + ": " + e.what());
  }
}

}  // namespace wqmesh
