// wqmesh: the check report (see wqmesh/report.h).
// SPDX-License-Identifier: GPL-3.0-or-later
#include "wqmesh/report.h"

#include <new>

#include "wqmesh/json.h"

namespace wqmesh {

CheckResult check_polyhedron(const char* data, std::size_t size, const InputLimits& limits,
                             const AnalysisOptions& options) {
  CheckResult result;
  try {
    const PolygonSoup soup = read_polyhedron(data, size, limits);
    result.format = soup.format;
    result.plc = build_plc(soup, result.warnings, &result.merge);
    result.analysis = analyze(result.plc, options);
    result.valid = true;
  } catch (const InputError& e) {
    result.error_kind = error_kind_name(e.kind());
    result.error = e.what();
  } catch (const std::bad_alloc&) {
    result.error_kind = error_kind_name(InputErrorKind::too_large);
    result.error = "the input needs more memory than is available";
  }
  return result;
}

namespace {

void write_merge(JsonWriter& j, const MergeReport& m) {
  j.begin_object();
  j.field("points_read", m.points_read).field("vertices", m.vertices);
  j.field("faces_read", m.faces_read).field("facets", m.facets);
  j.field("edges_before", m.edges_before).field("edges", m.edges);
  j.field("vertices_removed", m.vertices_removed);
  j.field("faces_split", m.faces_split).field("faces_flipped", m.faces_flipped);
  j.end_object();
}

void write_plc_counts(JsonWriter& j, const PLC& plc) {
  std::size_t holes = 0;
  for (const PlcFacet& f : plc.facets) holes += f.loops.empty() ? 0 : f.loops.size() - 1;
  j.begin_object();
  j.field("vertices", plc.vertices.size()).field("edges", plc.edges.size());
  j.field("facets", plc.facets.size()).field("holes", holes);
}

void write_point(JsonWriter& j, const Point3& p) { j.begin_array().value(p[0]).value(p[1]).value(p[2]).end_array(); }

// The coordinates of the sharp elements (paper, section 2), so that a reader
// (the web page) can mark them without a PLC of its own: "sharp_vertex_points"
// in the order of analysis.sharp_vertices, "sharp_edge_points" (the two
// endpoints, a then b) in the order of analysis.sharp_edges. Beyond the paper:
// report output only.
void write_sharp_points(JsonWriter& j, const PLC& plc, const Analysis& a) {
  j.key("sharp_vertex_points").begin_array();
  for (int u : a.sharp_vertices) write_point(j, plc.vertices[u]);
  j.end_array();
  j.key("sharp_edge_points").begin_array();
  for (int e : a.sharp_edges) {
    j.begin_array();
    write_point(j, plc.vertices[plc.edges[e].a]);
    write_point(j, plc.vertices[plc.edges[e].b]);
    j.end_array();
  }
  j.end_array();
}

}  // namespace

std::string check_json(const CheckResult& r, bool pretty) {
  JsonWriter j(pretty);
  j.begin_object();
  j.field("valid", r.valid);
  if (!r.format.empty()) j.field("format", r.format);
  j.key("warnings").begin_array();
  for (const std::string& w : r.warnings) j.value(w);
  j.end_array();
  if (!r.valid) {
    j.key("error").begin_object();
    j.field("kind", r.error_kind).field("message", r.error);
    j.end_object();
  } else {
    j.key("merge");
    write_merge(j, r.merge);
    j.key("plc");
    write_plc_counts(j, r.plc);
    write_sharp_points(j, r.plc, r.analysis);
    j.end_object();
    j.key("analysis");
    write_analysis_json(j, r.analysis);
  }
  j.end_object();
  return j.str();
}

}  // namespace wqmesh
