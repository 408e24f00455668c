#pragma once
/// @file Reader of CCD benchmark query files (Wang et al. 2021, "A Large Scale Benchmark and an
/// Inclusion-Based Algorithm for Continuous Collision Detection"; format in
/// ../shared/data/ccd-queries/README.md): 8 rows per query, each row a vertex as 3 rationals
/// (numerator, denominator pairs of integers) and the ground truth (1 = the primitives touch).

#include <Eigen/Core>
#include <array>
#include <filesystem>
#include <vector>

#include <stiffsoft/coupling/ccd/ccd_settings.hpp>

namespace stiffsoft::ccd {

/// Which pair of primitives a query file holds.
enum class CcdQueryKind {
  point_triangle,  ///< rows p, t0, t1, t2 at t = 0, then the same at t = 1 ("vertex-face")
  edge_edge,       ///< rows ea0, ea1, eb0, eb1 at t = 0, then the same at t = 1 ("edge-edge")
};

/// One CCD query with its exact ground truth.
struct CcdQuery {
  std::array<Eigen::Vector3d, 8> vertices;  ///< the 8 rows in file order, metres
  bool collides = false;                    ///< ground truth: contact for some t ∈ [0, 1]
};

/// Reads every query of one file. Coordinates are parsed as double(numerator) /
/// double(denominator), each integer converted with correct rounding from its decimal string
/// (numerators reach ~10³⁴, beyond any integer type); this is exact for the benchmark data,
/// whose denominators are powers of two. Throws std::runtime_error naming the file (and line)
/// when it cannot be opened or a row is malformed.
std::vector<CcdQuery> read_ccd_queries(const std::filesystem::path& file);

/// Kind of the queries in `file`, from its path: "vertex-face" → point_triangle, "edge-edge" →
/// edge_edge. Throws std::runtime_error when the path names neither.
CcdQueryKind ccd_query_kind(const std::filesystem::path& file);

/// Distance (m) between the primitives of `query` at time t, in long double: positions
/// (1 − t)·x0 + t·x1 and the distance are evaluated with 64-bit mantissas, as a reference to check
/// the double-precision CCD against.
long double query_distance(CcdQueryKind kind, const CcdQuery& query, long double t);

/// Time of impact of `query` (point_triangle_toi or edge_edge_toi by `kind`).
double query_toi(CcdQueryKind kind, const CcdQuery& query, const CcdSettings& settings);

}  // namespace stiffsoft::ccd
