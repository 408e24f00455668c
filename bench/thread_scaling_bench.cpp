/// @file The ceiling of two-thread speed-ups on this machine: kernels whose work splits
/// perfectly between threads (no serial part, no shared writes), timed on one thread and on
/// --threads threads, alternating, medians of --repeat runs; and serial stretches between
/// parallel loops, for the time a loop waits for sleeping threads to wake. A Newton iteration's speed-up
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
#include <memory>
#include <vector>

#include "bench_statistics.hpp"
#include "peers/machine.hpp"

namespace {

using Matrix12d = Eigen::Matrix<double, 12, 12>;

/// One kernel: `run` does its whole work once, split over the threads TBB allows. A kernel
/// with a serial part reports its seconds in `serial_seconds` (null: none) and how many
/// parallel loops follow one in `loops`.
struct Kernel {
  const char* name;
  std::function<void()> run;
  std::shared_ptr<double> serial_seconds = nullptr;
  int loops = 0;
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

/// `rounds` times a serial stretch of about `serial_us` µs (a sin chain on one thread), then a
/// parallel loop of about `parallel_us` µs of one thread's work: a Newton iteration's pattern
/// (serial merges and sorts between parallel loops). After a stretch long enough for the other
/// threads to go to sleep, each loop starts late by the time they take to wake up, which the
/// perfectly parallel kernels above never pay.
Kernel gapped(const char* name, int rounds, double serial_us, double parallel_us) {
  // About 20 ns per sin on this kind of machine; the measured split is what the table uses.
  constexpr double kSinNanoseconds = 20;
  const int serial_n = int(serial_us * 1000 / kSinNanoseconds);
  const int parallel_n = int(parallel_us * 1000 / kSinNanoseconds);
  auto x = std::make_shared<std::vector<double>>(std::size_t(parallel_n), 1.0);
  auto serial = std::make_shared<double>(0.0);
  return {name,
          [x, serial, rounds, serial_n] {
            *serial = 0;
            double y = 1.0;
            for (int r = 0; r < rounds; ++r) {
              const auto start = std::chrono::steady_clock::now();
              for (int i = 0; i < serial_n; ++i) y = std::sin(y) + 1.0;
              (*x)[0] += y * 1e-300;
              *serial += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
              const auto loop = [&](const tbb::blocked_range<std::size_t>& b) {
                for (std::size_t i = b.begin(); i < b.end(); ++i) (*x)[i] = std::sin((*x)[i]) + 1.0;
              };
              tbb::parallel_for(tbb::blocked_range<std::size_t>(0, x->size(), 1024), loop);
            }
          },
          serial, rounds};
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
  std::printf("| kernel | 1 thread (s) | %d threads (s) | speed-up | perfect split "
              "| late start per loop (µs) |\n|---|---|---|---|---|---|\n",
              threads);
  const std::vector<Kernel> kernels{products("12x12 products, 450 KiB (in cache)", 200, 3000),
                                    products("12x12 products, 4.4 MiB (streaming)", 2000, 300),
                                    matrix_vector("12x12 matrix-vector products, 2.5 MiB", 2300, 20000),
                                    scalar_chain(60),
                                    gapped("short serial stretches", 4000, 20, 200),
                                    gapped("long serial stretches, short loops", 1500, 500, 200),
                                    gapped("long serial stretches, long loops", 600, 500, 1000)};
  for (const Kernel& k : kernels) {
    std::vector<double> one, many, serial_share;
    for (int r = 0; r < repeat; ++r) {
      one.push_back(seconds(k, 1));
      if (k.serial_seconds) serial_share.push_back(*k.serial_seconds / one.back());
      many.push_back(seconds(k, threads));
    }
    const double t1 = stiffsoft::bench::median(one), tn = stiffsoft::bench::median(many);
    // Perfectly split, the serial part s stays and the rest takes 1/threads of its time.
    const double s = serial_share.empty() ? 0.0 : stiffsoft::bench::median(serial_share);
    const double ideal = t1 * (s + (1 - s) / threads);
    if (k.loops > 0)  // the split per round as measured on one thread
      std::printf("| %s (%.0f µs serial, then a %.0f µs loop) | %.3f | %.3f | %.2fx | %.2fx | %.0f |\n",
                  k.name, 1e6 * s * t1 / k.loops, 1e6 * (1 - s) * t1 / k.loops, t1, tn, t1 / tn, t1 / ideal,
                  1e6 * (tn - ideal) / k.loops);
    else
      std::printf("| %s | %.3f | %.3f | %.2fx | %.2fx | |\n", k.name, t1, tn, t1 / tn, double(threads));
  }
  return 0;
}
