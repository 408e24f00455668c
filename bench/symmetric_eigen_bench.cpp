/// @file symmetric_eigen_bench: the plain-loop eigen-decomposition of symmetric_eigen.hpp
/// against Eigen's SelfAdjointEigenSolver on the sizes the barrier's projections use (5×5 in
/// the distance span, 9×9 in the mollified edge pairs' translation complement), one thread:
/// microseconds per matrix over random symmetric matrices, the median of the repetitions,
/// with the machine and its load (docs/benchmarks.md, sessions 25 and 35).

#include <CLI/CLI.hpp>
#include <Eigen/Eigenvalues>
#include <chrono>
#include <cstdio>
#include <random>
#include <vector>

#include <bench_statistics.hpp>
#include <peers/machine.hpp>
#include <stiffsoft/coupling/contact/symmetric_eigen.hpp>

namespace {

/// Microseconds per matrix of `decompose` over `matrices`, the median of `repeat` passes.
/// `sink` keeps the results alive.
template <class Matrix, class Decompose>
double microseconds_per_matrix(const std::vector<Matrix>& matrices, int repeat, Decompose&& decompose, double& sink) {
  std::vector<double> passes;
  for (int r = 0; r < repeat; ++r) {
    const auto start = std::chrono::steady_clock::now();
    for (const Matrix& A : matrices) sink += decompose(A);
    const std::chrono::duration<double, std::micro> elapsed = std::chrono::steady_clock::now() - start;
    passes.push_back(elapsed.count() / double(matrices.size()));
  }
  return stiffsoft::bench::median(passes);
}

/// One table row for N×N matrices.
template <int N>
void compare(int count, int repeat, double& sink) {
  using Matrix = Eigen::Matrix<double, N, N>;
  std::mt19937 rng(N);
  std::normal_distribution<double> normal;
  std::vector<Matrix> matrices(count);
  for (Matrix& A : matrices) {
    Matrix B;
    for (int i = 0; i < N * N; ++i) B.data()[i] = normal(rng);
    A = B + B.transpose();
  }
  const double ours = microseconds_per_matrix(matrices, repeat, [](const Matrix& A) {
    const stiffsoft::contact::SymmetricEigen<N> es = stiffsoft::contact::symmetric_eigen<N>(A);
    return es.values.sum() + es.vectors(0, 0);
  }, sink);
  const double eigen = microseconds_per_matrix(matrices, repeat, [](const Matrix& A) {
    const Eigen::SelfAdjointEigenSolver<Matrix> es(A);
    return es.eigenvalues().sum() + es.eigenvectors()(0, 0);
  }, sink);
  std::printf("| %d×%d | %d | %.2f | %.2f | %.2f |\n", N, N, count, ours, eigen, eigen / ours);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"symmetric_eigen against Eigen's SelfAdjointEigenSolver, µs per matrix"};
  int count = 20000, repeat = 5;
  app.add_option("--matrices", count, "random symmetric matrices per size")->check(CLI::PositiveNumber);
  app.add_option("--repeat", repeat, "passes over them; the median is reported")->check(CLI::PositiveNumber);
  CLI11_PARSE(app, argc, argv);
  const stiffsoft::peers::Machine machine = stiffsoft::peers::this_machine();
  std::printf("%s, %u cores, load %.2f, %s\n\n", machine.cpu.c_str(), machine.cores, stiffsoft::peers::load_average(),
              machine.date.c_str());
  std::printf("| size | matrices | symmetric_eigen (µs) | SelfAdjointEigenSolver (µs) | ratio |\n|---|---|---|---|---|\n");
  double sink = 0;
  compare<5>(count, repeat, sink);
  compare<9>(count, repeat, sink);
  return sink == 0.123456789 ? 1 : 0;  // never: only keeps the work from being optimised away
}
