/// Linear-solver layer: the 3×3-block layout of the assembled Hessian, every backend (CHOLMOD,
/// the block Cholesky and block CG,
/// PETSc KSP with each preconditioner) on the same SPD Newton systems from real scenes (stored
/// under tests/coupling/data/linear_systems) to the requested residual, pattern reuse, failure
/// reports on indefinite matrices and iteration caps, the CHOLMOD fallback, PETSc's options
/// database, Eisenstat–Walker forcing terms, the command-line split, and an `mpirun -n 2` run
/// that must agree with the serial solve.

#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <random>
#include <set>

#include <stiffsoft/coupling/linear_solver/auto_solver.hpp>
#include <stiffsoft/coupling/linear_solver/block_cholesky_solver.hpp>
#include <stiffsoft/coupling/linear_solver/block_jacobi.hpp>
#include <stiffsoft/coupling/linear_solver/block_sparse_pattern.hpp>
#include <stiffsoft/coupling/linear_solver/cholmod_solver.hpp>
#include <stiffsoft/coupling/linear_solver/forcing_term.hpp>
#include <stiffsoft/coupling/linear_solver/linear_system_io.hpp>
#include "apps/cli/petsc_arguments.hpp"
#include <stiffsoft/coupling/linear_solver/petsc_session.hpp>
#include <stiffsoft/coupling/linear_solver/petsc_solver.hpp>
#include <temporary_folder.hpp>

extern char** environ;

namespace stiffsoft {
namespace {

const std::filesystem::path kDataDir =
    std::filesystem::path(STIFFSOFT_SOURCE_DIR) / "tests/coupling/data/linear_systems";
/// Hessians of Newton iterations of real scenes (bench/linear_solver_bench --dump, see the
/// folder's README.md): box_stack (10 boxes, a chain of 9 contacts), house_of_cards (15
/// cards, 18 contacts with loops: the hardest for Krylov), light (11 free bodies, no contact).
const std::vector<std::string> kSystems{"box_stack_step60", "house_of_cards_step8", "light_step30"};

double relative_residual(const LinearSystem& s, const Eigen::VectorXd& p) {
  return (s.b - s.upper.selfadjointView<Eigen::Upper>() * p).norm() / s.b.norm();
}

Eigen::MatrixXd dense(const Eigen::SparseMatrix<double>& upper) {
  const Eigen::SparseMatrix<double> full = upper.selfadjointView<Eigen::Upper>();
  return Eigen::MatrixXd(full);
}

/// A random symmetric matrix over DOF blocks of the given sizes with some off-diagonal block
/// couplings, as its upper triangle: dense diagonal blocks, dense coupled blocks.
Eigen::SparseMatrix<double> random_block_upper(const std::vector<int>& sizes, int couplings, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<int> offsets{0};
  for (int s : sizes) offsets.push_back(offsets.back() + s);
  const int n = offsets.back();
  std::vector<Eigen::Triplet<double>> t;
  for (std::size_t b = 0; b < sizes.size(); ++b)
    for (int r = offsets[b]; r < offsets[b + 1]; ++r)
      for (int c = r; c < offsets[b + 1]; ++c) t.emplace_back(r, c, r == c ? 50 + u(rng) : u(rng));
  std::uniform_int_distribution<int> pick(0, int(sizes.size()) - 1);
  for (int k = 0; k < couplings; ++k) {
    int a = pick(rng), b = pick(rng);
    if (a == b) continue;
    if (a > b) std::swap(a, b);
    for (int r = offsets[a]; r < offsets[a + 1]; ++r)
      for (int c = offsets[b]; c < offsets[b + 1]; ++c) t.emplace_back(r, c, u(rng));
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(t.begin(), t.end(), [](double, double b) { return b; });
  A.makeCompressed();
  return A;
}

/// The dense matrix a BlockSparsePattern stores (mirrored where the storage holds upper blocks only).
Eigen::MatrixXd from_blocks(const BlockSparsePattern& p, const std::vector<double>& values) {
  const int n = 3 * p.num_block_rows();
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < p.row_end() - p.row_begin(); ++i)
    for (int k = p.row_offsets()[i]; k < p.row_offsets()[i + 1]; ++k) {
      const int I = p.row_begin() + i, J = p.block_columns()[k];
      const Eigen::Map<const Eigen::Matrix3d> block(values.data() + 9 * k);  // column-major
      M.block<3, 3>(3 * I, 3 * J) = block;
      if (p.storage() == BlockStorage::Upper && I != J) M.block<3, 3>(3 * J, 3 * I) = block.transpose();
    }
  return M;
}

// --- block layout --------------------------------------------------------------------------

TEST(BlockSparsePattern, StoresTheWholeSymmetricMatrixInEitherStorage) {
  const Eigen::SparseMatrix<double> A = random_block_upper({12, 3, 12, 3, 3, 12}, 6, 1);
  for (const BlockStorage storage : {BlockStorage::Full, BlockStorage::Upper}) {
    const BlockSparsePattern p(A, storage);
    std::vector<double> values;
    p.gather_values(A, values);
    EXPECT_EQ(values.size(), p.num_values());
    EXPECT_EQ((from_blocks(p, values) - dense(A)).norm(), 0.0);
    if (storage == BlockStorage::Upper) {
      for (int I = 0; I < p.num_block_rows(); ++I)
        for (int k = p.row_offsets()[I]; k < p.row_offsets()[I + 1]; ++k) {
          EXPECT_GE(p.block_columns()[k], I);
        }
    }
  }
}

TEST(BlockSparsePattern, OwnedRowRangesTogetherGiveTheWholeMatrix) {
  const Eigen::SparseMatrix<double> A = random_block_upper({12, 12, 3, 3, 12, 3}, 8, 2);
  const std::vector<int> bounds = split_rows({12, 12, 3, 3, 12, 3}, 3);
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(A.rows(), A.cols());
  for (int part = 0; part < 3; ++part) {
    const BlockSparsePattern p(A, BlockStorage::Full, bounds[part] / 3, bounds[part + 1] / 3);
    std::vector<double> values;
    p.gather_values(A, values);
    M += from_blocks(p, values);
  }
  EXPECT_EQ((M - dense(A)).norm(), 0.0);
}

TEST(BlockSparsePattern, RejectsLowerEntriesAndSizesNotAMultipleOfThree) {
  Eigen::SparseMatrix<double> lower(6, 6);
  lower.insert(4, 1) = 1;
  lower.makeCompressed();
  EXPECT_THROW(BlockSparsePattern(lower, BlockStorage::Full), std::invalid_argument);
  Eigen::SparseMatrix<double> odd(7, 7);
  odd.makeCompressed();
  EXPECT_THROW(BlockSparsePattern(odd, BlockStorage::Full), std::invalid_argument);
}

TEST(BlockSparsePattern, DetectsAChangedPattern) {
  const Eigen::SparseMatrix<double> A = random_block_upper({12, 12, 12}, 1, 3);
  const BlockSparsePattern p(A, BlockStorage::Full);
  EXPECT_TRUE(p.same_pattern(A));
  const Eigen::SparseMatrix<double> B = random_block_upper({12, 12, 12}, 3, 4);
  EXPECT_FALSE(p.same_pattern(B));
}

TEST(BlockSparsePattern, GathersFromTheBlocksWhatItGathersFromTheirCompressedCopy) {
  const std::vector<int> sizes{12, 3, 12, 3, 3, 12, 3};
  const GatheredBlocks g = gather_blocks(random_block_upper(sizes, 9, 5), sizes);
  const double shift = 0.7;
  const Eigen::SparseMatrix<double> compressed = g.blocks.compressed(shift);
  const std::vector<int> bounds = split_rows(sizes, 2);
  for (const BlockStorage storage : {BlockStorage::Full, BlockStorage::Upper})
    for (int part = -1; part < 2; ++part) {  // all rows, then each half
      BlockSparsePattern p = part < 0 ? BlockSparsePattern(compressed, storage)
                                      : BlockSparsePattern(compressed, storage, bounds[part] / 3, bounds[part + 1] / 3);
      std::vector<double> expected, values;
      p.gather_values(compressed, expected);
      p.map_blocks(g.blocks);
      values.resize(p.num_values());
      p.gather_values(g.blocks, shift, values.data());
      EXPECT_EQ(values, expected) << "storage " << int(storage) << ", part " << part;  // bit for bit
      if (part < 0) {
        const Eigen::SparseMatrix<double> back = p.upper(values.data());
        EXPECT_TRUE(p.same_pattern(back));
        EXPECT_EQ((dense(back) - dense(compressed)).norm(), 0.0);
      } else {
        EXPECT_THROW(p.upper(values.data()), std::logic_error);
      }
    }
}

TEST(BlockSparsePattern, RefusesToMapBlocksItsPatternLacks) {
  const std::vector<int> sizes{12, 3, 3, 12};
  const GatheredBlocks few = gather_blocks(random_block_upper(sizes, 1, 6), sizes);
  const GatheredBlocks more = gather_blocks(random_block_upper(sizes, 6, 7), sizes);
  BlockSparsePattern p(few.blocks.compressed(), BlockStorage::Upper);
  EXPECT_THROW(p.map_blocks(more.blocks), std::invalid_argument);
  std::vector<double> values(p.num_values());
  EXPECT_THROW(p.gather_values(more.blocks, 0.0, values.data()), std::logic_error);  // not mapped
}

TEST(InferBlockSizes, FindsAffineBodiesAndSoftNodes) {
  const std::vector<int> sizes{12, 3, 3, 12, 12, 3};
  EXPECT_EQ(infer_block_sizes(random_block_upper(sizes, 0, 5)), sizes);
}

TEST(SplitRows, NeverCutsABlockAndBalancesRows) {
  const std::vector<int> bounds = split_rows({12, 12, 12, 12, 3, 3, 3, 3}, 2);
  ASSERT_EQ(bounds.size(), 3u);
  EXPECT_EQ(bounds.front(), 0);
  EXPECT_EQ(bounds[1], 36);  // 36 | 24 is as even as whole 12-blocks allow (30 is the middle)
  EXPECT_EQ(bounds.back(), 60);
  EXPECT_THROW(split_rows({12}, 0), std::invalid_argument);
}

TEST(BlockJacobi, AppliesTheInverseOfEachDiagonalBlock) {
  const std::vector<int> sizes{12, 3, 12};
  const Eigen::SparseMatrix<double> A = random_block_upper(sizes, 3, 6);
  BlockJacobi P(sizes, 0, 27);
  ASSERT_TRUE(P.compute(A));
  const Eigen::MatrixXd H = dense(A);
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(27, 27);
  for (int o : {0, 12, 15}) {
    const int s = o == 12 ? 3 : 12;
    D.block(o, o, s, s) = H.block(o, o, s, s);
  }
  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(27, -1, 2);
  Eigen::VectorXd y(27);
  P.apply(x.data(), y.data());
  EXPECT_LT((D * y - x).norm(), 1e-12 * x.norm());
  EXPECT_THROW(BlockJacobi(sizes, 0, 13), std::invalid_argument);  // cuts the second block
}

// --- every backend on stored Newton systems -----------------------------------------------------

TEST(LinearSystemIo, StoredSystemsAreSymmetricPositiveDefinite) {
  const std::filesystem::path dir = stiffsoft::testing::temporary_folder("stiffsoft_linear_system_io");
  for (const std::string& name : kSystems) {
    const LinearSystem s = load_linear_system(kDataDir, name);
    EXPECT_EQ(s.upper.rows() % 12, 0) << name;
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(dense(s.upper), Eigen::EigenvaluesOnly);
    EXPECT_GT(eig.eigenvalues().minCoeff(), 0) << name;
    save_linear_system(s, dir);
    const LinearSystem again = load_linear_system(dir, name);
    EXPECT_EQ((Eigen::MatrixXd(again.upper) - Eigen::MatrixXd(s.upper)).norm(), 0.0) << name;
    EXPECT_EQ((again.b - s.b).norm(), 0.0) << name;
  }
}

const std::vector<std::string> kBackends{"cholmod",
                                         "petsc:cg:none",
                                         "petsc:cg:jacobi",
                                         "petsc:cg:pbjacobi",
                                         "petsc:cg:vpbjacobi",
                                         "petsc:cg:icc",
                                         "petsc:cg:gamg",
                                         "petsc:cg:hypre",
                                         "petsc:minres:vpbjacobi",
                                         "petsc:minres:jacobi",
                                         "petsc:gmres:icc",
                                         "petsc",
                                         "block_cholesky",
                                         "block_cg",
                                         "auto"};

TEST(LinearSolver, EveryBackendSolvesTheStoredSystemsToTheRequestedResidual) {
  // Unpreconditioned CG needs 1227 iterations on house_of_cards at η = 1e-10 (MINRES with
  // Jacobi 1008), beyond the default cap of 1000 that hands such solves to the fallback.
  set_petsc_option("-ksp_max_it", "5000");
  for (const double eta : {1e-10, 1e-4}) {
    for (const std::string& name : kSystems) {
      const LinearSystem s = load_linear_system(kDataDir, name);
      for (const std::string& backend : kBackends) {
        SCOPED_TRACE(backend + " on " + name + ", eta " + std::to_string(eta));
        std::unique_ptr<LinearSolver> solver = make_linear_solver(backend);
        solver->set_relative_tolerance(eta);
        solver->analyze_pattern(s.upper);
        ASSERT_TRUE(solver->factorize(s.upper));
        const Eigen::VectorXd p = solver->solve(s.b);
        const LinearSolveReport& r = solver->last_report();
        EXPECT_TRUE(r.converged()) << to_string(r.status) << ": " << r.reason;
        EXPECT_FALSE(r.fallback_used) << r.primary_failure;
        const double residual = relative_residual(s, p);
        const double requested = solver->is_iterative() ? eta : 1e-10;
        EXPECT_LE(residual, requested);
        // The report's residual is the true one.
        EXPECT_NEAR(r.relative_residual, residual, 1e-3 * requested);
        if (solver->is_iterative()) {
          EXPECT_GT(r.iterations, 0);
        }
      }
    }
  }
  clear_petsc_option("-ksp_max_it");
}

TEST(PetscSolver, BaijAndSbaijGiveTheSameSolution) {
  const LinearSystem s = load_linear_system(kDataDir, kSystems[0]);
  Eigen::VectorXd p[2];
  int k = 0;
  for (const char* type : {"baij", "sbaij"}) {
    PetscSolverSettings settings;
    settings.pc_type = "jacobi";
    settings.matrix_type = type;
    settings.relative_tolerance = 1e-12;
    PetscSolver solver(settings);
    solver.analyze_pattern(s.upper);
    ASSERT_TRUE(solver.factorize(s.upper));
    p[k++] = solver.solve(s.b);
    EXPECT_TRUE(solver.last_report().converged());
  }
  EXPECT_LT((p[0] - p[1]).norm(), 1e-8 * p[0].norm());
}

TEST(PetscSolver, ReusesTheMatrixWhileThePatternIsUnchanged) {
  const LinearSystem s = load_linear_system(kDataDir, kSystems[1]);
  PetscSolverSettings settings;
  settings.relative_tolerance = 1e-10;
  PetscSolver solver(settings);
  solver.analyze_pattern(s.upper);
  Eigen::SparseMatrix<double> H = s.upper;
  for (int k = 0; k < 3; ++k) {
    // Same pattern, new values (as Newton's next iteration, or its diagonal shift).
    for (int i = 0; i < H.rows(); ++i) H.coeffRef(i, i) *= 1.5;
    ASSERT_TRUE(solver.factorize(H));
    const Eigen::VectorXd p = solver.solve(s.b);
    EXPECT_LE((s.b - H.selfadjointView<Eigen::Upper>() * p).norm() / s.b.norm(), 1e-10);
  }
  EXPECT_EQ(solver.preallocations(), 1);
  // A different pattern (another system) is noticed even without analyze_pattern().
  const LinearSystem other = load_linear_system(kDataDir, kSystems[2]);
  ASSERT_TRUE(solver.factorize(other.upper));
  EXPECT_LE(relative_residual(other, solver.solve(other.b)), 1e-10);
  EXPECT_EQ(solver.preallocations(), 2);
}

TEST(PetscSolver, KeepsItsAnalysisWhenAnalysingThePatternAgain) {
  // Each time step starts a new Hessian, often of the last step's pattern, and analyses it.
  const LinearSystem s = load_linear_system(kDataDir, kSystems[1]);
  PetscSolverSettings settings;
  settings.relative_tolerance = 1e-10;
  PetscSolver solver(settings);
  solver.analyze_pattern(s.upper);
  ASSERT_TRUE(solver.factorize(s.upper));
  const Eigen::VectorXd first = solver.solve(s.b);
  solver.analyze_pattern(s.upper);
  EXPECT_EQ(solver.preallocations(), 1);
  ASSERT_TRUE(solver.factorize(s.upper));
  EXPECT_EQ(solver.solve(s.b), first);  // the same solve, bit for bit
  const LinearSystem other = load_linear_system(kDataDir, kSystems[2]);
  solver.analyze_pattern(other.upper);
  EXPECT_EQ(solver.preallocations(), 2);
  ASSERT_TRUE(solver.factorize(other.upper));
  EXPECT_LE(relative_residual(other, solver.solve(other.b)), 1e-10);
}

TEST(PetscSolver, FactorisesBlocksInPlaceAsItsCompressedCopyAndFallsBackFromThem) {
  // Newton's path: the Hessian's blocks copied into PETSc's without a compressed matrix; the
  // CHOLMOD fallback forms one only when it runs.
  const LinearSystem s = load_linear_system(kDataDir, kSystems[1]);
  const GatheredBlocks g = gather_blocks(s.upper, infer_block_sizes(s.upper));
  const double shift = 1e-3 * s.upper.diagonal().cwiseAbs().maxCoeff();
  // ICC on SBAIJ (upper blocks) and Jacobi on BAIJ (every block); a cap of 3 CG iterations
  // sends every solve to the fallback.
  for (const auto& [pc, cap] : std::vector<std::pair<std::string, int>>{{"icc", 1000}, {"icc", 3}, {"jacobi", 1000}}) {
    PetscSolverSettings settings;
    settings.pc_type = pc;
    settings.relative_tolerance = 1e-10;
    settings.max_iterations = cap;
    PetscSolver compressed(settings), blocks(settings);
    compressed.analyze_pattern(g.blocks.compressed());
    for (int k = 0; k < 3; ++k) {  // new values each time (the first pass also checks PETSc's layout)
      ASSERT_TRUE(compressed.factorize(g.blocks.compressed((k + 1) * shift)));
      const Eigen::VectorXd expected = compressed.solve(s.b);
      blocks.analyze_blocks(g.blocks);
      ASSERT_TRUE(blocks.factorize_blocks(g.blocks, (k + 1) * shift));
      EXPECT_EQ(blocks.solve(s.b), expected) << pc << ", cap " << cap << ", pass " << k;  // bit for bit
      EXPECT_EQ(blocks.last_report().fallback_used, cap == 3);
    }
    EXPECT_EQ(blocks.preallocations(), 1);
  }
}

TEST(PetscSolver, UsesGivenDofBlocksAndChecksThem) {
  const LinearSystem s = load_linear_system(kDataDir, kSystems[0]);
  PetscSolverSettings settings;
  settings.pc_type = "vpbjacobi";
  PetscSolver solver(settings);
  solver.set_block_sizes(std::vector<int>(s.upper.rows() / 12, 12));
  solver.analyze_pattern(s.upper);
  ASSERT_TRUE(solver.factorize(s.upper));
  EXPECT_LE(relative_residual(s, solver.solve(s.b)), 1e-8);
  PetscSolver wrong;
  wrong.set_block_sizes({12, 12});
  EXPECT_THROW(wrong.analyze_pattern(s.upper), std::invalid_argument);
  EXPECT_THROW(wrong.set_block_sizes({12, 4}), std::invalid_argument);
}

TEST(PetscSolver, LooserToleranceTakesFewerIterations) {
  const LinearSystem s = load_linear_system(kDataDir, kSystems[1]);
  PetscSolverSettings settings;
  settings.pc_type = "jacobi";
  PetscSolver solver(settings);
  solver.analyze_pattern(s.upper);
  int iterations[2];
  int k = 0;
  for (const double eta : {1e-2, 1e-10}) {
    solver.set_relative_tolerance(eta);
    ASSERT_TRUE(solver.factorize(s.upper));
    const Eigen::VectorXd p = solver.solve(s.b);
    EXPECT_LE(relative_residual(s, p), eta);
    EXPECT_DOUBLE_EQ(solver.last_report().requested_tolerance, eta);
    iterations[k++] = solver.last_report().iterations;
  }
  EXPECT_LT(iterations[0], iterations[1]);
}

// --- failures -------------------------------------------------------------------------------

/// H − σI with σ in the middle of H's spectrum (geometric mean of its extreme eigenvalues).
Eigen::SparseMatrix<double> indefinite(const LinearSystem& s) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(dense(s.upper), Eigen::EigenvaluesOnly);
  const double sigma = std::sqrt(eig.eigenvalues().minCoeff() * eig.eigenvalues().maxCoeff());
  Eigen::SparseMatrix<double> A = s.upper;
  for (int i = 0; i < A.rows(); ++i) A.coeffRef(i, i) -= sigma;
  return A;
}

TEST(LinearSolver, ReportsAnIndefiniteMatrixInsteadOfReturningADirection) {
  for (const std::string& name : {kSystems[0], kSystems[1]}) {
    SCOPED_TRACE(name);
    const LinearSystem s = load_linear_system(kDataDir, name);
    const Eigen::SparseMatrix<double> A = indefinite(s);
    CholmodSolver cholmod;
    cholmod.analyze_pattern(A);
    EXPECT_FALSE(cholmod.factorize(A));
    EXPECT_EQ(cholmod.last_report().status, LinearSolveStatus::Indefinite);
    EXPECT_FALSE(cholmod.solve(s.b).allFinite());
    int reported = 0;
    for (const char* pc : {"none", "jacobi", "pbjacobi", "vpbjacobi", "icc", "gamg", "hypre"})
      for (const KrylovFallback fallback : {KrylovFallback::None, KrylovFallback::Cholmod}) {
        SCOPED_TRACE(std::string(pc) + (fallback == KrylovFallback::None ? "" : " with fallback"));
        PetscSolverSettings settings;
        settings.pc_type = pc;
        settings.fallback = fallback;
        PetscSolver solver(settings);
        solver.analyze_pattern(A);
        Eigen::VectorXd p;
        const bool factorized = solver.factorize(A);
        if (factorized) p = solver.solve(s.b);
        const LinearSolveReport& r = solver.last_report();
        if (factorized && p.allFinite()) {
          // Krylov methods need not notice (CG may never meet negative curvature); what comes
          // back must then still be the solution of H p = b, and a descent direction.
          EXPECT_TRUE(r.converged()) << to_string(r.status) << ": " << r.reason;
          EXPECT_LE((s.b - A.selfadjointView<Eigen::Upper>() * p).norm() / s.b.norm(), 1e-8);
          EXPECT_GT(s.b.dot(p), 0);
          continue;
        }
        ++reported;
        EXPECT_FALSE(r.converged());
        // CG saw negative curvature, a preconditioner failed to build, or CHOLMOD failed.
        EXPECT_TRUE(r.status == LinearSolveStatus::Indefinite ||
                    r.status == LinearSolveStatus::PreconditionerFailed)
            << to_string(r.status) << ": " << r.reason;
        EXPECT_FALSE(r.reason.empty());
      }
    // Measured: all 14 on house_of_cards; on box_stack (a chain of contacts) CG with ICC solves
    // H p = b exactly in one iteration and p is a descent direction, the other 12 report.
    EXPECT_GE(reported, 12);
    // block_cg: IC(0) fails at every boost, or CG (or its exact fallback) reports, or what it
    // returns solves H p = b and is a descent direction.
    BlockCholeskySolver block_cg(BlockCholesky::Fill::None);
    block_cg.set_block_sizes(std::vector<int>(A.rows() / 12, 12));
    block_cg.analyze_pattern(A);
    if (block_cg.factorize(A)) {
      const Eigen::VectorXd p = block_cg.solve(s.b);
      const LinearSolveReport& r = block_cg.last_report();
      if (p.allFinite()) {
        EXPECT_TRUE(r.converged()) << r.reason;
        EXPECT_LE((s.b - A.selfadjointView<Eigen::Upper>() * p).norm() / s.b.norm(), 1e-8);
        EXPECT_GT(s.b.dot(p), 0);
      } else {
        EXPECT_EQ(r.status, LinearSolveStatus::Indefinite) << r.reason;
      }
    } else {
      EXPECT_EQ(block_cg.last_report().status, LinearSolveStatus::Indefinite);
    }
  }
}

/// Kershaw's matrix K (J. Comput. Phys. 26, 1978) as 3×3 blocks, K ⊗ I₃, upper triangle: positive
/// definite, yet its incomplete Cholesky IC(0) meets a negative pivot.
Eigen::SparseMatrix<double> kershaw_blocks() {
  Eigen::Matrix4d K;
  K << 3, -2, 0, 2, -2, 3, -2, 0, 0, -2, 3, -2, 2, 0, -2, 3;
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d>(K).eigenvalues().minCoeff(), 0);
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < 4; ++i)
    for (int j = i; j < 4; ++j)
      if (K(i, j) != 0)
        for (int c = 0; c < 3; ++c) t.emplace_back(3 * i + c, 3 * j + c, K(i, j));
  Eigen::SparseMatrix<double> A(12, 12);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

TEST(PetscSolver, ShiftsAnIncompleteCholeskyThatBreaksDownInsteadOfFallingBack) {
  // As 3×3 blocks PETSc's block ICC applies no Manteuffel shift of its own: CG stops at once
  // with an indefinite preconditioner, and the solver must rebuild it from H + α diag(H) rather
  // than hand the solve to CHOLMOD.
  const Eigen::SparseMatrix<double> A = kershaw_blocks();
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(12, 1, 2);
  PetscSolverSettings settings;  // CG + ICC(0), CHOLMOD as the fallback
  ASSERT_EQ(settings.pc_type, "icc");
  ASSERT_EQ(settings.fallback, KrylovFallback::Cholmod);
  PetscSolver solver(settings);
  solver.set_block_sizes({3, 3, 3, 3});
  solver.analyze_pattern(A);
  ASSERT_TRUE(solver.factorize(A));
  const Eigen::VectorXd p = solver.solve(b);
  const LinearSolveReport& r = solver.last_report();
  EXPECT_TRUE(r.converged()) << r.reason;
  EXPECT_FALSE(r.fallback_used) << r.primary_failure;
  EXPECT_LE((b - A.selfadjointView<Eigen::Upper>() * p).norm() / b.norm(), settings.relative_tolerance);
}

TEST(BlockCg, IsPetscsIncompleteCholeskyOverTheSameBlocks) {
  // PETSc's ICC(0) over 3×3 blocks keeps the same blocks as IC(0) over an affine body's dense
  // 12×12 ones (each 12×12 block is 16 stored 3×3 blocks), so CG takes the same iterations.
  for (const std::string& name : {kSystems[0], kSystems[1]}) {
    const LinearSystem s = load_linear_system(kDataDir, name);
    const std::vector<int> sizes(s.upper.rows() / 12, 12);
    std::vector<int> iterations;
    std::vector<Eigen::VectorXd> p;
    for (const char* backend : {"block_cg", "petsc:cg:icc"}) {
      SCOPED_TRACE(std::string(backend) + " on " + name);
      const std::unique_ptr<LinearSolver> solver = make_linear_solver(backend);
      solver->set_block_sizes(sizes);
      solver->set_relative_tolerance(1e-8);
      solver->analyze_pattern(s.upper);
      ASSERT_TRUE(solver->factorize(s.upper));
      p.push_back(solver->solve(s.b));
      ASSERT_TRUE(solver->last_report().converged()) << solver->last_report().reason;
      iterations.push_back(solver->last_report().iterations);
    }
    EXPECT_EQ(iterations[0], iterations[1]) << name;  // measured: 1 on box_stack (a chain), 14 on house_of_cards
    EXPECT_LE((p[0] - p[1]).norm(), 1e-6 * p[1].norm()) << name;
  }
}

TEST(BlockCg, FallsBackToTheExactFactorWhenConjugateGradientsCannotFinish) {
  // A tolerance below round-off: CG stops at its iteration cap (or at a curvature that
  // round-off made ≤ 0), and the exact block factor of the same H solves instead.
  const LinearSystem s = load_linear_system(kDataDir, kSystems[1]);
  BlockCholeskySolver solver(BlockCholesky::Fill::None);
  solver.set_block_sizes(std::vector<int>(s.upper.rows() / 12, 12));
  solver.set_relative_tolerance(1e-20);
  solver.analyze_pattern(s.upper);
  ASSERT_TRUE(solver.factorize(s.upper));
  const Eigen::VectorXd p = solver.solve(s.b);
  const LinearSolveReport& r = solver.last_report();
  EXPECT_TRUE(r.fallback_used);
  EXPECT_NE(r.primary_failure.find("block_cg"), std::string::npos) << r.primary_failure;
  EXPECT_TRUE(r.converged()) << r.reason;
  EXPECT_GT(r.iterations, 0);
  EXPECT_LE(relative_residual(s, p), 1e-10);
  EXPECT_NEAR(r.relative_residual, relative_residual(s, p), 1e-12);
}

TEST(BlockCg, BoostsAnIncompleteCholeskyThatBreaksDown) {
  // Kershaw's matrix as 3×3 blocks: IC(0) over the blocks
  // meets a pivot block that is not positive definite; "block_cg" builds it again from
  // H + α diag(H) and CG still solves H p = b itself.
  const Eigen::SparseMatrix<double> A = kershaw_blocks();
  const std::vector<int> sizes{3, 3, 3, 3};
  BlockCholesky incomplete(BlockCholesky::Fill::None);
  incomplete.analyze(A, sizes);
  EXPECT_FALSE(incomplete.factorize(A));
  BlockCholeskySolver solver(BlockCholesky::Fill::None);
  solver.set_block_sizes(sizes);
  solver.set_relative_tolerance(1e-10);
  solver.analyze_pattern(A);
  ASSERT_TRUE(solver.factorize(A));
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(12, 1, 2);
  const Eigen::VectorXd p = solver.solve(b);
  EXPECT_TRUE(solver.last_report().converged()) << solver.last_report().reason;
  EXPECT_LE((b - A.selfadjointView<Eigen::Upper>() * p).norm() / b.norm(), 1e-10);
}

TEST(PetscSolver, ReportsTheIterationCapAndFallsBackToCholmod) {
  const LinearSystem s = load_linear_system(kDataDir, kSystems[1]);
  for (const KrylovFallback fallback : {KrylovFallback::None, KrylovFallback::Cholmod}) {
    PetscSolverSettings settings;
    settings.pc_type = "none";
    settings.max_iterations = 3;
    settings.relative_tolerance = 1e-12;
    settings.fallback = fallback;
    PetscSolver solver(settings);
    solver.analyze_pattern(s.upper);
    ASSERT_TRUE(solver.factorize(s.upper));
    const Eigen::VectorXd p = solver.solve(s.b);
    const LinearSolveReport& r = solver.last_report();
    EXPECT_EQ(r.iterations, 3);
    if (fallback == KrylovFallback::None) {
      EXPECT_EQ(r.status, LinearSolveStatus::IterationCap);
      EXPECT_EQ(r.reason, "DIVERGED_ITS");
      EXPECT_FALSE(p.allFinite());
    } else {
      EXPECT_TRUE(r.converged());
      EXPECT_TRUE(r.fallback_used);
      EXPECT_NE(r.primary_failure.find("DIVERGED_ITS"), std::string::npos) << r.primary_failure;
      EXPECT_LE(relative_residual(s, p), 1e-10);
    }
  }
}

TEST(LinearSolver, FactoryNamesTheAvailableBackendsForAnUnknownOne) {
  try {
    make_linear_solver("superlu");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("cholmod"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("petsc:KSP"), std::string::npos) << e.what();
  }
  for (const char* good : {"cholmod", "block_cholesky", "auto", "petsc", "petsc:cg", "petsc:minres:jacobi", "petsc:cg:hypre"})
    EXPECT_NO_THROW(check_linear_solver_name(good)) << good;
  for (const char* bad : {"lu", "petsc:", "petsc:cg:", "petsc:bicg", "petsc:cg:ilu", "petsc:cg:icc:x"})
    EXPECT_THROW(check_linear_solver_name(bad), std::invalid_argument) << bad;
  EXPECT_THROW(make_linear_solver("petsc:bicg"), std::invalid_argument);
  EXPECT_THROW(make_linear_solver("petsc:cg:ilu"), std::invalid_argument);
  EXPECT_THROW(make_linear_solver("petsc:cg:jacobi:extra"), std::invalid_argument);
  EXPECT_THROW(register_linear_solver("cholmod", [] { return std::make_unique<CholmodSolver>(); }),
               std::invalid_argument);
  EXPECT_EQ(make_linear_solver("petsc:gmres:gamg")->name(), "petsc:gmres:gamg");
  EXPECT_EQ(make_linear_solver("petsc:minres")->name(), "petsc:minres:icc");
  EXPECT_EQ(make_linear_solver("petsc")->name(), "petsc:cg:icc");
}

/// A soft-body-like SPD system: a g×g×g lattice of nodes (3 DOFs each) with springs along the
/// edges of the Kuhn tetrahedra of each cell, plus a mass term: 3D-mesh fill for CHOLMOD.
Eigen::SparseMatrix<double> lattice_upper(int g) {
  auto id = [g](int i, int j, int k) { return (i * g + j) * g + k; };
  std::vector<Eigen::Triplet<double>> t;
  for (int a = 0; a < 3 * g * g * g; ++a) t.emplace_back(a, a, 10.0);
  const int dirs[7][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {0, 1, 1}, {1, 0, 1}, {1, 1, 1}};
  for (int i = 0; i < g; ++i)
    for (int j = 0; j < g; ++j)
      for (int k = 0; k < g; ++k)
        for (const auto& d : dirs) {
          if (i + d[0] >= g || j + d[1] >= g || k + d[2] >= g) continue;
          const int a = id(i, j, k), b = id(i + d[0], j + d[1], k + d[2]);
          const Eigen::Vector3d u = Eigen::Vector3d(d[0], d[1], d[2]).normalized();
          const Eigen::Matrix3d K = 1e4 * (u * u.transpose() + 0.1 * Eigen::Matrix3d::Identity());
          for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) {
              if (r <= c) {
                t.emplace_back(3 * a + r, 3 * a + c, K(r, c));
                t.emplace_back(3 * b + r, 3 * b + c, K(r, c));
              }
              t.emplace_back(3 * a + r, 3 * b + c, -K(r, c));
            }
        }
  Eigen::SparseMatrix<double> A(3 * g * g * g, 3 * g * g * g);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  return A;
}

TEST(AutoSolver, TakesCholmodWhenItsFactorisationIsCheapAndPetscOtherwise) {
  const LinearSystem small = load_linear_system(kDataDir, kSystems[1]);
  const Eigen::SparseMatrix<double> large = lattice_upper(8);  // 1536 rows
  CholmodSolver probe;
  probe.analyze_pattern(large);
  EXPECT_GT(probe.factor_flops(), kAutoCholmodFlops);
  probe.analyze_pattern(small.upper);
  EXPECT_LT(probe.factor_flops(), kAutoCholmodFlops);

  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(large.rows(), -1, 1);
  AutoSolver solver;
  solver.set_relative_tolerance(1e-9);
  for (int round = 0; round < 2; ++round) {  // and back: the decision follows the pattern
    solver.analyze_pattern(small.upper);
    ASSERT_TRUE(solver.factorize(small.upper));
    EXPECT_LE(relative_residual(small, solver.solve(small.b)), 1e-10);
    EXPECT_EQ(solver.name(), "auto→cholmod");
    EXPECT_FALSE(solver.is_iterative());
    solver.analyze_pattern(large);
    ASSERT_TRUE(solver.factorize(large));
    const Eigen::VectorXd p = solver.solve(b);
    EXPECT_EQ(solver.name(), "auto→petsc:cg:icc");
    EXPECT_TRUE(solver.is_iterative());
    EXPECT_TRUE(solver.last_report().converged());
    EXPECT_LE((b - large.selfadjointView<Eigen::Upper>() * p).norm() / b.norm(), 1e-9);
  }
}

TEST(AutoSolver, TakesTheBlockCholeskyWhenEveryBlockIsAnAffineBody) {
  // house_of_cards: 15 cards, 180 rows. As affine bodies (12-blocks) → block Cholesky; as
  // 3-blocks (soft nodes) or without blocks → CHOLMOD. All three solve to round-off.
  const LinearSystem s = load_linear_system(kDataDir, kSystems[1]);
  const int rows = int(s.upper.rows());
  for (const auto& [sizes, expected] : std::vector<std::pair<std::vector<int>, std::string>>{
           {std::vector<int>(rows / 12, 12), "auto→block_cholesky"},
           {std::vector<int>(rows / 3, 3), "auto→cholmod"},
           {{}, "auto→cholmod"}}) {
    AutoSolver solver;
    solver.set_block_sizes(sizes);
    solver.analyze_pattern(s.upper);
    ASSERT_TRUE(solver.factorize(s.upper));
    EXPECT_LE(relative_residual(s, solver.solve(s.b)), 1e-10);
    EXPECT_EQ(solver.name(), expected);
    EXPECT_FALSE(solver.is_iterative());
  }
}

/// 3-D lattices read as 12-blocks (four nodes each): the first whose block factor costs
/// between CHOLMOD's bound and the block Cholesky's, and the first above the block Cholesky's.
std::pair<Eigen::SparseMatrix<double>, Eigen::SparseMatrix<double>> lattices_around_the_block_bound() {
  std::optional<Eigen::SparseMatrix<double>> middle, above;
  for (int g = 4; g <= 20 && !above; g += 2) {
    Eigen::SparseMatrix<double> A = lattice_upper(g);
    BlockCholeskySolver probe;
    probe.set_block_sizes(std::vector<int>(A.rows() / 12, 12));
    probe.analyze_pattern(A);
    if (!middle && probe.factor_flops() > kAutoCholmodFlops && probe.factor_flops() <= kAutoBlockCholeskyFlops)
      middle = A;
    else if (probe.factor_flops() > kAutoBlockCholeskyFlops)
      above = A;
  }
  if (!middle || !above) throw std::logic_error("no lattices on both sides of the block Cholesky's bound");
  return {*middle, *above};
}

TEST(AutoSolver, KeepsTheBlockCholeskyUpToItsOwnFlopBoundThenTakesBlockCg) {
  // The lattice below the block Cholesky's bound stays direct, the one above goes to the block
  // Krylov method (PETSc only when there are soft nodes, TakesCholmodWhen…).
  const auto [middle, above] = lattices_around_the_block_bound();
  for (const auto& [A, expected] : {std::pair{middle, std::string("auto→block_cholesky")},
                                    std::pair{above, std::string("auto→block_cg")}}) {
    AutoSolver solver;
    solver.set_relative_tolerance(1e-10);
    solver.set_block_sizes(std::vector<int>(A.rows() / 12, 12));
    solver.analyze_pattern(A);
    ASSERT_TRUE(solver.factorize(A));
    const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A.rows(), -1, 1);
    const Eigen::VectorXd p = solver.solve(b);
    EXPECT_EQ(solver.name(), expected) << A.rows() << " rows";
    EXPECT_LE((b - A.selfadjointView<Eigen::Upper>() * p).norm() / b.norm(), 1e-9);
  }
}

TEST(AutoSolver, AsksTheBlockCholeskyAboveTheRowsBoundAndNotCholmod) {
  // A chain of affine bodies, each coupled to the next, over kAutoKrylovRows rows: its block
  // factor has no fill, so the block Cholesky is asked and kept (on a 5,000-body pile of full's
  // kind its solve phase took half of block_cg's: docs/benchmarks.md, session 72). Read as soft nodes'
  // 3-blocks, the same matrix goes to the Krylov method without asking CHOLMOD, as before.
  const int bodies = kAutoKrylovRows / 12 + 1;
  std::vector<Eigen::Triplet<double>> t;
  for (int b = 0; b < bodies; ++b)
    for (int r = 0; r < 12; ++r) {
      t.emplace_back(12 * b + r, 12 * b + r, 4.0 + 0.01 * r);
      if (r + 1 < 12) t.emplace_back(12 * b + r, 12 * b + r + 1, 0.5);
      if (b + 1 < bodies) t.emplace_back(12 * b + r, 12 * (b + 1) + r, -1.0);
    }
  Eigen::SparseMatrix<double> A(12 * bodies, 12 * bodies);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A.rows(), -1, 1);
  for (const auto& [size, expected] : {std::pair{12, std::string("auto→block_cholesky")},
                                       std::pair{3, std::string("auto→petsc:cg:icc")}}) {
    AutoSolver solver;
    solver.set_relative_tolerance(1e-10);
    solver.set_block_sizes(std::vector<int>(A.rows() / size, size));
    solver.analyze_pattern(A);
    ASSERT_TRUE(solver.factorize(A));
    const Eigen::VectorXd p = solver.solve(b);
    EXPECT_EQ(solver.name(), expected) << A.rows() << " rows";
    EXPECT_LE((b - A.selfadjointView<Eigen::Upper>() * p).norm() / b.norm(), 1e-9);
  }
}

TEST(AutoSolver, ARestoredMemoryKeepsTheBackendAsTheUninterruptedRunHadIt) {
  // A run that chose the block Cholesky at some pattern keeps it while the pattern stays within
  // kAutoRedecideChange of that size, even where a fresh decision would take block_cg: a resumed
  // run (SimulationState::solver) must choose as the uninterrupted one did (session 56: full
  // resumed at step 250 took block_cg where the run had kept the block Cholesky, and diverged).
  const Eigen::SparseMatrix<double> above = lattices_around_the_block_bound().second;
  const std::vector<int> blocks(std::size_t(above.rows() / 12), 12);
  const long nonzeros = long(above.nonZeros());
  const auto analysed = [&](const std::optional<LinearSolverMemory>& memory) {
    auto solver = std::make_unique<AutoSolver>();
    solver->set_block_sizes(blocks);
    if (memory) solver->restore_memory(*memory);
    solver->analyze_pattern(above);
    return solver;
  };
  const LinearSolverMemory kept{nonzeros * 9 / 10, false};  // chosen direct at a 10 % smaller pattern
  EXPECT_EQ(analysed(std::nullopt)->name(), "auto→block_cg");
  const auto resumed = analysed(kept);
  EXPECT_EQ(resumed->name(), "auto→block_cholesky");
  EXPECT_EQ(resumed->memory().decided_nonzeros, kept.decided_nonzeros);
  EXPECT_FALSE(resumed->memory().krylov);
  ASSERT_TRUE(resumed->factorize(above));
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(above.rows(), -1, 1);
  EXPECT_LE((b - above.selfadjointView<Eigen::Upper>() * resumed->solve(b)).norm() / b.norm(), 1e-9);
  // A memory from a pattern more than kAutoRedecideChange away is decided again.
  const auto moved = analysed(LinearSolverMemory{nonzeros / 2, false});
  EXPECT_EQ(moved->name(), "auto→block_cg");
  EXPECT_EQ(moved->memory().decided_nonzeros, nonzeros);
  EXPECT_TRUE(moved->memory().krylov);
  // Before any analysis the memory is the one given back, so a state saved at once keeps it.
  AutoSolver fresh;
  fresh.restore_memory(kept);
  EXPECT_EQ(fresh.memory().decided_nonzeros, kept.decided_nonzeros);
}

TEST(CholmodSolver, TakesTheSupernodalMethodOnlyWhereItsDenseBlocksPay) {
  // A pile's system (stored, 12×12 body blocks, sparse factor) goes simplicial; a 3D lattice's
  // fill (soft-mesh-like) goes supernodal. Both solve to round-off, and both refuse an
  // indefinite matrix (simplicial factors are LLᵀ too, which fail on a non-positive pivot).
  const LinearSystem pile = load_linear_system(kDataDir, kSystems[1]);
  const Eigen::SparseMatrix<double> lattice = lattice_upper(8);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(lattice.rows(), -1, 1);
  CholmodSolver solver;
  solver.analyze_pattern(pile.upper);
  EXPECT_FALSE(solver.supernodal());
  ASSERT_TRUE(solver.factorize(pile.upper));
  EXPECT_LE(relative_residual(pile, solver.solve(pile.b)), 1e-10);
  EXPECT_FALSE(solver.factorize(indefinite(pile)));
  solver.analyze_pattern(lattice);
  EXPECT_TRUE(solver.supernodal());
  ASSERT_TRUE(solver.factorize(lattice));
  EXPECT_LE((b - lattice.selfadjointView<Eigen::Upper>() * solver.solve(b)).norm() / b.norm(), 1e-10);
  Eigen::SparseMatrix<double> shifted = lattice;  // its diagonal stays below 2e5: now negative definite
  for (int i = 0; i < shifted.rows(); ++i) shifted.coeffRef(i, i) -= 1e6;
  EXPECT_FALSE(solver.factorize(shifted));
}

// --- PETSc options, command line, forcing terms --------------------------------------------------

TEST(PetscSolver, TheOptionsDatabaseOverridesTheNamedMethod) {
  ensure_petsc_initialized();
  {
    // PETSc runs already: a session's options only go into its database.
    const PetscSession session(
        std::vector<std::string>{"-ksp_type", "minres", "-pc_type", "jacobi", "-ksp_rtol", "1e-3"});
    EXPECT_FALSE(session.owns_petsc());
  }
  PetscSolver solver;  // asks for CG with ICC
  for (const char* option : {"-ksp_type", "-pc_type", "-ksp_rtol"}) clear_petsc_option(option);
  EXPECT_EQ(solver.name(), "petsc:minres:jacobi");
  const LinearSystem s = load_linear_system(kDataDir, kSystems[0]);
  solver.set_relative_tolerance(1e-10);  // the command line's -ksp_rtol wins
  solver.analyze_pattern(s.upper);
  ASSERT_TRUE(solver.factorize(s.upper));
  const Eigen::VectorXd p = solver.solve(s.b);
  EXPECT_DOUBLE_EQ(solver.last_report().requested_tolerance, 1e-3);
  EXPECT_LE(relative_residual(s, p), 1e-3);
  EXPECT_EQ(PetscSolver().name(), "petsc:cg:icc");  // options cleared: the defaults again
}

TEST(ForcingTerm, FollowsEisenstatWalkerChoiceTwoWithItsSafeguards) {
  ForcingTermSettings s;
  s.eta_max = 0.9;  // Eisenstat–Walker's own cap, so that the formula shows (the default is tighter)
  // No previous iteration: η_0.
  EXPECT_DOUBLE_EQ(forcing_term(1.0, 0.0, 0.0, s), s.eta_initial);
  // γ (‖g_k‖/‖g_{k−1}‖)^α when the safeguard is inactive (γ η_{k−1}^α ≤ 0.1).
  const double eta_previous = 0.05;
  EXPECT_NEAR(forcing_term(0.3, 1.0, eta_previous, s), 0.9 * std::pow(0.3, s.alpha), 1e-15);
  // Safeguard: after a large η, a sudden drop is limited to γ η_{k−1}^α.
  EXPECT_NEAR(forcing_term(1e-3, 1.0, 0.5, s), 0.9 * std::pow(0.5, s.alpha), 1e-15);
  // Bounds.
  EXPECT_DOUBLE_EQ(forcing_term(2.0, 1.0, 0.01, s), s.eta_max);
  EXPECT_DOUBLE_EQ(forcing_term(1e-12, 1.0, 1e-6, s), s.eta_min);
  // The sequence tightens as ‖g‖ converges quadratically.
  double eta = forcing_term(1.0, 0.0, 0.0, s), g_prev = 1.0;
  for (const double g : {0.5, 0.1, 1e-3, 1e-7}) {
    const double next = forcing_term(g, g_prev, eta, s);
    EXPECT_LE(next, eta);
    eta = next;
    g_prev = g;
  }
  EXPECT_LT(eta, 1e-6);
}

TEST(ForcingTerm, TheDefaultCapHoldsEveryStepTight) {
  const ForcingTermSettings s;
  EXPECT_DOUBLE_EQ(forcing_term(1.0, 0.0, 0.0), s.eta_max);  // η_0 is clamped too
  EXPECT_DOUBLE_EQ(forcing_term(2.0, 1.0, s.eta_max), s.eta_max);
  EXPECT_LT(forcing_term(1e-3, 1.0, s.eta_max), s.eta_max);  // and tightens as ‖g‖ converges
}

// --- MPI -------------------------------------------------------------------------------------

std::string shell_quote(const std::string& s) { return "'" + s + "'"; }

/// Binary dump of a vector, for the parent test to compare ranks.
void write_vector(const std::filesystem::path& path, const Eigen::VectorXd& v) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(v.data()), std::streamsize(v.size() * sizeof(double)));
}

Eigen::VectorXd read_vector(const std::filesystem::path& path, int n) {
  Eigen::VectorXd v(n);
  std::ifstream in(path, std::ios::binary);
  in.read(reinterpret_cast<char*>(v.data()), std::streamsize(n * sizeof(double)));
  if (!in) v.setConstant(std::nan(""));
  return v;
}

const std::vector<std::string> kMpiBackends{"petsc:cg:vpbjacobi", "petsc:cg:jacobi", "petsc:cg:pbjacobi",
                                            "petsc:cg:icc",       "petsc:cg:gamg",   "petsc:cg:hypre",
                                            "petsc:gmres:icc"};

/// Runs only inside `mpirun -n 2` started by the test below (STIFFSOFT_MPI_CHILD set).
TEST(PetscSolverMpiChild, SolvesDistributedOnTwoRanks) {
  const char* out = std::getenv("STIFFSOFT_MPI_CHILD");
  if (!out) GTEST_SKIP() << "runs inside mpirun, started by PetscSolverMpi.TwoRanksAgreeWithTheSerialSolve";
  ensure_petsc_initialized();
  ASSERT_EQ(PetscSession::size(), 2);
  const int rank = PetscSession::rank();
  const LinearSystem s = load_linear_system(kDataDir, kSystems[1]);
  for (std::size_t k = 0; k < kMpiBackends.size(); ++k) {
    SCOPED_TRACE(kMpiBackends[k]);
    std::unique_ptr<LinearSolver> solver = make_linear_solver(kMpiBackends[k]);
    solver->set_relative_tolerance(1e-10);
    solver->analyze_pattern(s.upper);
    ASSERT_TRUE(solver->factorize(s.upper));
    const Eigen::VectorXd p = solver->solve(s.b);
    const LinearSolveReport& r = solver->last_report();
    EXPECT_TRUE(r.converged()) << r.reason;
    EXPECT_FALSE(r.fallback_used) << r.primary_failure;
    EXPECT_LE(relative_residual(s, p), 1e-10);
    const auto rows = dynamic_cast<const PetscSolver&>(*solver).owned_rows();
    EXPECT_EQ(rank == 0 ? rows.first : rows.second, rank == 0 ? 0 : int(s.upper.rows()));
    EXPECT_GT(rows.second - rows.first, 0);
    write_vector(std::filesystem::path(out) / ("p" + std::to_string(k) + "_rank" + std::to_string(rank)), p);
  }
}

TEST(PetscSolverMpi, TwoRanksAgreeWithTheSerialSolve) {
  if (std::system("command -v mpirun > /dev/null 2>&1") != 0) GTEST_SKIP() << "no mpirun";
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("stiffsoft_mpi_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  // The child must not inherit this process's MPI singleton environment (if it has one).
  std::string unset;
  for (const std::string& name : mpi_launcher_variables()) unset += " -u " + name;
  const std::string exe = std::filesystem::read_symlink("/proc/self/exe").string();
  const std::string log = (dir / "log.txt").string();
  const std::string command = "env" + unset + " STIFFSOFT_MPI_CHILD=" + shell_quote(dir.string()) +
                              " timeout 300 mpirun --allow-run-as-root --oversubscribe -n 2 " +
                              shell_quote(exe) + " --gtest_filter=PetscSolverMpiChild.* > " +
                              shell_quote(log) + " 2>&1";
  const int status = std::system(command.c_str());
  std::ifstream in(log);
  const std::string output((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_EQ(status, 0) << command << "\n" << output;

  const LinearSystem s = load_linear_system(kDataDir, kSystems[1]);
  CholmodSolver cholmod;
  cholmod.analyze_pattern(s.upper);
  ASSERT_TRUE(cholmod.factorize(s.upper));
  const Eigen::VectorXd reference = cholmod.solve(s.b);
  // ‖p − p*‖ ≤ ‖H⁻¹‖ ‖b − Hp‖ ≤ κ(H) η ‖p*‖ with η = 1e-10.
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(dense(s.upper), Eigen::EigenvaluesOnly);
  const double kappa = eig.eigenvalues().maxCoeff() / eig.eigenvalues().minCoeff();
  for (std::size_t k = 0; k < kMpiBackends.size(); ++k) {
    SCOPED_TRACE(kMpiBackends[k]);
    const Eigen::VectorXd p0 = read_vector(dir / ("p" + std::to_string(k) + "_rank0"), int(s.b.size()));
    const Eigen::VectorXd p1 = read_vector(dir / ("p" + std::to_string(k) + "_rank1"), int(s.b.size()));
    ASSERT_TRUE(p0.allFinite() && p1.allFinite()) << output;
    EXPECT_EQ((p0 - p1).norm(), 0.0);  // every rank holds the same gathered solution
    EXPECT_LE((p0 - reference).norm(), 1e-10 * kappa * reference.norm());
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace stiffsoft
