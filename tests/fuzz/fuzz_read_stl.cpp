// SPDX-License-Identifier: GPL-3.0-or-later
// wqmesh: libFuzzer target of the STL reader (ASCII and binary). Contract
// under test: read_stl on any bytes returns a soup that keeps the contract of
// input.h (a binary soup has triangles on line 0), or throws
// wqmesh::InputError. Any other exception, a crash, a sanitizer report or a
// broken contract is a finding.
#include <cstddef>
#include <cstdint>

#include "fuzz_check.h"
#include "wqmesh/input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const wqmesh::PolygonSoup soup = wqmesh::read_stl(reinterpret_cast<const char*>(data), size);
    wqmesh::fuzz::check_soup(soup, 3);
    if (soup.format == "STL-binary") {
      for (std::size_t f = 0; f < soup.faces.size(); ++f)
        wqmesh::fuzz::require(soup.faces[f].size() == 3 && soup.face_line[f] == 0,
                              "a binary STL face is a triangle on line 0");
    } else {
      wqmesh::fuzz::require(soup.format == "STL-ascii", "the format is STL-ascii or STL-binary");
    }
  } catch (const wqmesh::InputError&) {
    // The input is rejected with a typed error: the expected outcome.
  }
  return 0;
}
