// SPDX-License-Identifier: GPL-3.0-or-later
// wqmesh: writing tetrahedral meshes (Medit, VTK XML, TetGen) and the mesh
// statistics of section 6 (Table 2) as JSON. See wqmesh/output.h.
#include "wqmesh/output.h"

#include <cmath>
#include <fstream>
#include <limits>
#include <stdexcept>

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
    return format_double(v > 0 ? std::numeric_limits<double>::max()
                               : std::numeric_limits<double>::lowest());
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
    throw std::invalid_argument("write_vtu: " + std::to_string(quality.size()) +
                                " qualities for " + std::to_string(m) + " tets");
  if (labels != nullptr && labels->tet_class.size() != m)
    throw std::invalid_argument("write_vtu: " + std::to_string(labels->tet_class.size()) +
                                " labels for " + std::to_string(m) + " tets");
  if (!mesh.weights.empty() && mesh.weights.size() != n)
    throw std::invalid_argument("write_vtu: " + std::to_string(mesh.weights.size()) +
                                " weights for " + std::to_string(n) + " vertices");

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
      vtu_float_array(out, "min_dihedral", m,
                      [&](std::size_t i) { return quality[i].min_dihedral_deg; });
      vtu_float_array(out, "radius_edge", m, [&](std::size_t i) { return quality[i].radius_edge; });
      vtu_float_array(out, "aspect_ratio", m,
                      [&](std::size_t i) { return quality[i].aspect_ratio; });
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

void write_tetgen(const std::string& base, const TetMesh& mesh) {
  const std::string names[3] = {base + ".node", base + ".ele", base + ".face"};
  std::ofstream files[3];
  for (int i = 0; i < 3; ++i) {
    files[i].open(names[i]);
    if (!files[i]) throw std::runtime_error("write_tetgen: cannot open " + names[i]);
  }
  write_tetgen(files[0], files[1], files[2], mesh);
  for (int i = 0; i < 3; ++i) {
    files[i].close();
    if (!files[i]) throw std::runtime_error("write_tetgen: cannot write " + names[i]);
  }
}

void write_quality_bins(JsonWriter& j, const MeshStats& s) {
  j.key("radius_edge_bins").begin_object();
  j.field("0.6-1.4", s.radius_edge_bins[0]).field("1.4-2.2", s.radius_edge_bins[1]).field(">2.2", s.radius_edge_bins[2]);
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
