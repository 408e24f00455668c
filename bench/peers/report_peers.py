#!/usr/bin/env python3
"""Turns peer_bench CSVs into the Markdown tables of docs/peers.md and the plot of ms per
step against body count at h = 1/240.

    python3 bench/peers/report_peers.py out/peers/peers.csv [rerun.csv ...] \
        --markdown out/peers/peers.md --plot out/peers/peers_h240.png

Later CSVs replace the rows (engine, scene, h) of earlier ones, so timing-critical rows can be
re-run on a quieter machine and merged. Standard library only, except the plot, which needs
matplotlib (python3-matplotlib; scripts/setup_bench.sh installs it): without it the plot is
skipped with a message. Every number comes from the CSVs, except the seed's table, which is
quoted from ../shared/seeds/001 (its own machine) for the side-by-side ratios.
"""

import argparse
import csv
import math
import re
import os
import sys

ENGINES = ["stiffsoft", "stiffsoft-coarse", "stiffsoft-sleep", "bullet_mesh", "bullet_mesh-awake", "bullet", "mujoco", "mujoco-cg"]
OURS = ["stiffsoft", "stiffsoft-coarse", "stiffsoft-sleep"]
LABEL = {"stiffsoft": "stiffsoft", "stiffsoft-coarse": "stiffsoft coarse", "stiffsoft-sleep": "stiffsoft sleeping",
         "bullet_mesh": "Bullet mesh", "bullet_mesh-awake": "Bullet mesh awake",
         "bullet": "Bullet", "mujoco": "MuJoCo", "mujoco-cg": "MuJoCo CG"}
# The seed's Bullet set-up: every body a triangle mesh (GImpact), as in the ABD and Rigid-IPC papers;
# its table is set beside the first of these that the CSVs hold.
SEED_PEERS = ["bullet_mesh", "bullet"]
SCENE_ORDER = ["light", "medium", "full", "house_of_cards", "wrecking_ball", "chain_net"]
# Seed 001 ("Compare with Bullet"): ABD ms, Bullet(-mesh) ms, ABD Newton iterations, per pile and 1/h.
SEED = {
    ("light", 100): (3, 2, 1.9), ("light", 240): (2.2, 1.5, 1.5), ("light", 1000): (2, 3, 1.1),
    ("medium", 100): (92, 68, 7.6), ("medium", 240): (41, 58, 2.9), ("medium", 1000): (19, 82, 1.3),
    ("full", 100): (657, 629, 11.0), ("full", 240): (328, 809, 4.4), ("full", 1000): (102, 804, 1.8),
}


def read(paths):
    rows, comments = {}, []
    for path in paths:
        with open(path, encoding="utf-8") as f:
            lines = [line for line in f if not (line.startswith("#") and comments.append(line[1:].strip()) is None)]
        for row in csv.DictReader(lines):
            row["per_s"] = round(1 / float(row["dt"]))
            rows[(row["engine"], row["scene"], row["per_s"])] = row
    return rows, comments


def num(row, key):
    value = row.get(key, "")
    return float(value) if value not in ("", None) else math.nan


def fmt(x, digits=3):
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "–"
    return f"{x:.{digits}g}" if abs(x) < 10 ** digits else f"{x:.0f}"


def unfinished(row):
    """True for a run peer_bench stopped with --max-wall before its last step."""
    return "stopped unfinished" in row.get("warnings", "")


def unfinished_cell(row):
    """An unfinished run's cell: its median covers only the first steps (often the cheap free
    fall), so the cell gives what is certain: the whole run's mean is at least wall / planned."""
    match = re.search(r"(\d+) of (\d+) steps", row["warnings"])
    planned = int(match.group(2)) if match else int(row["steps"])
    wall = num(row, "wall_s")
    return f"unfinished: {row['steps']}/{planned} steps in {wall:.0f} s (mean ≥ {1e3 * wall / planned:.0f})"


def mm(x):
    return "–" if math.isnan(x) else f"{1e3 * x:.3g}"


def scene_key(name):
    return (SCENE_ORDER.index(name) if name in SCENE_ORDER else len(SCENE_ORDER), name)


def accuracy(row):
    """The accuracy cell of one engine's run."""
    if row is None:
        return "–"
    checked, bad = int(row["frames_checked"]), int(row["frames_intersecting"])
    frames = f"{bad}/{checked} frames intersect"
    tunnel = "**tunnelled**" if row["tunnelled"] == "1" else "no tunnelling"
    if row["engine"] in OURS:
        d = num(row, "smallest_distance_m")
        distance = f"min. distance {mm(d)} mm" if not math.isnan(d) else "no contact"
        return f"{distance}; {frames}; {tunnel}"
    return (f"overlap {mm(num(row, 'max_overlap_m'))} mm (engine: {mm(num(row, 'max_engine_depth_m'))} mm); "
            f"{frames}; {tunnel}")


def markdown(rows, comments):
    keys = sorted({(s, p) for (_, s, p) in rows}, key=lambda k: (scene_key(k[0]), k[1]))
    engines = [e for e in ENGINES if any(k[0] == e for k in rows)]
    out = []
    for c in comments:
        out.append(f"- {c}")
    durations = sorted({r["duration_s"] for r in rows.values() if not unfinished(r)})
    out.append(f"- simulated time per run: {', '.join(d + ' s' for d in durations)}")
    out.append("")
    head = ["scene", "bodies", "h", "steps"]
    for e in engines:
        head.append(f"{LABEL[e]} ms/step")
        if e in OURS:
            head.append("Newton it./step")
    ours = [o for o in OURS if o in engines]
    peers = [e for e in engines if e not in OURS]
    for o in ours:
        for e in peers:
            head.append(f"{LABEL[o]} / {LABEL[e]}")
    out.append("| " + " | ".join(head) + " |")
    out.append("|" + "---|" * len(head))
    for scene, per_s in keys:
        present = [rows[(e, scene, per_s)] for e in engines if (e, scene, per_s) in rows]
        steps = max(int(r["steps"]) for r in present)
        cells = [scene, present[0]["bodies"], f"1/{per_s}", str(steps)]
        ms = {}
        for e in engines:
            r = rows.get((e, scene, per_s))
            ms[e] = num(r, "ms_median") if r else math.nan
            if r and unfinished(r):  # stopped by --max-wall: no ratio from a partial run
                cells.append(unfinished_cell(r))
                ms[e] = math.nan
            else:
                cells.append(fmt(ms[e]))
            if e in OURS:
                cells.append(fmt(num(r, "newton_mean")) if r else "–")
        for o in ours:
            for e in peers:
                ratio = ms[o] / ms[e] if ms[e] > 0 else math.nan
                cells.append(fmt(ratio) + "×" if not math.isnan(ratio) else "–")
        out.append("| " + " | ".join(cells) + " |")

    out += ["", "Accuracy (same runs, definitions above): stiffsoft's smallest contact distance; for the peers "
            "the deepest overlap of one body's vertex inside another on the checked frames (and, in brackets, the "
            "deepest penetration their own contacts reported); for all, the exact intersection check of the checked "
            "frames and whether a body tunnelled.", ""]
    head = ["scene", "h"] + [LABEL[e] for e in engines]
    out.append("| " + " | ".join(head) + " |")
    out.append("|" + "---|" * len(head))
    for scene, per_s in keys:
        out.append("| " + " | ".join([scene, f"1/{per_s}"] + [accuracy(rows.get((e, scene, per_s))) for e in engines]) + " |")

    notes = [(k, r) for k, r in sorted(rows.items(), key=lambda kv: (scene_key(kv[0][1]), kv[0][2], kv[0][0]))
             if r["tunnel_note"] or r["warnings"] or r.get("statistics")]
    if notes:
        out += ["", "First tunnelling finding, engine warnings and MuJoCo's buffer use per run:", ""]
        for (e, s, p), r in notes:
            text = "; ".join(x for x in (r["tunnel_note"], ("warnings: " + r["warnings"]) if r["warnings"] else "",
                                         r.get("statistics", "")) if x)
            out.append(f"- {LABEL[e]}, {s}, h = 1/{p}: {text}")

    if ours:
        out += ["", "stiffsoft per phase (means per step, ms) and steps that hit Newton's iteration cap:", ""]
        out.append("| settings | scene | h | total ms (median) | Newton it. | broad phase | CCD | assembly | solve | unconverged |")
        out.append("|---|---|---|---|---|---|---|---|---|---|")
        for scene, per_s in keys:
          for o in ours:
            r = rows.get((o, scene, per_s))
            if r:
                out.append("| " + " | ".join([LABEL[o], scene, f"1/{per_s}", fmt(num(r, "ms_median")), fmt(num(r, "newton_mean"))] +
                                             [fmt(num(r, k)) for k in ("broad_phase_ms", "ccd_ms", "assembly_ms", "solve_ms")] +
                                             [r["unconverged"]]) + " |")

    seed_rows = [(s, p) for (s, p) in keys if (s, p) in SEED]
    peer = next((e for e in SEED_PEERS if e in engines), None)
    if seed_rows and ours and peer:
        name = LABEL[peer]
        out += ["", f"Beside the seed's table (seed 001, its machine; ratios are each table's ABD or stiffsoft time "
                f"over its own Bullet time, here {name}):", ""]
        out.append("| pile | h | " + " | ".join(f"{LABEL[o]} / {name} here" for o in ours) +
                   " | seed ABD / Bullet | " + " | ".join(f"{LABEL[o]} it." for o in ours) +
                   f" | seed ABD it. | {name} ms here | seed Bullet ms |")
        out.append("|" + "---|" * (6 + 2 * len(ours)))
        for s, p in seed_rows:
            bullet = rows.get((peer, s, p))
            abd, seed_bullet, seed_it = SEED[(s, p)]
            ratios, its = [], []
            for o in ours:
                r = rows.get((o, s, p))
                ratio = num(r, "ms_median") / num(bullet, "ms_median") if r and bullet else math.nan
                ratios.append(fmt(ratio) + "×" if not math.isnan(ratio) else "–")
                its.append(fmt(num(r, "newton_mean")) if r else "–")
            out.append("| " + " | ".join([s, f"1/{p}"] + ratios + [fmt(abd / seed_bullet) + "×"] + its +
                                         [fmt(seed_it), fmt(num(bullet, "ms_median")) if bullet else "–",
                                          fmt(seed_bullet)]) + " |")

    settings = {}
    for (e, s, p), r in rows.items():
        settings.setdefault(e, []).append((s, p, r["settings"]))
    out += ["", "Settings in force (as each engine reported them, first run per engine):", ""]
    for e in engines:
        s, p, line = sorted(settings[e], key=lambda x: (scene_key(x[0]), x[1]))[0]
        out.append(f"- {LABEL[e]} ({s}, 1/{p}): {line}")
    return "\n".join(out) + "\n"


def plot(rows, path, per_s=240):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print(f"report_peers: matplotlib is not installed (python3-matplotlib; scripts/setup_bench.sh installs it): "
              f"no plot written to {path}", file=sys.stderr)
        return False
    fig, ax = plt.subplots(figsize=(7, 4.5))
    markers = {"stiffsoft": "o", "stiffsoft-coarse": "D", "stiffsoft-sleep": "P", "bullet_mesh": "v", "bullet_mesh-awake": "<", "bullet": "s", "mujoco": "^", "mujoco-cg": ">"}
    for e in ENGINES:
        points = sorted((int(r["bodies"]), num(r, "ms_median"), r["scene"]) for (en, s, p), r in rows.items()
                        if en == e and p == per_s and not unfinished(r))
        if not points:
            continue
        ax.plot([x for x, _, _ in points], [y for _, y, _ in points], marker=markers[e], linestyle="-", label=LABEL[e])
        for x, y, name in points:
            ax.annotate(name, (x, y), textcoords="offset points", xytext=(4, 3), fontsize=7)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("bodies in the scene")
    ax.set_ylabel("median ms per step")
    ax.set_title(f"ms per step against body count, h = 1/{per_s} s")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    print(f"report_peers: wrote {path}")
    return True


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("csv", nargs="+", help="peer_bench CSVs; later ones replace earlier rows")
    parser.add_argument("--markdown", help="Markdown output (default: stdout)")
    parser.add_argument("--plot", help="PNG of ms/step vs bodies at h = 1/240")
    parser.add_argument("--merged-csv", help="write the merged rows to this CSV")
    args = parser.parse_args()
    rows, comments = read(args.csv)
    text = markdown(rows, comments)
    if args.markdown:
        with open(args.markdown, "w", encoding="utf-8") as f:
            f.write(text)
        print(f"report_peers: wrote {args.markdown}")
    else:
        sys.stdout.write(text)
    if args.merged_csv:
        fields = [k for k in next(iter(rows.values())).keys() if k != "per_s"]
        with open(args.merged_csv, "w", encoding="utf-8", newline="") as f:
            for c in comments:
                f.write(f"# {c}\n")
            writer = csv.DictWriter(f, fieldnames=fields, extrasaction="ignore")
            writer.writeheader()
            for key in sorted(rows, key=lambda k: (scene_key(k[1]), k[2], ENGINES.index(k[0]) if k[0] in ENGINES else 9)):
                writer.writerow(rows[key])
        print(f"report_peers: wrote {args.merged_csv}")
    if args.plot:
        plot(rows, args.plot)


if __name__ == "__main__":
    main()
