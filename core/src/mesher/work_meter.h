// wqmesh: the work meter of a run (private; beyond the paper, issue 10): the
// steps and work units every phase counts, the stuck-step watchdog, the
// progress calls, and why the run stopped. Each phase is handed the one
// meter of the run; it reads the vertex count of V for its reports.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "mesher/rules.h"
#include "mesher/subcomplex.h"
#include "triangulation.h"
#include "wqmesh/mesher.h"

namespace wqmesh::mesher {

enum class Phase { initialize, conform, refine, pump, done };

class WorkMeter {
 public:
  /// `vertices`: V, whose size the progress calls and the watchdog report.
  WorkMeter(const MeshOptions& options, const ProgressCallback& progress, const std::vector<MVertex>& vertices)
      : opt_(options), progress_(progress), verts_(vertices) {}

  /// The phase now running (named in the progress calls and the watchdog's
  /// message; the queues' upkeep depends on it).
  void set_phase(Phase p) { phase_ = p; }
  Phase phase() const { return phase_; }

  bool stopped() const { return !stop_reason_.empty(); }
  void cancel() { stop("cancelled"); }
  /// Stops the run for `reason` ("limit", "cancelled", "stalled") unless it
  /// was stopped already.
  void stop(const char* reason) {
    if (stop_reason_.empty()) stop_reason_ = reason;
  }
  const std::string& stop_reason() const { return stop_reason_; }
  /// Why the run stopped in words, when the mesher knows (for "stalled").
  const std::string& stop_message() const { return stop_message_; }

  // Work is counted in units: one per queue element looked at, per cell of
  // an inserted vertex's star, per feature or walk of an insertion's upkeep,
  // per cell of a PUMP weight change, per element of a whole-mesh scan. Every
  // unit is bounded by the size of a star (see the loop bounds in
  // triangulation.cpp). poll() counts units, and at least every kPollWork
  // units (and every kPollSteps steps) calls the progress callback, so that a
  // cancel, the vertex limit or the memory cap (the wasm callback) takes
  // effect within kPollWork units whatever the mesher does.
  static constexpr std::uint64_t kPollWork = 256;
  static constexpr std::size_t kPollSteps = 256;
  /// Counts `units` of work; `in_step`: work of the current step (a step is
  /// one insertion with its upkeep, one queue element, one rule-3 or rule-7
  /// candidate, one PUMP vertex), which the watchdog bounds: a step past
  /// MeshOptions::stall_work units ends the run with stopped = "stalled".
  /// Whole-mesh scans count with in_step = false (they are bounded by the
  /// mesh's size). Returns false once the run must stop. Never throws, unless
  /// the progress callback does (the wasm memory cap): it is never called
  /// from inside a CGAL insertion.
  bool poll(std::uint64_t units, bool in_step = true);
  /// INITIALIZE's insertions are steps too: polls, and says whether the
  /// run was cancelled or stalled (INITIALIZE then ends early; the vertex
  /// limit never stops it: a limit below its count is refused beforehand).
  bool interrupted() {
    step_done();
    poll(1);
    return !stop_reason_.empty() && stop_reason_ != "limit";
  }
  /// A step ended: the watchdog starts again.
  void step_done() { step_work_ = 0; }
  /// A step (an insertion by a rule, a PUMP vertex) is done: counts it, ends
  /// the watchdog's step, polls (a progress call at least every kPollSteps
  /// steps). False once the run must stop.
  bool tick();
  std::uint64_t work() const { return work_; }
  /// tri.cell_graph() polling every kPollWork cells (a phase's scan); empty
  /// if the run stops meanwhile.
  RegularTriangulation::CellGraph scan_cell_graph(const RegularTriangulation& tri);

  /// A loop cap was reached (Caps, Pump::kLabelRounds, Pump::kCriticalSteps,
  /// the ray-parity budget of extract.cpp): counted in caps_reached.
  void cap_reached() { ++caps_reached_; }
  std::size_t caps_reached() const { return caps_reached_; }

  /// Beyond the paper: the runaway guard of REFINE. Takes every insertion of
  /// REFINE (its rule; `vertices`: V's size after it). Rules 4 and 5 extend
  /// the current run of boundary insertions, rules 6 and 7 end it. Once a run
  /// is longer than Caps::kBoundaryRunFactor times V's size before its first
  /// insertion, plus Caps::kBoundaryRunSlack (the cap), each further
  /// insertion of it asks `spacing()` (called only then: the inserted
  /// vertex's distance to its nearest neighbour over the smallest protecting
  /// ball's radius); the first below Caps::kRunawaySpacing, or the run
  /// reaching Caps::kBoundaryRunBackstop times the cap, stops the run with
  /// stopped = "stalled", counts a cap in caps_reached, and sets a stop
  /// message naming the rules, the counts and `where()` (the last
  /// insertion's input feature, called only then). Returns false once the
  /// run must stop.
  bool refine_insertion(Rule rule, std::size_t vertices, const std::function<std::string()>& where,
                        const std::function<double()>& spacing);

 private:
  void report_progress();

  const MeshOptions& opt_;
  const ProgressCallback& progress_;
  const std::vector<MVertex>& verts_;
  Phase phase_ = Phase::initialize;
  std::size_t steps_ = 0, caps_reached_ = 0;
  std::uint64_t work_ = 0, next_poll_ = kPollWork, step_work_ = 0;
  /// The current run of rule 4-5 insertions in REFINE (refine_insertion):
  /// its length, V's size before it, and its rule-5 share.
  std::size_t boundary_run_ = 0, boundary_run_start_ = 0, boundary_run_rule5_ = 0;
  std::string stop_reason_, stop_message_;
};

}  // namespace wqmesh::mesher
