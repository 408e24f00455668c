#!/usr/bin/env python3
"""A convergence study driven from Python: backward Euler against BDF-2 on torque-free rotation.

A free box spins at 2 pi rad/s about its major principal axis (world z); the exact motion is
the steady rotation A(t) = Rz(2 pi t). For each integrator and time step h it measures the error
|A(T) - Rz(2 pi T)|_F at T = 1 s, fits the observed order and plots error against h
(OUT/convergence.png). BE should show order 1, BDF-2 order 2 (as studies/be_vs_bdf2.json).

    python3 examples/python/convergence.py [-o OUT] [--quick]
"""
import argparse
import math
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import stiffsoft

OMEGA = 2 * math.pi  # rad/s


def spinning_box(h, integrator, duration):
    scene = stiffsoft.Scene(name="spinning_box", description="examples/python/convergence.py")
    scene.time.dt = h
    scene.time.duration = duration
    scene.time.integrator = integrator
    scene.gravity = (0, 0, 0)
    scene.solver.tolerance = 1e-7  # m/s: tight, so that integration errors are measured, not the stopping rule
    scene.bodies.append(stiffsoft.Body(name="box", shape=stiffsoft.Shape.box((1.0, 0.5, 0.1)), kappa=1e10,
                                       angular_velocity=(0, 0, OMEGA)))
    return scene


def error_at_end(h, integrator, duration):
    sim = stiffsoft.Simulation(spinning_box(h, integrator, duration))
    sim.run()
    _, A = sim.body_pose("box")
    c, s = math.cos(OMEGA * sim.time), math.sin(OMEGA * sim.time)
    exact = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
    return float(np.linalg.norm(A - exact))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("-o", "--out", default="out/python", help="output folder")
    parser.add_argument("--quick", action="store_true", help="3 step sizes over 0.25 s (for tests)")
    args = parser.parse_args()
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    steps = [0.02, 0.01, 0.005] if args.quick else [0.01, 0.005, 0.0025, 0.00125, 0.000625]
    duration = 0.25 if args.quick else 1.0
    fig, ax = plt.subplots(figsize=(6, 4.5))
    for integrator, expected in (("backward_euler", 1), ("bdf2", 2)):
        errors = [error_at_end(h, integrator, duration) for h in steps]
        order = np.polyfit(np.log(steps), np.log(errors), 1)[0]
        print(f"{integrator:15s} errors {' '.join(f'{e:.3e}' for e in errors)}  "
              f"observed order {order:.2f} (expected {expected})")
        ax.loglog(steps, errors, "o-", label=f"{integrator}: order {order:.2f}")
    ax.set_xlabel("time step h (s)")
    ax.set_ylabel(f"|A(T) - Rz(2 pi T)|_F at T = {duration} s")
    ax.set_title("torque-free rotation: error against h")
    ax.legend()
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(out / "convergence.png", dpi=120)
    print(f"plot: {out / 'convergence.png'}")


if __name__ == "__main__":
    main()
