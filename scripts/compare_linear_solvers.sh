#!/usr/bin/env bash
# Every linear-solver backend on whole runs of scenes of growing size (docs/linear_solvers.md),
# in one command: builds linear_solver_runs_bench, runs it serially on every scene, then the
# largest scenes once on one rank and once under `mpirun -n 2` (same options, one thread per
# rank), and writes the CSVs, the Markdown table and the plot.
#
#   scripts/compare_linear_solvers.sh                 # default scenes, 20 steps per run
#   scripts/compare_linear_solvers.sh --steps 10      # any bench option passes to the serial run
#
# Environment: BUILD_DIR (default build/release, the Release preset), OUT (default
# out/linear_solvers), MPI_SCENES (default bricks_900,cube_on_mattress), MPI_BACKENDS, MPI_ARGS
# (options of the one- and two-rank runs; default: from t = 0.15 s, when bricks_900 is a
# pile in contact, 5 steps).
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${BUILD_DIR:-build/release}
OUT=${OUT:-out/linear_solvers}
MPI_SCENES=${MPI_SCENES:-bricks_900,cube_on_mattress}
MPI_BACKENDS=${MPI_BACKENDS:-cholmod,petsc:cg:icc,petsc:cg:gamg}
MPI_ARGS=${MPI_ARGS:---start 0.15 --steps 5}
mkdir -p "$OUT"
if [ "$BUILD_DIR" = build/release ]; then cmake --preset release >/dev/null; else
  cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null; fi
cmake --build "$BUILD_DIR" --target linear_solver_runs_bench -j "$(nproc)"
bench="$BUILD_DIR/bench/linear_solver_runs_bench"
"$bench" --csv "$OUT/serial.csv" "$@" | tee "$OUT/serial.md"
csvs=("$OUT/serial.csv")
if command -v mpirun >/dev/null 2>&1; then
  # shellcheck disable=SC2086  # MPI_ARGS is a list of options
  mpi_options=(--threads 1 --scenes "$MPI_SCENES" --backends "$MPI_BACKENDS" --refine 0.5 $MPI_ARGS)
  "$bench" "${mpi_options[@]}" --csv "$OUT/mpi1.csv" | tee "$OUT/mpi1.md"
  mpirun --allow-run-as-root --oversubscribe -n 2 "$bench" "${mpi_options[@]}" --csv "$OUT/mpi2.csv" |
    tee "$OUT/mpi2.md"
  csvs+=("$OUT/mpi1.csv" "$OUT/mpi2.csv")
else
  echo "compare_linear_solvers: no mpirun, serial rows only" >&2
fi
# Debian's python3 has python3-matplotlib; a python3 earlier on PATH may not.
PY=python3
[ -x /usr/bin/python3 ] && PY=/usr/bin/python3
"$PY" bench/report_linear_solvers.py "${csvs[@]}" --markdown "$OUT/linear_solvers.md" --plot "$OUT/linear_solvers.png"
echo "compare_linear_solvers: results in $OUT (serial.csv, mpi1.csv, mpi2.csv, linear_solvers.md, linear_solvers.png)"
