#include <stiffsoft/study/plot_script.hpp>

namespace stiffsoft::study {

const char* const kPlotScript = R"PY(#!/usr/bin/env python3
"""Plots of a stiffsoft study (written by `stiffsoft study`): error against the swept parameter
(log-log, fitted slope per series) and error against wall time (speed/accuracy frontier)."""
import json
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

data_file = sys.argv[1]
out = os.path.dirname(os.path.abspath(data_file))
with open(data_file) as f:
    data = json.load(f)


def finite_points(xs, ys):
    return [(x, y) for x, y in zip(xs, ys) if x is not None and y is not None and x > 0 and y > 0]


for q in data["quantities"]:
    unit = f" ({q['unit']})" if q["unit"] else ""
    fig, ax = plt.subplots(figsize=(6, 4.2))
    for s in q["series"]:
        pts = finite_points(s["x"], s["error"])
        if not pts:
            continue
        xs, es = zip(*pts)
        label = s["label"] or "error"
        if s["slope"] is not None:
            label += f"  (slope {s['slope']:.2f})"
        (line,) = ax.loglog(xs, es, "o-", label=label)
        if s["slope"] is not None:
            lo, hi = min(xs), max(xs)
            fx = [lo, hi]
            fy = [pow(x, s["slope"]) * s["scale"] for x in fx]
            ax.loglog(fx, fy, "--", color=line.get_color(), alpha=0.6, linewidth=1)
    ax.set_xlabel(q["x_label"])
    ax.set_ylabel(("relative error" if q["relative"] else "error") + unit)
    ax.set_title(f"{data['study']}: {q['name']}", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, q["slug"] + "_error.png"), dpi=110)
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(6, 4.2))
    everything = []
    for s in q["series"]:
        pts = [(w, e, x) for w, e, x in zip(s["wall"], s["error"], s["x"]) if w and e is not None and e > 0]
        if not pts:
            continue
        ws, es, xs = zip(*pts)
        ax.loglog(ws, es, "o", label=s["label"] or "runs")
        for w, e, x in pts:
            ax.annotate(f"{x:g}", (w, e), fontsize=7, xytext=(3, 3), textcoords="offset points")
        everything += pts
    everything.sort()
    front, best = [], float("inf")
    for w, e, _ in everything:
        if e < best:
            best = e
            front.append((w, e))
    if len(front) > 1:
        fw, fe = zip(*front)
        ax.loglog(fw, fe, "k-", linewidth=1, alpha=0.7, drawstyle="steps-post", label="frontier")
    ax.set_xlabel("wall time of the steps per run (s)")
    ax.set_ylabel(("relative error" if q["relative"] else "error") + unit)
    ax.set_title(f"{data['study']}: {q['name']} — speed/accuracy ({q['x_label']} annotated)", fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, q["slug"] + "_frontier.png"), dpi=110)
    plt.close(fig)
)PY";

}  // namespace stiffsoft::study
