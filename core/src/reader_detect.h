// SPDX-License-Identifier: GPL-3.0-or-later
// wqmesh: telling OFF, ASCII STL, binary STL and anything else apart by
// content (private header of the readers; see input.h for the rules).
#pragma once

#include <cstddef>
#include <cstdint>

namespace wqmesh {

/// 3 when the data starts with a UTF-8 byte order mark (EF BB BF), else 0.
std::size_t utf8_bom_length(const char* data, std::size_t size);

/// 84 + 50 n for the triangle count n in bytes 80-83 (little endian): the
/// size of a binary STL with this header. Needs at least 84 bytes.
std::uint64_t binary_stl_size(const char* data);

/// True when the first word, after a byte order mark and blanks, begins with
/// `solid` (any case): an ASCII STL, unless its size makes it binary.
bool starts_with_solid(const char* data, std::size_t size);

/// Throws the error for content that is none of the formats: `what` is the
/// format(s) expected ("an OFF or STL file"). The message quotes the first
/// bytes escaped and the size a binary STL with this header would have;
/// kind truncated when shorter than the 84-byte binary header, else syntax.
[[noreturn]] void throw_unknown_format(const char* data, std::size_t size, const char* what);

}  // namespace wqmesh
