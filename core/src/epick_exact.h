// wqmesh: the exact ring type of CGAL's Epick under wasm (private; force-
// included before every source of the wasm build, see CMakeLists.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Epick's ring predicates fall back to exact_ring.h's ExactRing instead of
// MP_Float when their interval filter fails (natively they use GMP's Mpzf,
// and this header is never included). This specialization of
// Exact_kernel_selector has to be seen before Epick is defined in every
// translation unit of one program (else two definitions of the same
// filtered predicates differ): the wasm build force-includes it.
#pragma once

#include <CGAL/Exact_kernel_selector.h>
#include <CGAL/Simple_cartesian.h>

#include "exact_ring.h"

namespace CGAL {

class Epick;

// Epick's exact kernels: the field type as CGAL selects it (unchanged), the
// ring type ExactRing instead of MP_Float.
template <>
struct Exact_kernel_selector<Type_equality_wrapper<Cartesian_base_no_ref_count<double, Epick>, Epick>, Cartesian_tag> {
  typedef Type_equality_wrapper<Cartesian_base_no_ref_count<double, Epick>, Epick> CK;
  typedef internal::Exact_field_selector<double>::Type Exact_nt;
  typedef wqmesh::exact::ExactRing Exact_rt;
  typedef Simple_cartesian<Exact_nt> Exact_kernel;
  typedef Simple_cartesian<Exact_rt> Exact_kernel_rt;
  typedef Cartesian_converter<CK, Exact_kernel> C2E;
  typedef Cartesian_converter<CK, Exact_kernel_rt> C2E_rt;
  typedef Cartesian_converter<Exact_kernel, CK> E2C;
  typedef Cartesian_converter<Exact_kernel_rt, CK> E2C_rt;
};

}  // namespace CGAL
