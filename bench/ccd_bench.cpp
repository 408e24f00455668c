/// @file ccd_bench FILE_OR_DIR...: runs the conservative CCD over benchmark query files (format in
/// ../shared/data/ccd-queries/README.md; directories are searched recursively for *.csv) and
/// prints per file and in total: queries, false negatives, false positives, and nanoseconds per
/// query (median over repetitions).

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include <stiffsoft/coupling/ccd/query_file.hpp>

namespace {

namespace fs = std::filesystem;
using stiffsoft::ccd::CcdQuery;
using stiffsoft::ccd::CcdQueryKind;
using stiffsoft::ccd::CcdSettings;

/// Result of one file.
struct FileResult {
  std::size_t queries = 0;
  std::size_t false_negatives = 0;
  std::size_t false_positives = 0;
  double median_seconds = 0;  ///< median wall time of one pass over the file's queries
};

/// Counts errors against the ground truth and times `repetitions` passes over `queries`.
FileResult run_file(CcdQueryKind kind, const std::vector<CcdQuery>& queries,
                    const CcdSettings& settings, int repetitions) {
  FileResult result;
  result.queries = queries.size();
  for (const CcdQuery& q : queries) {
    const bool hit = stiffsoft::ccd::query_toi(kind, q, settings) < settings.t_max;
    result.false_negatives += q.collides && !hit;
    result.false_positives += !q.collides && hit;
  }
  std::vector<double> seconds;
  volatile double sink = 0;  // keeps the calls from being optimized away
  for (int r = 0; r < repetitions; ++r) {
    const auto start = std::chrono::steady_clock::now();
    double sum = 0;
    for (const CcdQuery& q : queries) sum += stiffsoft::ccd::query_toi(kind, q, settings);
    const auto stop = std::chrono::steady_clock::now();
    sink = sink + sum;
    seconds.push_back(std::chrono::duration<double>(stop - start).count());
  }
  std::nth_element(seconds.begin(), seconds.begin() + seconds.size() / 2, seconds.end());
  result.median_seconds = seconds[seconds.size() / 2];
  return result;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Conservative CCD (Additive CCD) over CCD benchmark query files"};
  std::vector<std::string> inputs;
  CcdSettings settings;
  int repetitions = 7;
  app.add_option("inputs", inputs, "query files (*.csv) or folders searched recursively")
      ->required();
  app.add_option("--min-distance", settings.min_distance, "ξ, metres")->capture_default_str();
  app.add_option("--tolerance", settings.tolerance, "s in (0,1)")->capture_default_str();
  app.add_option("--max-iterations", settings.max_iterations, "iteration cap")
      ->capture_default_str();
  app.add_option("--repetitions", repetitions, "timed passes per file (median reported)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  try {
    stiffsoft::ccd::validate(settings);
    std::vector<fs::path> files;
    for (const std::string& input : inputs) {
      const fs::path path(input);
      if (fs::is_directory(path)) {
        for (const auto& entry : fs::recursive_directory_iterator(path)) {
          if (entry.is_regular_file() && entry.path().extension() == ".csv") {
            files.push_back(entry.path());
          }
        }
      } else if (fs::is_regular_file(path)) {
        files.push_back(path);
      } else {
        throw std::runtime_error("cannot read " + input + ": no such file or folder");
      }
    }
    std::sort(files.begin(), files.end());

    FileResult total;
    std::printf("%-60s %8s %6s %6s %10s\n", "file", "queries", "FN", "FP", "ns/query");
    for (const fs::path& file : files) {
      const CcdQueryKind kind = stiffsoft::ccd::ccd_query_kind(file);
      const std::vector<CcdQuery> queries = stiffsoft::ccd::read_ccd_queries(file);
      const FileResult r = run_file(kind, queries, settings, repetitions);
      std::printf("%-60s %8zu %6zu %6zu %10.1f\n", file.string().c_str(), r.queries,
                  r.false_negatives, r.false_positives,
                  r.queries ? 1e9 * r.median_seconds / r.queries : 0.0);
      total.queries += r.queries;
      total.false_negatives += r.false_negatives;
      total.false_positives += r.false_positives;
      total.median_seconds += r.median_seconds;
    }
    std::printf("%-60s %8zu %6zu %6zu %10.1f\n", "TOTAL", total.queries, total.false_negatives,
                total.false_positives,
                total.queries ? 1e9 * total.median_seconds / total.queries : 0.0);
    return total.false_negatives == 0 ? 0 : 2;
  } catch (const std::exception& e) {
    std::cerr << "ccd_bench: error: " << e.what() << "\n";
    return 1;
  }
}
