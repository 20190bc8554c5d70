// wqmesh: a small JSON reader, for the files wqmesh writes (the statistics of
// `wqmesh mesh --stats`, read back by `wqmesh measure --stats` to recount the
// classes of a written mesh).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "wqmesh/error.h"

namespace wqmesh {

/// One JSON value. Numbers are doubles (strtod: the writer's round-trip
/// precision reads back bit-exact); objects keep their keys in file order.
struct JsonValue {
  enum class Kind { null, boolean, number, string, array, object };
  Kind kind = Kind::null;
  bool boolean = false;
  double number = 0;
  std::string string;
  std::vector<JsonValue> array;
  std::vector<std::pair<std::string, JsonValue>> object;

  /// The member `key` of an object (the first one), or null if there is none
  /// or this is not an object.
  const JsonValue* find(const std::string& key) const;
};

/// Parses one JSON document (RFC 8259; \u escapes of the basic plane are
/// written as UTF-8, nesting is limited to 256 levels). Throws
/// InputError(syntax) naming the byte offset and what was expected, or
/// InputError(empty) for a document of white space only.
JsonValue parse_json(const std::string& text);

}  // namespace wqmesh
