// wqmesh: the one table of run options (names, command-line flags, types,
// ranges, defaults), shared by the native command line (examples/cli), the
// wasm bindings (wasm/bindings.cpp) and, through options_json(), the npm
// package (wasm/index.mjs exports it as `options`). Every interface checks a
// value with check_option_value, so the same ranges apply everywhere.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <string>
#include <vector>

#include "wqmesh/analysis.h"
#include "wqmesh/mesher.h"

namespace wqmesh {

enum class OptionType { number, integer, boolean };

/// One option. Booleans appear on the command line as one flag that sets
/// `flag_value` (e.g. `--no-pump` sets pump to false).
struct OptionSpec {
  const char* name;  ///< camelCase, the JavaScript name, e.g. "sliverAngle"
  const char* flag;  ///< the command-line flag, e.g. "--sliver-angle"; nullptr: wasm only
  OptionType type;
  double min, max;       ///< inclusive range (number, integer); 0, 1 for booleans
  double default_value;  ///< booleans: 0 or 1
  bool check;            ///< also an option of `check` (else of `mesh` only)
  double flag_value;     ///< booleans: the value the flag sets
  const char* doc;       ///< one sentence, for the usage text and the JS table
};

/// The options of a run, with their defaults (those of the table).
struct RunOptions {
  MeshOptions mesh;
  /// The options of the input analysis, from the mesh options: the margin of
  /// the bounding box B is mesh.box_margin (one margin for the analysis that
  /// builds B and the mesher that uses it).
  AnalysisOptions analysis() const {
    AnalysisOptions a;
    a.box_margin = mesh.box_margin;
    return a;
  }
  /// wasm only: the most bytes the call's C++ allocations may hold at once.
  double max_memory_bytes = 3.0 * 1024 * 1024 * 1024;
};

/// Every option, in a fixed order.
const std::vector<OptionSpec>& option_table();

/// The option named `name` (camelCase), or nullptr.
const OptionSpec* find_option(const std::string& name);
/// The option whose command-line flag is `flag`, or nullptr.
const OptionSpec* find_option_flag(const std::string& flag);

/// The known option names, comma-separated (for "unknown option" messages);
/// only those of `check` when `check_only`.
std::string option_names(bool check_only = false);

/// What a value must be, e.g. "a number in [1, 1e+06]" or "true or false".
std::string option_range_text(const OptionSpec& spec);

/// "" when `value` is valid for `spec` (in range, finite, whole for an
/// integer, 0 or 1 for a boolean), else why not, naming the option as `label`
/// (e.g. "--rho" or "rho") and its range: "--rho must be a number in [1, 1e+06], got 0.5".
std::string check_option_value(const OptionSpec& spec, double value, const std::string& label);

/// Sets the option on `options`; `value` must have passed check_option_value.
void apply_option(RunOptions& options, const OptionSpec& spec, double value);

/// The value of `spec` in `options` (for the JS defaults and round trips).
double option_value(const RunOptions& options, const OptionSpec& spec);

/// The table as a JSON array: [{"name", "flag" (or null), "type", "min",
/// "max", "default", "commands": ["check"?, "mesh"], "doc"}].
std::string options_json();

}  // namespace wqmesh
