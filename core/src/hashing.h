// wqmesh: hashes of points by their exact coordinates (private).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cstdint>
#include <cstring>

#include "wqmesh/types.h"

namespace wqmesh {

/// Hash of a point by the bits of its coordinates: identical points (with -0
/// folded into +0 by the caller) hash alike. 64-bit arithmetic on every
/// platform (size_t is 32 bits in wasm).
struct PointHash {
  std::size_t operator()(const Point3& p) const {
    std::uint64_t h = 1469598103934665603ull;
    for (double x : p) {
      std::uint64_t bits;
      std::memcpy(&bits, &x, sizeof bits);
      h = (h ^ bits) * 1099511628211ull;
      h ^= h >> 29;
    }
    return static_cast<std::size_t>(h ^ (h >> 32));
  }
};

}  // namespace wqmesh
