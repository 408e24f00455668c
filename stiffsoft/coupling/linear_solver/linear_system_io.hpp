#pragma once
/// @file Newton linear systems H p = b on disk, in MatrixMarket: NAME.mtx holds H
/// ("coordinate real symmetric", its lower triangle, every stored entry of the assembly kept,
/// explicit zeros included, so the block pattern survives) and NAME_b.mtx holds b ("array").

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <filesystem>
#include <string>

namespace stiffsoft {

/// One system H p = b with H symmetric positive definite.
struct LinearSystem {
  std::string name;                   ///< file stem, e.g. "box_stack_step040"
  Eigen::SparseMatrix<double> upper;  ///< H's upper triangle, CSC, n × n
  Eigen::VectorXd b;                  ///< right-hand side (−g in Newton), n
};

/// Writes dir/NAME.mtx and dir/NAME_b.mtx (17 significant digits); throws std::runtime_error
/// when a file cannot be written.
void save_linear_system(const LinearSystem& system, const std::filesystem::path& dir);

/// Reads dir/NAME.mtx and dir/NAME_b.mtx; throws std::runtime_error naming the file and line
/// for a missing file, a header other than the two above, or a size mismatch.
LinearSystem load_linear_system(const std::filesystem::path& dir, const std::string& name);

}  // namespace stiffsoft
