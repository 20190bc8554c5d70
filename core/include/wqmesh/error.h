// wqmesh: typed errors and warnings for bad input.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace wqmesh {

/// What is wrong with an input. Every kind has a stable snake_case name
/// (error_kind_name) used in JSON, on the command line and in the wasm API.
enum class InputErrorKind {
  io,                   ///< the file cannot be opened or read
  empty,                ///< no bytes, no points or no faces
  syntax,               ///< garbled: a token that is not what the format wants
  truncated,            ///< the data ends before the header's counts are met
  too_large,            ///< beyond the limits set in InputLimits
  non_finite,           ///< a NaN or infinite coordinate
  bad_index,            ///< a face refers to a vertex that does not exist
  too_few_faces,        ///< fewer than 4 faces cannot bound a polyhedron
  degenerate_face,      ///< a face with zero area or a repeated vertex
  duplicate_face,       ///< two faces on the same vertex set
  open_boundary,        ///< an edge with only one incident face
  non_manifold_edge,    ///< an edge with more than two incident faces
  non_manifold_vertex,  ///< the faces around a vertex form more than one fan
  not_orientable,       ///< no consistent orientation exists
  self_intersection,    ///< two faces cross or overlap (exact predicates)
  zero_volume,          ///< the enclosed volume is zero
  out_of_range,         ///< coordinates, extent, bounding box or volume beyond
                        ///< what double precision holds once scaled (scaling.h)
};

/// The stable name of an error kind, e.g. "open_boundary".
const char* error_kind_name(InputErrorKind kind);

/// An input that cannot be meshed. `what()` names the defect and where it is
/// (file line, face, edge or vertex indices, coordinates).
class InputError : public std::runtime_error {
 public:
  InputError(InputErrorKind kind, const std::string& message) : std::runtime_error(message), kind_(kind) {}
  InputErrorKind kind() const { return kind_; }

 private:
  InputErrorKind kind_;
};

/// Warnings collected while reading and repairing an input (orientation fixed,
/// non-planar polygon split, ...). Each is one human-readable sentence.
using Warnings = std::vector<std::string>;

}  // namespace wqmesh
