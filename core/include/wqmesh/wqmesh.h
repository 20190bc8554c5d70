// wqmesh: the public facade. One header to mesh a polyhedron with WQMESH
// (Cheng, Dey and Ray, "Weighted Delaunay Refinement for Polyhedra with Small
// Angles", 2005):
//
//   #include <wqmesh/wqmesh.h>
//   wqmesh::Options options;                       // the defaults of the table
//   options.set("rho", 2.2);                       // validated: throws if out of range
//   const wqmesh::Polyhedron in = wqmesh::Polyhedron::read_file("spike.off", options);
//   if (!in.valid()) { std::cerr << in.error_message(); return 2; }
//   const wqmesh::Result r = wqmesh::mesh(in, options);
//   if (r.conforming()) r.write_file("spike.mesh");  // .mesh, .vtu or .ele
//   std::cout << r.stats_json();
//
// The native command line (examples/cli) is built on it alone, the wasm
// bindings (wasm/bindings.cpp) as far as their memory accounting allows, and
// examples/cpp shows it against the installed package. The lower-level
// headers it includes (input.h, analysis.h, mesher.h, output.h, options.h,
// names.h, mesh_reader.h, json.h, json_reader.h) stay public for callers who need a single step.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cstddef>
#include <functional>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>

#include "wqmesh/analysis.h"
#include "wqmesh/error.h"
#include "wqmesh/input.h"
#include "wqmesh/json.h"
#include "wqmesh/json_reader.h"
#include "wqmesh/mesh_reader.h"
#include "wqmesh/mesher.h"
#include "wqmesh/names.h"
#include "wqmesh/options.h"
#include "wqmesh/output.h"
#include "wqmesh/quality.h"
#include "wqmesh/report.h"
#include "wqmesh/types.h"
#include "wqmesh/version.h"

namespace wqmesh {

/// The library's version, "major.minor.patch", from project(wqmesh VERSION)
/// in CMakeLists.txt (the same as WQMESH_VERSION and package.json's).
const char* version();

/// The options of a run, always valid: every value passed through the option
/// table (options.h: names, ranges, defaults), the same table the command
/// line's flags and the JavaScript options are checked with. A default
/// Options holds the table's defaults (rho0 2.2, theta 3 degrees, PUMP on,
/// box margin 0.5; section 5 of the paper uses the same rho0 and theta).
class Options {
 public:
  Options() = default;

  /// Sets the option named `name` (camelCase, e.g. "sliverAngle"; booleans
  /// as 0 or 1). Throws std::invalid_argument naming the option and its
  /// range when the name is unknown or the value out of range (NaN and
  /// infinities included); the options are then unchanged.
  Options& set(const std::string& name, double value);
  /// The same for an entry of the table, with `label` naming it in the
  /// message (e.g. the flag "--rho"). Returns "" or the message, and changes
  /// nothing on failure; never throws.
  std::string try_set(const OptionSpec& spec, double value, const std::string& label);
  /// The value of the option named `name`; std::invalid_argument if unknown.
  double get(const std::string& name) const;

  /// The mesher's options (MeshOptions, mesher.h).
  const MeshOptions& mesh() const { return run_.mesh; }
  /// The options of the input analysis, derived from the mesh options: the
  /// margin of the bounding box B (section 2: B is part of the PLC) is
  /// MeshOptions::box_margin, so the analysis and the mesher cannot disagree.
  AnalysisOptions analysis() const { return run_.analysis(); }
  /// wasm only: the cap on the C++ allocations of one call (maxMemoryBytes).
  double max_memory_bytes() const { return run_.max_memory_bytes; }
  const RunOptions& run() const { return run_; }

 private:
  RunOptions run_;
};

/// What a progress callback receives (mesher.h's Progress, its phase as an
/// enum): the phase, the vertices of the triangulation so far (box
/// included), the insertions and PUMP vertices so far, and an estimate in
/// [0, 1] of the fraction done.
struct MeshProgress {
  MeshPhase phase = MeshPhase::initialize;
  std::size_t vertices = 0;
  std::size_t steps = 0;
  double fraction = 0;
};

/// Called as mesher.h's ProgressCallback is: at each phase change and after a
/// bounded amount of work; returning false cancels the run (StopReason::
/// cancelled); it may throw to abandon the run (never from inside a CGAL
/// insertion).
using MeshProgressCallback = std::function<bool(const MeshProgress&)>;

class Result;

/// A polyhedron read, validated, turned into its PLC (section 2) and
/// analysed (input angles, sharp elements, f(u), the bounding box B;
/// sections 2 and 4.1), held together in one object so that a PLC is never
/// meshed with another's analysis. Made only by read_file or read_bytes, which
/// never throw for bad input: an invalid polyhedron carries the error kind and
/// a message naming the defect and where it is (input.h's contract). Copies
/// share the same immutable data.
class Polyhedron {
 public:
  /// Reads the file at `path` (OFF or STL, ASCII or binary, decided by
  /// content; at most limits.max_bytes bytes, refused as too_large before
  /// being read in full, from a pipe or a device too; a folder or an
  /// unreadable file is io), then as read_bytes.
  static Polyhedron read_file(const std::string& path, const Options& options = {}, const InputLimits& limits = {});
  /// Reads, validates and analyses `size` bytes (check_polyhedron, report.h),
  /// the bounding box with options.analysis().
  static Polyhedron read_bytes(const char* data, std::size_t size, const Options& options = {},
                               const InputLimits& limits = {});

  bool valid() const { return data_->valid; }
  /// The defect when not valid (nullopt when valid).
  std::optional<InputErrorKind> error_kind() const;
  /// The message when not valid ("" when valid).
  const std::string& error_message() const { return data_->error; }
  /// Repairs made while reading (one sentence each), valid or not.
  const Warnings& warnings() const { return data_->warnings; }
  /// "OFF", "STL-ascii" or "STL-binary" when read, else "".
  const std::string& format() const { return data_->format; }
  const MergeReport& merge() const { return data_->merge; }
  /// The PLC and its analysis (empty when not valid).
  const PLC& plc() const { return data_->plc; }
  const Analysis& analysis() const { return data_->analysis; }
  /// Seconds spent reading, validating and analysing.
  double read_seconds() const { return read_seconds_; }
  /// The JSON report of `wqmesh check` (check_json): valid or the error.
  std::string report_json(bool pretty = true) const;
  /// The underlying report (report.h).
  const CheckResult& check_result() const { return *data_; }

 private:
  Polyhedron(std::shared_ptr<const CheckResult> data, double seconds)
      : data_(std::move(data)), read_seconds_(seconds) {}
  std::shared_ptr<const CheckResult> data_;
  double read_seconds_ = 0;
  friend Result mesh(const Polyhedron&, const Options&, const MeshProgressCallback&);
};

/// A finished run: the mesh with its per-tet quality and classes, the
/// statistics, why it stopped, and the writers.
class Result {
 public:
  /// Everything the mesher returned (mesher.h: MeshResult).
  const MeshResult& raw() const { return result_; }
  /// The interior tets, weighted (section 3.2: PUMP's weights), with the
  /// boundary triangles and their input facets.
  const TetMesh& mesh() const { return result_.mesh; }
  StopReason stop_reason() const;
  /// Why it stopped, in words ("" when done).
  const std::string& stop_message() const { return result_.stop_message; }
  /// Every subsegment and subfacet is in the final triangulation (the mesh
  /// conforms to the PLC); the writers refuse a mesh that does not.
  bool conforming() const { return result_.conforming; }
  /// The quality statistics of the mesh (quality.h), unweighted: the
  /// geometry as written (the weighted view: raw().orthoradius_edge).
  MeshStats stats() const;
  /// Seconds from the bytes read to the mesh made (validation, analysis and
  /// meshing), the time_s of the statistics.
  double time_s() const { return time_s_; }
  /// The statistics as JSON, the layout of `wqmesh mesh --stats` and of the
  /// JavaScript MeshStats (report.h: mesh_stats_json). `peak_memory_mb`:
  /// the caller's measure, negative to leave it out.
  std::string stats_json(double peak_memory_mb = -1, bool pretty = true) const;

  /// Writes the mesh as Medit or VTU (output.h: write_medit, write_vtu with
  /// every quality array, the classes and a weight per vertex, 0 where PUMP
  /// moved nothing, so files of two runs hold the same arrays). TetGen needs
  /// four files: std::invalid_argument (use write_tetgen). Throws
  /// std::logic_error when the mesh does not conform.
  void write(std::ostream& out, OutputFormat format) const;
  /// TetGen .node, .ele, .face, .edge (output.h: write_tetgen).
  void write_tetgen(std::ostream& node, std::ostream& ele, std::ostream& face, std::ostream& edge) const;
  /// Writes to `path` by its ending: .mesh (Medit), .vtu (VTK) or .ele
  /// (TetGen: base.node, base.ele, base.face, base.edge beside each other).
  /// Throws std::invalid_argument for another ending, std::runtime_error when
  /// a file cannot be written, std::logic_error when the mesh does not conform.
  void write_file(const std::string& path) const;
  /// The format of a path's ending (.mesh, .vtu, .ele), or nullopt.
  static std::optional<OutputFormat> format_of_path(const std::string& path);

 private:
  Result() = default;
  std::shared_ptr<const CheckResult> input_;
  MeshOptions options_;
  MeshResult result_;
  double time_s_ = 0;
  friend Result mesh(const Polyhedron&, const Options&, const MeshProgressCallback&);
};

/// Meshes a valid polyhedron with WQMESH (section 4.3: INITIALIZE, CONFORM
/// with rules 1-3, REFINE with rules 4-7, then PUMP, section 3.2), as
/// mesh_polyhedron (mesher.h) does, with the same contract: deterministic,
/// stopped with StopReason::limit at options' maxVertices, cancelled by the
/// callback. The analysis is the polyhedron's when it was read with the same
/// box margin, else it is recomputed with options.analysis() (the bounding
/// box B is part of the PLC, section 2). Throws std::invalid_argument when
/// the polyhedron is not valid, std::runtime_error on an internal failure.
Result mesh(const Polyhedron& polyhedron, const Options& options = {}, const MeshProgressCallback& progress = {});

}  // namespace wqmesh
