// wqmesh: the Embind bindings of the wasm module. JavaScript sees
//   check(bytes: Uint8Array, pretty: boolean) -> string (the JSON report)
//   mesh(bytes: Uint8Array, options: object, progress: function|undefined)
//     -> { stats: string (JSON), vertices: Float64Array, weights: Float64Array,
//          tets: Uint32Array, boundary: Uint32Array, boundaryFacet: Int32Array,
//          tetClass: Uint8Array, minDihedral: Float64Array }
//        or { error: { kind, message } }
//   version() -> string
// wasm/index.mjs wraps them (loadWqmesh) and parses the report.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <exception>
#include <new>
#include <cstdint>
#include <string>
#include <vector>

#include "wqmesh/json.h"
#include "wqmesh/mesher.h"
#include "wqmesh/report.h"

#ifndef WQMESH_VERSION
#define WQMESH_VERSION "0.0.0"
#endif

namespace {

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
  std::string data;
  try {
    // One bulk copy: a Uint8Array view on the string's buffer, filled by set().
    // Nothing allocates wasm memory between making the view and using it.
    const unsigned length = bytes["length"].as<unsigned>();
    data.resize(length);
    if (length > 0) {
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

// Meshes the polyhedron in `bytes` with WQMESH. `options` may hold rho,
// sliverAngle, pump, maxVertices, maxSize, boxMargin; `progress`, when a
// function, is called as progress(phase, fraction, vertices) after a bounded
// amount of work and cancels the run when it returns false. Never throws.
emscripten::val mesh(const emscripten::val& bytes, const emscripten::val& options, const emscripten::val& progress) {
  if (!bytes.instanceof(emscripten::val::global("Uint8Array")))
    return error_value("io", "mesh() expects the file's bytes as a Uint8Array");
  try {
    std::string data(bytes["length"].as<unsigned>(), '\0');
    if (!data.empty())
      emscripten::val(emscripten::typed_memory_view(data.size(), reinterpret_cast<unsigned char*>(&data[0])))
          .call<void>("set", bytes);
    wqmesh::MeshOptions o;
    wqmesh::AnalysisOptions ao;
    auto number = [&](const char* key, double& target) {
      if (options.isUndefined() || options.isNull()) return;
      const emscripten::val v = options[key];
      if (v.isNumber()) target = v.as<double>();
    };
    number("rho", o.rho0);
    number("sliverAngle", o.theta_deg);
    number("maxSize", o.max_size);
    number("boxMargin", o.box_margin);
    double max_vertices = static_cast<double>(o.max_vertices);
    number("maxVertices", max_vertices);
    if (!(o.rho0 >= 1) || !(o.theta_deg >= 0 && o.theta_deg <= 90) || !(o.max_size >= 0) ||
        !(o.box_margin > 0) || !(max_vertices >= 8))
      return error_value("options", "options out of range: rho >= 1, 0 <= sliverAngle <= 90, maxSize >= 0, "
                                    "boxMargin > 0, maxVertices >= 8");
    o.max_vertices = static_cast<std::size_t>(max_vertices);
    ao.box_margin = o.box_margin;
    if (!options.isUndefined() && !options.isNull() && options["pump"].isFalse()) o.pump = false;
    const wqmesh::CheckResult input = wqmesh::check_polyhedron(data.data(), data.size(), {}, ao);
    if (!input.valid) return error_value(input.error_kind, input.error);
    wqmesh::ProgressCallback callback;
    if (progress.typeOf().as<std::string>() == "function")
      callback = [&](const wqmesh::Progress& p) {
        const emscripten::val r = progress(p.phase, p.fraction, static_cast<double>(p.vertices));
        return !r.isFalse();
      };
    const double t0 = emscripten::val::global("Date").call<double>("now");
    const wqmesh::MeshResult r = wqmesh::mesh_polyhedron(input.plc, input.analysis, o, callback);
    const double seconds = (emscripten::val::global("Date").call<double>("now") - t0) / 1000;
    emscripten::val out = emscripten::val::object();
    out.set("stats", wqmesh::mesh_stats_json(input.plc, r, o, seconds, -1, false));
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
  } catch (const std::bad_alloc&) {
    return error_value("limit", "the mesh does not fit in the wasm memory (4 GB): lower maxVertices");
  } catch (const std::exception& e) {
    return error_value("internal", std::string("internal error: ") + e.what());
  }
}

std::string version() { return WQMESH_VERSION; }

}  // namespace

EMSCRIPTEN_BINDINGS(wqmesh) {
  emscripten::function("check", &check);
  emscripten::function("mesh", &mesh);
  emscripten::function("version", &version);
}
