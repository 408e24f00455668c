#!/usr/bin/env python3
"""Newton's model by phase of a step, from the CSV that tools/newton_probe writes
(docs/newton.md, session 24). Each direction goes into one group: CCD-limited (α < 1), full
steps before the step's last four, or one of the last four; per group the medians of the
curvature ratio pᵀHp / pᵀ∇²Ep, the error of H p, ρ = ΔE / model, the slope φ′(α) / φ′(0) of
E along p at the step's end (0 at the line's minimum), and the gradient's distance
from the quadratic model at the step's end, ‖g(q + αp) − g − αHp‖ / ‖g‖, in all, from the
contacts that entered d̂ during the step, and per term.

Usage: newton_probe_table.py PROBE.csv   (prints a Markdown table)
"""
import collections
import csv
import statistics
import sys

GROUPS = ["CCD-limited (α < 1)", "α = 1, before the last 4", "last − 3", "last − 2", "last − 1", "last"]


def group_of(back, alpha):
    """The group of a direction `back` directions before its step's last one."""
    if back < 4:
        return "last" if back == 0 else f"last − {back}"
    return GROUPS[0] if alpha < 1 else GROUPS[1]


def main(path):
    rows = list(csv.DictReader(open(path)))
    if not rows:
        sys.exit(f"{path}: no probed directions")
    terms = [k[len("gradient_model_"):] for k in rows[0] if k.startswith("gradient_model_")]
    by_step = collections.defaultdict(list)
    for r in rows:
        by_step[r["step"]].append(r)
    groups = collections.defaultdict(list)
    for directions in by_step.values():
        for i, r in enumerate(directions):
            groups[group_of(len(directions) - 1 - i, float(r["alpha"]))].append(r)

    def median(group, column):
        values = [float(r[column]) for r in group]
        return f"{statistics.median(values):.3g}" if values else "–"

    head = ["directions", "count", "pᵀHp / pᵀ∇²Ep", "‖Hp − ∇²Ep‖ / ‖∇²Ep‖", "ρ", "φ′(α) / φ′(0)",
            "‖g(q+αp) − g − αHp‖ / ‖g‖", "… new contacts"]
    head += [f"… {t}" for t in terms] + ["speed (m/s)"]
    print("| " + " | ".join(head) + " |")
    print("|" + "---|" * len(head))
    for name in GROUPS:
        g = groups[name]
        cells = [name, str(len(g))] + [median(g, c) for c in ("curvature_ratio", "hessian_p", "rho", "slope_ratio", "gradient_model", "new_contacts")]
        cells += [median(g, "gradient_model_" + t) for t in terms] + [median(g, "speed")]
        print("| " + " | ".join(cells) + " |")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
