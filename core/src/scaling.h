// wqmesh: scale-safe geometry (beyond the paper, which works in exact reals).
// The analysis and the mesher work on the input normalised: translated by a
// per-axis centre c and scaled by a power of two, x' = (x - c) 2^-E with E =
// ilogb of the largest absolute translated coordinate, so that every
// coordinate they see is at most 2 in absolute value and no square, product
// or circumcenter formula can overflow, whatever the input's units. Both
// steps are exact for every input point (checked: a coordinate whose
// difference to c would round keeps c = 0 on its axis, one that would lose
// bits as a subnormal is refused), so the output, mapped back as x' 2^E + c,
// holds the input points at their exact coordinates; only the points the
// mesher constructs round there. Lengths scale by 2^E, weights (squared
// radii) by 2^2E, volumes by 2^3E; angles and ratios do not change.
// c is 0 (no translation) unless the input lies far from the origin against
// its extent (normalisation() says when): a model near the origin keeps its
// mesh bit for bit; one far from it is meshed as at the origin.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include "wqmesh/analysis.h"
#include "wqmesh/types.h"

namespace wqmesh {

/// ilogb of the largest absolute coordinate of `plc` (0 for no vertices or
/// all zeros).
int normalisation_exponent(const PLC& plc);

/// The map from the input's coordinates to the ones the analysis and the
/// mesher work in: x' = (x - centre) 2^-exponent, per axis.
struct Normalisation {
  Point3 centre{{0, 0, 0}};  ///< c, per axis; 0 on an axis not translated
  int exponent = 0;          ///< E
  bool translated() const { return centre[0] != 0 || centre[1] != 0 || centre[2] != 0; }
};

/// A translation must gain at least this many bits (the exponent of the
/// largest absolute coordinate, so of the unit in the last place of the
/// points the mesher constructs, drops by that much) to be made.
constexpr int kTranslationGainBits = 3;

/// The normalisation of `plc`. Beyond the paper: the centre on each axis is
/// the middle of the input's box on it, rounded to a multiple of the unit in
/// the last place of that axis's largest absolute coordinate, kept only when
/// x - c is exact for every coordinate x on the axis (else 0 there); the
/// centre is used only when it lowers the exponent by kTranslationGainBits
/// or more (the input lies far from the origin against its extent: its
/// box's centre 3 to 7 half extents or more away, as the exponents are whole
/// numbers), else it is 0 and E is
/// normalisation_exponent(plc): inputs near the origin keep the meshes they
/// had before the translation existed. Pure function of the coordinates:
/// analyze and mesh_polyhedron find the same map.
Normalisation normalisation(const PLC& plc);

/// `plc` with every point x mapped to (x - c) 2^-E (exact when `n` is
/// normalisation(plc) and check_representable passed; normals do not change).
PLC normalised_plc(const PLC& plc, const Normalisation& n);

/// The point p of the normalised coordinates in the input's: p 2^E + c,
/// exact for the input points, rounded once (the addition of c) for others.
Point3 input_point(const Point3& p, const Normalisation& n);

/// The analysis of the normalised input in the input's units: f(u) times
/// 2^E, the input box and B times 2^E plus c.
void analysis_to_input(Analysis& a, const Normalisation& n);

/// The inverse of analysis_to_input, for the mesher: f(u) and the input box
/// come back exactly (the box's corners are input coordinates); B, whose
/// corners analysis_to_input rounds when it adds c, is made again from the
/// input box (grown_box with a.box_margin), as analyze made it.
void analysis_to_normalised(Analysis& a, const Normalisation& n);

/// The box of the vertices of `plc` (which has at least one): the input box
/// of section 2.
Box vertex_box(const PLC& plc);

/// B (section 2): the box `input_box` grown on every side by `box_margin`
/// times its largest extent (analyze's formula).
Box grown_box(const Box& input_box, double box_margin);

/// Throws InputError(out_of_range) when `plc` (valid otherwise) cannot be
/// worked on in normalised coordinates (`n`, its normalisation) and reported
/// back in its own: a coordinate that translated and scaled by 2^-E is not
/// exact (a subnormal losing bits), an
/// extent (hi - lo along an axis) or a corner of the bounding box B (the
/// input box grown by `box_margin` times its largest extent) beyond the
/// largest double, or an enclosed volume that is not a normal double (above
/// about 1.8e308 or below about 2.2e-308). Messages name the vertex and
/// coordinate, the axis, or the volume (as a decimal power when it is not a
/// double).
void check_representable(const PLC& plc, const Normalisation& n, double box_margin);

/// The volume enclosed by `plc` as v * 2^exponent (v computed on the input
/// scaled by 2^-E, so it neither overflows nor underflows).
double plc_volume_scaled(const PLC& plc, int& exponent);

/// v * 2^e as a decimal string such as "8e+924", valid beyond double range.
std::string decimal_power(double v, int e);

}  // namespace wqmesh
