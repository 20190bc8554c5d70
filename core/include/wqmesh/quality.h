// wqmesh: shape measures of tetrahedra (paper, section 3) and mesh statistics
// (the paper's Table 2 bins).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <functional>
#include <vector>

#include "wqmesh/types.h"

namespace wqmesh {

/// Shape measures of one tetrahedron, possibly weighted (weights are squared
/// radii; all zero gives the unweighted measures).
/// Degenerate tetrahedra (zero volume, or coincident vertices) give no NaN:
/// radius, radius_edge and aspect_ratio are then +infinity, inradius 0,
/// dihedral angles 0 or 180, and an angle at a zero-length edge is 0.
struct TetQuality {
  double volume = 0;         ///< signed, > 0 when positively oriented
  double radius = 0;         ///< circumradius, or orthoradius if weighted
                             ///< (sqrt of the orthosphere's weight; 0 if
                             ///< that weight is negative)
  double shortest_edge = 0;  ///< l, the shortest edge length
  double longest_edge = 0;
  double radius_edge = 0;        ///< R/l (rho in section 3)
  double normalized_volume = 0;  ///< vol / l^3 (sigma in section 3), signed
                                 ///< like volume; 0 if l = 0
  double inradius = 0;           ///< 3 |vol| / (total area of the 4 faces)
  double aspect_ratio = 0;       ///< circumradius / inradius (unweighted)
  /// Interior dihedral angles at edges 01,02,03,12,13,23, in [0, 180]
  /// whatever the orientation.
  std::array<double, 6> dihedral_deg{};
  double min_dihedral_deg = 0, max_dihedral_deg = 0;
  /// The 3 corner angles of each of the 4 faces: [3f + k] is the angle at
  /// corner k of face f, where the faces opposite vertex 0, 1, 2, 3 are
  /// (1,2,3), (0,2,3), (0,1,3), (0,1,2).
  std::array<double, 12> face_angle_deg{};
  double min_face_angle_deg = 0;
};

/// Measures one tetrahedron. `w` may be null (unweighted). Plain double
/// arithmetic: these are measurements, not decisions. Scale-safe: the tet is
/// measured scaled by a power of two (see ScaledTet in quality.cpp), so no
/// intermediate overflows or underflows for any finite input; only a result
/// that itself cannot be represented in the input's units (the volume of a
/// tet 1e200 wide, or 1e-120 wide) becomes infinite or zero. Angles, R/l,
/// sigma and the aspect ratio are computed scale-free and stay exact to
/// rounding at every scale.
TetQuality tet_quality(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                       const std::array<double, 4>* w = nullptr);

/// tet_quality(a, b, c, d, w).radius_edge, bit for bit (the same
/// arithmetic), without the other measures (its angles above all): for the
/// weighted view of classify_tets, which keeps only R/l.
double tet_radius_edge(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                       const std::array<double, 4>* w = nullptr);

/// tet_quality(a, b, c, d).min_dihedral_deg, bit for bit (the same
/// arithmetic), without the other measures: for the mesher's sliver scans.
double tet_min_dihedral_deg(const Point3& a, const Point3& b, const Point3& c, const Point3& d);

/// tet_min_dihedral_deg(a, b, c, d), the same double, when that is at most
/// `bound`; otherwise some value above `bound` (180 when every angle is):
/// the angles certainly above the bound are not computed (issue 15, rule
/// 7's scan of every tet for the ones at theta or less).
double tet_min_dihedral_deg_upto(const Point3& a, const Point3& b, const Point3& c, const Point3& d, double bound);

/// The signed volume of a tet (> 0 when positively oriented) as a scaled
/// value v and an `exponent`: the volume is v * 2^exponent, |v| < 2 (the
/// longest edge component is scaled into [1, 2)), so its sign is right and
/// it can be compared even where the volume itself is not a double. Plain
/// double arithmetic.
double tet_volume_scaled(const Point3& a, const Point3& b, const Point3& c, const Point3& d, int& exponent);

/// The exact sign (+1, 0, -1) of the signed volume of a tet (CGAL's interval
/// filter, then MP_Float: the same on every platform).
int tet_orientation(const Point3& a, const Point3& b, const Point3& c, const Point3& d);

/// The signed volume of a tet, computed scaled (infinite or zero only when
/// the volume itself is beyond double range).
double tet_volume(const Point3& a, const Point3& b, const Point3& c, const Point3& d);

/// Statistics of a whole mesh.
struct MeshStats {
  std::size_t vertices = 0, tets = 0;
  double volume = 0;         ///< sum of signed tet volumes
  std::size_t inverted = 0;  ///< tets with volume <= 0 (exact sign, tet_orientation)
  double min_dihedral_deg = 180, max_dihedral_deg = 0;
  double min_face_angle_deg = 180;
  double max_radius_edge = 0;
  double max_aspect_ratio = 0;
  /// Table 2 of the paper: R/l in [0.6,1.4], (1.4,2.2], above 2.2 (tets with
  /// R/l below 0.6 are counted in `radius_edge_below`, which stays 0 since
  /// R/l >= sqrt(6)/4 ~ 0.61 for any unweighted tetrahedron).
  std::size_t radius_edge_below = 0;
  std::array<std::size_t, 3> radius_edge_bins{};
  /// Table 2: smallest dihedral in [0,3), [3,5), [5,10) degrees.
  std::array<std::size_t, 3> dihedral_bins{};
  /// Histogram of the smallest dihedral angle per tet, 1-degree bins over
  /// [0, 90): histogram[k] counts tets with k <= angle < k + 1.
  std::array<std::size_t, 90> min_dihedral_histogram{};
  /// Section 6: slivers, tets with R/l <= 2.2 and smallest dihedral < 3 degrees.
  std::size_t slivers = 0;
  /// Figure 3: histogram of the smallest face angle per tet, same 1-degree bins.
  std::array<std::size_t, 90> min_face_angle_histogram{};
};

/// The 1-degree bin of an angle in a histogram of `bins` bins: floor(angle),
/// clamped to [0, bins - 1] (negative and NaN angles go to bin 0). The smallest
/// dihedral of a tet is <= arccos(1/3) ~ 70.5 and its smallest face angle <= 60,
/// so the clamp never applies to them.
std::size_t histogram_bin(double angle_deg, std::size_t bins);

/// Per-tet quality for every tet of `mesh`: weighted if mesh.weights is set
/// and `use_weights` (radius and radius_edge are then the orthoradius and the
/// paper's orthoradius-edge ratio), else unweighted, the geometry of the
/// vertices alone (what a solver sees; the classes, classify.h, use it).
/// Throws std::invalid_argument if weights are used with a size other than
/// the number of vertices, std::out_of_range on a bad vertex index.
/// `keep_going`, when given, is called once per tet before its quality is
/// computed; once it returns false the computation stops, and the result
/// holds the qualities of the tets before that one only (a caller's cancel).
std::vector<TetQuality> mesh_quality(const TetMesh& mesh, const std::function<bool()>& keep_going = {},
                                     bool use_weights = true);

/// Table 2's R/l bin of a ratio: -1 below 0.6, 0 for [0.6, 1.4], 1 for
/// (1.4, 2.2], 2 above 2.2 (NaN too).
int radius_edge_bin(double rho);

/// Statistics over per-tet qualities (those of mesh_quality(mesh)). A tet
/// counts as inverted by the exact sign of its volume (tet_orientation on
/// mesh's points) unless its sigma exceeds 1e-9, where the rounded sign is
/// sure. Throws std::invalid_argument if quality.size() != mesh.tets.size().
MeshStats mesh_stats(const TetMesh& mesh, const std::vector<TetQuality>& quality);

}  // namespace wqmesh
