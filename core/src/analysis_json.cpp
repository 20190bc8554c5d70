// SPDX-License-Identifier: GPL-3.0-or-later
// wqmesh: the input analysis (paper, section 2) as JSON; the layout is
// described at write_analysis_json in wqmesh/analysis.h.
#include <cstddef>

#include "wqmesh/analysis.h"
#include "wqmesh/json.h"

namespace wqmesh {
namespace {

void write_box(JsonWriter& json, const Box& b) {
  json.begin_object();
  json.key("lo").begin_array();
  for (double x : b.lo) json.value(x);
  json.end_array();
  json.key("hi").begin_array();
  for (double x : b.hi) json.value(x);
  json.end_array();
  json.end_object();
}

}  // namespace

void write_analysis_json(JsonWriter& json, const Analysis& a) {
  std::size_t acute_ee = 0, acute_ef = 0;
  for (const auto& x : a.edge_edge) acute_ee += x.acute;
  for (const auto& x : a.edge_facet) acute_ef += x.acute;
  json.begin_object();
  json.key("counts").begin_object();
  json.field("sharp_vertices", a.sharp_vertices.size());
  json.field("sharp_edges", a.sharp_edges.size());
  json.field("edge_edge_angles", a.edge_edge.size());
  json.field("acute_edge_edge_angles", acute_ee);
  json.field("edge_facet_angles", a.edge_facet.size());
  json.field("acute_edge_facet_angles", acute_ef);
  json.field("dihedral_angles", a.dihedral.size());
  json.end_object();
  json.field("phi_m_degrees", a.phi_m_degrees);
  json.key("sharp_vertices").begin_array();
  for (int v : a.sharp_vertices) json.value(v);
  json.end_array();
  json.key("sharp_edges").begin_array();
  for (int e : a.sharp_edges) json.value(e);
  json.end_array();
  json.key("lfs").begin_array();
  for (std::size_t i = 0; i < a.sharp_vertices.size() && i < a.lfs.size(); ++i) {
    json.begin_object();
    json.field("vertex", a.sharp_vertices[i]);
    json.field("f", a.lfs[i]);
    json.end_object();
  }
  json.end_array();
  json.key("dihedral").begin_array();
  for (const auto& d : a.dihedral) {
    json.begin_object();
    json.field("edge", d.edge);
    json.field("internal", d.internal_degrees);
    json.field("external", d.external_degrees);
    json.field("sharp", d.sharp);
    json.end_object();
  }
  json.end_array();
  // Objects like the other lists, as wasm/index.d.ts describes them (the
  // lists are long: fandisk gives 60k edge-edge and 94k edge-facet angles,
  // 14 MB of compact JSON in all).
  json.key("edge_edge").begin_array();
  for (const auto& x : a.edge_edge) {
    json.begin_object();
    json.field("vertex", x.vertex).field("edge1", x.edge1).field("edge2", x.edge2);
    json.field("degrees", x.degrees).field("acute", x.acute);
    json.end_object();
  }
  json.end_array();
  json.key("edge_facet").begin_array();
  for (const auto& x : a.edge_facet) {
    json.begin_object();
    json.field("vertex", x.vertex).field("edge", x.edge).field("facet", x.facet);
    json.field("degrees", x.degrees).field("acute", x.acute);
    json.end_object();
  }
  json.end_array();
  json.key("input_box");
  write_box(json, a.input_box);
  json.key("bounding_box");
  write_box(json, a.bounding_box);
  json.field("box_margin", a.box_margin);
  json.end_object();
}

}  // namespace wqmesh
