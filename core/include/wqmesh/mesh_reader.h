// wqmesh: reading tetrahedral meshes written by wqmesh or by other meshers
// (Medit .mesh, TetGen .node/.ele), so that every mesh can be measured with
// the same quality module.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cstddef>
#include <string>

#include "wqmesh/error.h"
#include "wqmesh/types.h"

namespace wqmesh {

/// Reads a Medit ASCII mesh (.mesh): keywords are case-insensitive and may be
/// followed by their count on the same line or the next; `#` starts a comment.
/// Vertices (x y z ref), Tetrahedra (a b c d ref) and Triangles (a b c ref)
/// are kept: the triangles go to `boundary` with `boundary_facet` = ref - 1
/// (the reverse of write_medit). MeshVersionFormatted, Dimension (must be 3),
/// Edges, Corners, Ridges, Required*, Normals, Tangents, Quadrilaterals,
/// Hexahedra, Prisms and their kin are read and skipped; End or the end of the
/// data closes the mesh. Indices are 1-based in the file, 0-based in the
/// result. Tets are kept in the file's vertex order (no orientation is
/// enforced: see orient_tets_by_majority).
/// Throws InputError naming the 1-based line: empty, syntax (unknown keyword,
/// a token that is not a number, Dimension other than 3, a binary .meshb),
/// truncated (fewer entries than the count), bad_index (an index outside
/// 1..vertices, checked once the file is read), non_finite.
TetMesh read_medit(const char* data, std::size_t size);

/// Reads TetGen's .node and .ele (their contents). .node: `n dim attrs
/// markers`, then `i x y z [attributes] [marker]`; .ele: `m k attrs` (k = 4 or
/// 10: only the 4 corners are kept), then `i a b c d [...] [attributes]`. The
/// numbering starts at the first index of the .node file (0 or 1, as TetGen
/// does), and the .ele indices use the same base. `#` starts a comment.
/// Tets are kept in the file's vertex order. Errors as read_medit, with the
/// file ("node" or "ele") and the line in the message.
TetMesh read_tetgen(const char* node, std::size_t node_size, const char* ele, std::size_t ele_size);

/// Reads a mesh file, the format by name: `.mesh` is Medit; `.ele` or `.node`
/// (or a base name with neither, when BASE.ele exists) is TetGen, reading
/// BASE.node and BASE.ele beside each other. Throws InputError(io) when a
/// file cannot be read, (syntax) for another suffix; messages start with the
/// path.
TetMesh read_tet_mesh_file(const std::string& path);

/// Meshers disagree on the sign convention of a tet's vertex order. When more
/// tets have a negative signed volume than a positive one, swaps the last two
/// vertices of every tet (so the mesh follows TetMesh's contract) and returns
/// true; otherwise leaves the mesh as it is and returns false. Tets of zero or
/// inverted volume then remain as the minority with volume <= 0.
bool orient_tets_by_majority(TetMesh& mesh);

/// The number of distinct vertices used by the tets (files may list vertices
/// no tet uses, e.g. CGAL's far points).
std::size_t used_vertex_count(const TetMesh& mesh);

}  // namespace wqmesh
