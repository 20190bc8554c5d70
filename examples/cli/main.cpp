// wqmesh: the native command line.
//   wqmesh check IN [--compact] [--box-margin M]
//   wqmesh mesh IN -o OUT.(mesh|vtu|ele) [--stats OUT.json] [options]
// See kUsage for the options and the exit codes.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <chrono>

#include <sys/resource.h>

#include "wqmesh/mesher.h"
#include "wqmesh/output.h"
#include "wqmesh/report.h"

namespace {

constexpr const char* kUsage =
    "usage: wqmesh <command> [options]\n"
    "\n"
    "commands:\n"
    "  check IN [--compact] [--box-margin M]\n"
    "      Validate and analyse the polyhedron IN (OFF or STL, ASCII or binary,\n"
    "      decided by content). Prints a JSON report on stdout (input angles,\n"
    "      sharp vertices and edges, local feature sizes, the bounding box) and\n"
    "      warnings on stderr. --compact prints the JSON on one line; --box-margin\n"
    "      sets the margin of the bounding box B as a fraction of the input's\n"
    "      largest extent (default 0.5).\n"
    "      Exit code 0: valid input; 2: invalid input (message on stderr);\n"
    "      1: usage or internal error.\n"
    "  mesh IN -o OUT [--stats STATS.json] [--rho R] [--sliver-angle DEG]\n"
    "       [--no-pump] [--max-vertices N] [--max-size H] [--box-margin M] [--quiet]\n"
    "       [--measure-floor]\n"
    "      Mesh the polyhedron IN with WQMESH. OUT ends in .mesh (Medit), .vtu\n"
    "      (VTK, with per-tet quality and class) or .ele (TetGen: .node, .ele and\n"
    "      .face beside each other). --rho: rho0 of rule 6 (default 2.2);\n"
    "      --sliver-angle: theta of rule 7 and PUMP in degrees (default 3);\n"
    "      --no-pump: QMESH alone (no rule 7, no PUMP); --max-vertices: stop\n"
    "      with exit code 3 at this many vertices (default 1000000); --max-size:\n"
    "      split tets with a larger circumradius (default: none). Progress on\n"
    "      stderr unless --quiet. Exit code 0: done; 1: usage or internal error;\n"
    "      2: invalid input; 3: stopped by the vertex limit (the mesh is written\n"
    "      only if it conforms to the input). --measure-floor also times a plain\n"
    "      Delaunay triangulation of the final vertex set (ratio_to_delaunay).\n"
    "  --help, --version\n";

int usage_error(const std::string& message) {
  std::cerr << "wqmesh: " << message << "\n\n" << kUsage;
  return 1;
}

bool parse_double(const std::string& text, double& out) {
  char* end = nullptr;
  errno = 0;
  out = std::strtod(text.c_str(), &end);
  return errno == 0 && end != text.c_str() && *end == '\0';
}

int run_check(const std::vector<std::string>& args) {
  std::string path;
  bool pretty = true;
  wqmesh::AnalysisOptions options;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--compact") {
      pretty = false;
    } else if (a == "--box-margin") {
      if (i + 1 >= args.size() || !parse_double(args[i + 1], options.box_margin) ||
          !(options.box_margin > 0) || options.box_margin > 1e6)
        return usage_error("--box-margin needs a positive number");
      ++i;
    } else if (!a.empty() && a[0] == '-') {
      return usage_error("unknown option '" + a + "' for check");
    } else if (path.empty()) {
      path = a;
    } else {
      return usage_error("check takes one input file, got '" + path + "' and '" + a + "'");
    }
  }
  if (path.empty()) return usage_error("check needs an input file");

  std::ifstream in(path, std::ios::binary);
  if (!in) {
    std::cerr << "wqmesh: cannot open '" << path << "': " << std::strerror(errno) << "\n";
    return 2;
  }
  std::ostringstream bytes;
  bytes << in.rdbuf();
  const std::string data = bytes.str();

  const wqmesh::CheckResult result = wqmesh::check_polyhedron(data.data(), data.size(), {}, options);
  for (const std::string& w : result.warnings) std::cerr << "wqmesh: warning: " << w << "\n";
  std::cout << wqmesh::check_json(result, pretty) << "\n";
  if (!result.valid) {
    std::cerr << "wqmesh: " << path << ": " << result.error_kind << ": " << result.error << "\n";
    return 2;
  }
  return 0;
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

bool read_file(const std::string& path, std::string& data) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::ostringstream bytes;
  bytes << in.rdbuf();
  data = bytes.str();
  return true;
}

int run_mesh(const std::vector<std::string>& args) {
  std::string path, out, stats_path;
  bool quiet = false;
  wqmesh::MeshOptions options;
  wqmesh::AnalysisOptions analysis_options;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto number = [&](double& target, double lo, double hi) {
      if (i + 1 >= args.size() || !parse_double(args[i + 1], target) || !(target >= lo) || !(target <= hi))
        return false;
      ++i;
      return true;
    };
    double n = 0;
    if (a == "-o" && i + 1 < args.size()) {
      out = args[++i];
    } else if (a == "--stats" && i + 1 < args.size()) {
      stats_path = args[++i];
    } else if (a == "--rho") {
      if (!number(options.rho0, 1, 1e6)) return usage_error("--rho needs a number of at least 1");
    } else if (a == "--sliver-angle") {
      if (!number(options.theta_deg, 0, 90)) return usage_error("--sliver-angle needs degrees in [0, 90]");
    } else if (a == "--no-pump") {
      options.pump = false;
    } else if (a == "--max-vertices") {
      if (!number(n, 8, 1e9) || n != std::floor(n)) return usage_error("--max-vertices needs a whole number >= 8");
      options.max_vertices = static_cast<std::size_t>(n);
    } else if (a == "--max-size") {
      if (!number(options.max_size, 0, 1e300) || options.max_size <= 0)
        return usage_error("--max-size needs a positive number");
    } else if (a == "--box-margin") {
      if (!number(options.box_margin, 1e-3, 1e3)) return usage_error("--box-margin needs a number in [0.001, 1000]");
      analysis_options.box_margin = options.box_margin;
    } else if (a == "--quiet") {
      quiet = true;
    } else if (a == "--measure-floor") {
      options.measure_floor = true;
    } else if (!a.empty() && a[0] == '-') {
      return usage_error("unknown option '" + a + "' for mesh");
    } else if (path.empty()) {
      path = a;
    } else {
      return usage_error("mesh takes one input file, got '" + path + "' and '" + a + "'");
    }
  }
  if (path.empty()) return usage_error("mesh needs an input file");
  if (out.empty()) return usage_error("mesh needs -o OUT.mesh, OUT.vtu or OUT.ele");
  if (!ends_with(out, ".mesh") && !ends_with(out, ".vtu") && !ends_with(out, ".ele"))
    return usage_error("the output '" + out + "' must end in .mesh, .vtu or .ele");

  std::string data;
  if (!read_file(path, data)) {
    std::cerr << "wqmesh: cannot open '" << path << "': " << std::strerror(errno) << "\n";
    return 2;
  }
  const auto t0 = std::chrono::steady_clock::now();
  const wqmesh::CheckResult input = wqmesh::check_polyhedron(data.data(), data.size(), {}, analysis_options);
  for (const std::string& w : input.warnings) std::cerr << "wqmesh: warning: " << w << "\n";
  if (!input.valid) {
    std::cerr << "wqmesh: " << path << ": " << input.error_kind << ": " << input.error << "\n";
    return 2;
  }
  std::string last_phase;
  auto last_print = std::chrono::steady_clock::now();
  const wqmesh::ProgressCallback progress = [&](const wqmesh::Progress& p) {
    if (quiet) return true;
    const auto now = std::chrono::steady_clock::now();
    if (p.phase != last_phase || now - last_print > std::chrono::seconds(1)) {
      std::cerr << "wqmesh: " << p.phase << ": " << p.vertices << " vertices\n";
      last_phase = p.phase;
      last_print = now;
    }
    return true;
  };
  const wqmesh::MeshResult result = wqmesh::mesh_polyhedron(input.plc, input.analysis, options, progress);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  if (result.conforming) {
    if (ends_with(out, ".ele")) {
      wqmesh::write_tetgen(out.substr(0, out.size() - 4), result.mesh);
    } else {
      std::ofstream f(out, std::ios::binary);
      if (!f) {
        std::cerr << "wqmesh: cannot write '" << out << "'\n";
        return 1;
      }
      if (ends_with(out, ".mesh")) {
        wqmesh::write_medit(f, result.mesh);
      } else {
        wqmesh::TetLabels labels;
        for (wqmesh::TetClass c : result.tet_class) labels.tet_class.push_back(static_cast<int>(c));
        wqmesh::write_vtu(f, result.mesh, result.quality, &labels);
      }
      if (!f) {
        std::cerr << "wqmesh: writing '" << out << "' failed\n";
        return 1;
      }
    }
  } else {
    if (result.stopped.empty() || result.all_vertices > 0)
      std::cerr << "wqmesh: the mesh does not conform to the input; '" << out << "' not written\n";
    else
      std::cerr << "wqmesh: stopped before meshing; '" << out << "' not written\n";
  }
  struct rusage usage {};
  getrusage(RUSAGE_SELF, &usage);
  const double peak_mb = usage.ru_maxrss / 1024.0;  // Linux: kilobytes
  const std::string stats = wqmesh::mesh_stats_json(input.plc, result, options, seconds, peak_mb);
  if (!stats_path.empty()) {
    std::ofstream f(stats_path);
    f << stats << "\n";
    if (!f) {
      std::cerr << "wqmesh: cannot write '" << stats_path << "'\n";
      return 1;
    }
  }
  if (!quiet)
    std::cerr << "wqmesh: " << result.mesh.vertices.size() << " vertices, " << result.mesh.tets.size()
              << " tets, " << result.slivers << " slivers, " << result.skinny << " skinny, "
              << result.violations << " violations, " << seconds << " s\n";
  if (!result.stopped.empty()) {
    std::cerr << "wqmesh: stopped: " << result.stopped;
    if (!result.stop_message.empty()) std::cerr << ": " << result.stop_message;
    std::cerr << "\n";
    return 3;
  }
  if (!result.conforming) return 1;
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty()) return usage_error("no command given");
  const std::string command = args[0];
  args.erase(args.begin());
  try {
    if (command == "--help" || command == "-h" || command == "help") {
      std::cout << kUsage;
      return 0;
    }
    if (command == "--version") {
      std::cout << "wqmesh 0.1.0\n";
      return 0;
    }
    if (command == "check") return run_check(args);
    if (command == "mesh") return run_mesh(args);
    return usage_error("unknown command '" + command + "'");
  } catch (const std::exception& e) {
    std::cerr << "wqmesh: internal error: " << e.what() << "\n";
    return 1;
  }
}
