// wqmesh: mesh one polyhedron with the C++ facade (wqmesh/wqmesh.h).
//   wqmesh_example IN.(off|stl) OUT.(mesh|vtu|ele) [rho]
// Prints the statistics as JSON on stdout. Exit code 0: meshed and written;
// 2: invalid input; 3: the run stopped (vertex limit or watchdog); 1: usage.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <cstdlib>
#include <exception>
#include <iostream>

#include <wqmesh/wqmesh.h>

int main(int argc, char** argv) {
  if (argc < 3) {
    std::cerr << "usage: " << argv[0] << " IN.(off|stl) OUT.(mesh|vtu|ele) [rho]\n";
    return 1;
  }
  try {
    wqmesh::Options options;
    if (argc > 3) options.set("rho", std::atof(argv[3]));
    const wqmesh::Polyhedron in = wqmesh::Polyhedron::read_file(argv[1], options);
    if (!in.valid()) {
      std::cerr << argv[1] << ": " << wqmesh::to_string(*in.error_kind()) << ": " << in.error_message() << "\n";
      return 2;
    }
    const wqmesh::Result result = wqmesh::mesh(in, options, [](const wqmesh::MeshProgress& p) {
      std::cerr << wqmesh::to_string(p.phase) << ": " << p.vertices << " vertices\n";
      return true;  // false would cancel the run
    });
    if (result.stop_reason() != wqmesh::StopReason::done) {
      std::cerr << "stopped: " << wqmesh::to_string(result.stop_reason()) << ": " << result.stop_message() << "\n";
      return 3;
    }
    result.write_file(argv[2]);
    std::cout << result.stats_json() << "\n";
    std::cerr << "wqmesh " << wqmesh::version() << ": " << result.mesh().tets.size() << " tets, smallest dihedral "
              << result.stats().min_dihedral_deg << " degrees\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}
