// SPDX-License-Identifier: GPL-3.0-or-later
// wqmesh: telling OFF, ASCII STL, binary STL and anything else apart by
// content (private header of the readers; see input.h for the rules).
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>

namespace wqmesh {

/// 3 when the data starts with a UTF-8 byte order mark (EF BB BF), else 0.
std::size_t utf8_bom_length(const char* data, std::size_t size);

/// The bytes of the file at `path`. Throws InputError: io when it is a folder
/// or cannot be opened ("cannot open 'PATH': REASON") or read; too_large when
/// it has more than `max_bytes` bytes ("'PATH' has N bytes, beyond the limit
/// of M"), before reading any.
std::string read_file_bytes(const std::string& path, std::size_t max_bytes = std::numeric_limits<std::size_t>::max());

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
