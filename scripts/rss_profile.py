#!/usr/bin/env python3
"""Resident memory of a `stiffsoft run` over its steps: does a long run grow?

Starts `stiffsoft run SCENE -o OUT --steps N [--threads T]`, samples the process's VmRSS from
/proc every 0.5 s together with the steps done (rows of OUT/stats.csv, flushed at every frame),
and prints the RSS at each tenth of the run and the growth after the first contacts.

    python3 scripts/rss_profile.py scenes/full.json --steps 2000 -o out/rss_full [--threads 1]
"""
import argparse
import pathlib
import subprocess
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]


def rss_mib(pid):
    with open(f"/proc/{pid}/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024.0
    return float("nan")


def steps_done(stats):
    try:
        with open(stats) as f:
            return max(0, sum(1 for _ in f) - 1)
    except OSError:
        return 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scene")
    parser.add_argument("-o", "--out", required=True)
    parser.add_argument("--steps", type=int, required=True)
    parser.add_argument("--threads", type=int, default=1)
    parser.add_argument("--program", default=str(ROOT / "build" / "release" / "apps" / "stiffsoft"))
    args = parser.parse_args()
    out = pathlib.Path(args.out)
    child = subprocess.Popen([args.program, "run", args.scene, "-o", str(out), "--steps", str(args.steps),
                              "--threads", str(args.threads)], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    samples = []  # (seconds, steps, MiB)
    start = time.time()
    while child.poll() is None:
        try:
            samples.append((time.time() - start, steps_done(out / "stats.csv"), rss_mib(child.pid)))
        except OSError:
            break
        time.sleep(0.5)
    with open(out / "rss.csv", "w") as f:
        f.write("seconds,steps,rss_mib\n")
        for s in samples:
            f.write(f"{s[0]:.1f},{s[1]},{s[2]:.1f}\n")
    print(f"exit {child.returncode}; {len(samples)} samples over {samples[-1][0]:.0f} s; {out / 'rss.csv'}")
    print("steps   RSS (MiB)")
    for tenth in range(1, 11):
        target = args.steps * tenth / 10
        at = next((s for s in samples if s[1] >= target), samples[-1])
        print(f"{at[1]:5d}   {at[2]:8.1f}")
    peak = max(s[2] for s in samples)
    print(f"peak {peak:.1f} MiB")


if __name__ == "__main__":
    main()
