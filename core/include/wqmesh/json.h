// wqmesh: a small JSON writer. Doubles are written with round-trip precision
// (17 significant digits, shortest form); NaN and infinities become null.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace wqmesh {

/// Builds one JSON document. Usage:
///   JsonWriter j; j.begin_object(); j.key("n"); j.value(3); j.end_object();
///   std::string s = j.str();
/// Commas are inserted automatically; `pretty` indents with two spaces.
class JsonWriter {
 public:
  explicit JsonWriter(bool pretty = true) : pretty_(pretty) {}
  JsonWriter& begin_object();
  JsonWriter& end_object();
  JsonWriter& begin_array();
  JsonWriter& end_array();
  JsonWriter& key(const std::string& k);
  JsonWriter& value(double v);
  JsonWriter& value(std::int64_t v);
  JsonWriter& value(int v) { return value(static_cast<std::int64_t>(v)); }
  JsonWriter& value(std::size_t v) { return value(static_cast<std::int64_t>(v)); }
  JsonWriter& value(bool v);
  JsonWriter& value(const std::string& v);
  JsonWriter& value(const char* v) { return value(std::string(v)); }
  JsonWriter& null();
  /// Convenience: key then value.
  template <class T>
  JsonWriter& field(const std::string& k, const T& v) {
    key(k);
    return value(v);
  }
  const std::string& str() const { return out_; }

 private:
  void before_value();
  JsonWriter& close(char bracket);
  void newline();
  std::string out_;
  std::vector<bool> first_;  ///< per open container: no element written yet
  bool after_key_ = false;
  bool pretty_;
};

/// Escapes a string for JSON (quotes included).
std::string json_quote(const std::string& s);

/// A double with round-trip precision ("%.17g" shortened to the shortest form
/// that reads back to the same value).
std::string format_double(double v);

}  // namespace wqmesh
