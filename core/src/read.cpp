// SPDX-License-Identifier: GPL-3.0-or-later
// wqmesh: reading a polyhedron from bytes or a file, the format decided by
// content (see input.h).
#include <filesystem>
#include <fstream>
#include <string>

#include "wqmesh/input.h"

namespace wqmesh {

PolygonSoup read_polyhedron(const char* data, std::size_t size, const InputLimits& limits) {
  if (size == 0 || data == nullptr) throw InputError(InputErrorKind::empty, "the input is empty");
  // OFF iff its first token, after blanks and `#` comments, is an OFF keyword.
  std::size_t i = 0;
  for (;;) {
    while (i < size && (data[i] == ' ' || data[i] == '\t' || data[i] == '\n' || data[i] == '\r' ||
                        data[i] == '\f' || data[i] == '\v'))
      ++i;
    if (i < size && data[i] == '#') {
      while (i < size && data[i] != '\n') ++i;
      continue;
    }
    break;
  }
  std::size_t j = i;
  while (j < size && j - i < 16 && data[j] != ' ' && data[j] != '\t' && data[j] != '\n' &&
         data[j] != '\r' && data[j] != '#')
    ++j;
  if (j > i && is_off_keyword(std::string(data + i, j - i))) return read_off(data, size, limits);
  return read_stl(data, size, limits);
}

PolygonSoup read_polyhedron_file(const std::string& path, const InputLimits& limits) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw InputError(InputErrorKind::io, "cannot read '" + path + "': it is a folder");
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw InputError(InputErrorKind::io, "cannot open '" + path + "'");
  const std::streamoff end = in.tellg();
  if (end < 0) throw InputError(InputErrorKind::io, "cannot read '" + path + "'");
  if (static_cast<unsigned long long>(end) > limits.max_bytes)
    throw InputError(InputErrorKind::too_large,
                     "'" + path + "' has " + std::to_string(end) + " bytes, beyond the limit of " +
                         std::to_string(limits.max_bytes));
  std::string bytes(static_cast<std::size_t>(end), '\0');
  in.seekg(0);
  if (end > 0 && !in.read(&bytes[0], end))
    throw InputError(InputErrorKind::io, "cannot read '" + path + "'");
  try {
    return read_polyhedron(bytes.data(), bytes.size(), limits);
  } catch (const InputError& e) {
    throw InputError(e.kind(), path + ": " + e.what());
  }
}

}  // namespace wqmesh
