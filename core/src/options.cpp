// SPDX-License-Identifier: GPL-3.0-or-later
// wqmesh: the table of run options. See wqmesh/options.h.
#include "wqmesh/options.h"

#include <cmath>
#include <sstream>

#include "wqmesh/json.h"

namespace wqmesh {

namespace {

std::string number_text(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace

const std::vector<OptionSpec>& option_table() {
  // The ranges: rho0 >= 1 (an R/l below 1 would split almost every tet;
  // section 4.3's proof wants rho0 > 3.41, the paper's experiments use 2.2);
  // theta a dihedral angle; max_size 0 means no bound (beyond the paper);
  // box_margin and max_vertices bounded so that the bounding box and the
  // vertex count stay representable.
  static const std::vector<OptionSpec> table = {
      {"rho", "--rho", OptionType::number, 1, 1e6, 2.2, false, 0,
       "rho0 of rule 6: tets with circumradius over shortest edge (R/l) above it are split"},
      {"sliverAngle", "--sliver-angle", OptionType::number, 0, 90, 3, false, 0,
       "theta of rule 7 and PUMP, degrees: tets with a dihedral angle at most theta are slivers"},
      {"pump", "--no-pump", OptionType::boolean, 0, 1, 1, false, 0, "false: QMESH alone (no rule 7, no PUMP)"},
      {"improve", "--no-improve", OptionType::boolean, 0, 1, 1, false, 0,
       "beyond the paper: the improvement phase after PUMP (flips, smoothing, insertion inside; the boundary "
       "kept); false: the WQMESH output of the paper"},
      {"polish", "--polish", OptionType::boolean, 0, 1, 0, false, 1,
       "beyond the paper: with improve, a polish after its passes that raises the smallest dihedral angle "
       "further (slides across slanted facets); costs 3-6 times REFINE + PUMP's time on small models"},
      {"maxVertices", "--max-vertices", OptionType::integer, 8, 1e9, 1e6, false, 0,
       "the run stops (stopped \"limit\", exit code 3) when the vertex count reaches it"},
      {"maxSize", "--max-size", OptionType::number, 0, 1e300, 0, false, 0,
       "beyond the paper: tets with a larger circumradius are split (0: no bound; inside a vertex "
       "ball the bound is the ball's radius f(u)/4 when larger)"},
      {"boxMargin", "--box-margin", OptionType::number, 1e-3, 1e3, 0.5, true, 0,
       "margin of the bounding box B, a fraction of the input's largest extent"},
      {"measureFloor", "--measure-floor", OptionType::boolean, 0, 1, 0, false, 1,
       "also time a plain Delaunay triangulation of the final vertex set (stats.delaunay_floor_s)"},
      {"maxMemoryBytes", nullptr, OptionType::number, 65536, 4294967296.0, 3.0 * 1024 * 1024 * 1024, false, 0,
       "wasm only: the most bytes the call's C++ allocations may hold at once; beyond, the run "
       "ends with the error \"limit\""},
  };
  return table;
}

const OptionSpec* find_option(const std::string& name) {
  for (const OptionSpec& s : option_table())
    if (name == s.name) return &s;
  return nullptr;
}

const OptionSpec* find_option_flag(const std::string& flag) {
  for (const OptionSpec& s : option_table())
    if (s.flag != nullptr && flag == s.flag) return &s;
  return nullptr;
}

std::string option_names(bool check_only) {
  std::string out;
  for (const OptionSpec& s : option_table()) {
    if (check_only && !s.check) continue;
    if (!out.empty()) out += ", ";
    out += s.name;
  }
  return out;
}

std::string option_range_text(const OptionSpec& spec) {
  switch (spec.type) {
    case OptionType::boolean: return "true or false";
    case OptionType::integer: return "a whole number in [" + number_text(spec.min) + ", " + number_text(spec.max) + "]";
    case OptionType::number: break;
  }
  return "a number in [" + number_text(spec.min) + ", " + number_text(spec.max) + "]";
}

std::string check_option_value(const OptionSpec& spec, double value, const std::string& label) {
  // NaN fails every comparison; infinities are outside every range.
  bool ok = std::isfinite(value) && value >= spec.min && value <= spec.max;
  if (spec.type == OptionType::boolean) ok = value == 0 || value == 1;
  if (spec.type == OptionType::integer) ok = ok && value == std::floor(value);
  if (ok) return "";
  return label + " must be " + option_range_text(spec) +
         (spec.type == OptionType::boolean ? "" : ", got " + number_text(value));
}

void apply_option(RunOptions& o, const OptionSpec& spec, double value) {
  const std::string n = spec.name;
  if (n == "rho")
    o.mesh.rho0 = value;
  else if (n == "sliverAngle")
    o.mesh.theta_deg = value;
  else if (n == "pump")
    o.mesh.pump = value != 0;
  else if (n == "improve")
    o.mesh.improve = value != 0;
  else if (n == "polish")
    o.mesh.polish = value != 0;
  else if (n == "maxVertices")
    o.mesh.max_vertices = static_cast<std::size_t>(value);
  else if (n == "maxSize")
    o.mesh.max_size = value;
  else if (n == "measureFloor")
    o.mesh.measure_floor = value != 0;
  else if (n == "maxMemoryBytes")
    o.max_memory_bytes = value;
  else if (n == "boxMargin")
    o.mesh.box_margin = value;  // the analysis reads it too: RunOptions::analysis()
}

double option_value(const RunOptions& o, const OptionSpec& spec) {
  const std::string n = spec.name;
  if (n == "rho") return o.mesh.rho0;
  if (n == "sliverAngle") return o.mesh.theta_deg;
  if (n == "pump") return o.mesh.pump ? 1 : 0;
  if (n == "improve") return o.mesh.improve ? 1 : 0;
  if (n == "polish") return o.mesh.polish ? 1 : 0;
  if (n == "maxVertices") return static_cast<double>(o.mesh.max_vertices);
  if (n == "maxSize") return o.mesh.max_size;
  if (n == "measureFloor") return o.mesh.measure_floor ? 1 : 0;
  if (n == "maxMemoryBytes") return o.max_memory_bytes;
  if (n == "boxMargin") return o.mesh.box_margin;
  return 0;
}

std::string options_json() {
  JsonWriter j(false);
  j.begin_array();
  for (const OptionSpec& s : option_table()) {
    j.begin_object();
    j.field("name", s.name);
    j.key("flag");
    if (s.flag != nullptr)
      j.value(s.flag);
    else
      j.null();
    j.field("type", s.type == OptionType::number ? "number" : s.type == OptionType::integer ? "integer" : "boolean");
    if (s.type == OptionType::boolean) {
      j.field("default", s.default_value != 0);
    } else {
      j.field("min", s.min);
      j.field("max", s.max);
      j.field("default", s.default_value);
    }
    j.key("commands").begin_array();
    if (s.check) j.value("check");
    j.value("mesh");
    j.end_array();
    j.field("doc", s.doc);
    j.end_object();
  }
  j.end_array();
  return j.str();
}

}  // namespace wqmesh
