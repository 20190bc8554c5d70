// SPDX-License-Identifier: GPL-3.0-or-later
// wqmesh: shape measures of tetrahedra (paper, section 3) and mesh statistics
// (paper, section 6 and Table 2). See wqmesh/quality.h for the contracts.
//
// These are measurements for reporting, not decisions: they are evaluated in
// plain double arithmetic (no exact predicates) and are only required to be
// accurate for non-degenerate tetrahedra and well-defined (no NaN) otherwise.
#include "wqmesh/quality.h"

#include "exact.h"
#include "geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace wqmesh {

namespace {

using geometry::cross;
using geometry::dot;
using geometry::kPi;
using geometry::norm;
constexpr double kInf = std::numeric_limits<double>::infinity();

/// The angle between u and v in degrees, in [0, 180]. atan2(|u x v|, u . v) is
/// accurate near 0 and 180 degrees, where acos of the normalized dot product
/// loses half the digits. 0 when u or v is the zero vector (no NaN; the
/// explicit test also avoids atan2(+0, -0) = 180).
double angle_deg(const Point3& u, const Point3& v) {
  const double y = norm(cross(u, v));
  const double x = dot(u, v);
  if (y == 0 && x == 0) return 0;
  return std::atan2(y, x) * (180.0 / kPi);
}

/// The vector x from the origin vertex p0 to the orthocenter z of four weighted
/// points p0 + e_i (e_0 = 0) with weights (squared radii) W_i. The orthosphere
/// (paper, section 3) satisfies pi(p_i^, z^) = |z - p_i|^2 - W_i - Z^2 = 0 for
/// all i. Subtracting the equation of p0 gives the linear system
///   2 x . e_i = |e_i|^2 - W_i + W_0,   i = 1, 2, 3,
/// solved by Cramer's rule with det = e_1 . (e_2 x e_3) (= 6 vol != 0). With all
/// weights equal this is the circumcenter.
Point3 orthocenter_offset(const Point3& e1, const Point3& e2, const Point3& e3, double det, double r1, double r2,
                          double r3) {
  const Point3 c23 = cross(e2, e3), c31 = cross(e3, e1), c12 = cross(e1, e2);
  const double s = 1.0 / (2.0 * det);
  Point3 x;
  for (int k = 0; k < 3; ++k) x[k] = (r1 * c23[k] + r2 * c31[k] + r3 * c12[k]) * s;
  return x;
}

/// A tetrahedron scaled by a power of two, so that no formula below can
/// overflow or underflow for finite input (beyond the paper, which assumes
/// exact reals). The six edge vectors, in the order 01, 02, 03, 12, 13, 23,
/// are differences of the input doubles (first scaled by 2^-2 when a
/// coordinate is so large that a difference could overflow), then multiplied
/// by 2^-k so that their largest component lies in [1, 2). A length of the
/// scaled tet times 2^k (2^(2k) for areas and weights, 2^(3k) for volumes) is
/// the input's; angles and ratios need no scaling back. Subnormal differences
/// (points 1e-310 apart) become normal numbers: products of them no longer
/// underflow to zero.
struct ScaledTet {
  std::array<Point3, 6> edge;  ///< p_j - p_i for the edges 01,02,03,12,13,23, scaled
  int k = 0;                   ///< the exponent: input length = scaled length * 2^k
  bool zero = true;            ///< all four points equal

  explicit ScaledTet(const std::array<const Point3*, 4>& p) {
    static constexpr int kE[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
    double big = 0;
    for (const Point3* q : p)
      for (double x : *q) big = std::max(big, std::fabs(x));
    // 2^1021: below it the difference of two coordinates stays below 2^1022.
    const int pre = big >= std::ldexp(1.0, 1021) ? 2 : 0;
    double largest = 0;
    for (int i = 0; i < 6; ++i) {
      const Point3& a = *p[kE[i][0]];
      const Point3& b = *p[kE[i][1]];
      for (int c = 0; c < 3; ++c) {
        // pre == 0 almost always: ldexp(x, 0) is x (issue 15: the calls
        // were a few percent of a run).
        edge[i][c] = pre ? std::ldexp(b[c], -pre) - std::ldexp(a[c], -pre) : b[c] - a[c];
        largest = std::max(largest, std::fabs(edge[i][c]));
      }
    }
    if (!(largest > 0) || !std::isfinite(largest)) {  // one point, or not finite
      zero = largest == 0;
      k = pre;
      return;
    }
    zero = false;
    const int m = std::ilogb(largest);
    // x * 2^-m is the correctly rounded product, as ldexp(x, -m) is, when
    // 2^-m is a normal double (|m| <= 1022; m <= 1021 here): the same value
    // without a library call (issue 15).
    if (m >= -1022) {
      const double scale = std::ldexp(1.0, -m);
      for (Point3& e : edge)
        for (double& x : e) x *= scale;
    } else {
      for (Point3& e : edge)
        for (double& x : e) x = std::ldexp(x, -m);
    }
    k = m + pre;
  }
};

// Edges in the order 01, 02, 03, 12, 13, 23; `opposite` is the other pair.
constexpr int kEdge[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
constexpr int kOpposite[6][2] = {{2, 3}, {1, 3}, {1, 2}, {0, 3}, {0, 2}, {0, 1}};

/// The vector from vertex i to vertex j of the scaled tet, from the edge
/// differences (not from e_j - e_i, which would round twice).
Point3 edge_vector(const ScaledTet& s, int i, int j) {
  if (i == j) return Point3{{0, 0, 0}};
  const bool flip = i > j;
  const int lo = flip ? j : i, hi = flip ? i : j;
  int idx = 0;
  for (int t = 0; t < 6; ++t)
    if (kEdge[t][0] == lo && kEdge[t][1] == hi) idx = t;
  const Point3& v = s.edge[idx];
  return flip ? Point3{{-v[0], -v[1], -v[2]}} : v;
}

/// The dihedral angle at edge i (kEdge order) of the scaled tet, in degrees:
/// the angle between the projections of p_k - p_i and p_l - p_i on the plane
/// orthogonal to e = p_j - p_i, i.e. between e x (p_k - p_i) and
/// e x (p_l - p_i) (both rotated by the same quarter turn about e). In
/// [0, 180] whatever the orientation; a flat tet gives 0 or 180. The one
/// computation of tet_quality and tet_min_dihedral_deg, so they agree bit
/// for bit.
double dihedral_deg(const ScaledTet& s, int i) {
  const int pi = kEdge[i][0];
  const Point3& e = s.edge[i];
  const Point3 nk = cross(e, edge_vector(s, pi, kOpposite[i][0]));
  const Point3 nl = cross(e, edge_vector(s, pi, kOpposite[i][1]));
  return angle_deg(nk, nl);
}

/// The measures of the scaled tet that R/l needs: det (6 times its signed
/// volume), the shortest and longest edge, the circumradius and the radius
/// (the orthoradius with weights `w`, else the circumradius), scaled. The one
/// computation of tet_quality and tet_radius_edge, so they agree bit for bit.
struct RadiusPart {
  double det, shortest_edge, longest_edge, circumradius, radius;
};

RadiusPart radius_part(const ScaledTet& s, const std::array<double, 4>* w) {
  RadiusPart p;
  const int k = s.k;
  const Point3 &e1 = s.edge[0], &e2 = s.edge[1], &e3 = s.edge[2];
  // Signed volume, > 0 for the positive (right-handed) orientation of TetMesh.
  p.det = dot(e1, cross(e2, e3));
  p.shortest_edge = kInf;
  p.longest_edge = 0;
  for (int i = 0; i < 6; ++i) {
    const double len = norm(s.edge[i]);
    if (len < p.shortest_edge) p.shortest_edge = len;
    if (len > p.longest_edge) p.longest_edge = len;
  }
  // Circumradius and orthoradius (section 3), scaled. A zero volume has no
  // (finite) circumsphere: the radius is then +infinity.
  p.circumradius = kInf;
  p.radius = kInf;
  const double det = p.det;
  if (det != 0) {
    const double r1 = dot(e1, e1), r2 = dot(e2, e2), r3 = dot(e3, e3);
    p.circumradius = norm(orthocenter_offset(e1, e2, e3, det, r1, r2, r3));
    p.radius = p.circumradius;
    if (w != nullptr) {
      // Weights are squared radii: scaled by 2^(-2k).
      std::array<double, 4> W;
      for (int i = 0; i < 4; ++i) W[i] = std::ldexp((*w)[i], -2 * k);
      const Point3 x = orthocenter_offset(e1, e2, e3, det, r1 - W[1] + W[0], r2 - W[2] + W[0], r3 - W[3] + W[0]);
      // Z^2 = |z - p_0|^2 - W_0, the weight of the orthosphere; may be < 0.
      const double z2 = dot(x, x) - W[0];
      p.radius = z2 > 0 ? std::sqrt(z2) : 0.0;
    }
  }
  return p;
}

/// rho = R / L (section 3), scale-free. A zero shortest edge gives +infinity.
double radius_edge_of(const RadiusPart& p) { return p.shortest_edge > 0 ? p.radius / p.shortest_edge : kInf; }

}  // namespace

double tet_radius_edge(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                       const std::array<double, 4>* w) {
  const ScaledTet s(std::array<const Point3*, 4>{{&a, &b, &c, &d}});
  return radius_edge_of(radius_part(s, w));
}

double tet_volume_scaled(const Point3& a, const Point3& b, const Point3& c, const Point3& d, int& exponent) {
  const ScaledTet s(std::array<const Point3*, 4>{{&a, &b, &c, &d}});
  exponent = 3 * s.k;
  return dot(s.edge[0], cross(s.edge[1], s.edge[2])) / 6.0;
}

int tet_orientation(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  return exact::sign([&](auto z) {
    using NT = decltype(z);
    NT u[3], v[3], w[3];
    for (int i = 0; i < 3; ++i) {
      u[i] = NT(b[i]) - NT(a[i]);
      v[i] = NT(c[i]) - NT(a[i]);
      w[i] = NT(d[i]) - NT(a[i]);
    }
    return z + u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
           u[2] * (v[0] * w[1] - v[1] * w[0]);
  });
}

double tet_volume(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  int e = 0;
  const double v = tet_volume_scaled(a, b, c, d, e);
  return std::ldexp(v, e);
}

TetQuality tet_quality(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                       const std::array<double, 4>* w) {
  TetQuality q;
  const ScaledTet s(std::array<const Point3*, 4>{{&a, &b, &c, &d}});
  const int k = s.k;
  auto vec = [&](int i, int j) { return edge_vector(s, i, j); };

  // The signed volume (det / 6), the edges, the circumradius and the radius
  // (radius_part, shared with tet_radius_edge).
  const RadiusPart rp = radius_part(s, w);
  const double det = rp.det;
  q.volume = std::ldexp(det / 6.0, 3 * k);
  q.shortest_edge = rp.shortest_edge;
  q.longest_edge = rp.longest_edge;
  const double l = q.shortest_edge;  // scaled
  const double circumradius = rp.circumradius, radius = rp.radius;

  // rho = R / L and sigma = vol / L^3 (section 3), both scale-free. A zero
  // shortest edge gives rho = +infinity and sigma = 0.
  q.radius_edge = radius_edge_of(rp);
  q.normalized_volume = l > 0 ? (det / 6.0) / (l * l * l) : 0.0;

  // Faces opposite vertex 0, 1, 2, 3, each with its corners in this order.
  static constexpr int kFace[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  double area = 0;
  q.min_face_angle_deg = 180;
  for (int f = 0; f < 4; ++f) {
    area += 0.5 * norm(cross(vec(kFace[f][0], kFace[f][1]), vec(kFace[f][0], kFace[f][2])));
    for (int j = 0; j < 3; ++j) {
      const int apex = kFace[f][j];
      const double angle = angle_deg(vec(apex, kFace[f][(j + 1) % 3]), vec(apex, kFace[f][(j + 2) % 3]));
      q.face_angle_deg[3 * f + j] = angle;
      if (angle < q.min_face_angle_deg) q.min_face_angle_deg = angle;
    }
  }

  // Inradius r = 3 |vol| / (total face area); aspect ratio = circumradius / r
  // (unweighted), +infinity when r = 0. Both in the scaled tet.
  const double inradius = area > 0 ? 3.0 * std::fabs(det / 6.0) / area : 0.0;
  q.aspect_ratio = inradius > 0 ? circumradius / inradius : kInf;

  // The dihedral angles (see dihedral_deg).
  q.min_dihedral_deg = 180;
  q.max_dihedral_deg = 0;
  for (int i = 0; i < 6; ++i) {
    const double angle = dihedral_deg(s, i);
    q.dihedral_deg[i] = angle;
    if (angle < q.min_dihedral_deg) q.min_dihedral_deg = angle;
    if (angle > q.max_dihedral_deg) q.max_dihedral_deg = angle;
  }

  // Back to the input's units: lengths times 2^k (the volume above, 2^3k).
  q.shortest_edge = std::ldexp(q.shortest_edge, k);
  q.longest_edge = std::ldexp(q.longest_edge, k);
  q.radius = std::ldexp(radius, k);
  q.inradius = std::ldexp(inradius, k);
  return q;
}

double tet_min_dihedral_deg(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  const ScaledTet s(std::array<const Point3*, 4>{{&a, &b, &c, &d}});
  double smallest = 180;
  for (int i = 0; i < 6; ++i) {
    const double angle = dihedral_deg(s, i);
    if (angle < smallest) smallest = angle;
  }
  return smallest;
}

double tet_min_dihedral_deg_upto(const Point3& a, const Point3& b, const Point3& c, const Point3& d, double bound) {
  if (!(bound >= 1e-6 && bound < 89)) return tet_min_dihedral_deg(a, b, c, d);
  // An angle atan2(y, x) (y >= 0) is certainly above `bound` when x <= 0 < y
  // (90 degrees or more) or y > x tan(bound) (1 + 1e-9): the margin exceeds
  // the few ulps of atan2, of the conversion to degrees and of tan, so the
  // angle tet_min_dihedral_deg computes from the same y and x is above bound
  // too; its atan2 is skipped. The other angles are computed as there.
  const double slope = std::tan(bound * (kPi / 180.0)) * (1 + 1e-9);
  const ScaledTet s(std::array<const Point3*, 4>{{&a, &b, &c, &d}});
  double smallest = 180;
  for (int i = 0; i < 6; ++i) {
    const int pi = kEdge[i][0];
    const Point3& e = s.edge[i];
    const Point3 nk = cross(e, edge_vector(s, pi, kOpposite[i][0]));
    const Point3 nl = cross(e, edge_vector(s, pi, kOpposite[i][1]));
    const double y = norm(cross(nk, nl));
    const double x = dot(nk, nl);
    if (y > 0 && (x <= 0 || y > x * slope)) continue;
    const double angle = angle_deg(nk, nl);
    if (angle < smallest) smallest = angle;
  }
  return smallest;
}

std::vector<TetQuality> mesh_quality(const TetMesh& mesh, const std::function<bool()>& keep_going, bool use_weights) {
  const bool weighted = use_weights && !mesh.weights.empty();
  if (weighted && mesh.weights.size() != mesh.vertices.size())
    throw std::invalid_argument("mesh_quality: " + std::to_string(mesh.weights.size()) + " weights for " +
                                std::to_string(mesh.vertices.size()) + " vertices");
  const long n = static_cast<long>(mesh.vertices.size());
  std::vector<TetQuality> out;
  out.reserve(mesh.tets.size());
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    if (keep_going && !keep_going()) break;
    const std::array<int, 4>& tet = mesh.tets[t];
    for (int v : tet)
      if (v < 0 || v >= n)
        throw std::out_of_range("mesh_quality: tet " + std::to_string(t) + " has vertex index " + std::to_string(v));
    std::array<double, 4> w{};
    if (weighted)
      for (int k = 0; k < 4; ++k) w[k] = mesh.weights[tet[k]];
    out.push_back(tet_quality(mesh.vertices[tet[0]], mesh.vertices[tet[1]], mesh.vertices[tet[2]],
                              mesh.vertices[tet[3]], weighted ? &w : nullptr));
  }
  return out;
}

MeshStats mesh_stats(const TetMesh& mesh, const std::vector<TetQuality>& quality) {
  if (quality.size() != mesh.tets.size())
    throw std::invalid_argument("mesh_stats: " + std::to_string(quality.size()) + " qualities for " +
                                std::to_string(mesh.tets.size()) + " tets");
  MeshStats s;
  s.vertices = mesh.vertices.size();
  s.tets = mesh.tets.size();
  for (const TetQuality& q : quality) {
    s.volume += q.volume;
    // Inverted: the exact sign of the volume, decided without rounding when
    // sigma (scale-free, computed scaled) is too small to be sure of: a flat
    // tet of the mesh (four nearly coplanar points next to a sharp vertex,
    // sigma 1e-17) is positive in exact arithmetic, and a tet whose volume
    // underflows in the input's units is not inverted either.
    if (!(q.normalized_volume > 1e-9)) {
      const auto& t = mesh.tets[&q - quality.data()];
      if (tet_orientation(mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]], mesh.vertices[t[3]]) <= 0)
        ++s.inverted;
    }
    if (q.min_dihedral_deg < s.min_dihedral_deg) s.min_dihedral_deg = q.min_dihedral_deg;
    if (q.max_dihedral_deg > s.max_dihedral_deg) s.max_dihedral_deg = q.max_dihedral_deg;
    if (q.min_face_angle_deg < s.min_face_angle_deg) s.min_face_angle_deg = q.min_face_angle_deg;
    if (q.radius_edge > s.max_radius_edge) s.max_radius_edge = q.radius_edge;
    if (q.aspect_ratio > s.max_aspect_ratio) s.max_aspect_ratio = q.aspect_ratio;

    // Table 2, R/l (NaN, never produced by tet_quality, would count as > 2.2).
    const double rho = q.radius_edge;
    const int bin = radius_edge_bin(rho);
    if (bin < 0)
      ++s.radius_edge_below;
    else
      ++s.radius_edge_bins[bin];

    // Table 2, smallest dihedral angle: [0, 3), [3, 5), [5, 10) degrees.
    const double md = q.min_dihedral_deg;
    if (md < 3)
      ++s.dihedral_bins[0];
    else if (md < 5)
      ++s.dihedral_bins[1];
    else if (md < 10)
      ++s.dihedral_bins[2];

    // Section 6: a sliver has R/l <= 2.2 and a dihedral angle below 3 degrees.
    if (rho <= 2.2 && md < 3) ++s.slivers;

    // Figure 3: distributions of the smallest dihedral and face angles.
    s.min_dihedral_histogram[histogram_bin(md, s.min_dihedral_histogram.size())]++;
    s.min_face_angle_histogram[histogram_bin(q.min_face_angle_deg, s.min_face_angle_histogram.size())]++;
  }
  return s;
}

int radius_edge_bin(double rho) {
  if (rho < 0.6) return -1;
  if (rho <= 1.4) return 0;
  if (rho <= 2.2) return 1;
  return 2;
}

std::size_t histogram_bin(double angle_deg, std::size_t bins) {
  if (!(angle_deg > 0)) return 0;  // also NaN
  const double k = std::floor(angle_deg);
  if (k >= static_cast<double>(bins)) return bins - 1;
  return static_cast<std::size_t>(k);
}

}  // namespace wqmesh
