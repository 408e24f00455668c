#!/usr/bin/env python3
"""What one Newton iteration costs in a run: milliseconds per iteration, split by phase, from
the per-step stats.csv that `stiffsoft run` writes (docs/benchmarks.md, issue 22).

    python3 scripts/iteration_cost.py out/medium
    python3 scripts/iteration_cost.py out/full/stats.csv --first-step 60 --last-step 120
    python3 scripts/iteration_cost.py out/a out/b          # several runs, one row each

The argument is a stats.csv or the run folder that holds one. Per run it sums, over the
chosen steps, the seconds of each phase (broad phase, CCD, assembly, linear solve) and of the
whole step, and divides by the Newton iterations of those steps. "other" is the rest of the
step: line-search energies, surface maps, friction lagging and the bookkeeping between
phases. Only the standard library is used.
"""

import argparse
import csv
import os
import sys

PHASES = ["broad_phase", "ccd", "assembly", "solve"]


def read_rows(path):
    if os.path.isdir(path):
        path = os.path.join(path, "stats.csv")
    if not os.path.isfile(path):
        sys.exit(f"iteration_cost: {path}: no such file (expected a run folder or its stats.csv)")
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def summarise(rows, first, last):
    chosen = [r for r in rows if first <= int(float(r["step"])) <= last]
    if not chosen:
        return None
    iterations = sum(float(r["newton_iterations"]) for r in chosen)
    step = sum(float(r["seconds_step"]) for r in chosen)
    phases = {p: sum(float(r["seconds_" + p]) for r in chosen) for p in PHASES}
    return {
        "steps": len(chosen),
        "iterations": iterations,
        "ms_per_iteration": 1e3 * step / max(iterations, 1),
        "ms_per_step": 1e3 * step / len(chosen),
        "phases_ms": {p: 1e3 * s / max(iterations, 1) for p, s in phases.items()},
        "other_ms": 1e3 * (step - sum(phases.values())) / max(iterations, 1),
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("runs", nargs="+", help="run folders or stats.csv files")
    parser.add_argument("--first-step", type=int, default=0, help="first step counted (default 0)")
    parser.add_argument("--last-step", type=int, default=10**9, help="last step counted (default: all)")
    args = parser.parse_args()
    header = ["run", "steps", "it./step", "ms/step", "ms/it."] + [p + " ms/it." for p in PHASES] + ["other ms/it."]
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    for run in args.runs:
        s = summarise(read_rows(run), args.first_step, args.last_step)
        if s is None:
            print(f"| {run} | no steps in [{args.first_step}, {args.last_step}] |")
            continue
        cells = [run, str(s["steps"]), f"{s['iterations'] / s['steps']:.2f}", f"{s['ms_per_step']:.1f}",
                 f"{s['ms_per_iteration']:.2f}"]
        for p in PHASES:
            ms = s["phases_ms"][p]
            cells.append(f"{ms:.2f} ({100 * ms / s['ms_per_iteration']:.0f} %)")
        cells.append(f"{s['other_ms']:.2f} ({100 * s['other_ms'] / s['ms_per_iteration']:.0f} %)")
        print("| " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
