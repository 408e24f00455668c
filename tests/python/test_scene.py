"""Scenes from Python: keyword constructors, enums by name, lists by reference, dicts and
files in and out, mesh arrays, and the same errors as scene files."""
import json

import numpy as np
import pytest

import stiffsoft
from scenes import ball_on_box


def test_keywords_start_from_the_defaults():
    body = stiffsoft.Body(name="box", density=800)
    assert body.density == 800
    assert body.kappa == stiffsoft.Body().kappa  # untouched keys keep the C++ defaults
    assert body.kind == stiffsoft.Motion.dynamic and body.model == stiffsoft.Model.affine


def test_enums_take_their_scene_file_names():
    body = stiffsoft.Body(kind="kinematic", model="soft")
    assert body.kind == stiffsoft.Motion.kinematic and body.model == stiffsoft.Model.soft and stiffsoft.Model("auto") == stiffsoft.Model.auto
    scene = stiffsoft.Scene()
    scene.time.integrator = "bdf2"
    assert scene.time.integrator == stiffsoft.Integrator.bdf2


def test_bad_keywords_name_the_argument():
    with pytest.raises(TypeError, match="unexpected keyword argument 'desnity'"):
        stiffsoft.Body(desnity=3)
    with pytest.raises(TypeError, match="Body.density"):
        stiffsoft.Body(density="heavy")
    with pytest.raises(ValueError, match='Body.kind.*unknown value "flying".*dynamic, fixed, kinematic'):
        stiffsoft.Body(kind="flying")
    with pytest.raises(TypeError, match="expected a Motion or its name"):
        stiffsoft.Body().kind = 3


def test_lists_are_the_scene_itself():
    scene = ball_on_box()
    scene.bodies[1].density = 500  # changes the scene, not a copy
    assert scene.body("box").density == 500
    scene.body("box").density = 600
    assert scene.bodies[1].density == 600
    scene.bodies = [scene.bodies[0]]  # a Python list converts
    assert len(scene.bodies) == 1
    with pytest.raises(KeyError, match='no body is named "box"'):
        scene.body("box")


def test_dict_round_trip(tmp_path):
    scene = ball_on_box()
    d = scene.to_dict()
    assert d["bodies"][2]["model"] == "soft" and d["time"]["dt"] == 0.01
    again = stiffsoft.Scene.from_dict(d)
    assert again.to_dict() == d
    scene.save(tmp_path / "s.json")
    loaded = stiffsoft.Scene.load(tmp_path / "s.json")
    assert loaded.to_dict() == d
    assert json.loads((tmp_path / "s.json").read_text()) == d


def test_errors_name_the_json_path():
    d = ball_on_box().to_dict()
    d["bodies"][1]["density"] = -2
    with pytest.raises(stiffsoft.SceneError) as e:
        stiffsoft.Simulation(d)
    assert e.value.json_path == "bodies[1].density"
    assert "must be > 0" in e.value.expected and e.value.file == "<dict>"
    assert isinstance(e.value, ValueError)
    scene = ball_on_box()
    scene.bodies[2].material.poisson = 0.5
    with pytest.raises(stiffsoft.SceneError, match=r"ball_on_box \(built in code\): bodies\[2\]\.material\.poisson"):
        stiffsoft.Simulation(scene)


def test_overlapping_bodies_are_refused():
    scene = ball_on_box()
    scene.bodies[2].position = (0, 0.1, 0)  # inside the box
    with pytest.raises(stiffsoft.SceneError, match="ball"):
        stiffsoft.Simulation(scene)


def test_missing_scene_file():
    with pytest.raises(stiffsoft.SceneError, match="no_such_scene.json"):
        stiffsoft.Simulation("no_such_scene.json")


def cube_arrays():
    """A unit cube as 8 vertices, 12 outward triangles and 5 tetrahedra."""
    v = np.array([[x, y, z] for z in (0, 1) for y in (0, 1) for x in (0, 1)], dtype=float) - 0.5
    f = np.array([[0, 2, 1], [1, 2, 3], [4, 5, 6], [5, 7, 6], [0, 1, 4], [1, 5, 4],
                  [2, 6, 3], [3, 6, 7], [0, 4, 2], [2, 4, 6], [1, 3, 5], [3, 7, 5]])
    t = np.array([[0, 1, 3, 5], [0, 2, 6, 3], [0, 4, 5, 6], [3, 5, 6, 7], [0, 3, 5, 6]])
    negative = np.linalg.det(v[t[:, 1:]] - v[t[:, :1]]) < 0
    t[negative, 1], t[negative, 2] = t[negative, 2], t[negative, 1].copy()
    return v, f, t


def test_bodies_from_arrays(tmp_path):
    v, f, t = cube_arrays()
    scene = ball_on_box(duration=0.03)
    del scene.bodies[2]
    scene.bodies.append(stiffsoft.Body(name="cube", position=(0, 0.4, 0), scale=(0.2, 0.2, 0.2)))
    scene.bodies[-1].set_mesh(v, triangles=f, folder=tmp_path)
    scene.bodies.append(stiffsoft.Body(name="jelly", model="soft", position=(0, 0.8, 0), scale=(0.2, 0.2, 0.2),
                                       material=stiffsoft.Material(young=1e5, poisson=0.3)))
    scene.bodies[-1].set_mesh(v, tets=t, folder=tmp_path)
    assert scene.bodies[2].mesh_file.suffix == ".obj" and scene.bodies[3].mesh_file.suffix == ".msh"
    assert scene.bodies[2].shape is None
    sim = stiffsoft.Simulation(scene)
    assert sim.bodies[2].representation == "affine" and sim.bodies[3].representation == "soft"
    assert sim.tets.shape == (5, 4)
    for stats in sim.steps():
        assert stats.converged
    # the same arrays give the same file
    assert stiffsoft.mesh_file(v, triangles=f, folder=tmp_path) == scene.bodies[2].mesh_file


def test_mesh_arrays_are_checked(tmp_path):
    v, f, _ = cube_arrays()
    with pytest.raises(ValueError, match=r"triangles: indices must lie in \[0, 8\)"):
        stiffsoft.write_mesh(tmp_path / "a.obj", v, triangles=f + 1)
    with pytest.raises(ValueError, match=r"vertices: expected an array of shape \(n, 3\)"):
        stiffsoft.write_mesh(tmp_path / "a.obj", v[:, :2], triangles=f)
    with pytest.raises(ValueError, match="either triangles"):
        stiffsoft.write_mesh(tmp_path / "a.obj", v)
    with pytest.raises(ValueError, match="written as .msh"):
        stiffsoft.write_mesh(tmp_path / "a.obj", v, tets=f)
