#!/usr/bin/env python3
"""How much faster a Newton iteration is on more threads, measured the way issue 22 asks
(docs/benchmarks.md, sessions 59–60): a window of steps of one scene, resumed from the same
checkpoint on one thread and on N, in alternated rounds, frames off.

    python3 scripts/thread_speedup.py scenes/full.json --from-step 700
    python3 scripts/thread_speedup.py scenes/bricks_900.json --from-step 80 --steps 40 --rounds 5

The scene is copied with its frames off (`output.frame_dt` beyond the run) and run once to
`--from-step` with a checkpoint (kept in the output folder and reused while the scene copy, the
step and the program are the same). Each round resumes that checkpoint on one thread and on `--threads`
(the order alternating between rounds, so that a drift of the machine's speed favours neither),
leaves out the first `--skip` steps after the resume (a resumed process first touches its
memory and analyses its first patterns: docs/benchmarks.md, session 59) and divides the
window's step seconds by its Newton iterations, phase by phase (scripts/iteration_cost.py).
The two runs must take the same iterations with the same results (every stats.csv column but
the wall-clock ones): the script says so when they do not. It prints a Markdown table with the
machine and its load; `--out` keeps the runs. Only the standard library is used.
"""

import argparse
import hashlib
import json
import os
import platform
import shutil
import statistics
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from iteration_cost import PHASES, read_rows, summarise  # noqa: E402


def with_absolute_meshes(scene, scene_dir):
    """The scene with every body's mesh file (`bodies[].mesh`, relative to the scene file's
    folder: docs/scenes.md) made absolute, so that the copy in the output folder reads the same."""
    for body in scene.get("bodies", []):
        mesh = body.get("mesh") if isinstance(body, dict) else None
        if isinstance(mesh, str) and not os.path.isabs(mesh):
            body["mesh"] = os.path.abspath(os.path.join(scene_dir, mesh))
    return scene


def frames_off_copy(scene_path, from_step, out):
    """Writes the scene with frames off and a duration far past `from_step` (the same copy for
    any window, so that the checkpoint is reused); its path."""
    try:
        with open(scene_path) as f:
            scene = with_absolute_meshes(json.load(f), os.path.dirname(os.path.abspath(scene_path)))
        dt = float(scene["time"]["dt"])
    except (OSError, ValueError, KeyError, TypeError) as e:
        sys.exit(f"thread_speedup: {scene_path}: cannot read the scene's time.dt ({e})")
    scene["time"]["duration"] = max(float(scene["time"].get("duration", 0.0)), (from_step + 100000) * dt)
    scene.setdefault("output", {})["frame_dt"] = 10.0 * scene["time"]["duration"]
    path = os.path.join(out, "scene.json")
    with open(path, "w") as f:
        json.dump(scene, f, indent=1)
    return path


def run(binary, scene, folder, steps, threads, resume):
    command = [binary, "run", scene, "-o", folder, "--steps", str(steps), "--threads", str(threads),
               "--checkpoint-every", "1000000"] + (["--resume"] if resume else [])
    result = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if result.returncode != 0:
        sys.exit(f"thread_speedup: `{' '.join(command)}` failed ({result.returncode}):\n{result.stdout[-2000:]}")


def checkpoint(binary, scene, out, from_step, threads):
    """The run to `from_step`, made once per scene copy, step and build of the program."""
    folder = os.path.join(out, "checkpoint")
    program = os.stat(binary)
    with open(scene, "rb") as f:
        key = hashlib.sha256(f.read() + f"{from_step} {program.st_size} {program.st_mtime_ns}".encode()).hexdigest()
    key_file = os.path.join(out, "checkpoint.key")
    if os.path.isdir(folder) and os.path.isfile(key_file):
        with open(key_file) as f:
            if f.read() == key:
                return folder
    shutil.rmtree(folder, ignore_errors=True)
    run(binary, scene, folder, from_step, threads, resume=False)
    with open(key_file, "w") as f:
        f.write(key)
    return folder


def results(rows, first, last):
    """stats.csv's rows (read_rows) of steps [first, last] without the wall-clock columns."""
    return [{k: v for k, v in r.items() if not k.startswith("seconds_")}
            for r in rows if first <= int(float(r["step"])) <= last]


def machine():
    model = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo") as f:
            model = next((line.split(":", 1)[1].strip() for line in f if line.startswith("model name")), model)
    except OSError:
        pass
    return f"{os.cpu_count()} cores, {model}"


def load():
    try:
        return "{:.2f} {:.2f} {:.2f}".format(*os.getloadavg())
    except OSError:
        return "unknown"


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("scene", help="scene file (.json)")
    parser.add_argument("--from-step", type=int, required=True, help="the checkpoint's step, where windows start")
    parser.add_argument("--skip", type=int, default=12, help="steps left out after the resume (default 12)")
    parser.add_argument("--steps", type=int, default=48, help="steps measured after them (default 48)")
    parser.add_argument("--rounds", type=int, default=3, help="rounds of one run on each thread count (default 3)")
    parser.add_argument("--threads", type=int, default=2, help="the thread count set against one (default 2)")
    parser.add_argument("--binary", default="build/release/apps/stiffsoft", help="the stiffsoft program")
    parser.add_argument("--out", default="out/thread_speedup", help="folder for the scene copy and the runs")
    args = parser.parse_args()
    if not (os.path.isfile(args.binary) and os.access(args.binary, os.X_OK)):
        sys.exit(f"thread_speedup: {args.binary}: no such program (build it: bash scripts/build.sh stiffsoft)")
    if args.from_step < 0 or args.skip < 0 or args.steps < 1 or args.rounds < 1 or args.threads < 2:
        sys.exit("thread_speedup: expected --from-step ≥ 0, --skip ≥ 0, --steps ≥ 1, --rounds ≥ 1, --threads ≥ 2")
    os.makedirs(args.out, exist_ok=True)
    first, last = args.from_step + args.skip + 1, args.from_step + args.skip + args.steps
    scene = frames_off_copy(args.scene, args.from_step, args.out)
    start = checkpoint(args.binary, scene, args.out, args.from_step, args.threads)

    print(f"# {args.scene}, steps {first}–{last} resumed from step {args.from_step}, frames off")
    print(f"# machine: {machine()}; load {load()} at the start")
    header = ["round", "threads", "it.", "ms/it."] + [p + " ms/it." for p in PHASES] + ["other ms/it."]
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    speedups, identical = [], True
    for r in range(args.rounds):
        ms, rows = {}, {}
        for threads in ((1, args.threads) if r % 2 == 0 else (args.threads, 1)):
            folder = os.path.join(args.out, f"run_{threads}")
            shutil.rmtree(folder, ignore_errors=True)
            shutil.copytree(start, folder)
            run(args.binary, scene, folder, last, threads, resume=True)
            stats = read_rows(folder)
            s = summarise(stats, first, last)
            if s is None or s["steps"] != args.steps:
                sys.exit(f"thread_speedup: {folder}/stats.csv lacks steps {first}–{last}")
            ms[threads], rows[threads] = s["ms_per_iteration"], results(stats, first, last)
            cells = [str(r + 1), str(threads), f"{s['iterations']:.0f}", f"{s['ms_per_iteration']:.2f}"]
            cells += [f"{s['phases_ms'][p]:.2f}" for p in PHASES] + [f"{s['other_ms']:.2f}"]
            print("| " + " | ".join(cells) + " |", flush=True)
        identical = identical and rows[1] == rows[args.threads]
        speedups.append(ms[1] / ms[args.threads])
    print()
    print("speed-ups: " + ", ".join(f"{x:.2f}×" for x in speedups) +
          f"; median {statistics.median(speedups):.2f}× on {args.threads} threads against one")
    print(f"load {load()} at the end")
    print("results: " + ("the same on both thread counts (every stats.csv column but the wall-clock ones)"
                         if identical else "DIFFERENT between the thread counts: the runs are not deterministic"))
    return 0 if identical else 1


if __name__ == "__main__":
    sys.exit(main())
