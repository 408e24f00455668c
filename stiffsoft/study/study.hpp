#pragma once
/// @file `stiffsoft study STUDY.json -o DIR`: a convergence study, from the study file to the
/// report (docs/accuracy.md describes the file format and the outputs).

#include <filesystem>

namespace stiffsoft::study {

/// Options of `stiffsoft study`.
struct StudyOptions {
  std::filesystem::path study;    ///< the study file (.json)
  std::filesystem::path out;      ///< output folder (DIR/runs holds the cached runs)
  int jobs = 0;                   ///< runs at a time; 0: the number of cores
  bool check = true;              ///< run `stiffsoft check` on every run's frames (unless the study turns it off)
  std::filesystem::path program;  ///< the `stiffsoft` program that runs and checks; empty: this program itself
};

/// Runs a study: expands the sweep, runs what is not cached (in parallel child processes of
/// this binary), and writes DIR/study.csv, DIR/report.md and the plots. Returns the exit code:
/// 0 done, 1 the plots could not be drawn (CSV and report still written). Bad study input
/// throws StudyError before any run starts.
int run_study(const StudyOptions& options);

}  // namespace stiffsoft::study
