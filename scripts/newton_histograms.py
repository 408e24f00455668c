#!/usr/bin/env python3
"""Where Newton's iterations go in one run: summarises the per-step stats.csv that
`stiffsoft run` writes (docs/newton.md, issue 17).

    /usr/bin/python3 scripts/newton_histograms.py out/medium/stats.csv
    /usr/bin/python3 scripts/newton_histograms.py out/medium --plot docs/newton/medium.png

The argument is a stats.csv or the run folder that holds one. Prints:
  - mean / median / p90 / max Newton iterations per step, and a text histogram;
  - line-search trials per iteration (line_search_steps / newton_iterations, summed over the
    steps) overall, in the slowest 10 % of steps and in the rest, and in the steps that took
    one iteration; and halvings per iteration overall (line_search_halvings, where stats.csv
    has it);
  - the steps with a CCD-limited iteration (smallest_ccd_step < 1): how many, their mean
    iterations and trials per iteration against the other steps;
  - the steps whose κ differs from the previous row's (κ is reported at the end of a step,
    so a change means κ was doubled or re-balanced during that step): how many, mean
    iterations against the others;
  - Pearson and Spearman correlations of iterations with the number of contacts and with
    |Δ contacts| (change from the previous step);
  - the 10 slowest steps.
With --plot OUT.png it also writes a figure: the histogram, and iterations against time with
the CCD-limited steps marked and the contact count on a second axis.

Needs numpy (matplotlib only for --plot): Debian's /usr/bin/python3 has both
(python3-numpy, python3-matplotlib); a python3 earlier on PATH may not.
"""

import argparse
import csv
import math
import os
import sys

import numpy as np

# Histogram bins of iterations per step: [lo, hi] inclusive.
BINS = [(1, 1), (2, 2), (3, 3), (4, 5), (6, 10), (11, 20), (21, 40), (41, 80), (81, 160), (161, 10**9)]
BAR_WIDTH = 50


def read_stats(path):
    """Columns of a stats.csv as float arrays, keyed by the header's names."""
    if os.path.isdir(path):
        path = os.path.join(path, "stats.csv")
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"{path}: no rows")
    needed = ["step", "time", "newton_iterations", "line_search_steps", "smallest_ccd_step", "contacts", "kappa"]
    missing = [c for c in needed if c not in rows[0]]
    if missing:
        sys.exit(f"{path}: missing columns {', '.join(missing)}")
    columns = {}
    for name in rows[0]:
        try:
            columns[name] = np.array([float(r[name]) for r in rows])
        except ValueError:
            pass  # a non-numeric column: not used here
    return path, columns


def ranks(a):
    """Average ranks (ties share the mean rank), for Spearman's correlation."""
    order = np.argsort(a, kind="mergesort")
    r = np.empty(len(a))
    sorted_a = a[order]
    i = 0
    while i < len(a):
        j = i
        while j + 1 < len(a) and sorted_a[j + 1] == sorted_a[i]:
            j += 1
        r[order[i : j + 1]] = 0.5 * (i + j)
        i = j + 1
    return r


def correlation(a, b):
    """(Pearson, Spearman); NaN where either series is constant."""
    if len(a) < 3 or np.std(a) == 0 or np.std(b) == 0:
        return float("nan"), float("nan")
    return float(np.corrcoef(a, b)[0, 1]), float(np.corrcoef(ranks(a), ranks(b))[0, 1])


def ratio(num, den):
    return num / den if den else float("nan")


def group_line(label, mask, it, ls):
    n = int(mask.sum())
    if n == 0:
        return f"  {label:<34} {0:5d} steps"
    return (f"  {label:<34} {n:5d} steps  mean it./step {it[mask].mean():6.2f}  median {np.median(it[mask]):5.1f}"
            f"  trials/it. {ratio(ls[mask].sum(), it[mask].sum()):5.2f}  share of all it. {it[mask].sum() / it.sum():6.1%}")


def summarise(path, c, out=sys.stdout):
    p = lambda *a: print(*a, file=out)
    step, t = c["step"], c["time"]
    it, ls, ccd = c["newton_iterations"], c["line_search_steps"], c["smallest_ccd_step"]
    contacts, kappa = c["contacts"], c["kappa"]
    n = len(it)
    p(f"== {path}: {n} steps, t = {t[0]:.4g} .. {t[-1]:.4g} s")
    if "converged" in c:
        p(f"  not converged: {int((c['converged'] == 0).sum())} steps")
    p(f"  Newton iterations per step: mean {it.mean():.2f}  median {np.median(it):.1f}  "
      f"p90 {np.percentile(it, 90):.1f}  max {int(it.max())}  total {int(it.sum())}")

    p("\n  histogram of iterations per step")
    counts = [int(((it >= lo) & (it <= hi)).sum()) for lo, hi in BINS]
    top = max(counts) or 1
    for (lo, hi), k in zip(BINS, counts):
        label = f"{lo}" if lo == hi else (f"{lo}-{hi}" if hi < 10**9 else f">={lo}")
        bar = "#" * int(round(BAR_WIDTH * k / top))
        if k and not bar:
            bar = "."
        p(f"  {label:>7} | {bar:<{BAR_WIDTH}} {k:5d} ({k / n:5.1%})")

    p("\n  line-search trials per iteration (sum of trials / sum of iterations)")
    p(f"  overall: {ratio(ls.sum(), it.sum()):.2f}   ({int(ls.sum())} trials, {int(it.sum())} iterations)")
    if "line_search_halvings" in c:  # stats.csv since session 40
        halvings = c["line_search_halvings"]
        p(f"  halvings per iteration: {ratio(halvings.sum(), it.sum()):.2f}   ({int(halvings.sum())} halvings; "
          "the other extra trials retry a geodesic trial's α on the straight line)")
    k10 = max(1, int(math.ceil(0.1 * n)))
    slow = np.zeros(n, bool)
    slow[np.argsort(-it, kind="mergesort")[:k10]] = True
    p(group_line("slowest 10 % of steps", slow, it, ls))
    p(group_line("other 90 %", ~slow, it, ls))
    one = it == 1
    p(group_line("steps with 1 iteration", one, it, ls))
    if one.any():
        p(f"  {'':<34} trials in those steps: mean {ls[one].mean():.2f}, max {int(ls[one].max())} "
          "(all in the final, converging iteration)")

    p("\n  CCD-limited steps (smallest_ccd_step < 1 in some iteration)")
    limited = ccd < 1
    p(group_line("CCD-limited", limited, it, ls))
    p(group_line("not CCD-limited", ~limited, it, ls))
    if limited.any():
        p(f"  {'':<34} smallest α from CCD in limited steps: median {np.median(ccd[limited]):.3g}, "
          f"min {ccd[limited].min():.3g}")
    in_contact = contacts > 0
    p(group_line("not CCD-limited, contacts > 0", ~limited & in_contact, it, ls))
    p(group_line("no contacts at step end", ~in_contact, it, ls))

    p("\n  κ changes (κ differs from the previous row)")
    changed = np.zeros(n, bool)
    changed[1:] = kappa[1:] != kappa[:-1]
    p(group_line("κ changed", changed, it, ls))
    p(group_line("κ unchanged", ~changed, it, ls))
    p(f"  {'':<34} κ: first {kappa[0]:.4g}, last {kappa[-1]:.4g}, {len(np.unique(kappa))} distinct values")
    if changed.any():
        idx = np.nonzero(changed)[0]
        shown = ", ".join(f"step {int(step[i])}: {kappa[i - 1]:.3g} -> {kappa[i]:.3g}" for i in idx[:8])
        p(f"  {'':<34} {shown}{' ...' if len(idx) > 8 else ''}")

    p("\n  correlation of iterations per step with           Pearson  Spearman")
    dc = np.zeros(n)
    dc[1:] = np.abs(np.diff(contacts))
    for label, x in (("contacts (at step end)", contacts), ("|Δ contacts| from the previous step", dc),
                     ("smallest_ccd_step", ccd)):
        r, rho = correlation(it, x)
        p(f"  {label:<49} {r:7.2f}  {rho:8.2f}")
    r, rho = correlation(it[in_contact], contacts[in_contact])
    p(f"  {'contacts, steps with contacts only':<49} {r:7.2f}  {rho:8.2f}")

    p("\n  10 slowest steps")
    p(f"  {'step':>6} {'t (s)':>8} {'iter.':>6} {'trials':>7} {'tr./it.':>8} {'contacts':>9} {'Δcont.':>7} "
      f"{'CCD α':>10} {'κ':>11}")
    for i in np.argsort(-it, kind="mergesort")[:10]:
        p(f"  {int(step[i]):6d} {t[i]:8.4f} {int(it[i]):6d} {int(ls[i]):7d} {ratio(ls[i], it[i]):8.2f} "
          f"{int(contacts[i]):9d} {int(dc[i]):7d} {ccd[i]:10.3g} {kappa[i]:11.4g}")
    p("")


def plot(path, c, out_png):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    it, t, ccd, contacts = c["newton_iterations"], c["time"], c["smallest_ccd_step"], c["contacts"]
    fig, (a, b) = plt.subplots(1, 2, figsize=(8, 2.8), dpi=80)
    width = max(1, int(math.ceil(it.max() / 60)))  # integer bins, at most about 60 of them
    edges = np.arange(0.5, it.max() + width + 0.5, width)
    a.hist(it, bins=edges, color="tab:blue", edgecolor="black", linewidth=0.3)
    a.axvline(it.mean(), color="black", linestyle=":", linewidth=0.8)
    a.set_xlabel("Newton iterations per step")
    a.set_ylabel("steps")
    a.set_title(f"mean {it.mean():.1f}, median {np.median(it):.0f}, max {int(it.max())}", fontsize=9)
    limited = ccd < 1
    b.plot(t, it, color="tab:blue", linewidth=0.8, label="iterations")
    b.scatter(t[limited], it[limited], s=6, color="tab:red", zorder=3, label="CCD-limited step")
    b.set_xlabel("t (s)")
    b.set_ylabel("iterations")
    b2 = b.twinx()
    b2.plot(t, contacts, color="tab:gray", linewidth=0.8, linestyle="--")
    b2.set_ylabel("contacts", color="tab:gray")
    b.legend(fontsize=7, loc="upper right", framealpha=0.6)
    name = os.path.basename(os.path.dirname(os.path.abspath(path)))
    fig.suptitle(name, fontsize=10)
    fig.tight_layout()
    fig.savefig(out_png, dpi=80)
    plt.close(fig)
    print(f"wrote {out_png} ({os.path.getsize(out_png) / 1024:.0f} kB)")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("stats", help="a stats.csv, or the run folder holding one")
    ap.add_argument("--plot", metavar="OUT.png", help="also write a histogram figure")
    args = ap.parse_args()
    path, c = read_stats(args.stats)
    summarise(path, c)
    if args.plot:
        plot(path, c, args.plot)


if __name__ == "__main__":
    main()
