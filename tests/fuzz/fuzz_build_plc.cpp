// SPDX-License-Identifier: GPL-3.0-or-later
// wqmesh: libFuzzer target of the whole input path: bytes -> read_polyhedron
// (OFF or STL by content) -> build_plc (validation, orientation, merging).
// Contract under test: the path returns a soup and a PLC that keep the
// contracts of input.h and types.h, or throws wqmesh::InputError. Any other
// exception (CGAL's precondition failures included), a crash, a sanitizer
// report or a broken contract is a finding.
#include <cstddef>
#include <cstdint>

#include "fuzz_check.h"
#include "wqmesh/input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const wqmesh::PolygonSoup soup = wqmesh::read_polyhedron(reinterpret_cast<const char*>(data), size);
    wqmesh::fuzz::check_soup(soup, soup.format == "OFF" ? 0 : 3);
    wqmesh::Warnings warnings;
    wqmesh::MergeReport report;
    const wqmesh::PLC plc = wqmesh::build_plc(soup, warnings, &report);
    wqmesh::fuzz::check_plc(plc);
    wqmesh::fuzz::require(report.facets == plc.facets.size() && report.edges == plc.edges.size() &&
                              report.vertices - report.vertices_removed == plc.vertices.size(),
                          "the merge report counts the PLC");
  } catch (const wqmesh::InputError&) {
    // The input is rejected with a typed error: the expected outcome.
  }
  return 0;
}
