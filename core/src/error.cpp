// SPDX-License-Identifier: GPL-3.0-or-later
// wqmesh: stable names of input error kinds (see error.h).
#include "wqmesh/error.h"

namespace wqmesh {

const char* error_kind_name(InputErrorKind kind) {
  switch (kind) {
    case InputErrorKind::io: return "io";
    case InputErrorKind::empty: return "empty";
    case InputErrorKind::syntax: return "syntax";
    case InputErrorKind::truncated: return "truncated";
    case InputErrorKind::too_large: return "too_large";
    case InputErrorKind::non_finite: return "non_finite";
    case InputErrorKind::bad_index: return "bad_index";
    case InputErrorKind::too_few_faces: return "too_few_faces";
    case InputErrorKind::degenerate_face: return "degenerate_face";
    case InputErrorKind::duplicate_face: return "duplicate_face";
    case InputErrorKind::open_boundary: return "open_boundary";
    case InputErrorKind::non_manifold_edge: return "non_manifold_edge";
    case InputErrorKind::non_manifold_vertex: return "non_manifold_vertex";
    case InputErrorKind::not_orientable: return "not_orientable";
    case InputErrorKind::self_intersection: return "self_intersection";
    case InputErrorKind::zero_volume: return "zero_volume";
    case InputErrorKind::out_of_range: return "out_of_range";
  }
  return "unknown";
}

}  // namespace wqmesh
