// wqmesh: the closed value sets of the public API (why a run stopped, the
// phase it is in, what is wrong with an input, the class of an output tet, an
// output format) and their stable string names, in one place. The names are
// those of the JSON statistics, the command line and the JavaScript package
// (wasm/index.d.ts: InputErrorKind, Phase, MeshStats.stopped); they never
// change. Each set has a to_string/from_string pair and a list of every value.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "wqmesh/error.h"
#include "wqmesh/mesher.h"

namespace wqmesh {

/// Why a run ended (MeshResult::stopped holds the name). `done`: it finished
/// (the name is the empty string); `limit`: MeshOptions::max_vertices was
/// reached; `cancelled`: the progress callback returned false; `stalled`: one
/// step went past MeshOptions::stall_work units of work (the watchdog, beyond
/// the paper), or REFINE's rules 4-5 split the boundary without end (the
/// runaway guard, beyond the paper).
enum class StopReason { done, limit, cancelled, stalled };

/// The phases of a run in the order they come (section 4.3: INITIALIZE,
/// CONFORM with rules 1-3, REFINE with rules 4-7, PUMP), then the extraction
/// of the interior tets, then (beyond the paper, MeshOptions::improve) the
/// improvement phase. Progress::phase holds the name.
enum class MeshPhase { initialize, conform, refine, pump, extract, improve };

/// The output formats of the writers (output.h): Medit .mesh, VTK .vtu,
/// TetGen .node/.ele/.face/.edge. Names "medit", "vtu", "tetgen" (those of
/// the JavaScript writeMesh).
enum class OutputFormat { medit, vtu, tetgen };

/// Stable names: "" / "limit" / "cancelled" / "stalled"; "initialize" ...
/// "extract", "improve"; error_kind_name (error.h) for InputErrorKind; "good",
/// "skinny_near", "sliver_near", "violation" for TetClass; "medit", "vtu",
/// "tetgen".
const char* to_string(StopReason reason);
const char* to_string(MeshPhase phase);
const char* to_string(InputErrorKind kind);
const char* to_string(TetClass tet_class);
const char* to_string(OutputFormat format);

/// The value named `name` (exactly, case-sensitive), or nullopt.
std::optional<StopReason> stop_reason_from_string(const std::string& name);
std::optional<MeshPhase> mesh_phase_from_string(const std::string& name);
std::optional<InputErrorKind> error_kind_from_string(const std::string& name);
std::optional<TetClass> tet_class_from_string(const std::string& name);
std::optional<OutputFormat> output_format_from_string(const std::string& name);

/// Every value of each set, in declaration order (the one list the tests
/// compare the JavaScript unions with).
const std::vector<StopReason>& all_stop_reasons();
const std::vector<MeshPhase>& all_mesh_phases();
const std::vector<InputErrorKind>& all_error_kinds();
const std::vector<TetClass>& all_tet_classes();
const std::vector<OutputFormat>& all_output_formats();

}  // namespace wqmesh
