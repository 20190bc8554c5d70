// wqmesh: exact signs of polynomial expressions in input doubles (private).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Contract: `expr` is a generic callable `expr(NT)` that evaluates a
// polynomial in the input coordinates using only +, - and * over the number
// type NT (doubles are converted with NT(x)). exact_sign first evaluates it in
// interval arithmetic and, when the interval contains 0, again with CGAL's
// MP_Float, which is exact for +, - and * on doubles. The result is the sign of
// the exact value, the same on every platform (native and wasm).
#pragma once

#include <CGAL/Interval_nt.h>
#include <CGAL/MP_Float.h>

#include "wqmesh/types.h"

namespace wqmesh::exact {

template <class Expr>
int sign(const Expr& expr) {
  {
    CGAL::Protect_FPU_rounding<true> guard;
    const CGAL::Interval_nt<false> v = expr(CGAL::Interval_nt<false>(0));
    const CGAL::Uncertain<CGAL::Sign> s = CGAL::sign(v);
    if (CGAL::is_certain(s)) return static_cast<int>(CGAL::get_certain(s));
  }
  const CGAL::MP_Float v = expr(CGAL::MP_Float(0));
  return static_cast<int>(CGAL::sign(v));
}

/// Sign of (b - a) . (c - a): positive when the angle bac is acute, 0 when it
/// is right, negative when obtuse.
inline int dot_sign(const Point3& a, const Point3& b, const Point3& c) {
  return sign([&](auto z) {
    using NT = decltype(z);
    NT s = z;
    for (int i = 0; i < 3; ++i) s = s + (NT(b[i]) - NT(a[i])) * (NT(c[i]) - NT(a[i]));
    return s;
  });
}

}  // namespace wqmesh::exact
