#!/usr/bin/env python3
"""Where a two-thread run of `stiffsoft run` keeps one core waiting (docs/benchmarks.md,
"Session 35", issue 22): from a `perf record` with DWARF call stacks, the main thread's samples
inside Simulation::step at which no worker thread was busy, by Newton phase and by the
stiffsoft functions on their stacks.

    perf record -F 2000 --call-graph dwarf,16384 -o perf.data -- \\
        build/release/apps/stiffsoft run scenes/full.json -o out/full --steps 100 --threads 2
    perf script -i perf.data -F tid,time,ip,sym,dso > perf.txt
    python3 scripts/serial_samples.py perf.txt

A worker counts as busy at time t when it has a sample within --window seconds of t whose
innermost frame is not in TBB's scheduler (spinning or sleeping workers are idle); with
samples every 1/F s, a window of half that period (the default, for F = 2000) is about right.
A sampling estimate: a few per cent either way. Only the standard library is used.
"""

import argparse
import bisect
import collections
import re
import sys

# The Newton phase of a sample: the first match among the three frames below newton_minimize.
PHASES = [("max_step", "CCD"), ("SweptCandidates", "broad phase"), ("BroadPhase", "broad phase"),
          ("factoriz", "solve"), ("analy", "solve"), ("Solver::solve", "solve"), ("solve_in_place", "solve"),
          ("add_hessian", "assembly"), ("assemble", "assembly"), ("add_gradient", "gradient"),
          ("value", "energy"), ("update", "constraints")]


def read_samples(path):
    """[(tid, time, [frame names, innermost first])] from `perf script -F tid,time,ip,sym,dso`."""
    samples, current = [], None
    with open(path, errors="replace") as f:
        for line in f:
            if not line.strip():
                continue
            header = re.match(r"\s*(\d+)\s+([\d.]+):", line)
            if header and not line.startswith("\t"):
                current = (int(header.group(1)), float(header.group(2)), [])
                samples.append(current)
            elif current is not None:
                parts = line.strip().split(None, 1)
                if len(parts) == 2:
                    current[2].append(parts[1])
    return samples


def name(frame):
    return re.sub(r"\(.*", "", frame.split(" (")[0])


def idle(frames):
    return bool(frames) and ("libtbb" in frames[0] or ("kernel" in frames[0] and any("libtbb" in f for f in frames[:8])))


def phase(names):
    if "stiffsoft::newton_minimize" not in names:
        return "outside Newton"
    k = names.index("stiffsoft::newton_minimize")
    below = " ".join(names[max(0, k - 3):k])
    return next((p for key, p in PHASES if key in below), "other")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("perf_script", help="output of perf script -F tid,time,ip,sym,dso")
    parser.add_argument("--window", type=float, default=0.00026, help="seconds (default 0.00026)")
    parser.add_argument("--depth", type=int, default=3, help="stiffsoft frames shown per stack (default 3)")
    parser.add_argument("--top", type=int, default=25, help="stacks listed (default 25)")
    args = parser.parse_args()
    samples = read_samples(args.perf_script)
    if not samples:
        sys.exit(f"serial_samples: {args.perf_script}: no samples")
    per_thread = collections.Counter(s[0] for s in samples)
    main_tid = min(per_thread)
    busy = sorted(t for tid, t, frames in samples if tid != main_tid and not idle(frames))
    in_step = serial = 0
    by_phase, serial_by_phase, stacks = collections.Counter(), collections.Counter(), collections.Counter()
    for tid, t, frames in samples:
        if tid != main_tid:
            continue
        names = [name(f) for f in frames]
        if not any("Simulation::step" in n for n in names):
            continue
        in_step += 1
        p = phase(names)
        by_phase[p] += 1
        i = bisect.bisect_left(busy, t - args.window)
        if i < len(busy) and busy[i] <= t + args.window:
            continue
        serial += 1
        serial_by_phase[p] += 1
        own = [n for n, f in zip(names, frames) if n.startswith("stiffsoft::")]
        stacks[" < ".join(own[:args.depth]) if own else (names[0] if names else "?")] += 1
    if not in_step:
        sys.exit("serial_samples: no main-thread sample inside Simulation::step (call stacks recorded with --call-graph dwarf?)")
    print(f"main-thread samples in Simulation::step: {in_step}; with no worker busy: {serial} ({100 * serial / in_step:.1f} %)")
    print("| phase | samples | with no worker busy |\n|---|---|---|")
    for p, n in by_phase.most_common():
        print(f"| {p} | {n} | {serial_by_phase[p]} ({100 * serial_by_phase[p] / n:.0f} %) |")
    print("\nshare of the step's samples, by stack:")
    for stack, n in stacks.most_common(args.top):
        print(f"{100 * n / in_step:5.2f} %  {stack}")


if __name__ == "__main__":
    main()
