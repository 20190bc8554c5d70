// wqmesh: the Embind bindings of the wasm module. JavaScript sees
//   check(bytes: Uint8Array, options: object|undefined, pretty: boolean)
//     -> string (the JSON report; options: those of the table marked for check)
//   mesh(bytes: Uint8Array, options: object|undefined, progress: function|undefined)
//     -> { stats: string (JSON), vertices: Float64Array, weights: Float64Array,
//          tets: Uint32Array, boundary: Uint32Array, boundaryFacet: Int32Array,
//          tetClass: Uint8Array, minDihedral: Float64Array, radiusEdge: Float64Array
//          (unweighted R/l), orthoradiusEdge: Float64Array (with the weights),
//          protectingBalls: Float64Array, protectingBallIsVertex: Uint8Array }
//        or { error: { kind, message } }
//   writeMesh(result: object, format: "medit"|"vtu"|"tetgen", bytes: boolean)
//     -> string | Uint8Array (tetgen: { node, ele, face, edge }) or { error }
//   optionTable() -> string (JSON, wqmesh::options_json)
//   memoryStats() -> { heapBytes, liveBytes }
//   version() -> string
// wasm/index.mjs wraps them. Options are read and checked with the core's
// table (wqmesh/options.h), the same as the native command line's.
//
// Memory: the module grows its memory up to 4 GB (-sMAXIMUM_MEMORY); past
// that, malloc returns null (-sABORTING_MALLOC=0) instead of aborting. The
// replaced global operator new counts the live bytes of every C++ allocation
// against options.maxMemoryBytes, and mesh() turns running short of either
// into a "limit" error; the run unwinds, its memory is freed and the module
// stays usable. One care: CGAL's Triangulation_data_structure_3 fills a
// static map while it inserts a point into a small hole and clears it at the
// end, so an exception thrown from an allocation inside that insertion would
// leave the map dirty and break every later insertion of the module. Hence,
// while the mesher runs, nothing throws from an allocation: crossing the cap
// is only recorded, a failed malloc first gives back a ballast kept for it,
// and the progress callback, which the mesher calls between insertions, ends
// the run by throwing there (StopForMemory). Elsewhere (reading the input,
// the output arrays) an allocation beyond the cap or the memory throws
// std::bad_alloc at once.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <emscripten/bind.h>
#include <emscripten/heap.h>
#include <emscripten/val.h>

#include <malloc.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <new>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

// The facade (reading, options, meshing, statistics); the writers of
// writeMesh() take the arrays of a JS result, so they call output.h directly.
#include "wqmesh/wqmesh.h"

// ---- Counted allocations -------------------------------------------------------

namespace {

std::size_t live_bytes = 0;                             // usable bytes of live operator-new blocks
std::size_t peak_bytes = 0;                             // the largest live_bytes since reset
std::size_t memory_cap = static_cast<std::size_t>(-1);  // maxMemoryBytes during mesh()
bool cap_reached = false;                               // an allocation went beyond the cap
bool memory_short = false;                              // the mesher must stop: cap crossed or ballast used
bool deferred = false;                                  // the mesher runs: record shortages, do not refuse
void* ballast = nullptr;                                // raw malloc, released when malloc fails in the mesher

void* raw_alloc(std::size_t n, std::size_t align) {
  void* p = nullptr;
  if (align > alignof(std::max_align_t)) {
    if (posix_memalign(&p, align, n) != 0) p = nullptr;
  } else {
    p = std::malloc(n);
  }
  return p;
}

// An allocation within the cap; nullptr when refused or out of memory.
void* counted_alloc(std::size_t n, std::size_t align) {
  if (n == 0) n = 1;
  if (n > memory_cap || live_bytes > memory_cap - n) {
    cap_reached = true;
    if (!deferred) return nullptr;
    memory_short = true;
  }
  void* p = raw_alloc(n, align);
  if (!p && deferred && ballast) {
    std::free(ballast);
    ballast = nullptr;
    memory_short = true;
    p = raw_alloc(n, align);
  }
  if (p) {
    live_bytes += malloc_usable_size(p);
    if (live_bytes > peak_bytes) peak_bytes = live_bytes;
  }
  return p;
}

void counted_free(void* p) noexcept {
  if (!p) return;
  const std::size_t n = malloc_usable_size(p);
  live_bytes = n < live_bytes ? live_bytes - n : 0;
  std::free(p);
}

void* counted_new(std::size_t n, std::size_t align) {
  void* p = counted_alloc(n, align);
  if (!p) throw std::bad_alloc();
  return p;
}

}  // namespace

void* operator new(std::size_t n) { return counted_new(n, 0); }
void* operator new[](std::size_t n) { return counted_new(n, 0); }
void* operator new(std::size_t n, std::align_val_t a) { return counted_new(n, static_cast<std::size_t>(a)); }
void* operator new[](std::size_t n, std::align_val_t a) { return counted_new(n, static_cast<std::size_t>(a)); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept { return counted_alloc(n, 0); }
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept { return counted_alloc(n, 0); }
void* operator new(std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
  return counted_alloc(n, static_cast<std::size_t>(a));
}
void* operator new[](std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
  return counted_alloc(n, static_cast<std::size_t>(a));
}
void operator delete(void* p) noexcept { counted_free(p); }
void operator delete[](void* p) noexcept { counted_free(p); }
void operator delete(void* p, std::size_t) noexcept { counted_free(p); }
void operator delete[](void* p, std::size_t) noexcept { counted_free(p); }
void operator delete(void* p, std::align_val_t) noexcept { counted_free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { counted_free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { counted_free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { counted_free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { counted_free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { counted_free(p); }
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept { counted_free(p); }
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept { counted_free(p); }

namespace {

/// The default of options.maxMemoryBytes (wqmesh::RunOptions, the option
/// table) is 3 GiB, below the 4 GB ceiling so that the last allocations of a
/// run (the output arrays) still fit.
constexpr double kMaxMemory = 4.0 * 1024 * 1024 * 1024;  // -sMAXIMUM_MEMORY

/// The ballast given back when malloc fails while the mesher runs: far more
/// than the mesher allocates between two progress calls (256 insertions).
constexpr std::size_t kBallast = 16 << 20;

// Applies a cap to the allocations of one call and lifts it on the way out
// (normal return or unwinding), before any error message is built.
class MemoryCap {
 public:
  explicit MemoryCap(double bytes) {
    cap_reached = memory_short = deferred = false;
    peak_bytes = live_bytes;
    if (bytes < kMaxMemory) memory_cap = static_cast<std::size_t>(bytes);
  }
  ~MemoryCap() { memory_cap = static_cast<std::size_t>(-1); }
  MemoryCap(const MemoryCap&) = delete;
  MemoryCap& operator=(const MemoryCap&) = delete;
};

// While it lives, allocations do not throw (see the note at the top): the
// mesher runs, with a ballast to give back.
class DeferShortage {
 public:
  DeferShortage() {
    ballast = std::malloc(kBallast);
    deferred = true;
  }
  ~DeferShortage() {
    deferred = false;
    std::free(ballast);
    ballast = nullptr;
  }
  DeferShortage(const DeferShortage&) = delete;
  DeferShortage& operator=(const DeferShortage&) = delete;
};

// Thrown by the progress callback to end a run that is short of memory.
struct StopForMemory {};

using emscripten::val;

// Reads the JS options object into `out` with the core's option table: every
// key must name an option (of check, when `for_check`), booleans must be
// booleans, numbers numbers, and every value within the table's range. An
// undefined value keeps the default. Returns "" or the error message.
std::string read_options(const val& options, bool for_check, wqmesh::Options& out) {
  if (options.isUndefined() || options.isNull()) return "";
  if (options.typeOf().as<std::string>() != "object" || val::global("Array").call<bool>("isArray", options))
    return "the options must be an object, e.g. { rho: 2.2 }";
  const val keys = val::global("Object").call<val>("keys", options);
  const unsigned n = keys["length"].as<unsigned>();
  for (unsigned i = 0; i < n; ++i) {
    const std::string name = keys[i].as<std::string>();
    const val v = options[name];
    if (v.isUndefined()) continue;
    const wqmesh::OptionSpec* spec = wqmesh::find_option(name);
    if (spec == nullptr || (for_check && !spec->check)) {
      std::string message = "unknown option '" + name + "' for " + (for_check ? "check" : "mesh") +
                            "; the known options are: " + wqmesh::option_names(for_check);
      if (name == "signal" || name == "onProgress")
        message += " (signal and onProgress go in the third argument, { onProgress, signal })";
      return message;
    }
    double value = 0;
    if (spec->type == wqmesh::OptionType::boolean) {
      if (!v.isTrue() && !v.isFalse()) return std::string(spec->name) + " must be true or false";
      value = v.isTrue() ? 1 : 0;
    } else {
      if (!v.isNumber()) return std::string(spec->name) + " must be a number, got a " + v.typeOf().as<std::string>();
      value = v.as<double>();
    }
    const std::string error = out.try_set(*spec, value, spec->name);
    if (!error.empty()) return error;
  }
  return "";
}

// The length of a Uint8Array, as a double (a size_t would wrap beyond 4 GB).
double byte_length(const val& bytes) { return bytes["length"].as<double>(); }

std::string too_large_message(double length) {
  const wqmesh::InputLimits limits;
  return "the input has " + std::to_string(static_cast<unsigned long long>(length)) + " bytes, beyond the limit of " +
         std::to_string(limits.max_bytes);
}

// A report for a failure that escaped check_polyhedron (which should catch
// everything about the input itself), so that JS always gets a report.
std::string failure_json(const char* kind, const std::string& message, bool pretty) {
  wqmesh::JsonWriter json(pretty);
  json.begin_object();
  json.field("valid", false);
  json.key("error");
  json.begin_object();
  json.field("kind", kind);
  json.field("message", message);
  json.end_object();
  json.end_object();
  return json.str();
}

// The bytes of a Uint8Array in a string of the heap: one bulk copy through a
// view on the string's buffer (nothing allocates between making the view and
// using it).
void copy_bytes(const val& bytes, std::string& data) {
  data.resize(static_cast<std::size_t>(byte_length(bytes)));
  if (!data.empty())
    val(emscripten::typed_memory_view(data.size(), reinterpret_cast<unsigned char*>(&data[0])))
        .call<void>("set", bytes);
}

// Copies the bytes of a Uint8Array into the wasm heap, then reads, validates
// and analyses them. Never throws to JS.
std::string check(const val& bytes, const val& options, bool pretty) {
  if (!bytes.instanceof (val::global("Uint8Array")))
    return failure_json("io", "check() expects the file's bytes as a Uint8Array", pretty);
  wqmesh::Options o;
  const std::string option_error = read_options(options, true, o);
  if (!option_error.empty()) return failure_json("options", option_error, pretty);
  const double length = byte_length(bytes);
  if (length > static_cast<double>(wqmesh::InputLimits().max_bytes))
    return failure_json("too_large", too_large_message(length), pretty);
  std::string data;
  try {
    copy_bytes(bytes, data);
  } catch (const std::bad_alloc&) {
    return failure_json("too_large", "the input does not fit in memory", pretty);
  }
  try {
    return wqmesh::Polyhedron::read_bytes(data.data(), data.size(), o).report_json(pretty);
  } catch (const std::bad_alloc&) {
    return failure_json("too_large", "the input does not fit in memory", pretty);
  } catch (const std::exception& e) {
    return failure_json("internal", std::string("internal error: ") + e.what(), pretty);
  } catch (...) {
    return failure_json("internal", "internal error: unknown exception", pretty);
  }
}

// A copy of an array as a JS typed array (a live view of the heap would die
// when memory grows).
template <class T>
val copy_out(const T* data, std::size_t n) {
  return val(emscripten::typed_memory_view(n, data)).call<val>("slice");
}

val error_value(const std::string& kind, const std::string& message) {
  val out = val::object();
  val error = val::object();
  error.set("kind", kind);
  error.set("message", message);
  out.set("error", error);
  return out;
}

// The "limit" error of a run short of memory. The cap is lifted by then
// (MemoryCap's destructor ran) and the run's memory is freed.
val memory_error(double max_memory, const char* phase, std::size_t vertices) {
  const std::string where = std::string(" (in ") + phase + ", at " + std::to_string(vertices) + " vertices)";
  if (cap_reached)
    return error_value(
        "limit",
        "the run needs more than maxMemoryBytes = " + std::to_string(static_cast<unsigned long long>(max_memory)) +
            " bytes of wasm memory" + where + ": lower maxVertices or raise maxMemoryBytes (at most 4294967296)");
  return error_value("limit",
                     "the run does not fit in the wasm memory (4 GB at most, less where the browser "
                     "gives less)" +
                         where + ": lower maxVertices or maxMemoryBytes");
}

// Meshes the polyhedron in `bytes` with WQMESH. `options` holds options of the
// table (wqmesh/options.h); `progress`, when a function, is called as
// progress(phase, fraction, vertices, steps) after a bounded amount of work
// and cancels the run when it returns false. Never throws: failures come back
// as { error: { kind, message } }.
val mesh(const val& bytes, const val& options, const val& progress) {
  if (!bytes.instanceof (val::global("Uint8Array")))
    return error_value("io", "mesh() expects the file's bytes as a Uint8Array");
  wqmesh::Options run;
  const std::string option_error = read_options(options, false, run);
  if (!option_error.empty()) return error_value("options", option_error);
  const double length = byte_length(bytes);
  if (length > static_cast<double>(wqmesh::InputLimits().max_bytes))
    return error_value("too_large", too_large_message(length));
  const double max_memory = run.max_memory_bytes();
  const bool js_progress = progress.typeOf().as<std::string>() == "function";

  // Where the run was when memory ran out, for the message.
  const char* phase = "read";
  std::size_t vertices = 0;
  try {
    const MemoryCap cap(max_memory);
    std::string data;
    copy_bytes(bytes, data);
    // time_s as the command line's: from the bytes read to the mesh made
    // (validation and analysis included): Result::time_s.
    const wqmesh::Polyhedron input = wqmesh::Polyhedron::read_bytes(data.data(), data.size(), run);
    if (!input.valid()) {
      // check_polyhedron calls a std::bad_alloc too_large: the cap's, here.
      if (cap_reached && input.error_kind() == wqmesh::InputErrorKind::too_large) throw std::bad_alloc();
      return error_value(input.check_result().error_kind, input.error_message());
    }
    std::string().swap(data);
    phase = "initialize";
    // Always a callback: it records where the run is, ends it when memory is
    // short (the mesher calls it between insertions) and calls JS when asked.
    const wqmesh::MeshProgressCallback callback = [&](const wqmesh::MeshProgress& p) {
      phase = wqmesh::to_string(p.phase);
      vertices = p.vertices;
      if (memory_short) throw StopForMemory();
      if (!js_progress) return true;
      const val r =
          progress(std::string(phase), p.fraction, static_cast<double>(p.vertices), static_cast<double>(p.steps));
      return !r.isFalse();
    };
    std::optional<wqmesh::Result> run_result;
    {
      const DeferShortage defer;
      run_result.emplace(wqmesh::mesh(input, run, callback));
    }
    const wqmesh::MeshResult& r = run_result->raw();
    if (memory_short) {  // after the last call of the callback (the extraction)
      phase = "extract";
      vertices = r.all_vertices;
      throw StopForMemory();
    }
    phase = "output";
    vertices = r.all_vertices;
    val out = val::object();
    // peak_memory_mb: the peak of the live C++ allocations of this call.
    out.set("stats", run_result->stats_json(peak_bytes / 1048576.0, false));
    // The vertices, tets and boundary triangles are copied straight from the
    // mesh's arrays (contiguous std::arrays; indices are >= 0, so their int
    // bits are the uint32 values), without a flattened copy in the heap.
    static_assert(sizeof(wqmesh::Point3) == 3 * sizeof(double), "Point3 is 3 contiguous doubles");
    static_assert(sizeof(r.mesh.tets[0]) == 4 * sizeof(std::uint32_t), "a tet is 4 contiguous ints");
    static_assert(sizeof(r.mesh.boundary[0]) == 3 * sizeof(std::uint32_t), "a triangle is 3 contiguous ints");
    const double* xyz = r.mesh.vertices.empty() ? nullptr : r.mesh.vertices[0].data();
    const auto* tets = reinterpret_cast<const std::uint32_t*>(r.mesh.tets.data());
    const auto* tris = reinterpret_cast<const std::uint32_t*>(r.mesh.boundary.data());
    std::vector<std::uint8_t> classes, ball_is_vertex;
    std::vector<double> angles, radius_edge, balls;
    const std::vector<double>& orthoradius_edge = r.orthoradius_edge;
    for (wqmesh::TetClass c : r.tet_class) classes.push_back(static_cast<std::uint8_t>(c));
    for (const wqmesh::TetQuality& q : r.quality) {
      angles.push_back(q.min_dihedral_deg);
      radius_edge.push_back(q.radius_edge);
    }
    for (const wqmesh::ProtectingBall& b : r.protecting_balls) {
      balls.insert(balls.end(), {b.center[0], b.center[1], b.center[2], b.radius});
      ball_is_vertex.push_back(b.vertex_ball ? 1 : 0);
    }
    std::vector<double> weights = r.mesh.weights;
    weights.resize(r.mesh.vertices.size(), 0.0);
    out.set("vertices", copy_out(xyz, 3 * r.mesh.vertices.size()));
    out.set("weights", copy_out(weights.data(), weights.size()));
    out.set("tets", copy_out(tets, 4 * r.mesh.tets.size()));
    out.set("boundary", copy_out(tris, 3 * r.mesh.boundary.size()));
    out.set("boundaryFacet", copy_out(r.mesh.boundary_facet.data(), r.mesh.boundary_facet.size()));
    out.set("tetClass", copy_out(classes.data(), classes.size()));
    out.set("minDihedral", copy_out(angles.data(), angles.size()));
    out.set("orthoradiusEdge", copy_out(orthoradius_edge.data(), orthoradius_edge.size()));
    out.set("radiusEdge", copy_out(radius_edge.data(), radius_edge.size()));
    out.set("protectingBalls", copy_out(balls.data(), balls.size()));
    out.set("protectingBallIsVertex", copy_out(ball_is_vertex.data(), ball_is_vertex.size()));
    return out;
  } catch (const StopForMemory&) {
    return memory_error(max_memory, phase, vertices);
  } catch (const std::bad_alloc&) {
    return memory_error(max_memory, phase, vertices);
  } catch (const std::exception& e) {
    return error_value("internal", std::string("internal error: ") + e.what());
  } catch (...) {
    return error_value("internal", "internal error: unknown exception");
  }
}

// Thrown while reading a result object for the writers: not a mesh result.
struct BadResult {
  std::string message;
};

// result[name] as a vector, which must be a typed array of type `js_type`
// whose length is a multiple of `width`.
template <class T>
std::vector<T> typed_array(const val& result, const char* name, const char* js_type, std::size_t width) {
  const val a = result[name];
  if (!a.instanceof (val::global(js_type))) throw BadResult{std::string("result.") + name + " must be a " + js_type};
  std::vector<T> v(a["length"].as<std::size_t>());
  if (v.size() % width != 0)
    throw BadResult{std::string("result.") + name + " has " + std::to_string(v.size()) +
                    " entries, not a multiple of " + std::to_string(width)};
  if (!v.empty()) val(emscripten::typed_memory_view(v.size(), v.data())).call<void>("set", a);
  return v;
}

// The mesh of a result object of mesh() (vertices, weights, tets, boundary,
// boundaryFacet), its indices checked, and its classes (tetClass).
wqmesh::TetMesh mesh_of(const val& result, std::vector<int>& classes) {
  if (result.typeOf().as<std::string>() != "object" || result.isNull())
    throw BadResult{"the writers take the result of mesh()"};
  wqmesh::TetMesh m;
  const std::vector<double> xyz = typed_array<double>(result, "vertices", "Float64Array", 3);
  const std::size_t n = xyz.size() / 3;
  for (std::size_t i = 0; i < n; ++i) m.vertices.push_back({{xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]}});
  m.weights = typed_array<double>(result, "weights", "Float64Array", 1);
  if (m.weights.size() != n)
    throw BadResult{"result.weights has " + std::to_string(m.weights.size()) + " entries for " + std::to_string(n) +
                    " vertices"};
  const std::vector<std::uint32_t> tets = typed_array<std::uint32_t>(result, "tets", "Uint32Array", 4);
  const std::vector<std::uint32_t> tris = typed_array<std::uint32_t>(result, "boundary", "Uint32Array", 3);
  for (std::size_t i = 0; i < tets.size(); ++i)
    if (tets[i] >= n) throw BadResult{"result.tets[" + std::to_string(i) + "] is not a vertex index"};
  for (std::size_t i = 0; i < tris.size(); ++i)
    if (tris[i] >= n) throw BadResult{"result.boundary[" + std::to_string(i) + "] is not a vertex index"};
  for (std::size_t i = 0; i < tets.size(); i += 4)
    m.tets.push_back({{int(tets[i]), int(tets[i + 1]), int(tets[i + 2]), int(tets[i + 3])}});
  for (std::size_t i = 0; i < tris.size(); i += 3)
    m.boundary.push_back({{int(tris[i]), int(tris[i + 1]), int(tris[i + 2])}});
  m.boundary_facet = typed_array<int>(result, "boundaryFacet", "Int32Array", 1);
  if (m.boundary_facet.size() != m.boundary.size())
    throw BadResult{"result.boundaryFacet has " + std::to_string(m.boundary_facet.size()) + " entries for " +
                    std::to_string(m.boundary.size()) + " boundary triangles"};
  const std::vector<std::uint8_t> c = typed_array<std::uint8_t>(result, "tetClass", "Uint8Array", 1);
  if (c.size() != m.tets.size())
    throw BadResult{"result.tetClass has " + std::to_string(c.size()) + " entries for " +
                    std::to_string(m.tets.size()) + " tets"};
  classes.assign(c.begin(), c.end());
  return m;
}

val text_value(const std::string& s, bool bytes) {
  if (bytes) return copy_out(reinterpret_cast<const std::uint8_t*>(s.data()), s.size());
  return val(s);
}

// Writes a result of mesh() with the core's writers (the native command
// line's): "medit" (.mesh), "vtu" (with wqmesh::write_vtu's cell and point
// data) or "tetgen" ({ node, ele, face, edge }). Strings, or UTF-8 bytes
// (Uint8Array) when `bytes`. Never throws: { error: { kind: "type" or
// "limit" or "internal", message } }.
val write_mesh(const val& result, const std::string& format, bool bytes) {
  try {
    std::vector<int> classes;
    const wqmesh::TetMesh m = mesh_of(result, classes);
    if (format == "medit") {
      std::ostringstream out;
      wqmesh::write_medit(out, m);
      return text_value(out.str(), bytes);
    }
    if (format == "vtu") {
      std::ostringstream out;
      wqmesh::TetLabels labels;
      labels.tet_class = classes;
      wqmesh::write_vtu(out, m, wqmesh::mesh_quality(m, {}, false), &labels);
      return text_value(out.str(), bytes);
    }
    if (format == "tetgen") {
      std::ostringstream node, ele, face, edge;
      wqmesh::write_tetgen(node, ele, face, edge, m);
      val out = val::object();
      out.set("node", text_value(node.str(), bytes));
      out.set("ele", text_value(ele.str(), bytes));
      out.set("face", text_value(face.str(), bytes));
      out.set("edge", text_value(edge.str(), bytes));
      return out;
    }
    return error_value("type", "unknown format '" + format + "' (medit, vtu or tetgen)");
  } catch (const BadResult& e) {
    return error_value("type", e.message);
  } catch (const std::bad_alloc&) {
    return error_value("limit", "the output does not fit in the wasm memory");
  } catch (const std::exception& e) {
    return error_value("internal", std::string("internal error: ") + e.what());
  }
}

std::string option_table_json() { return wqmesh::options_json(); }

// The wasm memory (which only grows) and the bytes C++ holds now.
val memory_stats() {
  val out = val::object();
  out.set("heapBytes", static_cast<double>(emscripten_get_heap_size()));
  out.set("liveBytes", static_cast<double>(live_bytes));
  return out;
}

std::string version() { return wqmesh::version(); }

}  // namespace

EMSCRIPTEN_BINDINGS(wqmesh) {
  emscripten::function("check", &check);
  emscripten::function("mesh", &mesh);
  emscripten::function("writeMesh", &write_mesh);
  emscripten::function("optionTable", &option_table_json);
  emscripten::function("memoryStats", &memory_stats);
  emscripten::function("version", &version);
}
