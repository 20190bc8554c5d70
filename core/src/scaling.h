// wqmesh: scale-safe geometry (beyond the paper, which works in exact reals).
// The analysis and the mesher work on the input scaled by a power of two,
// 2^-E with E = ilogb of the largest absolute input coordinate, so that every
// coordinate they see is at most 2 in absolute value and no square, product
// or circumcenter formula can overflow, whatever the input's units. Scaling by
// a power of two is exact for every input point (checked: a coordinate that
// would lose bits as a subnormal is refused), and there is no translation
// (which would round), so the output, scaled back by 2^E, holds the input
// points at their exact coordinates. Lengths scale by 2^E, weights (squared
// radii) by 2^2E, volumes by 2^3E; angles and ratios do not change.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include "wqmesh/analysis.h"
#include "wqmesh/types.h"

namespace wqmesh {

/// E for `plc`: ilogb of its largest absolute coordinate (0 for no vertices
/// or all zeros). Pure function of the coordinates: analyze and
/// mesh_polyhedron find the same E.
int normalisation_exponent(const PLC& plc);

/// Throws InputError(out_of_range) when `plc` (valid otherwise) cannot be
/// worked on in scaled coordinates and reported back in its own: a
/// coordinate that scaled by 2^-E is not exact (a subnormal losing bits), an
/// extent (hi - lo along an axis) or a corner of the bounding box B (the
/// input box grown by `box_margin` times its largest extent) beyond the
/// largest double, or an enclosed volume that is not a normal double (above
/// about 1.8e308 or below about 2.2e-308). Messages name the vertex and
/// coordinate, the axis, or the volume (as a decimal power when it is not a
/// double).
void check_representable(const PLC& plc, int exponent, double box_margin);

/// `plc` with every coordinate multiplied by 2^s (exact when s = -E and
/// check_representable passed; normals do not change).
PLC scaled_plc(const PLC& plc, int s);

/// Multiplies the lengths of an analysis by 2^s: f(u), the input box and B.
void scale_analysis(Analysis& a, int s);

/// The volume enclosed by `plc` as v * 2^exponent (v computed on the input
/// scaled by 2^-E, so it neither overflows nor underflows).
double plc_volume_scaled(const PLC& plc, int& exponent);

/// v * 2^e as a decimal string such as "8e+924", valid beyond double range.
std::string decimal_power(double v, int e);

}  // namespace wqmesh
