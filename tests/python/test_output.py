"""Output from Python: the same files as `stiffsoft run`, studies, and the examples."""
import csv
import filecmp
import json
import subprocess
import sys

import pytest

import stiffsoft

# stats.csv columns that are wall-clock times, different in every run.
TIMING_COLUMNS = {"seconds_broad_phase", "seconds_ccd", "seconds_assembly", "seconds_solve", "seconds_step"}


def stats_without_timings(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return [{k: v for k, v in row.items() if k not in TIMING_COLUMNS} for row in rows]


def test_python_writes_the_frames_stiffsoft_run_writes(tmp_path, repo, program):
    scene = repo / "scenes" / "soft_ball_on_boxes.json"
    subprocess.run([program, "run", str(scene), "-o", str(tmp_path / "cli"), "--steps", "8"], check=True,
                   capture_output=True)
    stats = stiffsoft.run(scene, tmp_path / "py", steps=8)
    assert len(stats) == 8
    cli, py = tmp_path / "cli", tmp_path / "py"
    files = sorted(p.relative_to(cli) for p in cli.rglob("*") if p.is_file())
    assert sorted(p.relative_to(py) for p in py.rglob("*") if p.is_file()) == files
    frames = [f for f in files if f.suffix in (".vtu", ".vtm", ".pvd")]
    assert len(frames) > 3
    for f in files:
        if f.name == "stats.csv":
            assert stats_without_timings(cli / f) == stats_without_timings(py / f)
        else:
            assert filecmp.cmp(cli / f, py / f, shallow=False), f"{f} differs"


def test_recorder_as_context_and_iterator(tmp_path, repo):
    sim = stiffsoft.Simulation(repo / "scenes" / "box_stack.json")
    with stiffsoft.Recorder(sim, tmp_path / "out") as rec:
        for _ in sim.steps(steps=5, recorder=rec):
            pass
    assert rec.frame_count >= 2 and rec.pvd_path == tmp_path / "out" / "box_stack.pvd"
    assert len(stats_without_timings(tmp_path / "out" / "stats.csv")) == 5


def test_run_study_from_python(tmp_path, repo, program, monkeypatch):
    """A two-value sweep of an existing study, run as `stiffsoft study` runs it."""
    study = tmp_path / "study.json"
    spec = json.loads((repo / "studies" / "be_vs_bdf2.json").read_text())
    spec["scene"] = str(repo / "studies" / "scenes" / "spinning_box.json")
    spec["sweep"][0]["values"] = [0.02, 0.01]
    spec["quantities"] = spec["quantities"][:1]
    spec["quantities"][0]["at"] = 0.2
    spec["quantities"][0].pop("expected_order")
    study.write_text(json.dumps(spec))
    monkeypatch.setenv("STIFFSOFT_PROGRAM", program)
    code = stiffsoft.run_study(study, tmp_path / "out", jobs=2)
    assert code in (0, 1)  # 1: the plots could not be drawn; the CSV is written either way
    rows = list(csv.DictReader(open(tmp_path / "out" / "study.csv")))
    assert len(rows) == 4
    with pytest.raises(stiffsoft.StudyError):
        stiffsoft.run_study(tmp_path / "missing.json", tmp_path / "out2")


@pytest.mark.parametrize("example", ["ball_on_boxes.py", "convergence.py"])
def test_examples_run(tmp_path, repo, example):
    """The examples, in their short versions (--quick), write their plot."""
    result = subprocess.run([sys.executable, str(repo / "examples" / "python" / example), "--quick",
                             "-o", str(tmp_path)], capture_output=True, text=True, timeout=600)
    assert result.returncode == 0, result.stdout + result.stderr
    assert any(p.suffix == ".png" and p.stat().st_size > 10000 for p in tmp_path.iterdir())
