#!/usr/bin/env python3
"""A hybrid scene built in Python: a soft rubber ball dropped on a stack of affine boxes.

Runs it, writes the frames for ParaView (OUT/ball_on_boxes.pvd, exactly as `stiffsoft run`),
and plots the ball's height and Newton's iterations per step against time (OUT/ball_on_boxes.png).

    python3 examples/python/ball_on_boxes.py [-o OUT] [--quick]
"""
import argparse
import pathlib

import matplotlib

matplotlib.use("Agg")  # files only, no display needed
import matplotlib.pyplot as plt

import stiffsoft
from stiffsoft import Body, Material, Shape


def make_scene(duration):
    scene = stiffsoft.Scene(name="ball_on_boxes",
                            description="examples/python: a soft ball dropped on three affine boxes")
    scene.time.dt = 0.005          # s
    scene.time.duration = duration  # s
    scene.contact.mu = 0.3
    scene.contact.dhat = 0.0005    # m; bodies start more than d^ apart
    scene.bodies.append(Body(name="ground", kind="fixed", shape=Shape.box((2.0, 0.05, 2.0)),
                             position=(0, -0.025, 0)))
    for i, (size, y, turn) in enumerate([(0.4, 0.101, 0), (0.35, 0.303, 15), (0.3, 0.505, 35)]):
        scene.bodies.append(Body(name=f"box_{i + 1}", shape=Shape.box((size, 0.2, size)),
                                 position=(0, y, 0), rotation_deg=(0, turn, 0), density=800))  # kg/m^3
    scene.bodies.append(Body(name="ball", model="soft", shape=Shape.sphere(0.12), mesh_size=0.04,
                             material=Material(model="stable_neo_hookean", young=2e5, poisson=0.45),
                             density=1100, position=(0.03, 0.95, 0), velocity=(0, -1.0, 0)))
    return scene


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("-o", "--out", default="out/python", help="output folder")
    parser.add_argument("--quick", action="store_true", help="0.3 s instead of 1.5 s (for tests)")
    args = parser.parse_args()
    out = pathlib.Path(args.out)

    sim = stiffsoft.Simulation(make_scene(0.3 if args.quick else 1.5))
    ball = sim.bodies[sim.body("ball")]
    masses = sim.node_masses[ball.nodes]
    times, heights, iterations = [], [], []
    with stiffsoft.Recorder(sim, out / "ball_on_boxes") as recorder:
        for stats in sim.steps(recorder=recorder):
            y = sim.node_positions("ball")[:, 1]
            times.append(stats.time)
            heights.append(float((masses * y).sum() / masses.sum()))  # centre of mass (m)
            iterations.append(stats.newton.iterations)
            if not stats.converged:
                print(f"step {stats.step}: {stats.newton.failure}")

    fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(7, 5))
    top.plot(times, heights)
    top.set_ylabel("ball centre height (m)")
    bottom.step(times, iterations, where="post")
    bottom.set_ylabel("Newton iterations")
    bottom.set_xlabel("time (s)")
    fig.suptitle("soft ball on affine boxes")
    fig.tight_layout()
    fig.savefig(out / "ball_on_boxes.png", dpi=120)
    print(f"{len(times)} steps, {sum(iterations) / len(times):.1f} Newton iterations per step; "
          f"ball at {heights[-1]:.3f} m; frames: {recorder.pvd_path}; plot: {out / 'ball_on_boxes.png'}")


if __name__ == "__main__":
    main()
