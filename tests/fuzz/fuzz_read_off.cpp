// SPDX-License-Identifier: GPL-3.0-or-later
// wqmesh: libFuzzer target of the OFF reader. Contract under test: read_off
// on any bytes returns a soup that keeps the contract of input.h, or throws
// wqmesh::InputError. Any other exception, a crash, a sanitizer report or a
// broken contract is a finding.
#include <cstddef>
#include <cstdint>

#include "fuzz_check.h"
#include "wqmesh/input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const wqmesh::PolygonSoup soup = wqmesh::read_off(reinterpret_cast<const char*>(data), size);
    wqmesh::fuzz::check_soup(soup, 0);
    wqmesh::fuzz::require(soup.format == "OFF", "the format is OFF");
  } catch (const wqmesh::InputError&) {
    // The input is rejected with a typed error: the expected outcome.
  }
  return 0;
}
