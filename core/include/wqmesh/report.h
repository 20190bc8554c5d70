// wqmesh: one call that reads, validates and analyses an input, and its JSON
// report. The command line (`wqmesh check`) and the wasm module both use it,
// so both print the same report for the same bytes.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cstddef>
#include <string>

#include "wqmesh/analysis.h"
#include "wqmesh/error.h"
#include "wqmesh/input.h"
#include "wqmesh/types.h"

namespace wqmesh {

struct CheckResult {
  bool valid = false;
  std::string error_kind;  ///< error_kind_name(...) when not valid
  std::string error;       ///< the message when not valid
  std::string format;      ///< "OFF", "STL-ascii", "STL-binary" when read
  Warnings warnings;
  MergeReport merge;
  PLC plc;
  Analysis analysis;
};

/// Reads `data` (OFF or STL, by content), builds the PLC and analyses it.
/// Never throws for bad input: an InputError becomes valid = false with its
/// kind and message; std::bad_alloc becomes a too_large error.
CheckResult check_polyhedron(const char* data, std::size_t size, const InputLimits& limits = {},
                             const AnalysisOptions& options = {});

/// The report as JSON: {"valid", "format", "warnings", "merge", "plc" (counts,
/// and "sharp_vertex_points" / "sharp_edge_points": the coordinates of
/// analysis.sharp_vertices / sharp_edges, in their order), "analysis"} or {"valid": false, "error": {"kind", "message"}}.
std::string check_json(const CheckResult& result, bool pretty = true);

}  // namespace wqmesh
