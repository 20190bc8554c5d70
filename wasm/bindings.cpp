// wqmesh: the Embind bindings of the wasm module. JavaScript sees
//   check(bytes: Uint8Array, pretty: boolean) -> string (the JSON report)
//   mesh(bytes: Uint8Array, options: object, progress: function|undefined)
//     -> { stats: string (JSON), vertices: Float64Array, weights: Float64Array,
//          tets: Uint32Array, boundary: Uint32Array, boundaryFacet: Int32Array,
//          tetClass: Uint8Array, minDihedral: Float64Array }
//        or { error: { kind, message } }
//   version() -> string
// wasm/index.mjs wraps them (loadWqmesh) and parses the report.
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
#include <emscripten/val.h>

#include <malloc.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <new>
#include <string>
#include <vector>

#include "wqmesh/input.h"
#include "wqmesh/json.h"
#include "wqmesh/mesher.h"
#include "wqmesh/report.h"

#ifndef WQMESH_VERSION
#define WQMESH_VERSION "0.0.0"
#endif

// ---- Counted allocations -------------------------------------------------------

namespace {

std::size_t live_bytes = 0;                   // usable bytes of live operator-new blocks
std::size_t peak_bytes = 0;                   // the largest live_bytes since reset
std::size_t memory_cap = static_cast<std::size_t>(-1);  // maxMemoryBytes during mesh()
bool cap_reached = false;    // an allocation went beyond the cap
bool memory_short = false;   // the mesher must stop: cap crossed or ballast used
bool deferred = false;       // the mesher runs: record shortages, do not refuse
void* ballast = nullptr;     // raw malloc, released when malloc fails in the mesher

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

/// The default of options.maxMemoryBytes: 3 GiB, below the 4 GB ceiling so
/// that the last allocations of a run (the output arrays) still fit.
constexpr double kDefaultMaxMemory = 3.0 * 1024 * 1024 * 1024;
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

// The length of a Uint8Array, as a double (a size_t would wrap beyond 4 GB).
double byte_length(const emscripten::val& bytes) { return bytes["length"].as<double>(); }

std::string too_large_message(double length) {
  const wqmesh::InputLimits limits;
  return "the input has " + std::to_string(static_cast<unsigned long long>(length)) +
         " bytes, beyond the limit of " + std::to_string(limits.max_bytes);
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

// Copies the bytes of a Uint8Array into the wasm
// heap, then reads, validates and analyses them. Never throws to JS.
std::string check(const emscripten::val& bytes, bool pretty) {
  if (!bytes.instanceof(emscripten::val::global("Uint8Array"))) {
    return failure_json("io", "check() expects the file's bytes as a Uint8Array", pretty);
  }
  const double length = byte_length(bytes);
  if (length > static_cast<double>(wqmesh::InputLimits().max_bytes))
    return failure_json("too_large", too_large_message(length), pretty);
  std::string data;
  try {
    // One bulk copy: a Uint8Array view on the string's buffer, filled by set().
    // Nothing allocates wasm memory between making the view and using it.
    data.resize(static_cast<std::size_t>(length));
    if (!data.empty()) {
      emscripten::val view(emscripten::typed_memory_view(
          data.size(), reinterpret_cast<unsigned char*>(&data[0])));
      view.call<void>("set", bytes);
    }
  } catch (const std::bad_alloc&) {
    return failure_json("too_large", "the input does not fit in memory", pretty);
  }
  try {
    const wqmesh::CheckResult result = wqmesh::check_polyhedron(data.data(), data.size());
    return wqmesh::check_json(result, pretty);
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
emscripten::val copy_out(const T* data, std::size_t n) {
  return emscripten::val(emscripten::typed_memory_view(n, data)).call<emscripten::val>("slice");
}

emscripten::val error_value(const std::string& kind, const std::string& message) {
  emscripten::val out = emscripten::val::object();
  emscripten::val error = emscripten::val::object();
  error.set("kind", kind);
  error.set("message", message);
  out.set("error", error);
  return out;
}

// The "limit" error of a run short of memory. The cap is lifted by then
// (MemoryCap's destructor ran) and the run's memory is freed.
emscripten::val memory_error(double max_memory, const char* phase, std::size_t vertices) {
  const std::string where = std::string(" (in ") + phase + ", at " + std::to_string(vertices) + " vertices)";
  if (cap_reached)
    return error_value("limit", "the run needs more than maxMemoryBytes = " +
                                    std::to_string(static_cast<unsigned long long>(max_memory)) +
                                    " bytes of wasm memory" + where +
                                    ": lower maxVertices or raise maxMemoryBytes (at most 4294967296)");
  return error_value("limit", "the run does not fit in the wasm memory (4 GB at most, less where the browser "
                              "gives less)" + where + ": lower maxVertices or maxMemoryBytes");
}

// Meshes the polyhedron in `bytes` with WQMESH. `options` may hold rho,
// sliverAngle, pump, maxVertices, maxSize, boxMargin, maxMemoryBytes;
// `progress`, when a function, is called as progress(phase, fraction,
// vertices) after a bounded amount of work and cancels the run when it returns
// false. Never throws: failures come back as { error: { kind, message } }.
emscripten::val mesh(const emscripten::val& bytes, const emscripten::val& options, const emscripten::val& progress) {
  if (!bytes.instanceof(emscripten::val::global("Uint8Array")))
    return error_value("io", "mesh() expects the file's bytes as a Uint8Array");
  const double length = byte_length(bytes);
  if (length > static_cast<double>(wqmesh::InputLimits().max_bytes))
    return error_value("too_large", too_large_message(length));
  wqmesh::MeshOptions o;
  wqmesh::AnalysisOptions ao;
  double max_vertices = static_cast<double>(o.max_vertices);
  double max_memory = kDefaultMaxMemory;
  const bool has_options = !options.isUndefined() && !options.isNull();
  auto number = [&](const char* key, double& target) {
    if (!has_options) return;
    const emscripten::val v = options[key];
    if (v.isNumber()) target = v.as<double>();
  };
  number("rho", o.rho0);
  number("sliverAngle", o.theta_deg);
  number("maxSize", o.max_size);
  number("boxMargin", o.box_margin);
  number("maxVertices", max_vertices);
  number("maxMemoryBytes", max_memory);
  // The ranges of the command line; NaN and infinities fail every test.
  if (!(o.rho0 >= 1 && o.rho0 <= 1e6) || !(o.theta_deg >= 0 && o.theta_deg <= 90) ||
      !(o.max_size >= 0 && o.max_size <= 1e300) || !(o.box_margin >= 1e-3 && o.box_margin <= 1e3) ||
      !(max_vertices >= 8 && max_vertices <= 1e9) || !(max_memory >= 65536 && max_memory <= kMaxMemory))
    return error_value("options", "options out of range: 1 <= rho <= 1e6, 0 <= sliverAngle <= 90, "
                                  "0 <= maxSize (finite), 0.001 <= boxMargin <= 1000, 8 <= maxVertices <= 1e9, "
                                  "65536 <= maxMemoryBytes <= 4294967296");
  o.max_vertices = static_cast<std::size_t>(max_vertices);
  ao.box_margin = o.box_margin;
  if (has_options && options["pump"].isFalse()) o.pump = false;
  const bool js_progress = progress.typeOf().as<std::string>() == "function";

  // Where the run was when memory ran out, for the message.
  const char* phase = "read";
  std::size_t vertices = 0;
  try {
    const MemoryCap cap(max_memory);
    std::string data(static_cast<std::size_t>(length), '\0');
    if (!data.empty())
      emscripten::val(emscripten::typed_memory_view(data.size(), reinterpret_cast<unsigned char*>(&data[0])))
          .call<void>("set", bytes);
    const wqmesh::CheckResult input = wqmesh::check_polyhedron(data.data(), data.size(), {}, ao);
    if (!input.valid) {
      // check_polyhedron calls a std::bad_alloc too_large: the cap's, here.
      if (cap_reached && input.error_kind == "too_large") throw std::bad_alloc();
      return error_value(input.error_kind, input.error);
    }
    std::string().swap(data);
    phase = "initialize";
    // Always a callback: it records where the run is, ends it when memory is
    // short (the mesher calls it between insertions) and calls JS when asked.
    const wqmesh::ProgressCallback callback = [&](const wqmesh::Progress& p) {
      phase = p.phase == "conform" ? "conform" : p.phase == "refine" ? "refine" : p.phase == "pump" ? "pump"
            : p.phase == "extract" ? "extract" : "initialize";
      vertices = p.vertices;
      if (memory_short) throw StopForMemory();
      if (!js_progress) return true;
      const emscripten::val r = progress(p.phase, p.fraction, static_cast<double>(p.vertices));
      return !r.isFalse();
    };
    const double t0 = emscripten::val::global("Date").call<double>("now");
    wqmesh::MeshResult r;
    {
      const DeferShortage defer;
      r = wqmesh::mesh_polyhedron(input.plc, input.analysis, o, callback);
    }
    if (memory_short) {  // after the last call of the callback (the extraction)
      phase = "extract";
      vertices = r.all_vertices;
      throw StopForMemory();
    }
    const double seconds = (emscripten::val::global("Date").call<double>("now") - t0) / 1000;
    phase = "output";
    vertices = r.all_vertices;
    emscripten::val out = emscripten::val::object();
    // peak_memory_mb: the peak of the live C++ allocations of this call.
    out.set("stats", wqmesh::mesh_stats_json(input.plc, r, o, seconds, peak_bytes / 1048576.0, false));
    std::vector<double> xyz;
    for (const auto& p : r.mesh.vertices) xyz.insert(xyz.end(), p.begin(), p.end());
    std::vector<std::uint32_t> tets, tris;
    for (const auto& t : r.mesh.tets) tets.insert(tets.end(), t.begin(), t.end());
    for (const auto& t : r.mesh.boundary) tris.insert(tris.end(), t.begin(), t.end());
    std::vector<std::uint8_t> classes;
    std::vector<double> angles;
    for (wqmesh::TetClass c : r.tet_class) classes.push_back(static_cast<std::uint8_t>(c));
    for (const wqmesh::TetQuality& q : r.quality) angles.push_back(q.min_dihedral_deg);
    std::vector<double> weights = r.mesh.weights;
    weights.resize(r.mesh.vertices.size(), 0.0);
    out.set("vertices", copy_out(xyz.data(), xyz.size()));
    out.set("weights", copy_out(weights.data(), weights.size()));
    out.set("tets", copy_out(tets.data(), tets.size()));
    out.set("boundary", copy_out(tris.data(), tris.size()));
    out.set("boundaryFacet", copy_out(r.mesh.boundary_facet.data(), r.mesh.boundary_facet.size()));
    out.set("tetClass", copy_out(classes.data(), classes.size()));
    out.set("minDihedral", copy_out(angles.data(), angles.size()));
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

std::string version() { return WQMESH_VERSION; }

}  // namespace

EMSCRIPTEN_BINDINGS(wqmesh) {
  emscripten::function("check", &check);
  emscripten::function("mesh", &mesh);
  emscripten::function("version", &version);
}
