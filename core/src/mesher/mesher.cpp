// wqmesh: the Mesher's own bookkeeping: its construction, the steps and work
// units every phase counts (the stops of issue 10), progress reports, traces.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesher/mesher.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace wqmesh::mesher {

Mesher::Mesher(const Domain& domain, const MeshOptions& options, const ProgressCallback& progress)
    : dom_(domain), opt_(options), progress_(progress), balls_(domain.box) {
  trace_ = std::getenv("WQMESH_TRACE") != nullptr;
  facet_dt_.resize(domain.p.facets.size());
  // Each facet's planar triangulation projects along the largest component of
  // its normal and tests circles in the plane's metric (see PlanarDelaunay):
  // points collinear in 3D stay collinear there, and no point is hidden.
  for (std::size_t f = 0; f < domain.p.facets.size(); ++f) facet_dt_[f].set_plane(domain.p.facets[f].normal);
  vertex_sectors_.assign(domain.p.vertices.size(), {});
}

void Mesher::trace(const Insertion& ins, Rule rule, int id) const {
  double len = 0;
  if (ins.has_segment) {
    const int a = int(ins.split_segment >> 32), b = int(ins.split_segment & 0xFFFFFFFFu);
    len = std::sqrt(dist2(tri_.point(a), tri_.point(b)));
  }
  static const char* kOn[] = {"vertex", "edge", "facet", "free"};
  std::fprintf(stderr, "wqmesh trace: rule %d -> %d on %s %d at (%.17g, %.17g, %.17g) split %s length %g\n",
               rule_number(rule), id, kOn[int(ins.on)], ins.element, ins.p[0], ins.p[1], ins.p[2],
               ins.has_segment ? (ins.sector >= 0 ? "shield" : "subsegment") : "-", len);
}

bool Mesher::tick() {
  ++steps_;
  step_done();
  if (steps_ % kPollSteps == 0) next_poll_ = work_;  // a progress call at least every kPollSteps steps
  return poll(0, false);
}

bool Mesher::poll(std::uint64_t units, bool in_step) {
  work_ += units;
  if (in_step) {
    step_work_ += units;
    if (step_work_ > opt_.stall_work && stop_reason_.empty()) {
      static const char* kNames[] = {"initialize", "conform", "refine", "pump", "done"};
      stop_reason_ = "stalled";
      stop_message_ = std::string("a step of ") + kNames[int(phase_)] + " (step " + std::to_string(steps_ + 1) +
                      ", at " + std::to_string(verts_.size()) + " vertices) did more than " +
                      std::to_string(opt_.stall_work) +
                      " units of work without finishing: the stuck-step watchdog ended the run";
    }
  }
  if (work_ >= next_poll_) {
    next_poll_ = work_ + kPollWork;
    report_progress();
  }
  return stop_reason_.empty();
}

RegularTriangulation::CellGraph Mesher::scan_cell_graph() {
  return tri_.cell_graph([this](std::size_t cells) { return poll(cells, false); });
}

void Mesher::report_progress() {
  if (progress_) {
    Progress p;
    p.phase = phase_ == Phase::conform  ? "conform"
              : phase_ == Phase::refine ? "refine"
              : phase_ == Phase::pump   ? "pump"
                                        : "initialize";
    p.vertices = verts_.size();
    p.steps = steps_;
    // Refinement has no known end; the fraction grows with the vertex count
    // towards the limit (an estimate), inside the phase's share of the run.
    const double base = phase_ == Phase::conform ? 0.05 : phase_ == Phase::refine ? 0.3 : 0.8;
    const double share = phase_ == Phase::conform ? 0.25 : phase_ == Phase::refine ? 0.5 : 0.15;
    p.fraction = base + share * (1 - 1 / (1 + double(steps_) / 20000));
    if (!progress_(p) && stop_reason_.empty()) stop_reason_ = "cancelled";
  }
}

}  // namespace wqmesh::mesher
