// wqmesh: exact signs of polynomial expressions in input doubles (private).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Contract: `expr` is a generic callable `expr(NT)` that evaluates a
// polynomial in the input coordinates using only +, - and * over the number
// type NT (doubles are converted with NT(x); NT is default-constructible to
// 0). exact::sign returns the sign of the polynomial's exact value, the same
// on every platform (native and wasm), in three stages:
//   1. Approx: the value in double precision with a running bound on its
//      error (plain round-to-nearest arithmetic: no rounding-mode switch,
//      which wasm cannot do, and no library call per operation);
//   2. Expansion: when the bound does not decide, the exact value as a sum of
//      non-overlapping doubles (Shewchuk, "Adaptive precision floating-point
//      arithmetic and fast robust geometric predicates", 1997: two-sum,
//      Dekker's two-product, expansion sums, scaling and compression);
//   3. CGAL's MP_Float, only when an expansion could not stay exact (a
//      product under about 2^-960 or an operand above 2^995, where
//      two-product loses bits, or any overflow).
// Beyond the paper (issue 15): until this file, stage 1 was CGAL's
// Interval_nt and stage 2 MP_Float. Under wasm (CGAL_ALWAYS_ROUND_TO_NEAREST)
// every interval bound took a call to nextafter and came out up to three
// times wider than with directed rounding, and MP_Float allocates per
// operation: facets' in-circle tests of nearly cocircular ball points went
// to MP_Float about 40 times as often as natively. Every stage gives the
// exact sign, so the answers (and the meshes) do not depend on which stage
// decides. tests/native/exact_test.cpp checks each stage against MP_Float.
#pragma once

#include <cmath>
#include <cstring>
#include <memory>

#include <CGAL/MP_Float.h>

#include "wqmesh/types.h"

namespace wqmesh::exact {

namespace detail {

constexpr double kUnit = 0x1p-53;         // unit roundoff of round-to-nearest
constexpr double kInflate = 1 + 0x1p-50;  // covers the roundings of a bound's own sum
constexpr double kUnderflow = 0x1p-1070;  // covers products lost below 2^-1074

/// A double v with a bound e on its distance to the exact value:
/// |exact - v| <= e. Each operation adds its own rounding (at most kUnit |v|
/// for round-to-nearest) and the propagated errors of its operands; the new
/// bound is computed in round-to-nearest too and then scaled by kInflate,
/// which exceeds the at most four roundings in it ((1 + 2^-53)^4 < 1 + 2^-50),
/// and a product adds kUnderflow for the at most six roundings below the
/// normal range in it (each under 2^-1075). An overflow makes v or e
/// infinite or NaN, and decided() is then false.
struct Approx {
  double v = 0, e = 0;
  Approx() = default;
  explicit Approx(double x) : v(x) {}
  Approx(double value, double error) : v(value), e(error) {}
  /// Whether the sign of v is the exact sign (false for inf or NaN).
  bool decided() const { return e < std::fabs(v); }
};
inline Approx operator+(const Approx& a, const Approx& b) {
  const double v = a.v + b.v;
  return {v, (a.e + b.e + kUnit * std::fabs(v)) * kInflate};
}
inline Approx operator-(const Approx& a, const Approx& b) {
  const double v = a.v - b.v;
  return {v, (a.e + b.e + kUnit * std::fabs(v)) * kInflate};
}
inline Approx operator-(const Approx& a) { return {-a.v, a.e}; }
inline Approx operator*(const Approx& a, const Approx& b) {
  const double v = a.v * b.v;
  return {v, (std::fabs(a.v) * b.e + std::fabs(b.v) * a.e + a.e * b.e + kUnit * std::fabs(v) + kUnderflow) * kInflate};
}

// ---- error-free transformations (round-to-nearest). Every partial product
// of two_product is exact (halves of at most 26 bits), so a fused
// multiply-add in their place changes nothing; Exact.TwoProductAndSumsAreErrorFree
// checks the products bit for bit (it also passes when built with -mfma
// -ffp-contract=fast). -----------------------------------------------------------
inline void two_sum(double a, double b, double& x, double& y) {
  x = a + b;
  const double bv = x - a;
  const double av = x - bv;
  y = (a - av) + (b - bv);
}
inline void split(double a, double& hi, double& lo) {
  const double c = 134217729.0 * a;  // 2^27 + 1
  hi = c - (c - a);
  lo = a - hi;
}
/// x + y = a * b exactly when `exact` stays true: a, b at most 2^995 in
/// magnitude (no overflow in split) and the product zero or at least 2^-960
/// (its low part representable).
inline void two_product(double a, double b, double& x, double& y, bool& exact) {
  x = a * b;
  const double ax = std::fabs(a), bx = std::fabs(b), px = std::fabs(x);
  if (ax > 0x1p995 || bx > 0x1p995 || !(px < 0x1p1023) || (px < 0x1p-960 && a != 0 && b != 0)) exact = false;
  double ah, al, bh, bl;
  split(a, ah, al);
  split(b, bh, bl);
  y = al * bl - (((x - ah * bh) - al * bh) - ah * bl);
}

/// An exact value as a sum of non-overlapping doubles, smallest magnitude
/// first, no zero component (so 0 has none and the sign is the last
/// component's). Components live inline up to kInline, then on the heap.
/// exact() is false once an operation could not be carried out exactly
/// (see two_product; or a sum overflowed); the value is then meaningless.
class Expansion {
 public:
  Expansion() = default;
  explicit Expansion(double x) {
    if (x != 0) c_[n_++] = x;
    if (!std::isfinite(x)) exact_ = false;
  }
  Expansion(const Expansion& o) { assign(o); }
  Expansion& operator=(const Expansion& o) {
    if (this != &o) assign(o);
    return *this;
  }

  int sign() const { return n_ == 0 ? 0 : c_[n_ - 1] > 0 ? 1 : -1; }
  bool exact() const { return exact_; }
  int size() const { return n_; }
  double operator[](int i) const { return c_[i]; }

  friend Expansion operator+(const Expansion& a, const Expansion& b) { return sum(a, b, false); }
  friend Expansion operator-(const Expansion& a, const Expansion& b) { return sum(a, b, true); }
  friend Expansion operator-(const Expansion& a) {
    Expansion r(a);
    for (int i = 0; i < r.n_; ++i) r.c_[i] = -r.c_[i];
    return r;
  }
  friend Expansion operator*(const Expansion& a, const Expansion& b) {
    if (a.n_ < b.n_) return b * a;  // scale the longer one by each of the shorter's components
    Expansion r, t;
    for (int j = 0; j < b.n_; ++j) {
      scale(a, b.c_[j], t);
      if (j == 0)
        r = t;
      else
        r = sum(r, t, false);
    }
    r.compress();
    r.exact_ = r.exact_ && a.exact_ && b.exact_;
    return r;
  }

 private:
  static constexpr int kInline = 16;
  double buf_[kInline];
  std::unique_ptr<double[]> heap_;
  double* c_ = buf_;
  int n_ = 0, cap_ = kInline;
  bool exact_ = true;

  void reserve(int n) {  // drops the components
    n_ = 0;
    if (n <= cap_) return;
    heap_.reset(new double[n]);
    c_ = heap_.get();
    cap_ = n;
  }
  void assign(const Expansion& o) {
    reserve(o.n_);
    std::memcpy(c_, o.c_, sizeof(double) * o.n_);
    n_ = o.n_;
    exact_ = o.exact_;
  }
  void push(double x) {
    if (x != 0) c_[n_++] = x;
  }
  void check_finite() {
    if (n_ > 0 && !std::isfinite(c_[n_ - 1])) exact_ = false;  // an overflow reaches the largest component
  }

  // a + b or a - b: merge by magnitude, then one chain of two-sums
  // (Shewchuk's fast expansion sum with zero elimination; two_sum in place
  // of fast_two_sum throughout, which is exact without its precondition).
  static Expansion sum(const Expansion& a, const Expansion& b, bool negate_b) {
    Expansion h;
    h.exact_ = a.exact_ && b.exact_;
    h.reserve(a.n_ + b.n_ + 1);
    const double s = negate_b ? -1.0 : 1.0;
    if (b.n_ == 0) {
      h.assign(a);
      h.exact_ = a.exact_ && b.exact_;
      return h;
    }
    if (a.n_ == 0) {
      for (int i = 0; i < b.n_; ++i) h.c_[i] = s * b.c_[i];
      h.n_ = b.n_;
      return h;
    }
    int i = 0, j = 0;
    double ei = a.c_[0], fj = s * b.c_[0];
    auto next = [&](double& q) {  // the component of smaller magnitude
      if ((fj > ei) == (fj > -ei)) {
        q = ei;
        ++i;
        ei = i < a.n_ ? a.c_[i] : 0;
      } else {
        q = fj;
        ++j;
        fj = j < b.n_ ? s * b.c_[j] : 0;
      }
    };
    double q;
    next(q);
    while (i < a.n_ && j < b.n_) {
      double x, y, g;
      next(g);
      two_sum(q, g, x, y);
      h.push(y);
      q = x;
    }
    for (; i < a.n_; ++i) {
      double x, y;
      two_sum(q, a.c_[i], x, y);
      h.push(y);
      q = x;
    }
    for (; j < b.n_; ++j) {
      double x, y;
      two_sum(q, s * b.c_[j], x, y);
      h.push(y);
      q = x;
    }
    h.push(q);
    h.check_finite();
    return h;
  }

  // h = e * b (Shewchuk's scale expansion with zero elimination).
  static void scale(const Expansion& e, double b, Expansion& h) {
    h.exact_ = e.exact_;
    h.reserve(2 * e.n_ + 1);
    double q, y;
    two_product(e.c_[0], b, q, y, h.exact_);
    h.push(y);
    for (int i = 1; i < e.n_; ++i) {
      double p1, p0, s, t;
      two_product(e.c_[i], b, p1, p0, h.exact_);
      two_sum(q, p0, s, t);
      h.push(t);
      two_sum(p1, s, q, t);
      h.push(t);
    }
    h.push(q);
    h.check_finite();
  }

  // Shewchuk's compression: the same value in as few components as his
  // bound allows, still non-overlapping, smallest first (in place).
  void compress() {
    if (n_ < 2) return;
    int bottom = n_ - 1;
    double q = c_[bottom];
    for (int i = n_ - 2; i >= 0; --i) {
      double x, y;
      two_sum(q, c_[i], x, y);
      if (y != 0) {
        c_[bottom--] = x;
        q = y;
      } else {
        q = x;
      }
    }
    int top = 0;
    for (int i = bottom + 1; i < n_; ++i) {
      double x, y;
      two_sum(c_[i], q, x, y);
      if (y != 0) c_[top++] = y;
      q = x;
    }
    if (q != 0) c_[top++] = q;
    n_ = top;
  }
};

}  // namespace detail

template <class Expr>
int sign(const Expr& expr) {
  const detail::Approx a = expr(detail::Approx(0));
  if (a.decided()) return a.v > 0 ? 1 : -1;
  const detail::Expansion x = expr(detail::Expansion(0));
  if (x.exact()) return x.sign();
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
