// SPDX-License-Identifier: GPL-3.0-or-later
// wqmesh: the stable names of the closed value sets. See wqmesh/names.h.
#include "wqmesh/names.h"

namespace wqmesh {

namespace {

template <class E>
std::optional<E> from_name(const std::vector<E>& all, const std::string& name) {
  for (E e : all)
    if (name == to_string(e)) return e;
  return std::nullopt;
}

}  // namespace

const char* to_string(StopReason reason) {
  switch (reason) {
    case StopReason::done: return "";
    case StopReason::limit: return "limit";
    case StopReason::cancelled: return "cancelled";
    case StopReason::stalled: return "stalled";
  }
  return "unknown";
}

const char* to_string(MeshPhase phase) {
  switch (phase) {
    case MeshPhase::initialize: return "initialize";
    case MeshPhase::conform: return "conform";
    case MeshPhase::refine: return "refine";
    case MeshPhase::pump: return "pump";
    case MeshPhase::extract: return "extract";
    case MeshPhase::improve: return "improve";
  }
  return "unknown";
}

const char* to_string(InputErrorKind kind) { return error_kind_name(kind); }

const char* to_string(TetClass tet_class) {
  switch (tet_class) {
    case TetClass::good: return "good";
    case TetClass::skinny_near: return "skinny_near";
    case TetClass::sliver_near: return "sliver_near";
    case TetClass::violation: return "violation";
  }
  return "unknown";
}

const char* to_string(OutputFormat format) {
  switch (format) {
    case OutputFormat::medit: return "medit";
    case OutputFormat::vtu: return "vtu";
    case OutputFormat::tetgen: return "tetgen";
  }
  return "unknown";
}

const std::vector<StopReason>& all_stop_reasons() {
  static const std::vector<StopReason> all = {StopReason::done, StopReason::limit, StopReason::cancelled,
                                              StopReason::stalled};
  return all;
}

const std::vector<MeshPhase>& all_mesh_phases() {
  static const std::vector<MeshPhase> all = {MeshPhase::initialize, MeshPhase::conform, MeshPhase::refine,
                                             MeshPhase::pump,       MeshPhase::extract, MeshPhase::improve};
  return all;
}

const std::vector<InputErrorKind>& all_error_kinds() {
  // Not a second list: the enumerators of InputErrorKind (error.h) run from 0
  // without a gap, and error_kind_name (error.cpp) names each of them and
  // returns "unknown" past the last. tests/node/names.test.mjs checks the
  // enum against error.cpp's names and wasm/index.d.ts.
  static const std::vector<InputErrorKind> all = [] {
    std::vector<InputErrorKind> kinds;
    for (int i = 0; std::string(error_kind_name(static_cast<InputErrorKind>(i))) != "unknown"; ++i)
      kinds.push_back(static_cast<InputErrorKind>(i));
    return kinds;
  }();
  return all;
}

const std::vector<TetClass>& all_tet_classes() {
  static const std::vector<TetClass> all = {TetClass::good, TetClass::skinny_near, TetClass::sliver_near,
                                            TetClass::violation};
  return all;
}

const std::vector<OutputFormat>& all_output_formats() {
  static const std::vector<OutputFormat> all = {OutputFormat::medit, OutputFormat::vtu, OutputFormat::tetgen};
  return all;
}

std::optional<StopReason> stop_reason_from_string(const std::string& name) {
  return from_name(all_stop_reasons(), name);
}
std::optional<MeshPhase> mesh_phase_from_string(const std::string& name) { return from_name(all_mesh_phases(), name); }
std::optional<InputErrorKind> error_kind_from_string(const std::string& name) {
  return from_name(all_error_kinds(), name);
}
std::optional<TetClass> tet_class_from_string(const std::string& name) { return from_name(all_tet_classes(), name); }
std::optional<OutputFormat> output_format_from_string(const std::string& name) {
  return from_name(all_output_formats(), name);
}

}  // namespace wqmesh
