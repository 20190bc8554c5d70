// wqmesh: the work meter (beyond the paper, issue 10): the steps and work
// units every phase counts, the watchdog, the progress reports.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesher/work_meter.h"

#include <cstdio>
#include <string>

namespace wqmesh::mesher {

bool WorkMeter::tick() {
  ++steps_;
  step_done();
  if (steps_ % kPollSteps == 0) next_poll_ = work_;  // a progress call at least every kPollSteps steps
  return poll(0, false);
}

bool WorkMeter::poll(std::uint64_t units, bool in_step) {
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

bool WorkMeter::refine_insertion(Rule rule, std::size_t vertices, const std::function<std::string()>& where,
                                 const std::function<double()>& spacing) {
  if (rule != Rule::rule4_split_encroached_subsegment && rule != Rule::rule5_split_encroached_subfacet) {
    boundary_run_ = 0;
    return stop_reason_.empty();
  }
  if (boundary_run_++ == 0) {
    boundary_run_start_ = vertices - 1;
    boundary_run_rule5_ = 0;
  }
  if (rule == Rule::rule5_split_encroached_subfacet) ++boundary_run_rule5_;
  const std::size_t cap = std::size_t(Caps::kBoundaryRunFactor) * boundary_run_start_ + Caps::kBoundaryRunSlack;
  if (boundary_run_ <= cap || !stop_reason_.empty()) return stop_reason_.empty();
  // Past the cap: a run that keeps its points apart (a finite refinement
  // graded by a small angle's gap) goes on, up to the backstop.
  const double ratio = spacing();
  const bool backstop = boundary_run_ > std::size_t(Caps::kBoundaryRunBackstop) * cap;
  if (!backstop && ratio >= Caps::kRunawaySpacing) return true;
  char why[160];
  if (backstop)
    std::snprintf(why, sizeof why, "%d times that", Caps::kBoundaryRunBackstop);
  else
    std::snprintf(why, sizeof why, "then a point %.2g times the smallest protecting ball's radius from its neighbours",
                  ratio);
  cap_reached();
  stop_reason_ = "stalled";
  stop_message_ = "a runaway in refine: rules 4 and 5 inserted " + std::to_string(boundary_run_) +
                  " points in a row (rule 5: " + std::to_string(boundary_run_rule5_) +
                  ", rule 4: " + std::to_string(boundary_run_ - boundary_run_rule5_) +
                  ") without a rule-6 or rule-7 insertion, more than " + std::to_string(Caps::kBoundaryRunFactor) +
                  " times the " + std::to_string(boundary_run_start_) + " vertices before them plus " +
                  std::to_string(Caps::kBoundaryRunSlack) + ", " + why + "; the last on " + where() +
                  " (an angle below 90 degrees between two input elements left without protecting balls "
                  "splits their subfacets without end): the runaway guard ended the run";
  return false;
}

RegularTriangulation::CellGraph WorkMeter::scan_cell_graph(const RegularTriangulation& tri) {
  return tri.cell_graph([this](std::size_t cells) { return poll(cells, false); });
}

void WorkMeter::report_progress() {
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
