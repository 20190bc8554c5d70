// SPDX-License-Identifier: GPL-3.0-or-later
// wqmesh: the public facade. See wqmesh/wqmesh.h.
#include "wqmesh/wqmesh.h"

#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <stdexcept>
#include <vector>

namespace wqmesh {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// Reads at most limits.max_bytes bytes of `path`: a larger file (by its size,
// before reading, or by what a pipe or a device yields) is refused as
// too_large without being read in full. On failure fills `error` (kind io or
// too_large, as check_polyhedron reports errors) and returns false.
bool read_input(const std::string& path, const InputLimits& limits, std::string& data, CheckResult& error) {
  const std::size_t max_bytes = limits.max_bytes;
  error.valid = false;
  auto fail = [&](InputErrorKind kind, const std::string& message) {
    error.error_kind = to_string(kind);
    error.error = message;
    return false;
  };
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    return fail(InputErrorKind::io, "cannot read '" + path + "': it is a folder");
  std::ifstream in(path, std::ios::binary);
  if (!in) return fail(InputErrorKind::io, "cannot open '" + path + "': " + std::strerror(errno));
  const auto too_large = [&](const std::string& size) {
    return fail(InputErrorKind::too_large,
                "'" + path + "' has " + size + " bytes, beyond the limit of " + std::to_string(max_bytes));
  };
  if (std::filesystem::is_regular_file(path, ec)) {
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (!ec && size > max_bytes) return too_large(std::to_string(size));
  }
  data.clear();
  std::vector<char> chunk(1 << 16);
  while (in) {
    in.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
    data.append(chunk.data(), static_cast<std::size_t>(in.gcount()));
    if (data.size() > max_bytes) return too_large("more than " + std::to_string(max_bytes));
  }
  if (in.bad()) return fail(InputErrorKind::io, "cannot read '" + path + "'");
  return true;
}

}  // namespace

const char* version() { return WQMESH_VERSION; }

// ---- Options ------------------------------------------------------------------

std::string Options::try_set(const OptionSpec& spec, double value, const std::string& label) {
  const std::string error = check_option_value(spec, value, label);
  if (error.empty()) apply_option(run_, spec, value);
  return error;
}

Options& Options::set(const std::string& name, double value) {
  const OptionSpec* spec = find_option(name);
  if (spec == nullptr)
    throw std::invalid_argument("unknown option '" + name + "'; the known options are: " + option_names());
  const std::string error = try_set(*spec, value, name);
  if (!error.empty()) throw std::invalid_argument(error);
  return *this;
}

double Options::get(const std::string& name) const {
  const OptionSpec* spec = find_option(name);
  if (spec == nullptr)
    throw std::invalid_argument("unknown option '" + name + "'; the known options are: " + option_names());
  return option_value(run_, *spec);
}

// ---- Polyhedron ---------------------------------------------------------------

Polyhedron Polyhedron::read_bytes(const char* data, std::size_t size, const Options& options,
                                  const InputLimits& limits) {
  const auto t0 = std::chrono::steady_clock::now();
  auto result = std::make_shared<CheckResult>(check_polyhedron(data, size, limits, options.analysis()));
  return Polyhedron(std::move(result), seconds_since(t0));
}

Polyhedron Polyhedron::read_file(const std::string& path, const Options& options, const InputLimits& limits) {
  std::string data;
  auto unread = std::make_shared<CheckResult>();
  if (!read_input(path, limits, data, *unread)) return Polyhedron(std::move(unread), 0);
  return read_bytes(data.data(), data.size(), options, limits);
}

std::optional<InputErrorKind> Polyhedron::error_kind() const {
  if (data_->valid) return std::nullopt;
  return error_kind_from_string(data_->error_kind);
}

std::string Polyhedron::report_json(bool pretty) const { return check_json(*data_, pretty); }

// ---- Meshing ------------------------------------------------------------------

Result mesh(const Polyhedron& polyhedron, const Options& options, const MeshProgressCallback& progress) {
  if (!polyhedron.valid())
    throw std::invalid_argument("wqmesh::mesh: the polyhedron is not valid (" + polyhedron.data_->error_kind + ": " +
                                polyhedron.data_->error + ")");
  const auto t0 = std::chrono::steady_clock::now();
  const CheckResult& in = *polyhedron.data_;
  // B is part of the PLC (section 2): mesh with the analysis of this margin.
  Analysis reanalysed;
  const bool same_box = in.analysis.box_margin == options.mesh().box_margin;
  if (!same_box) reanalysed = analyze(in.plc, options.analysis());
  ProgressCallback callback;
  if (progress) {
    callback = [&progress](const Progress& p) {
      MeshProgress m;
      m.phase = mesh_phase_from_string(p.phase).value_or(MeshPhase::initialize);
      m.vertices = p.vertices;
      m.steps = p.steps;
      m.fraction = p.fraction;
      return progress(m);
    };
  }
  Result r;
  r.input_ = polyhedron.data_;
  r.options_ = options.mesh();
  r.result_ = mesh_polyhedron(in.plc, same_box ? in.analysis : reanalysed, options.mesh(), callback);
  r.time_s_ = polyhedron.read_seconds() + seconds_since(t0);
  return r;
}

// ---- Result -------------------------------------------------------------------

StopReason Result::stop_reason() const {
  const std::optional<StopReason> s = stop_reason_from_string(result_.stopped);
  if (!s) throw std::logic_error("wqmesh: unknown stop reason '" + result_.stopped + "'");
  return *s;
}

MeshStats Result::stats() const { return mesh_stats(result_.mesh, result_.quality); }

std::string Result::stats_json(double peak_memory_mb, bool pretty) const {
  return mesh_stats_json(input_->plc, result_, options_, time_s_, peak_memory_mb, pretty);
}

std::optional<OutputFormat> Result::format_of_path(const std::string& path) {
  if (ends_with(path, ".mesh")) return OutputFormat::medit;
  if (ends_with(path, ".vtu")) return OutputFormat::vtu;
  if (ends_with(path, ".ele")) return OutputFormat::tetgen;
  return std::nullopt;
}

void Result::write(std::ostream& out, OutputFormat format) const {
  if (!result_.conforming) throw std::logic_error("wqmesh: the mesh does not conform to the input");
  switch (format) {
    case OutputFormat::medit: write_medit(out, result_.mesh); return;
    case OutputFormat::vtu: {
      TetLabels labels;
      for (TetClass c : result_.tet_class) labels.tet_class.push_back(static_cast<int>(c));
      // The same arrays on every run: weights of 0 where PUMP moved nothing.
      TetMesh weighted = result_.mesh;
      weighted.weights.resize(weighted.vertices.size(), 0.0);
      write_vtu(out, weighted, result_.quality, &labels);
      return;
    }
    case OutputFormat::tetgen: break;
  }
  throw std::invalid_argument("wqmesh: TetGen output is four files: use write_tetgen or write_file");
}

void Result::write_tetgen(std::ostream& node, std::ostream& ele, std::ostream& face, std::ostream& edge) const {
  if (!result_.conforming) throw std::logic_error("wqmesh: the mesh does not conform to the input");
  wqmesh::write_tetgen(node, ele, face, edge, result_.mesh);
}

void Result::write_file(const std::string& path) const {
  const std::optional<OutputFormat> format = format_of_path(path);
  if (!format) throw std::invalid_argument("the output '" + path + "' must end in .mesh, .vtu or .ele");
  if (!result_.conforming) throw std::logic_error("wqmesh: the mesh does not conform to the input");
  if (*format == OutputFormat::tetgen) {
    wqmesh::write_tetgen(path.substr(0, path.size() - 4), result_.mesh);
    return;
  }
  std::ofstream f(path, std::ios::binary);
  if (!f) throw std::runtime_error("cannot write '" + path + "'");
  write(f, *format);
  if (!f) throw std::runtime_error("writing '" + path + "' failed");
}

}  // namespace wqmesh
