// wqmesh: the statistics of a meshing run as JSON (see wqmesh/mesher.h).
// SPDX-License-Identifier: GPL-3.0-or-later
#include <algorithm>
#include <array>
#include <cmath>

#include "scaling.h"
#include "wqmesh/json.h"
#include "wqmesh/mesher.h"
#include "wqmesh/output.h"

namespace wqmesh {

double plc_volume(const PLC& plc) {
  // Computed scaled (scaling.h): infinite or zero only when the volume is
  // beyond double range, which analyze refuses (out_of_range).
  int e = 0;
  const double v = plc_volume_scaled(plc, e);
  return std::ldexp(v, e);
}

std::string mesh_stats_json(const PLC& plc, const MeshResult& r, const MeshOptions& options, double time_s,
                            double peak_memory_mb, bool pretty) {
  const MeshStats s = mesh_stats(r.mesh, r.quality);
  JsonWriter j(pretty);
  j.begin_object();
  j.field("input_points", r.input_points);
  j.field("sharp_elements", r.sharp_elements);
  j.field("points_inserted", r.points_inserted);
  j.field("vertices", r.mesh.vertices.size());
  j.field("tets", r.mesh.tets.size());
  // Every statistic and class on the mesh as written, unweighted (classify.h
  // in core/src/mesher: recountable from the mesh file and protecting_balls).
  j.field("min_dihedral_deg", r.mesh.tets.empty() ? 0.0 : s.min_dihedral_deg);
  j.field("max_radius_edge", s.max_radius_edge);
  write_quality_bins(j, s);
  j.field("slivers", r.slivers);
  j.field("skinny", r.skinny);
  j.field("near_small_angle", r.near_small_angle);
  j.field("violations", r.violations);
  j.field("near_small_angle_share", r.mesh.tets.empty() ? 0.0 : double(r.near_small_angle) / r.mesh.tets.size());
  // The weighted view (the paper's own measure for a pumped mesh): the
  // orthoradius-edge ratio with PUMP's weights, in Table 2's bins; no class
  // depends on it.
  std::array<std::size_t, 4> ortho_bins{};  // below 0.6, then Table 2's three
  double max_ortho = 0;
  for (double rho : r.orthoradius_edge) {
    ++ortho_bins[radius_edge_bin(rho) + 1];
    max_ortho = std::max(max_ortho, rho);
  }
  j.key("orthoradius_edge_bins").begin_object();
  j.field("<0.6", ortho_bins[0]).field("0.6-1.4", ortho_bins[1]).field("1.4-2.2", ortho_bins[2]);
  j.field(">2.2", ortho_bins[3]);
  j.end_object();
  j.field("max_orthoradius_edge", max_ortho);
  j.field("orthoradius_skinny", r.orthoradius_skinny);
  j.field("slivers_before_pump", r.slivers_before_pump);
  j.field("pumped_vertices", r.pumped_vertices);
  j.field("volume_input", plc_volume(plc));
  j.field("volume_mesh", s.volume);
  j.field("conforming", r.conforming);
  j.field("stopped", r.stopped);
  if (!r.stop_message.empty()) j.field("stop_message", r.stop_message);
  j.field("time_s", time_s);
  if (peak_memory_mb >= 0) j.field("peak_memory_mb", peak_memory_mb);
  j.field("all_vertices", r.all_vertices);
  j.field("caps_reached", r.caps_reached);
  if (r.delaunay_floor_s > 0) {
    j.field("delaunay_floor_s", r.delaunay_floor_s);
    j.field("ratio_to_delaunay", time_s / r.delaunay_floor_s);
  }
  j.field("tets_per_second", time_s > 0 ? double(r.mesh.tets.size()) / time_s : 0.0);
  j.key("options").begin_object();
  j.field("rho0", options.rho0).field("theta_deg", options.theta_deg).field("pump", options.pump);
  j.field("box_margin", options.box_margin).field("max_vertices", options.max_vertices);
  j.field("max_size", options.max_size).field("improve", options.improve).field("polish", options.polish);
  j.end_object();
  // Beyond the paper: the improvement phase (MeshOptions::improve).
  const ImproveStats& im = r.improve;
  j.key("improve").begin_object();
  j.field("ran", im.ran).field("passes", im.passes);
  j.field("flips23", im.flips23).field("flips32", im.flips32).field("flips44", im.flips44);
  j.field("flips22", im.flips22).field("edge_removals", im.edge_removals);
  j.field("multi_face_removals", im.multi_face_removals).field("polished", im.polished);
  j.field("smoothed", im.smoothed).field("inserted", im.inserted).field("contractions", im.contractions);
  j.field("slid", im.slid).field("inserted_on_boundary", im.inserted_on_boundary);
  j.field("min_dihedral_before", im.min_dihedral_before).field("min_dihedral_after", im.min_dihedral_after);
  j.field("slivers_before", im.slivers_before).field("skinny_before", im.skinny_before);
  j.field("near_small_angle_before", im.near_small_angle_before).field("violations_before", im.violations_before);
  j.field("tets_before", im.tets_before);
  j.field("near_small_angle_share_before",
          im.tets_before == 0 ? 0.0 : double(im.near_small_angle_before) / im.tets_before);
  j.end_object();
  j.key("rule_points").begin_array();
  for (std::size_t n : r.rule_points) j.value(n);
  j.end_array();
  j.key("phases").begin_array();
  for (const PhaseStats& p : r.phases) {
    j.begin_object();
    j.field("name", p.name).field("time_s", p.time_s).field("points_inserted", p.points_inserted);
    j.end_object();
  }
  j.end_array();
  // Every violation (skinny or sliver tet not near a small input angle), up
  // to kListedViolations of them (all are counted in "violations"), so that
  // they can be looked at and counted by others.
  constexpr std::size_t kListedViolations = 1000;
  j.key("violation_tets").begin_array();
  std::size_t listed = 0;
  for (std::size_t i = 0; i < r.tet_class.size() && listed < kListedViolations; ++i) {
    if (r.tet_class[i] != TetClass::violation) continue;
    ++listed;
    const auto& t = r.mesh.tets[i];
    const TetQuality& q = r.quality[i];
    j.begin_object();
    j.field("tet", i);
    j.key("vertices").begin_array().value(t[0]).value(t[1]).value(t[2]).value(t[3]).end_array();
    j.field("kind", q.radius_edge > options.rho0 ? "skinny" : "sliver");
    j.field("min_dihedral_deg", q.min_dihedral_deg).field("radius_edge", q.radius_edge);
    if (i < r.orthoradius_edge.size()) j.field("orthoradius_edge", r.orthoradius_edge[i]);
    j.end_object();
  }
  j.end_array();
  j.key("protecting_balls").begin_array();
  for (const ProtectingBall& b : r.protecting_balls) {
    j.begin_object();
    j.key("center").begin_array().value(b.center[0]).value(b.center[1]).value(b.center[2]).end_array();
    j.field("radius", b.radius).field("vertex_ball", b.vertex_ball);
    j.end_object();
  }
  j.end_array();
  j.end_object();
  return j.str();
}

}  // namespace wqmesh
