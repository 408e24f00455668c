#pragma once
/// @file A compact, exact binary file format for TetMesh (the mesh cache's format).

#include <cstdint>
#include <filesystem>

#include <stiffsoft/meshing/tet_mesh.hpp>

namespace stiffsoft {

/// Writes `mesh` bit-exactly, little-endian: the 8 bytes "STSFTETM", u32 format version 1,
/// u64 `tag` (free for the caller, e.g. a recipe hash), i64 |X|, i64 |T|, |X|·3 f64 (row by row),
/// |T|·4 i32, u64 number of node sets, then per set (in name order) u64 name length, the name's
/// bytes, u64 count, count i32. Written atomically (temporary file in the same folder, renamed).
/// @throws std::runtime_error naming the file when it cannot be written
void write_tet_mesh_binary(const std::filesystem::path& file, const TetMesh& mesh, std::uint64_t tag = 0);

/// Reads a file written by write_tet_mesh_binary() and checks it (check_tet_mesh).
/// @param tag set to the stored tag when not null
/// @throws std::runtime_error naming the file when it cannot be read, is not in this format
/// (magic, version, sizes, trailing bytes), or the mesh fails check_tet_mesh()
TetMesh read_tet_mesh_binary(const std::filesystem::path& file, std::uint64_t* tag = nullptr);

}  // namespace stiffsoft
