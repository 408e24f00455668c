#!/usr/bin/env python3
"""How the cost of a Newton iteration grows with the scene (docs/benchmarks.md, "Scaling with
the number of bodies", issue 22): for several runs of `stiffsoft run`, the milliseconds per
iteration over a window of steps, split by phase, against the number of bodies and the mean
number of contacts, with least-squares exponents of log(ms per iteration) on log(bodies) and
on log(contacts).

    python3 scripts/iteration_scaling.py out/light:30:240 out/medium:30:240 out/full:60:120 \\
        --plot docs/iteration_scaling.png

Each argument is RUN[,RUN...][:FIRST[:LAST]]: run folders of one scene (their stats.csv and
scene.resolved.json) and the steps counted; with several runs of a scene (repeated on a noisy
machine) each figure is their median. The table is written as Markdown to stdout; --plot needs
matplotlib.
"""

import argparse
import json
import math
import os
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from iteration_cost import PHASES, read_rows, summarise  # noqa: E402


def parse_run(text):
    parts = text.split(":")
    runs = parts[0].split(",")
    first = int(parts[1]) if len(parts) > 1 and parts[1] else 0
    last = int(parts[2]) if len(parts) > 2 and parts[2] else 10**9
    return runs, first, last


def body_count(run):
    path = os.path.join(run, "scene.resolved.json")
    if not os.path.isfile(path):
        sys.exit(f"iteration_scaling: {path}: no such file (expected the folder of a `stiffsoft run`)")
    with open(path) as f:
        return len(json.load(f)["bodies"])


def mean_contacts(rows, first, last):
    """Contacts per iteration: each step's active contacts weighted by its iterations."""
    chosen = [r for r in rows if first <= int(float(r["step"])) <= last]
    iterations = sum(float(r["newton_iterations"]) for r in chosen)
    return sum(float(r["contacts"]) * float(r["newton_iterations"]) for r in chosen) / max(iterations, 1)


def fitted_exponent(xs, ys):
    """Slope of the least-squares line through (log x, log y)."""
    lx = [math.log(x) for x in xs]
    ly = [math.log(y) for y in ys]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    sxx = sum((a - mx) ** 2 for a in lx)
    return sum((a - mx) * (b - my) for a, b in zip(lx, ly)) / sxx if sxx > 0 else float("nan")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("runs", nargs="+", help="RUN[,RUN...][:FIRST[:LAST]]: run folders of one scene and the steps counted")
    parser.add_argument("--plot", help="write log-log plots of ms per iteration against bodies and contacts here")
    args = parser.parse_args()
    points = []
    header = ["scene", "bodies", "steps", "contacts (mean per iteration)", "ms per iteration"] + PHASES
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    for text in args.runs:
        runs, first, last = parse_run(text)
        summaries, contacts, first_rows = [], [], None
        for run in runs:
            rows = read_rows(run)
            first_rows = first_rows or rows
            s = summarise(rows, first, last)
            if s is None:
                sys.exit(f"iteration_scaling: {run}: no steps in [{first}, {last}]")
            summaries.append(s)
            contacts.append(mean_contacts(rows, first, last))
        bodies, contact = body_count(runs[0]), statistics.median(contacts)
        ms = statistics.median(s["ms_per_iteration"] for s in summaries)
        points.append((os.path.basename(os.path.normpath(runs[0])), bodies, contact, ms))
        steps = [int(float(r["step"])) for r in first_rows if first <= int(float(r["step"])) <= last]
        phases = [statistics.median(s["phases_ms"][p] for s in summaries) for p in PHASES]
        cells = [points[-1][0], f"{bodies:,}", f"{min(steps)}–{max(steps)}", f"{contact:,.0f}", f"{ms:.2f}"]
        cells += [f"{v:.2f}" for v in phases]
        print("| " + " | ".join(cells) + " |")
    if len(points) > 1:
        by_bodies = fitted_exponent([p[1] for p in points], [p[3] for p in points])
        by_contacts = fitted_exponent([p[2] for p in points], [p[3] for p in points])
        print(f"\nexponent in the body count: {by_bodies:.2f}; in the contact count: {by_contacts:.2f}")
    if args.plot:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, axes = plt.subplots(1, 2, figsize=(10, 4.2), sharey=True)
        for ax, column, label, exponent in ((axes[0], 1, "bodies", by_bodies), (axes[1], 2, "contacts (mean per iteration)", by_contacts)):
            xs = [p[column] for p in points]
            ax.loglog(xs, [p[3] for p in points], "o", color="tab:blue")  # not joined: scenes of several kinds
            for p in points:
                ax.annotate(p[0], (p[column], p[3]), textcoords="offset points", xytext=(5, -12), fontsize=8)
            if len(points) > 1:
                x0, m0 = xs[0], points[0][3]
                guide = sorted(xs)
                ax.loglog(guide, [m0 * (x / x0) ** 1.1 for x in guide], "--", color="gray", label="n^1.1 from the first point")
                ax.legend(fontsize=8)
                ax.set_title(f"fitted exponent {exponent:.2f}")
            ax.set_xlabel(label)
            ax.grid(True, which="both", alpha=0.3)
        axes[0].set_ylabel("ms per Newton iteration (one thread)")
        fig.tight_layout()
        fig.savefig(args.plot, dpi=110)


if __name__ == "__main__":
    main()
