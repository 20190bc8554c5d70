// SPDX-License-Identifier: GPL-3.0-or-later
// wqmesh: writing tetrahedral meshes (Medit, VTK XML, TetGen) and the mesh
// statistics of section 6 (Table 2) as JSON. See wqmesh/output.h.
#include "wqmesh/output.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <stdexcept>
#include <utility>

#include "wqmesh/json.h"

namespace wqmesh {

namespace {

/// The input facet of boundary triangle i, or -1 (also when boundary_facet is
/// shorter than boundary).
int facet_of(const TetMesh& mesh, std::size_t i) {
  return i < mesh.boundary_facet.size() ? mesh.boundary_facet[i] : -1;
}

/// A double for VTK's ASCII reader, which does not parse "inf" or "nan":
/// finite values with round-trip precision, +-infinity clamped to the largest
/// finite double, NaN written as 0.
std::string vtk_double(double v) {
  if (std::isnan(v)) return "0";
  if (std::isinf(v))
    return format_double(v > 0 ? std::numeric_limits<double>::max() : std::numeric_limits<double>::lowest());
  return format_double(v);
}

void write_point(std::ostream& out, const Point3& p) {
  out << format_double(p[0]) << ' ' << format_double(p[1]) << ' ' << format_double(p[2]);
}

template <class Get>
void vtu_float_array(std::ostream& out, const char* name, std::size_t n, const Get& get) {
  out << "        <DataArray type=\"Float64\" Name=\"" << name << "\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < n; ++i) out << "          " << vtk_double(get(i)) << '\n';
  out << "        </DataArray>\n";
}

}  // namespace

void write_medit(std::ostream& out, const TetMesh& mesh) {
  out << "MeshVersionFormatted 2\n\nDimension 3\n\n";
  out << "Vertices\n" << mesh.vertices.size() << '\n';
  for (const Point3& p : mesh.vertices) {
    write_point(out, p);
    out << " 0\n";
  }
  out << "\nTetrahedra\n" << mesh.tets.size() << '\n';
  for (const std::array<int, 4>& t : mesh.tets)
    out << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << ' ' << t[3] + 1 << " 1\n";
  out << "\nTriangles\n" << mesh.boundary.size() << '\n';
  for (std::size_t i = 0; i < mesh.boundary.size(); ++i) {
    const std::array<int, 3>& f = mesh.boundary[i];
    out << f[0] + 1 << ' ' << f[1] + 1 << ' ' << f[2] + 1 << ' ' << facet_of(mesh, i) + 1 << '\n';
  }
  out << "\nEnd\n";
}

void write_vtu(std::ostream& out, const TetMesh& mesh, const std::vector<TetQuality>& quality,
               const TetLabels* labels) {
  const std::size_t n = mesh.vertices.size(), m = mesh.tets.size();
  if (!quality.empty() && quality.size() != m)
    throw std::invalid_argument("write_vtu: " + std::to_string(quality.size()) + " qualities for " + std::to_string(m) +
                                " tets");
  if (labels != nullptr && labels->tet_class.size() != m)
    throw std::invalid_argument("write_vtu: " + std::to_string(labels->tet_class.size()) + " labels for " +
                                std::to_string(m) + " tets");
  if (!mesh.weights.empty() && mesh.weights.size() != n)
    throw std::invalid_argument("write_vtu: " + std::to_string(mesh.weights.size()) + " weights for " +
                                std::to_string(n) + " vertices");

  out << "<?xml version=\"1.0\"?>\n"
         "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
         "  <UnstructuredGrid>\n"
      << "    <Piece NumberOfPoints=\"" << n << "\" NumberOfCells=\"" << m << "\">\n";

  if (!mesh.weights.empty()) {
    out << "      <PointData Scalars=\"weight\">\n";
    vtu_float_array(out, "weight", n, [&](std::size_t i) { return mesh.weights[i]; });
    out << "      </PointData>\n";
  }

  if (!quality.empty() || labels != nullptr) {
    out << "      <CellData>\n";
    if (!quality.empty()) {
      vtu_float_array(out, "min_dihedral", m, [&](std::size_t i) { return quality[i].min_dihedral_deg; });
      vtu_float_array(out, "radius_edge", m, [&](std::size_t i) { return quality[i].radius_edge; });
      // The weighted view beside it: the orthoradius-edge ratio with the
      // point data's weights (the paper's rho for a pumped mesh).
      if (!mesh.weights.empty()) {
        const std::vector<TetQuality> weighted = mesh_quality(mesh, {}, true);
        vtu_float_array(out, "orthoradius_edge", m, [&](std::size_t i) { return weighted[i].radius_edge; });
      }
      // Circumradius over inradius, 3 for a regular tet: not VTK's normalised
      // "aspect_ratio" or "radius_ratio" (1 for a regular tet), hence the name.
      vtu_float_array(out, "radius_ratio_R_over_r", m, [&](std::size_t i) { return quality[i].aspect_ratio; });
      vtu_float_array(out, "volume", m, [&](std::size_t i) { return quality[i].volume; });
    }
    if (labels != nullptr) {
      out << "        <DataArray type=\"Int32\" Name=\"class\" format=\"ascii\">\n";
      for (int c : labels->tet_class) out << "          " << c << '\n';
      out << "        </DataArray>\n";
    }
    out << "      </CellData>\n";
  }

  out << "      <Points>\n"
         "        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (const Point3& p : mesh.vertices) {
    out << "          ";
    write_point(out, p);
    out << '\n';
  }
  out << "        </DataArray>\n"
         "      </Points>\n"
         "      <Cells>\n"
         "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  for (const std::array<int, 4>& t : mesh.tets)
    out << "          " << t[0] << ' ' << t[1] << ' ' << t[2] << ' ' << t[3] << '\n';
  out << "        </DataArray>\n"
         "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < m; ++i) out << "          " << 4 * (i + 1) << '\n';
  out << "        </DataArray>\n"
         "        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  // VTK_TETRA = 10.
  for (std::size_t i = 0; i < m; ++i) out << "          10\n";
  out << "        </DataArray>\n"
         "      </Cells>\n"
         "    </Piece>\n"
         "  </UnstructuredGrid>\n"
         "</VTKFile>\n";
}

void write_tetgen(std::ostream& node, std::ostream& ele, std::ostream& face, const TetMesh& mesh) {
  node << mesh.vertices.size() << " 3 0 0\n";
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    node << i << ' ';
    write_point(node, mesh.vertices[i]);
    node << '\n';
  }
  ele << mesh.tets.size() << " 4 0\n";
  for (std::size_t i = 0; i < mesh.tets.size(); ++i) {
    const std::array<int, 4>& t = mesh.tets[i];
    ele << i << ' ' << t[0] << ' ' << t[1] << ' ' << t[2] << ' ' << t[3] << '\n';
  }
  face << mesh.boundary.size() << " 1\n";
  for (std::size_t i = 0; i < mesh.boundary.size(); ++i) {
    const std::array<int, 3>& f = mesh.boundary[i];
    face << i << ' ' << f[0] << ' ' << f[1] << ' ' << f[2] << ' ' << facet_of(mesh, i) + 1 << '\n';
  }
}

std::vector<std::array<int, 2>> boundary_segments(const TetMesh& mesh) {
  // Each edge of the closed boundary with the facets of the triangles at it.
  std::map<std::pair<int, int>, std::vector<int>> facets;
  for (std::size_t i = 0; i < mesh.boundary.size(); ++i) {
    const std::array<int, 3>& f = mesh.boundary[i];
    for (int k = 0; k < 3; ++k) {
      const int a = f[k], b = f[(k + 1) % 3];
      facets[{std::min(a, b), std::max(a, b)}].push_back(facet_of(mesh, i));
    }
  }
  std::vector<std::array<int, 2>> edges;
  for (const auto& [edge, fs] : facets) {
    bool segment = fs.size() != 2;  // a border edge or a non-manifold one: keep it
    for (int f : fs) segment = segment || f < 0 || f != fs[0];
    if (segment) edges.push_back({{edge.first, edge.second}});
  }
  // Orient the subsegments of each chain one way (TetGen's -r links two
  // subsegments at a vertex only when one ends where the next begins): walk
  // from every vertex that is not inside a chain (not on exactly two
  // subsegments) along the unvisited subsegments, then around closed loops.
  std::map<int, std::vector<std::size_t>> at;  // vertex -> its subsegments
  for (std::size_t i = 0; i < edges.size(); ++i)
    for (int v : edges[i]) at[v].push_back(i);
  std::vector<bool> done(edges.size(), false);
  std::vector<std::array<int, 2>> out;
  auto walk = [&](int v, std::size_t e) {
    while (!done[e]) {
      done[e] = true;
      const int w = edges[e][0] == v ? edges[e][1] : edges[e][0];
      out.push_back({{v, w}});
      const std::vector<std::size_t>& next = at[w];
      if (next.size() != 2) break;
      e = next[0] == e ? next[1] : next[0];
      v = w;
    }
  };
  for (int pass = 0; pass < 2; ++pass)
    for (const auto& [v, es] : at)
      if (pass == 1 || es.size() != 2)
        for (std::size_t e : es) walk(v, e);
  return out;
}

void write_tetgen_edges(std::ostream& edge, const TetMesh& mesh) {
  const std::vector<std::array<int, 2>> segments = boundary_segments(mesh);
  edge << segments.size() << " 1\n";
  for (std::size_t i = 0; i < segments.size(); ++i)
    edge << i << ' ' << segments[i][0] << ' ' << segments[i][1] << " 1\n";
}

void write_tetgen(std::ostream& node, std::ostream& ele, std::ostream& face, std::ostream& edge, const TetMesh& mesh) {
  write_tetgen(node, ele, face, mesh);
  write_tetgen_edges(edge, mesh);
}

void write_tetgen(const std::string& base, const TetMesh& mesh) {
  const std::string names[4] = {base + ".node", base + ".ele", base + ".face", base + ".edge"};
  std::ofstream files[4];
  for (int i = 0; i < 4; ++i) {
    files[i].open(names[i]);
    if (!files[i]) throw std::runtime_error("write_tetgen: cannot open " + names[i]);
  }
  write_tetgen(files[0], files[1], files[2], files[3], mesh);
  for (int i = 0; i < 4; ++i) {
    files[i].close();
    if (!files[i]) throw std::runtime_error("write_tetgen: cannot write " + names[i]);
  }
}

void write_quality_bins(JsonWriter& j, const MeshStats& s) {
  j.key("radius_edge_bins").begin_object();
  j.field("0.6-1.4", s.radius_edge_bins[0])
      .field("1.4-2.2", s.radius_edge_bins[1])
      .field(">2.2", s.radius_edge_bins[2]);
  j.end_object();
  j.key("dihedral_bins").begin_object();
  j.field("0-3", s.dihedral_bins[0]).field("3-5", s.dihedral_bins[1]).field("5-10", s.dihedral_bins[2]);
  j.end_object();
}

std::string stats_json(const MeshStats& s, bool pretty) {
  JsonWriter j(pretty);
  j.begin_object();
  j.field("vertices", s.vertices);
  j.field("tets", s.tets);
  j.field("volume", s.volume);
  j.field("inverted", s.inverted);
  j.field("min_dihedral_deg", s.min_dihedral_deg);
  j.field("max_dihedral_deg", s.max_dihedral_deg);
  j.field("min_face_angle_deg", s.min_face_angle_deg);
  j.field("max_radius_edge", s.max_radius_edge);
  j.field("max_aspect_ratio", s.max_aspect_ratio);
  j.field("radius_edge_below", s.radius_edge_below);
  write_quality_bins(j, s);
  j.field("slivers", s.slivers);
  j.key("min_dihedral_histogram").begin_array();
  for (std::size_t c : s.min_dihedral_histogram) j.value(c);
  j.end_array();
  j.key("min_face_angle_histogram").begin_array();
  for (std::size_t c : s.min_face_angle_histogram) j.value(c);
  j.end_array();
  j.end_object();
  return j.str();
}

}  // namespace wqmesh
