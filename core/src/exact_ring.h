// wqmesh: ExactRing, an exact ring number type for CGAL's kernels (private).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Epick's filtered predicates of the ring kind (orientation, coplanar
// orientation, power and in-sphere tests) fall back, when their interval
// filter fails, to Simple_cartesian<Exact_ring_selector<double>::Type>:
// natively GMP's Mpzf, without GMP (wasm) CGAL's MP_Float, which allocates a
// vector per operation and works in 16-bit limbs. ExactRing is exact::detail's
// expansion (exact.h: non-overlapping doubles, inline storage) as a CGAL ring
// number type, which turns to MP_Float for the rest of an expression only
// where an expansion cannot stay exact (two-product under 2^-960 or over
// 2^995, overflow). Exact either way, so every predicate's answer, and every
// mesh, is the one MP_Float gives; only the time differs. Beyond the paper
// (issue 15: the wasm gap in INITIALIZE and CONFORM, where the ball points'
// cospherical and coplanar configurations defeat the filters).

#pragma once

#include <memory>
#include <utility>

#include <CGAL/MP_Float.h>

#include "exact.h"

namespace wqmesh::exact {

class ExactRing {
 public:
  ExactRing() = default;
  ExactRing(double x) : e_(x) {  // NOLINT: implicit, as a number type's conversions are
    if (!e_.exact()) mp_ = std::make_shared<CGAL::MP_Float>(x);
  }
  ExactRing(int x) : ExactRing(static_cast<double>(x)) {}  // NOLINT
  explicit ExactRing(const CGAL::MP_Float& m) : mp_(std::make_shared<CGAL::MP_Float>(m)) {}

  int sign() const { return mp_ ? static_cast<int>(CGAL::sign(*mp_)) : e_.sign(); }
  CGAL::MP_Float to_mp() const {
    if (mp_) return *mp_;
    CGAL::MP_Float s(0);
    for (int i = 0; i < e_.size(); ++i) s = s + CGAL::MP_Float(e_[i]);
    return s;
  }
  double to_double() const {
    if (mp_) return CGAL::to_double(*mp_);
    double s = 0;
    for (int i = 0; i < e_.size(); ++i) s += e_[i];
    return s;
  }
  std::pair<double, double> to_interval() const { return CGAL::to_interval(to_mp()); }

  friend ExactRing operator+(const ExactRing& a, const ExactRing& b) {
    if (!a.mp_ && !b.mp_) {
      ExactRing r(a.e_ + b.e_, 0);
      if (r.e_.exact()) return r;
    }
    return ExactRing(a.to_mp() + b.to_mp());
  }
  friend ExactRing operator-(const ExactRing& a, const ExactRing& b) {
    if (!a.mp_ && !b.mp_) {
      ExactRing r(a.e_ - b.e_, 0);
      if (r.e_.exact()) return r;
    }
    return ExactRing(a.to_mp() - b.to_mp());
  }
  friend ExactRing operator*(const ExactRing& a, const ExactRing& b) {
    if (!a.mp_ && !b.mp_) {
      ExactRing r(a.e_ * b.e_, 0);
      if (r.e_.exact()) return r;
    }
    return ExactRing(a.to_mp() * b.to_mp());
  }
  friend ExactRing operator-(const ExactRing& a) {
    if (a.mp_) return ExactRing(-*a.mp_);
    return ExactRing(-a.e_, 0);
  }
  ExactRing& operator+=(const ExactRing& b) { return *this = *this + b; }
  ExactRing& operator-=(const ExactRing& b) { return *this = *this - b; }
  ExactRing& operator*=(const ExactRing& b) { return *this = *this * b; }

  friend int compare(const ExactRing& a, const ExactRing& b) { return (a - b).sign(); }
  friend bool operator<(const ExactRing& a, const ExactRing& b) { return compare(a, b) < 0; }
  friend bool operator>(const ExactRing& a, const ExactRing& b) { return compare(a, b) > 0; }
  friend bool operator<=(const ExactRing& a, const ExactRing& b) { return compare(a, b) <= 0; }
  friend bool operator>=(const ExactRing& a, const ExactRing& b) { return compare(a, b) >= 0; }
  friend bool operator==(const ExactRing& a, const ExactRing& b) { return compare(a, b) == 0; }
  friend bool operator!=(const ExactRing& a, const ExactRing& b) { return compare(a, b) != 0; }

 private:
  ExactRing(const detail::Expansion& e, int) : e_(e) {}
  detail::Expansion e_;                 // the value, when mp_ is null (always exact then)
  std::shared_ptr<CGAL::MP_Float> mp_;  // the value once an expansion could not stay exact
};

}  // namespace wqmesh::exact

namespace CGAL {

CGAL_DEFINE_COERCION_TRAITS_FROM_TO(int, wqmesh::exact::ExactRing)
CGAL_DEFINE_COERCION_TRAITS_FROM_TO(double, wqmesh::exact::ExactRing)

template <>
class Algebraic_structure_traits<wqmesh::exact::ExactRing>
    : public Algebraic_structure_traits_base<wqmesh::exact::ExactRing, Integral_domain_without_division_tag> {
 public:
  typedef Tag_true Is_exact;
  typedef Tag_false Is_numerical_sensitive;
};

template <>
class Real_embeddable_traits<wqmesh::exact::ExactRing>
    : public INTERN_RET::Real_embeddable_traits_base<wqmesh::exact::ExactRing, Tag_true> {
 public:
  struct Sgn : public CGAL::cpp98::unary_function<Type, ::CGAL::Sign> {
    ::CGAL::Sign operator()(const Type& x) const { return static_cast<::CGAL::Sign>(x.sign()); }
  };
  struct Compare : public CGAL::cpp98::binary_function<Type, Type, Comparison_result> {
    Comparison_result operator()(const Type& x, const Type& y) const {
      return static_cast<Comparison_result>(compare(x, y));
    }
  };
  struct To_double : public CGAL::cpp98::unary_function<Type, double> {
    double operator()(const Type& x) const { return x.to_double(); }
  };
  struct To_interval : public CGAL::cpp98::unary_function<Type, std::pair<double, double>> {
    std::pair<double, double> operator()(const Type& x) const { return x.to_interval(); }
  };
};

}  // namespace CGAL
