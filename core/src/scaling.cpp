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

PLC scaled_plc(const PLC& plc, int s) {
  PLC out = plc;
  if (s != 0)
    for (Point3& p : out.vertices)
      for (double& x : p) x = std::ldexp(x, s);
  return out;
}

void scale_analysis(Analysis& a, int s) {
  if (s == 0) return;
  for (double& f : a.lfs) f = std::ldexp(f, s);
  for (Box* b : {&a.input_box, &a.bounding_box})
    for (int q = 0; q < 3; ++q) {
      b->lo[q] = std::ldexp(b->lo[q], s);
      b->hi[q] = std::ldexp(b->hi[q], s);
    }
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

void check_representable(const PLC& plc, int E, double box_margin) {
  if (plc.vertices.empty()) return;
  static const char* kAxis = "xyz";
  char text[400];
  for (std::size_t v = 0; v < plc.vertices.size(); ++v)
    for (int q = 0; q < 3; ++q) {
      const double x = plc.vertices[v][q];
      if (std::ldexp(std::ldexp(x, -E), E) != x) {
        std::snprintf(text, sizeof text,
                      "vertex %zu: coordinate %c = %.17g is too small beside the largest coordinate (about 2^%d): "
                      "scaled to the input's extent it is a subnormal number and would lose digits",
                      v, kAxis[q], x, E);
        throw InputError(InputErrorKind::out_of_range, text);
      }
    }
  // The boxes, in scaled coordinates (no overflow there), then in the input's.
  Point3 lo = plc.vertices[0], hi = lo;
  for (const Point3& p : plc.vertices)
    for (int q = 0; q < 3; ++q) {
      lo[q] = std::min(lo[q], p[q]);
      hi[q] = std::max(hi[q], p[q]);
    }
  double extent = 0;
  for (int q = 0; q < 3; ++q) {
    const double s = std::ldexp(hi[q], -E) - std::ldexp(lo[q], -E);
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
    const double a = std::ldexp(std::ldexp(lo[q], -E) - grow, E);
    const double b = std::ldexp(std::ldexp(hi[q], -E) + grow, E);
    if (!std::isfinite(a) || !std::isfinite(b)) {
      std::snprintf(text, sizeof text,
                    "the bounding box B (the input's box grown by %g times its extent) reaches beyond the largest "
                    "double along %c (from %s to %s)",
                    box_margin, kAxis[q], decimal_power(std::ldexp(lo[q], -E) - grow, E).c_str(),
                    decimal_power(std::ldexp(hi[q], -E) + grow, E).c_str());
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
