// wqmesh: reading OFF and STL polyhedra and turning them into a PLC
// (paper, section 2), with validation.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "wqmesh/error.h"
#include "wqmesh/types.h"

namespace wqmesh {

/// Limits on what an input may hold; beyond them, InputError(too_large).
struct InputLimits {
  std::size_t max_bytes = std::size_t(1) << 30;  ///< 1 GiB of file
  std::size_t max_points = 5'000'000;
  std::size_t max_faces = 10'000'000;
  std::size_t max_face_size = 100'000;  ///< vertices of one polygon
};

/// Reads an OFF file (ASCII; headers OFF, COFF, NOFF, CNOFF, STOFF...; `#`
/// comments anywhere; counts on the header line or the next, the edge count
/// optional; polygons of any size; whatever follows the coordinates of a
/// vertex (normals, colours) or the indices of a face (colours) on its line is
/// ignored). A UTF-8 byte order mark at the start is skipped; lines end in
/// LF, CRLF or a lone CR (each counts as one line end). Throws InputError
/// (syntax, truncated, too_large, non_finite, bad_index, empty) naming the
/// 1-based line and quoting the offending token escaped (escape_bytes).
/// face_line[i] is the line of face i's vertex count.
PolygonSoup read_off(const char* data, std::size_t size, const InputLimits& limits = {});

/// Reads an STL file, ASCII or binary, decided by content: binary exactly
/// when the size is 84 + 50 n for the n in bytes 80-83 of its header (even if
/// it starts with "solid"; no text file under InputLimits::max_bytes has such
/// a size, since four text bytes make n at least 0x09090909); else ASCII when
/// the first word (after a UTF-8 byte order mark and blanks) is `solid`; else
/// InputError(syntax) "not an STL file", quoting the first bytes and the size
/// a binary STL with that header would have (truncated when shorter than the
/// 84-byte header). Corners are merged when their coordinates are identical.
/// ASCII keywords are case-insensitive; lines end in LF, CRLF or CR; a facet
/// has exactly three vertices (a fourth `vertex` is a syntax error); normals
/// are not used (nor checked); several solids may follow one another.
/// face_line[i] is the line of triangle i's `facet` keyword (ASCII) or 0
/// (binary). Errors name the line (ASCII) or the 0-based triangle (binary).
PolygonSoup read_stl(const char* data, std::size_t size, const InputLimits& limits = {});

/// True when `token` is an OFF header keyword: "OFF" after optional letters
/// S, T, C, N (OFF, COFF, NOFF, CNOFF, STCOFF...).
bool is_off_keyword(const std::string& token);

/// Reads OFF or STL from bytes, deciding the format by content, not by name:
/// binary STL when the size matches its header exactly (see read_stl); OFF
/// when the first token after a UTF-8 byte order mark, blanks and `#`
/// comments is an OFF keyword; ASCII STL when it is `solid`; otherwise
/// InputError(syntax) "not an OFF or STL file", quoting the first bytes
/// (escaped) and the size a binary STL with that header would have
/// (truncated instead when the input is shorter than the 84-byte header).
PolygonSoup read_polyhedron(const char* data, std::size_t size, const InputLimits& limits = {});

/// The bytes quoted for a message: printable ASCII as is, backslash and
/// quote escaped, every other byte (NUL, control, non-ASCII) as \xHH, and
/// at most `max` bytes, followed by "..." when there were more. So a message
/// never ends early at a NUL and shows exactly what the input holds.
std::string escape_bytes(const char* data, std::size_t size, std::size_t max = 40);
inline std::string escape_bytes(const std::string& s, std::size_t max = 40) {
  return escape_bytes(s.data(), s.size(), max);
}

/// Reads a file from disk (throws InputError(io) if it cannot be read).
PolygonSoup read_polyhedron_file(const std::string& path, const InputLimits& limits = {});

/// What merging did, for the report: counts before (as read) and after (PLC).
struct MergeReport {
  std::size_t points_read = 0, vertices = 0;  ///< after identical points merge
  std::size_t faces_read = 0, facets = 0;
  std::size_t edges_before = 0, edges = 0;  ///< polygon edges vs PLC edges
  std::size_t vertices_removed = 0;         ///< inside a facet or a collinear chain
  std::size_t faces_split = 0;              ///< non-planar polygons split in triangles
  std::size_t faces_flipped = 0;            ///< orientation repaired
};

/// Validates a polygon soup and builds its PLC (paper, section 2).
/// Steps: merge identical points; reject empty input, non-finite coordinates,
/// bad indices, fewer than 4 faces, degenerate or duplicate faces, open
/// boundary, non-manifold edges or vertices, non-orientable surfaces and
/// self-intersections (exact predicates), each with an InputError naming it;
/// orient the surface consistently and outwards (with a warning when it had to
/// flip faces); split non-planar polygons into triangles (warning); merge
/// adjacent faces that are exactly coplanar into one facet; join exactly
/// collinear edge chains into one input edge; drop vertices that are then
/// inside a facet or an edge.
///
/// Details of the contract:
/// - Checks run in this order, the first failure is thrown: empty;
///   non_finite (any point, used or not); bad_index and degenerate_face for
///   faces of fewer than 3 vertices; degenerate_face for a vertex repeated
///   after merging; duplicate_face; degenerate_face for collinear vertices
///   (and self_intersection for a polygon whose projection is not simple);
///   non_manifold_edge; open_boundary; too_few_faces (so an open or
///   non-manifold soup is reported as such first); non_manifold_vertex;
///   not_orientable; self_intersection; zero_volume.
/// - Every polygon is triangulated (ear clipping) for the checks; a planar one
///   comes back as one facet through the coplanar merge, a non-planar one
///   stays split (its triangles are facets unless exactly coplanar).
/// - Orientation: each connected shell keeps the orientation of the majority
///   of its faces; then a shell inside an odd number of other shells (a
///   cavity) is oriented towards the cavity, every other shell outwards.
/// - PlcEdge::facets[0] is the facet whose loop runs from a to b, facets[1]
///   the one running from b to a.
/// - PLC vertices are in the order of the soup's points.
/// - MergeReport::vertices counts distinct used points; vertices_removed
///   those not in the PLC; faces_flipped the input faces reversed in all.
PLC build_plc(const PolygonSoup& soup, Warnings& warnings, MergeReport* report = nullptr);

}  // namespace wqmesh
