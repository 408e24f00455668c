#!/usr/bin/env python3
"""Summary of a `newton_trace` CSV (docs/newton.md, session 36): Newton's directions grouped by
their place from their step's end (last, last − 1, …, and all earlier ones together), over the
steps with at least two directions:

    build/release/tools/newton_trace scenes/medium.json --steps 240 --threads 2 --csv trace.csv
    python3 scripts/newton_trace.py trace.csv

Columns: directions; median speed (largest surface step / h, m/s); share CCD-limited (α < 1);
stick/slip changes the direction's accepted step made (mean) and the share that made any;
where along p the energy is lowest of 1, 1.5, 2 and 3 p (shares, over the directions CCD lets go
to 2 p); and for the active contact whose distance the step changes most, medians of its d / d̂
at the iterate and of (d̂ − d₁) / (d̂ − d₀), the share with that ratio in 0.35–0.65 (Newton taking
a contact half-way out of d̂), and the median count of contacts taken 0.35–0.65 of the way out.
Only the standard library is used.
"""

import argparse
import collections
import csv
import math
import statistics
import sys

LINE = ["line_1", "line_1.5", "line_2", "line_3"]


def number(text):
    return float(text) if text != "" else math.nan


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("csv", help="newton_trace's output")
    parser.add_argument("--earlier", type=int, default=6, help="directions this far or further from the end are pooled")
    args = parser.parse_args()

    steps = collections.OrderedDict()
    with open(args.csv) as f:
        for row in csv.DictReader(f):
            steps.setdefault(int(row["step"]), []).append(row)
    groups = collections.defaultdict(list)
    for rows in steps.values():
        if len(rows) < 2:
            continue
        for i, row in enumerate(rows):
            groups[min(len(rows) - 1 - i, args.earlier)].append(row)
    if not groups:
        sys.exit("newton_trace.py: no step with two or more directions in " + args.csv)

    def median(values):
        values = [v for v in values if not math.isnan(v)]
        return statistics.median(values) if values else math.nan

    print("| directions | count | speed (m/s) | CCD-limited | stick/slip changes | with changes | lowest E at 1 / 1.5 / 2 / 3 p "
          "| moving contact's d / d̂ | its ratio | ratio 0.35–0.65 | contacts taken half-way out |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for place in sorted(groups, reverse=True):
        rows = groups[place]
        name = f"{place} or more before the last" if place == args.earlier else ("last" if place == 0 else f"last − {place}")
        flips = [int(r["flips_after"]) - int(r["flips_before"]) for r in rows]
        lowest = collections.Counter()
        for r in rows:
            line = [number(r[c]) for c in LINE]
            if math.isnan(line[2]):
                continue
            finite = [(v, s) for v, s in zip(line, (1, 1.5, 2, 3)) if not math.isnan(v)]
            lowest[min(finite)[1]] += 1
        sampled = sum(lowest.values())
        shares = " / ".join(f"{lowest[s] / sampled:.2f}" if sampled else "–" for s in (1, 1.5, 2, 3))
        ratios = [number(r["gap_ratio"]) for r in rows]
        print(f"| {name} | {len(rows)} | {median([number(r['speed']) for r in rows]):.3g} "
              f"| {sum(number(r['alpha']) < 1 for r in rows) / len(rows):.2f} "
              f"| {sum(flips) / len(rows):.2f} | {sum(f > 0 for f in flips) / len(rows):.2f} | {shares} "
              f"| {median([number(r['gap_start']) for r in rows]):.2f} | {median(ratios):.2f} "
              f"| {sum(0.35 < x < 0.65 for x in ratios if not math.isnan(x)) / len(rows):.2f} "
              f"| {median([number(r['halving']) for r in rows]):.1f} |")


if __name__ == "__main__":
    main()
