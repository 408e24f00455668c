/// @file The ceiling of two-thread speed-ups on this machine: kernels whose work splits
/// perfectly between threads (no serial part, no shared writes), timed on one thread and on
/// --threads threads, alternating, medians of --repeat runs. A Newton iteration's speed-up
/// with `--threads 2` is judged against these: on a virtual machine whose two cores share one
/// physical core's floating-point units, vectorised arithmetic cannot run twice as fast
/// whatever the code does. `thread_scaling_bench --help` lists the options.

#include <CLI/CLI.hpp>
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <Eigen/Core>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <vector>

#include "bench_statistics.hpp"
#include "peers/machine.hpp"

namespace {

using Matrix12d = Eigen::Matrix<double, 12, 12>;

/// One kernel: `run` does its whole work once, split over the threads TBB allows.
struct Kernel {
  const char* name;
  std::function<void()> run;
};

/// C_i ← A_i B_i + B_i for `count` pairs of 12×12 matrices, `sweeps` times: the dense
/// fixed-size products of the assembly and the block Cholesky.
Kernel products(const char* name, int count, int sweeps) {
  auto a = std::make_shared<std::vector<Matrix12d>>(count, Matrix12d::Random());
  auto b = std::make_shared<std::vector<Matrix12d>>(count, 0.5 * Matrix12d::Identity());
  return {name, [a, b, count, sweeps] {
            for (int s = 0; s < sweeps; ++s)
              tbb::parallel_for(tbb::blocked_range<int>(0, count, 8), [&](const tbb::blocked_range<int>& r) {
                for (int i = r.begin(); i < r.end(); ++i) (*a)[i] = ((*a)[i] * (*b)[i]).eval() + (*b)[i];
              });
          }};
}

/// y_i ← A_i x_{7i mod count} for `count` 12×12 blocks, `sweeps` times: the conjugate
/// gradients' block products (and, alike, their triangular solves), 144 multiply–adds per 1,152
/// bytes read, against the products above that reuse each block twelve times.
Kernel matrix_vector(const char* name, int count, int sweeps) {
  auto a = std::make_shared<std::vector<Matrix12d>>(count, Matrix12d::Random());
  using Vector12d = Eigen::Matrix<double, 12, 1>;
  auto x = std::make_shared<std::vector<Vector12d>>(count, Vector12d::Ones());
  auto y = std::make_shared<std::vector<Vector12d>>(count);
  return {name, [a, x, y, count, sweeps] {
            for (int s = 0; s < sweeps; ++s)
              tbb::parallel_for(tbb::blocked_range<int>(0, count, 32), [&](const tbb::blocked_range<int>& r) {
                for (int i = r.begin(); i < r.end(); ++i) (*y)[i].noalias() = (*a)[i] * (*x)[(7 * i) % count];
              });
          }};
}

/// x ← sin(x) + 1 over 2^20 numbers, `sweeps` times: scalar work bound by latency.
Kernel scalar_chain(int sweeps) {
  auto x = std::make_shared<std::vector<double>>(1 << 20, 1.0);
  return {"scalar sin chain, 8 MiB", [x, sweeps] {
            for (int s = 0; s < sweeps; ++s)
              tbb::parallel_for(tbb::blocked_range<std::size_t>(0, x->size(), 4096), [&](const tbb::blocked_range<std::size_t>& r) {
                for (std::size_t i = r.begin(); i < r.end(); ++i) (*x)[i] = std::sin((*x)[i]) + 1.0;
              });
          }};
}

double seconds(const Kernel& k, int threads) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  const auto start = std::chrono::steady_clock::now();
  k.run();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Two-thread speed-up of perfectly parallel kernels: the machine's ceiling"};
  int threads = 2, repeat = 5;
  app.add_option("--threads", threads, "threads of the parallel runs")->capture_default_str()->check(CLI::PositiveNumber);
  app.add_option("--repeat", repeat, "alternated runs per kernel; times are medians")->capture_default_str()->check(CLI::PositiveNumber);
  CLI11_PARSE(app, argc, argv);

  const stiffsoft::peers::Machine machine = stiffsoft::peers::this_machine();
  std::printf("# machine: %u cores, cpu: %s, load %.2f, %s\n", machine.cores, machine.cpu.c_str(),
              stiffsoft::peers::load_average(), machine.date.c_str());
  std::printf("| kernel | 1 thread (s) | %d threads (s) | speed-up |\n|---|---|---|---|\n", threads);
  const std::vector<Kernel> kernels{products("12x12 products, 450 KiB (in cache)", 200, 3000),
                                    products("12x12 products, 4.4 MiB (streaming)", 2000, 300),
                                    matrix_vector("12x12 matrix-vector products, 2.5 MiB", 2300, 20000),
                                    scalar_chain(60)};
  for (const Kernel& k : kernels) {
    std::vector<double> one, many;
    for (int r = 0; r < repeat; ++r) {
      one.push_back(seconds(k, 1));
      many.push_back(seconds(k, threads));
    }
    const double t1 = stiffsoft::bench::median(one), tn = stiffsoft::bench::median(many);
    std::printf("| %s | %.3f | %.3f | %.2fx |\n", k.name, t1, tn, t1 / tn);
  }
  return 0;
}
