// wqmesh: every CGAL typedef of the project lives here (private header).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/MP_Float.h>

#include "wqmesh/types.h"

namespace wqmesh::cgal {

// Kernel: exact predicates, inexact constructions.
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Vector = K::Vector_3;
using Segment = K::Segment_3;
using Triangle = K::Triangle_3;

inline Point to_cgal(const Point3& p) { return Point(p[0], p[1], p[2]); }

}  // namespace wqmesh::cgal
