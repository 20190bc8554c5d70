// SPDX-License-Identifier: GPL-3.0-or-later
// wqmesh: scale-safe geometry; see scaling.h for the contracts.
#include "scaling.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <string>

#include "wqmesh/error.h"

namespace wqmesh {

int normalisation_exponent(const PLC& plc) {
  double big = 0;
  for (const Point3& p : plc.vertices)
    for (double x : p) big = std::max(big, std::fabs(x));
  if (!(big > 0) || !std::isfinite(big)) return 0;
  return std::ilogb(big);
}

namespace {

/// x - c is exact in doubles: Knuth's two-sum of x and -c (round to
/// nearest, no overflow) gives x - c = d + e exactly, and e is 0.
bool exact_difference(double x, double c) {
  const double d = x - c;
  if (!std::isfinite(d)) return false;
  const double xs = d + c, cs = d - xs;  // the parts of d from x and from -c
  return (x - xs) + (-c - cs) == 0;
}

}  // namespace

Normalisation normalisation(const PLC& plc) {
  Normalisation n;
  n.exponent = normalisation_exponent(plc);
  if (plc.vertices.empty()) return n;
  const Box box = vertex_box(plc);
  Point3 centre{{0, 0, 0}};
  for (int q = 0; q < 3; ++q) {
    const double lo = box.lo[q], hi = box.hi[q];
    const double big = std::max(std::fabs(lo), std::fabs(hi));
    if (!(big >= DBL_MIN) || !std::isfinite(big)) continue;
    // u: the unit in the last place of the axis's largest coordinate (a
    // multiple of every coordinate's unit on the axis); c: the box's middle
    // rounded to a multiple of u, kept only if every difference is exact.
    const double u = std::ldexp(1.0, std::ilogb(big) - (DBL_MANT_DIG - 1));
    const double c = std::nearbyint((lo / 2 + hi / 2) / u) * u;
    bool exact = std::isfinite(c);
    for (std::size_t v = 0; exact && v < plc.vertices.size(); ++v) exact = exact_difference(plc.vertices[v][q], c);
    if (exact) centre[q] = c;
  }
  double big = 0;
  for (const Point3& p : plc.vertices)
    for (int q = 0; q < 3; ++q) big = std::max(big, std::fabs(p[q] - centre[q]));
  if (!(big > 0)) return n;
  const int translated = std::ilogb(big);
  if (n.exponent - translated < kTranslationGainBits) return n;
  n.centre = centre;
  n.exponent = translated;
  return n;
}

PLC normalised_plc(const PLC& plc, const Normalisation& n) {
  PLC out = plc;
  for (Point3& p : out.vertices)
    for (int q = 0; q < 3; ++q) p[q] = std::ldexp(p[q] - n.centre[q], -n.exponent);  // x - 0 is x
  return out;
}

Point3 input_point(const Point3& p, const Normalisation& n) {
  Point3 out = p;
  for (int q = 0; q < 3; ++q) {
    if (n.exponent != 0) out[q] = std::ldexp(out[q], n.exponent);
    if (n.centre[q] != 0) out[q] += n.centre[q];
  }
  return out;
}

void analysis_to_input(Analysis& a, const Normalisation& n) {
  for (double& f : a.lfs) f = std::ldexp(f, n.exponent);
  for (Box* b : {&a.input_box, &a.bounding_box}) {
    b->lo = input_point(b->lo, n);
    b->hi = input_point(b->hi, n);
  }
}

void analysis_to_normalised(Analysis& a, const Normalisation& n) {
  for (double& f : a.lfs) f = std::ldexp(f, -n.exponent);
  for (Box* b : {&a.input_box, &a.bounding_box})
    for (int q = 0; q < 3; ++q)
      for (double* x : {&b->lo[q], &b->hi[q]}) {
        if (n.centre[q] != 0) *x -= n.centre[q];
        if (n.exponent != 0) *x = std::ldexp(*x, -n.exponent);
      }
  if (n.translated()) a.bounding_box = grown_box(a.input_box, a.box_margin);
}

Box vertex_box(const PLC& plc) {
  Box b{plc.vertices[0], plc.vertices[0]};
  for (const Point3& p : plc.vertices)
    for (int q = 0; q < 3; ++q) {
      b.lo[q] = std::min(b.lo[q], p[q]);
      b.hi[q] = std::max(b.hi[q], p[q]);
    }
  return b;
}

Box grown_box(const Box& input_box, double box_margin) {
  const Box& b = input_box;
  const double extent = std::max({b.hi[0] - b.lo[0], b.hi[1] - b.lo[1], b.hi[2] - b.lo[2]});
  const double grow = box_margin * extent;
  Box B;
  for (int q = 0; q < 3; ++q) {
    B.lo[q] = b.lo[q] - grow;
    B.hi[q] = b.hi[q] + grow;
  }
  return B;
}

double plc_volume_scaled(const PLC& plc, int& exponent) {
  // V = 1/3 sum over facets of (a point of F - g) . (area vector of F); the
  // area vector of a facet is the sum over its loops (holes turn the other
  // way). Any g gives V (the area vectors of a closed surface sum to zero);
  // a vertex of the input keeps the terms small when the input lies far from
  // the origin (coordinates of 1e8 around a unit-sized part).
  const int e = normalisation_exponent(plc);
  exponent = 3 * e;
  if (plc.vertices.empty()) return 0;
  auto P = [&](int v) {
    const Point3& p = plc.vertices[v];
    return Point3{{std::ldexp(p[0], -e), std::ldexp(p[1], -e), std::ldexp(p[2], -e)}};
  };
  double volume = 0;
  const Point3 g = P(0);
  for (const PlcFacet& f : plc.facets) {
    if (f.loops.empty() || f.loops[0].empty()) continue;
    const Point3 o = P(f.loops[0][0]);
    for (const auto& loop : f.loops) {
      double area[3] = {0, 0, 0};
      for (std::size_t i = 0; i < loop.size(); ++i) {
        const Point3 p = P(loop[i]);
        const Point3 q = P(loop[(i + 1) % loop.size()]);
        const double a[3] = {p[0] - o[0], p[1] - o[1], p[2] - o[2]};
        const double b[3] = {q[0] - o[0], q[1] - o[1], q[2] - o[2]};
        area[0] += a[1] * b[2] - a[2] * b[1];
        area[1] += a[2] * b[0] - a[0] * b[2];
        area[2] += a[0] * b[1] - a[1] * b[0];
      }
      volume += ((o[0] - g[0]) * area[0] + (o[1] - g[1]) * area[1] + (o[2] - g[2]) * area[2]) / 6;
    }
  }
  return volume;
}

std::string decimal_power(double v, int e) {
  if (v == 0 || !std::isfinite(v)) {
    char t[32];
    std::snprintf(t, sizeof t, "%g", v);
    return t;
  }
  // log10 |v 2^e| = log10 |v| + e log10 2, split into mantissa and exponent.
  const double l = std::log10(std::fabs(v)) + e * std::log10(2.0);
  double d = std::floor(l);
  double m = std::pow(10.0, l - d);
  if (m >= 9.995) {
    m /= 10;
    d += 1;
  }
  char t[48];
  std::snprintf(t, sizeof t, "%s%.3ge%+d", v < 0 ? "-" : "", m, static_cast<int>(d));
  return t;
}

void check_representable(const PLC& plc, const Normalisation& n, double box_margin) {
  if (plc.vertices.empty()) return;
  static const char* kAxis = "xyz";
  char text[400];
  const int E = n.exponent;
  for (std::size_t v = 0; v < plc.vertices.size(); ++v)
    for (int q = 0; q < 3; ++q) {
      const double x = plc.vertices[v][q] - n.centre[q];  // exact (normalisation)
      if (std::ldexp(std::ldexp(x, -E), E) != x) {
        std::snprintf(text, sizeof text,
                      "vertex %zu: coordinate %c = %.17g is too small beside the largest coordinate (about 2^%d): "
                      "scaled to the input's extent it is a subnormal number and would lose digits",
                      v, kAxis[q], plc.vertices[v][q], E);
        throw InputError(InputErrorKind::out_of_range, text);
      }
    }
  // The boxes, in normalised coordinates (no overflow there), then in the
  // input's (lo and hi are exact differences to c, see normalisation).
  const Box box = vertex_box(plc);
  const Point3 &lo = box.lo, &hi = box.hi;
  Point3 los, his;  // normalised
  double extent = 0;
  for (int q = 0; q < 3; ++q) {
    los[q] = std::ldexp(lo[q] - n.centre[q], -E);
    his[q] = std::ldexp(hi[q] - n.centre[q], -E);
    const double s = his[q] - los[q];
    extent = std::max(extent, s);
    if (!std::isfinite(std::ldexp(s, E))) {
      std::snprintf(text, sizeof text,
                    "the input's extent along %c, from %.17g to %.17g, is %s: beyond the largest double (%.6g)",
                    kAxis[q], lo[q], hi[q], decimal_power(s, E).c_str(), DBL_MAX);
      throw InputError(InputErrorKind::out_of_range, text);
    }
  }
  const double grow = box_margin * extent;
  for (int q = 0; q < 3; ++q) {
    const double a = std::ldexp(los[q] - grow, E) + n.centre[q];
    const double b = std::ldexp(his[q] + grow, E) + n.centre[q];
    if (!std::isfinite(a) || !std::isfinite(b)) {
      std::snprintf(text, sizeof text,
                    "the bounding box B (the input's box grown by %g times its extent) reaches beyond the largest "
                    "double along %c (from %s to %s)",
                    box_margin, kAxis[q], decimal_power(los[q] - grow, E).c_str(),
                    decimal_power(his[q] + grow, E).c_str());
      throw InputError(InputErrorKind::out_of_range, text);
    }
  }
  int ve = 0;
  const double vs = plc_volume_scaled(plc, ve);
  const double volume = std::ldexp(std::fabs(vs), ve);
  if (vs != 0 && !(volume >= DBL_MIN && volume <= DBL_MAX)) {
    std::snprintf(text, sizeof text,
                  "the enclosed volume, about %s, is not a normal double (between %.6g and %.6g): it cannot be "
                  "reported in the input's units",
                  decimal_power(std::fabs(vs), ve).c_str(), DBL_MIN, DBL_MAX);
    throw InputError(InputErrorKind::out_of_range, text);
  }
}

}  // namespace wqmesh
