// wqmesh: the native command line.
//   wqmesh check IN [--compact] [--box-margin M]
//   wqmesh mesh IN -o OUT.(mesh|vtu|ele) [--stats OUT.json] [options]
//   wqmesh measure MESH.(mesh|ele) [--input IN] [--stats STATS.json] [--json]
// See kUsage for the options and the exit codes.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <new>
#include <sstream>
#include <string>
#include <vector>

#include <chrono>

#include <sys/resource.h>

// The facade only (wqmesh.h includes the lower-level headers it builds on).
#include "wqmesh/wqmesh.h"

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
    "      Exit code 0: valid input; 2: invalid input (message on stderr; an\n"
    "      input beyond 1 GiB, 5e6 points or 1e7 faces is too_large);\n"
    "      1: usage or internal error.\n"
    "  mesh IN -o OUT [--stats STATS.json] [--rho R] [--sliver-angle DEG]\n"
    "       [--no-pump] [--no-improve] [--polish] [--max-vertices N] [--max-size H]\n"
    "       [--box-margin M] [--quiet] [--measure-floor]\n"
    "      Mesh the polyhedron IN with WQMESH. OUT ends in .mesh (Medit), .vtu\n"
    "      (VTK, with per-tet quality and class) or .ele (TetGen: .node, .ele,\n"
    "      .face and .edge beside each other). --rho: rho0 of rule 6 (default 2.2);\n"
    "      --sliver-angle: theta of rule 7 and PUMP in degrees (default 3);\n"
    "      --no-pump: QMESH alone (no rule 7, no PUMP); --no-improve: no\n"
    "      improvement phase after PUMP (beyond the paper: flips, smoothing and\n"
    "      insertion inside, the boundary kept), the paper's output; --polish:\n"
    "      after the improvement phase's passes, a polish that raises the smallest\n"
    "      dihedral angle further (beyond the paper; 3-6 times REFINE + PUMP's time\n"
    "      on small models, off by default); --max-vertices: stop\n"
    "      with exit code 3 at this many vertices (default 1000000); --max-size:\n"
    "      split tets with a larger circumradius (default 0: none; inside a vertex\n"
    "      ball the bound is the ball's radius f(u)/4 if larger). Progress on\n"
    "      stderr unless --quiet. Exit code 0: done; 1: usage or internal error;\n"
    "      2: invalid input; 3: stopped by the vertex limit or by the stuck-step\n"
    "      watchdog or the runaway guard (stopped \"stalled\"; the mesh is written\n"
    "      only if it conforms to the input). --measure-floor also times a plain\n"
    "      Delaunay triangulation of the final vertex set (ratio_to_delaunay).\n"
    "  measure MESH [--input IN] [--stats STATS.json] [--json]\n"
    "      Measure a tetrahedral mesh made by any mesher with wqmesh's quality\n"
    "      module. MESH is Medit (.mesh) or TetGen (.ele or .node, the other file\n"
    "      beside it). Prints the vertices used by tets, the tets, the smallest\n"
    "      dihedral angle, the tets whose smallest dihedral angle is below 3, 5\n"
    "      and 10 degrees, the tets with R/l above 2.2 (unweighted) and, with\n"
    "      --input, the relative volume error against the polyhedron IN. The tets\n"
    "      are first oriented by majority (meshers differ in convention). --stats:\n"
    "      the statistics `wqmesh mesh --stats` wrote for MESH; their protecting\n"
    "      balls and thresholds (rho0, theta_deg) classify the tets again (skinny,\n"
    "      slivers, near a small angle, violations; README, Every output tet has a\n"
    "      class) and the counts are compared with the statistics' own. --json\n"
    "      prints one JSON object on one line.\n"
    "      Exit code 0: measured; 2: unreadable mesh, invalid IN or unreadable\n"
    "      STATS (message on stderr); 1: usage or internal error.\n"
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

// Reads the option of `spec` at args[i] (its flag) into `options` with the
// core's option table (wqmesh/options.h, the ranges of the wasm module too):
// a boolean flag sets its value, any other flag takes the next argument.
// Advances i past what it read. Returns "" or the usage error.
std::string parse_option(const std::vector<std::string>& args, std::size_t& i, const wqmesh::OptionSpec& spec,
                         wqmesh::Options& options) {
  double value = spec.flag_value;
  if (spec.type != wqmesh::OptionType::boolean) {
    if (i + 1 >= args.size() || !parse_double(args[i + 1], value))
      return std::string(spec.flag) + " needs " + wqmesh::option_range_text(spec);
    ++i;
  }
  return options.try_set(spec, value, spec.flag);
}

// "wqmesh: PATH: KIND: MESSAGE" for an input that cannot be meshed.
void print_input_error(const std::string& path, const wqmesh::Polyhedron& in) {
  std::cerr << "wqmesh: " << path << ": " << in.check_result().error_kind << ": " << in.error_message() << "\n";
}

int run_check(const std::vector<std::string>& args) {
  std::string path;
  bool pretty = true;
  wqmesh::Options options;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--compact") {
      pretty = false;
    } else if (const wqmesh::OptionSpec* spec = wqmesh::find_option_flag(a); spec != nullptr && spec->check) {
      const std::string error = parse_option(args, i, *spec, options);
      if (!error.empty()) return usage_error(error);
    } else if (!a.empty() && a[0] == '-') {
      return usage_error("unknown option '" + a + "' for check");
    } else if (path.empty()) {
      path = a;
    } else {
      return usage_error("check takes one input file, got '" + path + "' and '" + a + "'");
    }
  }
  if (path.empty()) return usage_error("check needs an input file");

  const wqmesh::Polyhedron in = wqmesh::Polyhedron::read_file(path, options);
  for (const std::string& w : in.warnings()) std::cerr << "wqmesh: warning: " << w << "\n";
  std::cout << in.report_json(pretty) << "\n";
  if (!in.valid()) {
    print_input_error(path, in);
    return 2;
  }
  return 0;
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

int run_mesh(const std::vector<std::string>& args) {
  std::string path, out, stats_path;
  bool quiet = false;
  wqmesh::Options options;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    const wqmesh::OptionSpec* spec = wqmesh::find_option_flag(a);
    if (a == "-o" && i + 1 < args.size()) {
      out = args[++i];
    } else if (a == "--stats" && i + 1 < args.size()) {
      stats_path = args[++i];
    } else if (spec != nullptr) {
      const std::string error = parse_option(args, i, *spec, options);
      if (!error.empty()) return usage_error(error);
    } else if (a == "--quiet") {
      quiet = true;
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
  if (!wqmesh::Result::format_of_path(out))
    return usage_error("the output '" + out + "' must end in .mesh, .vtu or .ele");

  const wqmesh::Polyhedron input = wqmesh::Polyhedron::read_file(path, options);
  for (const std::string& w : input.warnings()) std::cerr << "wqmesh: warning: " << w << "\n";
  if (!input.valid()) {
    print_input_error(path, input);
    return 2;
  }
  bool printed = false;
  wqmesh::MeshPhase last_phase = wqmesh::MeshPhase::initialize;
  auto last_print = std::chrono::steady_clock::now();
  const wqmesh::MeshProgressCallback progress = [&](const wqmesh::MeshProgress& p) {
    if (quiet) return true;
    const auto now = std::chrono::steady_clock::now();
    if (!printed || p.phase != last_phase || now - last_print > std::chrono::seconds(1)) {
      std::cerr << "wqmesh: " << wqmesh::to_string(p.phase) << ": " << p.vertices << " vertices\n";
      printed = true;
      last_phase = p.phase;
      last_print = now;
    }
    return true;
  };
  const wqmesh::Result result = wqmesh::mesh(input, options, progress);
  const double seconds = result.time_s();

  if (result.conforming()) {
    try {
      result.write_file(out);
    } catch (const std::runtime_error& e) {
      std::cerr << "wqmesh: " << e.what() << "\n";
      return 1;
    }
  } else {
    if (result.stop_reason() == wqmesh::StopReason::done || result.raw().all_vertices > 0)
      std::cerr << "wqmesh: the mesh does not conform to the input; '" << out << "' not written\n";
    else
      std::cerr << "wqmesh: stopped before meshing; '" << out << "' not written\n";
  }
  struct rusage usage {};
  getrusage(RUSAGE_SELF, &usage);
  const double peak_mb = usage.ru_maxrss / 1024.0;  // Linux: kilobytes
  const std::string stats = result.stats_json(peak_mb);
  if (!stats_path.empty()) {
    std::ofstream f(stats_path);
    f << stats << "\n";
    if (!f) {
      std::cerr << "wqmesh: cannot write '" << stats_path << "'\n";
      return 1;
    }
  }
  const wqmesh::MeshResult& r = result.raw();
  if (!quiet)
    std::cerr << "wqmesh: " << r.mesh.vertices.size() << " vertices, " << r.mesh.tets.size() << " tets, " << r.slivers
              << " slivers, " << r.skinny << " skinny, " << r.violations << " violations, " << seconds << " s\n";
  if (result.stop_reason() != wqmesh::StopReason::done) {
    std::cerr << "wqmesh: stopped: " << wqmesh::to_string(result.stop_reason());
    if (!result.stop_message().empty()) std::cerr << ": " << result.stop_message();
    std::cerr << "\n";
    return 3;
  }
  if (!result.conforming()) return 1;
  return 0;
}

// Measures a mesh written by any mesher (Medit or TetGen files) with the
// quality module, so that every tool is judged by the same code.
/// What `measure --stats` reads from a statistics file of `wqmesh mesh`.
struct StatsFile {
  std::vector<wqmesh::ProtectingBall> balls;
  double rho0 = 0, theta_deg = 0;
  std::size_t counts[4] = {0, 0, 0, 0};  ///< skinny, slivers, near_small_angle, violations
};
constexpr const char* kClassKeys[4] = {"skinny", "slivers", "near_small_angle", "violations"};

/// Reads STATS; throws InputError naming the file and the key that is missing.
StatsFile read_stats_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw wqmesh::InputError(wqmesh::InputErrorKind::io, path + ": cannot be read");
  std::ostringstream text;
  text << in.rdbuf();
  wqmesh::JsonValue v;
  try {
    v = wqmesh::parse_json(text.str());
  } catch (const wqmesh::InputError& e) {
    throw wqmesh::InputError(e.kind(), path + ": " + e.what());
  }
  using Kind = wqmesh::JsonValue::Kind;
  const auto missing = [&](const std::string& key) {
    return wqmesh::InputError(wqmesh::InputErrorKind::syntax,
                              path + ": not the statistics of `wqmesh mesh`: no valid \"" + key + "\"");
  };
  const auto number = [&](const wqmesh::JsonValue* o, const std::string& key) {
    const wqmesh::JsonValue* x = o == nullptr ? nullptr : o->find(key);
    if (x == nullptr || x->kind != Kind::number) throw missing(key);
    return x->number;
  };
  StatsFile s;
  const wqmesh::JsonValue* options = v.find("options");
  s.rho0 = number(options, "rho0");
  s.theta_deg = number(options, "theta_deg");
  for (int k = 0; k < 4; ++k) s.counts[k] = static_cast<std::size_t>(number(&v, kClassKeys[k]));
  const wqmesh::JsonValue* balls = v.find("protecting_balls");
  if (balls == nullptr || balls->kind != Kind::array) throw missing("protecting_balls");
  for (const wqmesh::JsonValue& b : balls->array) {
    const wqmesh::JsonValue* c = b.find("center");
    if (c == nullptr || c->kind != Kind::array || c->array.size() != 3) throw missing("protecting_balls[].center");
    wqmesh::ProtectingBall ball;
    for (int k = 0; k < 3; ++k) {
      if (c->array[k].kind != Kind::number) throw missing("protecting_balls[].center");
      ball.center[k] = c->array[k].number;
    }
    ball.radius = number(&b, "radius");
    s.balls.push_back(ball);
  }
  return s;
}

int run_measure(const std::vector<std::string>& args) {
  std::string path, input, stats_path;
  bool json = false;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--input") {
      if (i + 1 >= args.size() || args[i + 1].empty() || args[i + 1][0] == '-')
        return usage_error("--input needs the polyhedron file (OFF or STL) the mesh was made from");
      input = args[++i];
    } else if (a == "--stats") {
      if (i + 1 >= args.size() || args[i + 1].empty() || args[i + 1][0] == '-')
        return usage_error("--stats needs the statistics file `wqmesh mesh --stats` wrote for the mesh");
      stats_path = args[++i];
    } else if (a == "--json") {
      json = true;
    } else if (!a.empty() && a[0] == '-') {
      return usage_error("unknown option '" + a + "' for measure");
    } else if (path.empty()) {
      path = a;
    } else {
      return usage_error("measure takes one mesh file, got '" + path + "' and '" + a + "'");
    }
  }
  if (path.empty()) return usage_error("measure needs a mesh file (.mesh, .ele or .node)");

  wqmesh::TetMesh mesh;
  try {
    mesh = wqmesh::read_tet_mesh_file(path);
  } catch (const wqmesh::InputError& e) {
    std::cerr << "wqmesh: " << wqmesh::to_string(e.kind()) << ": " << e.what() << "\n";
    return 2;
  }
  double volume_input = std::nan("");
  if (!input.empty()) {
    const wqmesh::Polyhedron in = wqmesh::Polyhedron::read_file(input);
    if (!in.valid()) {
      print_input_error(input, in);
      return 2;
    }
    volume_input = wqmesh::plc_volume(in.plc());
  }
  StatsFile stats_file;
  wqmesh::MeshClasses classes;
  bool classes_match = true;
  if (!stats_path.empty()) {
    try {
      stats_file = read_stats_file(stats_path);
      // The classes of the mesh as read (before any reorientation: they do
      // not depend on the vertex order), by the mesher's own definition.
      classes = wqmesh::classify_mesh(mesh, stats_file.balls, stats_file.rho0, stats_file.theta_deg);
    } catch (const wqmesh::InputError& e) {
      std::cerr << "wqmesh: " << wqmesh::to_string(e.kind()) << ": " << e.what() << "\n";
      return 2;
    }
    const std::size_t mine[4] = {classes.skinny, classes.slivers, classes.near_small_angle, classes.violations};
    for (int k = 0; k < 4; ++k) classes_match = classes_match && mine[k] == stats_file.counts[k];
  }
  const bool flipped = wqmesh::orient_tets_by_majority(mesh);
  const wqmesh::MeshStats s = wqmesh::mesh_stats(mesh, wqmesh::mesh_quality(mesh));
  const std::size_t below3 = s.dihedral_bins[0], below5 = below3 + s.dihedral_bins[1],
                    below10 = below5 + s.dihedral_bins[2];
  const double error = std::isnan(volume_input) ? volume_input : std::fabs(s.volume - volume_input) / volume_input;

  wqmesh::JsonWriter j(false);
  j.begin_object();
  j.field("mesh", path);
  j.field("format", ends_with(path, ".mesh") ? "medit" : "tetgen");
  j.field("vertices", wqmesh::used_vertex_count(mesh));
  j.field("file_vertices", mesh.vertices.size());
  j.field("tets", mesh.tets.size());
  j.field("orientation_flipped", flipped);
  j.field("inverted", s.inverted);
  j.field("min_dihedral_deg", s.min_dihedral_deg);
  j.field("max_dihedral_deg", s.max_dihedral_deg);
  j.field("dihedral_below_3", below3);
  j.field("dihedral_below_5", below5);
  j.field("dihedral_below_10", below10);
  j.field("radius_edge_above_2_2", s.radius_edge_bins[2]);
  j.field("max_radius_edge", s.max_radius_edge);
  j.field("slivers", s.slivers);
  j.field("volume_mesh", s.volume);
  j.key("volume_input");
  if (std::isnan(volume_input))
    j.null();
  else
    j.value(volume_input);
  j.key("relative_volume_error");
  if (std::isnan(error))
    j.null();
  else
    j.value(error);
  if (!stats_path.empty()) {
    j.field("stats", stats_path);
    j.key("classes").begin_object();
    j.field("skinny", classes.skinny).field("slivers", classes.slivers);
    j.field("near_small_angle", classes.near_small_angle).field("violations", classes.violations);
    j.field("near_small_angle_share", mesh.tets.empty() ? 0.0 : double(classes.near_small_angle) / mesh.tets.size());
    j.end_object();
    j.field("classes_match_stats", classes_match);
  }
  j.end_object();
  if (json) {
    std::cout << j.str() << "\n";
    return 0;
  }
  std::cout << "mesh                   " << path << "\n"
            << "vertices               " << wqmesh::used_vertex_count(mesh) << " (" << mesh.vertices.size()
            << " in the file)\n"
            << "tets                   " << mesh.tets.size() << (flipped ? " (orientation flipped)" : "") << "\n"
            << "inverted               " << s.inverted << "\n"
            << "min dihedral (deg)     " << s.min_dihedral_deg << "\n"
            << "tets below 3/5/10 deg  " << below3 << " / " << below5 << " / " << below10 << "\n"
            << "tets with R/l > 2.2    " << s.radius_edge_bins[2] << "\n"
            << "volume                 " << s.volume << "\n";
  if (!std::isnan(error))
    std::cout << "input volume           " << volume_input << "\n"
              << "relative volume error  " << error << "\n";
  if (!stats_path.empty())
    std::cout << "skinny / slivers       " << classes.skinny << " / " << classes.slivers << "\n"
              << "near a small angle     " << classes.near_small_angle << "\n"
              << "violations             " << classes.violations << "\n"
              << "classes as in stats    " << (classes_match ? "yes" : "no") << "\n";
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
      std::cout << "wqmesh " << wqmesh::version() << "\n";
      return 0;
    }
    if (command == "check") return run_check(args);
    if (command == "mesh") return run_mesh(args);
    if (command == "measure") return run_measure(args);
    return usage_error("unknown command '" + command + "'");
  } catch (const std::bad_alloc&) {
    std::cerr << "wqmesh: out of memory: lower --max-vertices\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "wqmesh: internal error: " << e.what() << "\n";
    return 1;
  }
}
