// SPDX-License-Identifier: GPL-3.0-or-later
// wqmesh benchmark: CGAL Mesh_3 as a peer mesher. Reads a polyhedron (OFF or
// STL) with wqmesh's reader, triangulates and orients it with CGAL's polygon
// mesh processing, and meshes its interior with make_mesh_3 on a
// Polyhedral_mesh_domain_with_features_3 (detect_features(), perturb and exude
// on). Sizes follow one rule: a single size s gives edge_size = facet_size =
// cell_size = s and facet_distance = s / 10, with facet_angle 25 and
// cell_radius_edge_ratio 2.2.
//
//   wqmesh_mesh3_peer IN --size S [-o OUT.mesh]
//       One run at size S; writes the interior tets as Medit.
//   wqmesh_mesh3_peer IN --target-tets N [--tolerance 0.2] [--max-steps 12]
//       Bisection (in log s) for a size whose tet count is within the
//       tolerance of N; prints one JSON line per probe, then the answer.
//
// Output on stdout: JSON lines. Bisection: {"probe", "size", "tets",
// "time_s"} per run, then {"size", "steps", "tets", "within_tolerance",
// "target_tets", "saturated", "input_volume"} (the probe nearest the target;
// saturated: doubling s stopped lowering the tet count, so no size reaches
// the target). One run:
// {"size", "tets", "vertices", "domain_time_s", "mesh_time_s",
// "input_volume"}. Exit code 0 done, 1 usage or internal
// error, 2 unreadable or unusable input. Random numbers are seeded with 0, so
// a size gives the same mesh each time.
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Polyhedral_mesh_domain_with_features_3.h>
#include <CGAL/Random.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/make_mesh_3.h>

#include "wqmesh/error.h"
#include "wqmesh/input.h"
#include "wqmesh/json.h"

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Polyhedron = CGAL::Mesh_polyhedron_3<K>::type;
using Domain = CGAL::Polyhedral_mesh_domain_with_features_3<K>;
using Tr = CGAL::Mesh_triangulation_3<Domain, CGAL::Default, CGAL::Sequential_tag>::type;
using C3t3 = CGAL::Mesh_complex_3_in_triangulation_3<Tr, Domain::Corner_index, Domain::Curve_index>;
using Criteria = CGAL::Mesh_criteria_3<Tr>;
using Clock = std::chrono::steady_clock;
namespace PMP = CGAL::Polygon_mesh_processing;

constexpr const char* kUsage =
    "usage: wqmesh_mesh3_peer IN --size S [-o OUT.mesh]\n"
    "       wqmesh_mesh3_peer IN --target-tets N [--tolerance T] [--max-steps K]\n";

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

/// The input as a closed triangle mesh, outward oriented; throws
/// std::runtime_error when it cannot be made one.
Polyhedron read_polyhedron(const std::string& path) {
  const wqmesh::PolygonSoup soup = wqmesh::read_polyhedron_file(path);
  std::vector<K::Point_3> points;
  points.reserve(soup.points.size());
  for (const wqmesh::Point3& p : soup.points) points.emplace_back(p[0], p[1], p[2]);
  std::vector<std::vector<std::size_t>> polygons;
  polygons.reserve(soup.faces.size());
  for (const std::vector<int>& f : soup.faces) {
    std::vector<std::size_t> polygon;
    for (int v : f) {
      if (v < 0 || static_cast<std::size_t>(v) >= points.size()) throw std::runtime_error("bad vertex index");
      polygon.push_back(static_cast<std::size_t>(v));
    }
    polygons.push_back(std::move(polygon));
  }
  PMP::orient_polygon_soup(points, polygons);
  Polyhedron poly;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, poly);
  if (!PMP::triangulate_faces(poly)) throw std::runtime_error("a face could not be triangulated");
  if (!CGAL::is_closed(poly)) throw std::runtime_error("the surface is not closed");
  if (!PMP::is_outward_oriented(poly)) PMP::reverse_face_orientations(poly);
  return poly;
}

/// One make_mesh_3 run at size s. The domain's random numbers (`rng`, used
/// for its initial points and inside tests) and CGAL's default ones are
/// reseeded first, so that a size gives the same mesh in any process.
C3t3 mesh_at(const Domain& domain, CGAL::Random& rng, double s) {
  namespace params = CGAL::parameters;
  rng = CGAL::Random(0);
  CGAL::get_default_random() = CGAL::Random(0);
  const Criteria criteria(params::edge_size = s, params::facet_angle = 25, params::facet_size = s,
                          params::facet_distance = s / 10, params::cell_radius_edge_ratio = 2.2, params::cell_size = s);
  return CGAL::make_mesh_3<C3t3>(domain, criteria, params::perturb(), params::exude());
}

/// Interior tets as Medit (Vertices, Tetrahedra; vertices used by them only).
void write_medit(const std::string& path, const C3t3& c3t3) {
  std::map<Tr::Vertex_handle, std::size_t> index;
  std::vector<Tr::Vertex_handle> vertices;
  for (auto c = c3t3.cells_in_complex_begin(); c != c3t3.cells_in_complex_end(); ++c)
    for (int i = 0; i < 4; ++i)
      if (index.emplace(c->vertex(i), vertices.size()).second) vertices.push_back(c->vertex(i));
  std::ofstream out(path, std::ios::binary);
  if (!out) throw std::runtime_error("cannot write '" + path + "'");
  out << "MeshVersionFormatted 2\n\nDimension 3\n\nVertices\n" << vertices.size() << '\n';
  for (const Tr::Vertex_handle& v : vertices) {
    const K::Point_3 p = c3t3.triangulation().geom_traits().construct_point_3_object()(v->point());
    out << wqmesh::format_double(p.x()) << ' ' << wqmesh::format_double(p.y()) << ' ' << wqmesh::format_double(p.z())
        << " 0\n";
  }
  out << "\nTetrahedra\n" << c3t3.number_of_cells_in_complex() << '\n';
  for (auto c = c3t3.cells_in_complex_begin(); c != c3t3.cells_in_complex_end(); ++c)
    out << index[c->vertex(0)] + 1 << ' ' << index[c->vertex(1)] + 1 << ' ' << index[c->vertex(2)] + 1 << ' '
        << index[c->vertex(3)] + 1 << " 1\n";
  out << "\nEnd\n";
  if (!out) throw std::runtime_error("writing '" + path + "' failed");
}

std::size_t used_vertices(const C3t3& c3t3) {
  std::map<Tr::Vertex_handle, int> seen;
  for (auto c = c3t3.cells_in_complex_begin(); c != c3t3.cells_in_complex_end(); ++c)
    for (int i = 0; i < 4; ++i) seen.emplace(c->vertex(i), 0);
  return seen.size();
}

bool parse_number(const char* text, double& out) {
  char* end = nullptr;
  out = std::strtod(text, &end);
  return end != text && *end == '\0' && std::isfinite(out);
}

int run(int argc, char** argv) {
  std::string in, out;
  double size = 0, target = 0, tolerance = 0.2, max_steps = 12;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (a == "-o" && has_value) {
      out = argv[++i];
    } else if (a == "--size" && has_value) {
      if (!parse_number(argv[++i], size) || !(size > 0)) return std::cerr << "mesh3_peer: bad --size\n" << kUsage, 1;
    } else if (a == "--target-tets" && has_value) {
      if (!parse_number(argv[++i], target) || !(target >= 1))
        return std::cerr << "mesh3_peer: bad --target-tets\n" << kUsage, 1;
    } else if (a == "--tolerance" && has_value) {
      if (!parse_number(argv[++i], tolerance) || !(tolerance > 0))
        return std::cerr << "mesh3_peer: bad --tolerance\n" << kUsage, 1;
    } else if (a == "--max-steps" && has_value) {
      if (!parse_number(argv[++i], max_steps) || !(max_steps >= 1))
        return std::cerr << "mesh3_peer: bad --max-steps\n" << kUsage, 1;
    } else if (!a.empty() && a[0] != '-' && in.empty()) {
      in = a;
    } else {
      return std::cerr << "mesh3_peer: unexpected argument '" << a << "'\n" << kUsage, 1;
    }
  }
  if (in.empty() || (size > 0) == (target > 0)) return std::cerr << kUsage, 1;

  const auto t0 = Clock::now();
  Polyhedron poly;
  try {
    poly = read_polyhedron(in);
  } catch (const wqmesh::InputError& e) {
    std::cerr << "mesh3_peer: " << e.what() << "\n";
    return 2;
  } catch (const std::runtime_error& e) {
    std::cerr << "mesh3_peer: " << in << ": " << e.what() << "\n";
    return 2;
  }
  const double volume = std::fabs(PMP::volume(poly));
  CGAL::Random rng(0);
  Domain domain(poly, &rng);
  domain.detect_features();
  const double domain_time = seconds_since(t0);

  int steps = 0;
  double best_size = 0, best_ratio = 0;
  std::size_t best_tets = 0, previous_tets = 0;
  bool saturated = false;
  if (target > 0) {
    // Bracket [too small, too large] in log s, then bisect. A regular tet of
    // edge s has volume s^3 / (6 sqrt 2) ~ s^3 / 8.5: the first guess.
    double lo = 0, hi = 0;  // lo: a size with too many tets, hi: too few
    double s = std::cbrt(8.5 * volume / target);
    while (steps < static_cast<int>(max_steps)) {
      const auto t1 = Clock::now();
      const C3t3 c3t3 = mesh_at(domain, rng, s);
      ++steps;
      const std::size_t tets = c3t3.number_of_cells_in_complex();
      wqmesh::JsonWriter j(false);
      j.begin_object().field("probe", steps).field("size", s).field("tets", tets).field("time_s", seconds_since(t1));
      j.end_object();
      std::cout << j.str() << std::endl;
      const double ratio = tets > 0 ? std::fabs(std::log(double(tets) / target)) : 1e300;
      if (steps == 1 || ratio < best_ratio) best_size = s, best_ratio = ratio, best_tets = tets;
      if (std::fabs(double(tets) - target) <= tolerance * target) break;
      if (double(tets) > target) {
        // Doubling s no longer lowers the count: the protection of the
        // input's features alone needs more tets than the target.
        if (lo > 0 && hi == 0 && double(tets) >= 0.98 * double(previous_tets)) {
          saturated = true;
          break;
        }
        lo = s;
      } else {
        hi = s;
      }
      previous_tets = tets;
      s = (lo > 0 && hi > 0) ? std::sqrt(lo * hi) : (lo > 0 ? 2 * lo : hi / 2);
    }
  }
  wqmesh::JsonWriter j(false);
  j.begin_object();
  if (target > 0) {
    // The bisection's answer: the probe nearest the target (in log tets).
    j.field("size", best_size).field("steps", steps).field("tets", best_tets);
    j.field("within_tolerance", std::fabs(double(best_tets) - target) <= tolerance * target);
    j.field("target_tets", target).field("saturated", saturated);
  } else {
    const auto t2 = Clock::now();
    const C3t3 c3t3 = mesh_at(domain, rng, size);
    const double mesh_time = seconds_since(t2);
    if (!out.empty()) write_medit(out, c3t3);
    j.field("size", size).field("tets", c3t3.number_of_cells_in_complex()).field("vertices", used_vertices(c3t3));
    j.field("domain_time_s", domain_time).field("mesh_time_s", mesh_time);
  }
  j.field("input_volume", volume);
  j.end_object();
  std::cout << j.str() << std::endl;
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "mesh3_peer: internal error: " << e.what() << "\n";
    return 1;
  }
}
