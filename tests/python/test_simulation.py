"""Stepping, statistics, state and its round trip, NumPy dtypes and shapes, reading and
setting positions, threads and Ctrl-C."""
import pickle
import signal
import subprocess
import sys
import textwrap
import time

import numpy as np
import pytest

import stiffsoft
from scenes import ball_on_box


@pytest.fixture(scope="module")
def prepared():
    """A hybrid scene, built once (gmsh meshes the ball)."""
    return ball_on_box(duration=0.1, integrator="bdf2")


def test_step_run_and_iterate(prepared):
    sim = stiffsoft.Simulation(prepared)
    first = sim.step()
    assert first.step == 1 and first.time == pytest.approx(0.01) and first.converged
    assert sim.step_count == 1 and sim.time == pytest.approx(0.01)
    more = sim.run(steps=2)
    assert [s.step for s in more] == [2, 3]
    it = sim.steps(until=0.05)
    assert len(it) == 2
    assert [s.step for s in it] == [4, 5]
    rest = sim.run()  # to the scene's duration
    assert rest[-1].step == 10 and sim.time == pytest.approx(0.1)
    assert sim.run() == []


def test_callback_sees_every_step_and_can_stop(prepared):
    sim = stiffsoft.Simulation(prepared)
    seen = []

    def callback(stats):
        seen.append(stats.step)
        return stats.step < 3  # False stops

    stats = sim.run(callback=callback)
    assert seen == [1, 2, 3] and len(stats) == 3 and sim.step_count == 3
    with pytest.raises(ValueError, match="steps or until"):
        sim.run(steps=1, until=1.0)
    with pytest.raises(ValueError, match="steps: must be >= 0"):
        sim.run(steps=-1)


def test_stats_as_dict_and_row(prepared):
    sim = stiffsoft.Simulation(prepared)
    s = sim.step()
    d = s.as_dict()
    assert list(d) == stiffsoft.StepStats.columns() and s.row() == list(d.values())
    assert d["newton_iterations"] == s.newton.iterations and d["time"] == s.time
    assert d["converged"] == 1.0 and s.times.assembly >= 0 and s.seconds > 0


def test_restore_continues_exactly(prepared):
    sim = stiffsoft.Simulation(prepared)
    sim.run(steps=3)
    saved = sim.state()
    sim.run(steps=3)
    expected_q, expected_x = sim.q, sim.surface()
    sim.restore(saved)
    assert sim.step_count == 3
    sim.run(steps=3)
    np.testing.assert_array_equal(sim.q, expected_q)
    np.testing.assert_array_equal(sim.surface(), expected_x)
    # a pickled state in a new simulation of the same scene
    other = stiffsoft.Simulation(prepared)
    other.restore(pickle.loads(pickle.dumps(saved)))
    other.run(steps=3)
    np.testing.assert_array_equal(other.q, expected_q)
    smaller = ball_on_box()
    del smaller.bodies[2]
    with pytest.raises(ValueError):  # another model: its DOFs do not match
        stiffsoft.Simulation(smaller).restore(saved)


def test_arrays_have_documented_dtypes_and_shapes(prepared):
    sim = stiffsoft.Simulation(prepared)
    sim.run(steps=2)
    n_v = sim.vertex_body.shape[0]
    n_n = sim.rest_positions.shape[0]
    for name in ("surface", "surface_velocity", "contact_forces", "friction_forces"):
        a = getattr(sim, name)()
        assert a.shape == (n_v, 3) and a.dtype == np.float64, name
    for name in ("node_positions", "node_velocities"):
        a = getattr(sim, name)()
        assert a.shape == (n_n, 3) and a.dtype == np.float64, name
    assert sim.von_mises().shape == (sim.tets.shape[0],)
    assert sim.triangles.shape[1] == 3 and sim.triangles.dtype == np.int32
    assert sim.q.ndim == 1 and sim.q.dtype == np.float64 and sim.q.shape == sim.qdot.shape
    # model arrays are read-only views that keep the simulation alive
    tri = sim.triangles
    assert not tri.flags.writeable and tri.base is not None
    with pytest.raises(ValueError):
        tri[0, 0] = 1
    ball = sim.bodies[2]
    assert sim.surface("ball").shape == (ball.vertices.stop - ball.vertices.start, 3)
    np.testing.assert_array_equal(sim.surface("ball"), sim.surface()[ball.vertices])
    np.testing.assert_array_equal(sim.node_positions("ball"), sim.node_positions()[ball.nodes])
    assert set(np.unique(sim.vertex_body[ball.vertices])) == {2}


def test_affine_pose_and_velocity(prepared):
    sim = stiffsoft.Simulation(prepared)
    p, A = sim.body_pose("box")
    assert p.shape == (3,) and A.shape == (3, 3)
    np.testing.assert_allclose(A, np.eye(3))
    sim.set_body_pose("box", p=p + [0, 0.0004, 0])
    np.testing.assert_allclose(sim.body_pose(1)[0], p + [0, 0.0004, 0])
    sim.set_body_velocity("box", v=(0.1, 0, 0), omega=(0, 1.0, 0))
    v, w = sim.body_velocity("box")
    np.testing.assert_allclose(v, [0.1, 0, 0])
    np.testing.assert_allclose(w, [0, 1.0, 0], atol=1e-12)
    with pytest.raises(ValueError, match='intersect'):
        sim.set_body_pose("box", p=p - [0, 0.05, 0])  # into the ground
    np.testing.assert_allclose(sim.body_pose("box")[0], p + [0, 0.0004, 0])  # unchanged
    with pytest.raises(ValueError, match="is soft"):
        sim.body_pose("ball")
    with pytest.raises(ValueError, match="is fixed"):
        sim.set_body_pose("ground", p=(0, 0, 0))
    with pytest.raises(KeyError, match="no body is named"):
        sim.body_pose("nothing")
    assert sim.step().converged


def test_soft_nodes_can_be_moved(prepared):
    sim = stiffsoft.Simulation(prepared)
    x = sim.node_positions("ball")
    sim.set_node_positions(x + [0, 0.05, 0], body="ball")
    np.testing.assert_allclose(sim.node_positions("ball"), x + [0, 0.05, 0])
    sim.set_node_velocities(np.tile([0.0, -2.0, 0.0], (len(x), 1)), body="ball")
    np.testing.assert_allclose(sim.node_velocities("ball")[:, 1], -2.0)
    with pytest.raises(ValueError, match="expected %d rows" % len(x)):
        sim.set_node_positions(x[:3], body="ball")
    with pytest.raises(ValueError, match="intersect"):
        sim.set_node_positions(x - [0, 0.2, 0], body="ball")
    assert sim.step().converged


def test_threads_do_not_change_results(prepared):
    stiffsoft.set_threads(1)
    a = stiffsoft.Simulation(prepared)
    a.run(steps=3)
    stiffsoft.set_threads(0)
    b = stiffsoft.Simulation(prepared)
    b.run(steps=3)
    np.testing.assert_array_equal(a.q, b.q)
    with pytest.raises(ValueError):
        stiffsoft.set_threads(-1)


def test_ctrl_c_stops_after_the_current_step(tmp_path, repo):
    """SIGINT while stepping: KeyboardInterrupt after a whole step, files whole, sim usable."""
    script = textwrap.dedent(f"""
        import sys
        import stiffsoft
        sim = stiffsoft.Simulation({str(repo / 'scenes' / 'box_stack.json')!r})
        rec = stiffsoft.Recorder(sim, {str(tmp_path / 'out')!r})
        print("started", flush=True)
        try:
            sim.run(steps=10**6, recorder=rec)
        except KeyboardInterrupt:
            steps = sim.step_count
            rows = sum(1 for _ in open({str(tmp_path / 'out' / 'stats.csv')!r})) - 1
            print("interrupted", steps, rows, sim.step().step == steps + 1, flush=True)
            sys.exit(0)
        print("not interrupted")
        sys.exit(1)
    """)
    child = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, text=True)
    assert child.stdout.readline().strip() == "started"
    time.sleep(1.0)
    child.send_signal(signal.SIGINT)
    out, _ = child.communicate(timeout=60)
    assert child.returncode == 0, out
    word, steps, rows, stepped = out.split()
    assert word == "interrupted" and int(steps) > 0
    assert int(rows) == int(steps)  # every step taken is in stats.csv: the recorder was finished
    assert stepped == "True"
