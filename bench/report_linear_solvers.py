#!/usr/bin/env python3
"""Table and plot of linear_solver_runs_bench CSVs (docs/linear_solvers.md).

    report_linear_solvers.py runs.csv [mpi.csv ...] --markdown table.md --plot solvers.png

Rows of all CSVs are merged. The Markdown table has one row per scene, rank count and backend;
the plot shows milliseconds per step (left) and per linear solve (right) against DOFs, one
line per backend (its colour), rank count and start (runs from a --start state are series
of their own: square markers, dotted on one rank, dashed under mpirun), log-log. Without
matplotlib (python3-matplotlib) the plot is skipped with a message and the table is still
written.
"""
import argparse
import csv
import sys


def read_rows(paths):
    rows = []
    for path in paths:
        with open(path, newline="") as f:
            rows.extend(csv.DictReader(f))
    for r in rows:
        for key in ("dofs", "tets", "ranks", "steps", "unconverged_steps", "fallbacks"):
            r[key] = int(r[key])
        for key in ("ms_per_step", "newton_per_step", "ms_per_newton", "ms_per_solve", "krylov_per_solve",
                    "relative_residual", "deviation_m"):
            r[key] = float(r[key])
    return rows


def markdown(rows):
    lines = ["| scene | DOFs | ranks | backend | ms/step | Newton it./step | ms/Newton it. | ms/solve | "
             "Krylov it./solve | last ‖b−Hp‖/‖b‖ | unconverged | deviation from CHOLMOD (m) |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    # The fastest backend of each scene and rank count in bold.
    best = {}
    for r in rows:
        key = (r["scene"], r["ranks"])
        best[key] = min(best.get(key, float("inf")), r["ms_per_step"])
    for r in sorted(rows, key=lambda r: (r["dofs"], r["scene"], r["ranks"])):
        ms = f"{r['ms_per_step']:.2f}"
        if r["ms_per_step"] == best[(r["scene"], r["ranks"])]:
            ms = f"**{ms}**"
        lines.append(
            f"| {r['scene']} | {r['dofs']} | {r['ranks']} | {r['backend']} | {ms} | {r['newton_per_step']:.1f} | "
            f"{r['ms_per_newton']:.2f} | {r['ms_per_solve']:.3f} | {r['krylov_per_solve']:.1f} | "
            f"{r['relative_residual']:.1e} | {r['unconverged_steps']} | {r['deviation_m']:.1e} |")
    return "\n".join(lines) + "\n"


def plot(rows, path):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("report_linear_solvers: matplotlib is not installed (python3-matplotlib): plot skipped",
              file=sys.stderr)
        return
    series = {}
    for r in rows:
        label = r["backend"]
        if " from t" in r["scene"]:  # --start: steps of a later, contact-rich state, a series of their own
            label += ", from " + r["scene"].split(" from ", 1)[1]
        if r["ranks"] > 1:
            label += f" (mpirun -n {r['ranks']})"
        series.setdefault(label, []).append(r)
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
    # One colour per backend; the line style tells the start and the rank count apart.
    backends = sorted({r["backend"] for r in rows})
    colour = {b: plt.get_cmap("tab10")(i % 10) for i, b in enumerate(backends)}
    for label, points in sorted(series.items()):
        points.sort(key=lambda r: r["dofs"])
        dofs = [r["dofs"] for r in points]
        style = "--" if "mpirun" in label else (":" if ", from t" in label else "-")
        marker = "s" if ", from t" in label else "o"
        c = colour[points[0]["backend"]]
        axes[0].plot(dofs, [r["ms_per_step"] for r in points], style, color=c, marker=marker, label=label)
        axes[1].plot(dofs, [r["ms_per_solve"] for r in points], style, color=c, marker=marker, label=label)
    for ax, title in zip(axes, ("time per step", "time per linear solve (set-up + solve)")):
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("DOFs")
        ax.set_ylabel("ms")
        ax.set_title(title)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    print(f"report_linear_solvers: wrote {path}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv", nargs="+", help="linear_solver_runs_bench CSV files")
    parser.add_argument("--markdown", help="write the table here (default: stdout)")
    parser.add_argument("--plot", help="write the PNG plot here")
    args = parser.parse_args()
    rows = read_rows(args.csv)
    table = markdown(rows)
    if args.markdown:
        with open(args.markdown, "w") as f:
            f.write(table)
    else:
        sys.stdout.write(table)
    if args.plot:
        plot(rows, args.plot)


if __name__ == "__main__":
    main()
