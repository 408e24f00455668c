#!/usr/bin/env python3
"""Writes the generated scenes of scenes/: the Bullet-comparison piles (light, medium,
full) and the scenes whose coordinates need computing (box_stack, incline_stick,
incline_slide, house_of_cards, wrecking_ball, chain_net) and the larger brick piles of the
linear-solver benchmark (bricks_900, bricks_2400). Deterministic (fixed seed), standard
library only. Every scene is checked before it is written: each pair of bodies must be
separated by a lower bound on their distance >= max(3 mm, 2 d̂), where d̂ is the scene's
contact.dhat or its default 1e-3 × bounding-box diagonal.

    python3 scripts/make_piles.py            # writes scenes/*.json, prints triangle counts
    python3 scripts/make_piles.py --check    # only checks, writes nothing
    python3 scripts/make_piles.py --verify   # checks, and fails where a file of scenes/ differs

Triangle counts follow stiffsoft/meshing/primitive.cpp: box and plane 12; UV sphere with n
segments: rings = max(2, n // 2), 2 n (rings − 1); cylinder with n segments: 4 n;
torus with n segments: m = max(3, n // 2) around the tube, 2 n m.
"""

import json
import math
import os
import random
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SCENES = os.path.join(os.path.dirname(HERE), "scenes")
MIN_GAP = 3e-3  # metres: the smallest initial gap any generated scene may have


# ---------------------------------------------------------------- primitives

def triangles(mesh):
    kind = mesh["primitive"]
    n = mesh.get("resolution", 16)
    if kind in ("box", "plane"):
        return 12
    if kind == "sphere":
        rings = max(2, n // 2)
        return 2 * n * (rings - 1)
    if kind == "cylinder":
        return 4 * n
    if kind == "torus":
        return 2 * n * max(3, n // 2)
    raise ValueError(kind)


def box(sx, sy, sz):
    return {"primitive": "box", "size": [sx, sy, sz]}


def sphere(r, n):
    return {"primitive": "sphere", "radius": r, "resolution": n}


def cylinder(r, h, n):
    return {"primitive": "cylinder", "radius": r, "height": h, "resolution": n}


def torus(R, r, n):
    return {"primitive": "torus", "radius": R, "minor_radius": r, "resolution": n}


# ---------------------------------------------------------------- rotations (R = Rz Ry Rx)

def matmul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def apply(m, v):
    return [sum(m[i][k] * v[k] for k in range(3)) for i in range(3)]


def transpose(m):
    return [[m[j][i] for j in range(3)] for i in range(3)]


def rot_x(a):
    c, s = math.cos(a), math.sin(a)
    return [[1, 0, 0], [0, c, -s], [0, s, c]]


def rot_y(a):
    c, s = math.cos(a), math.sin(a)
    return [[c, 0, s], [0, 1, 0], [-s, 0, c]]


def rot_z(a):
    c, s = math.cos(a), math.sin(a)
    return [[c, -s, 0], [s, c, 0], [0, 0, 1]]


def rotation(deg):
    x, y, z = (math.radians(d) for d in deg)
    return matmul(rot_z(z), matmul(rot_y(y), rot_x(x)))


def euler_deg(m):
    """XYZ Euler angles (degrees) of m = Rz Ry Rx."""
    y = math.asin(max(-1.0, min(1.0, -m[2][0])))
    x = math.atan2(m[2][1], m[2][2])
    z = math.atan2(m[1][0], m[0][0])
    return [math.degrees(x), math.degrees(y), math.degrees(z)]


# ---------------------------------------------------------------- distance lower bounds

def sub(a, b):
    return [a[i] - b[i] for i in range(3)]


def dot(a, b):
    return sum(a[i] * b[i] for i in range(3))


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def norm(a):
    return math.sqrt(dot(a, a))


def shape_of(body):
    """(kind, centre, rotation, parameters): boxes (cylinders by their bounding box),
    spheres and tori, with the body's scale folded in (scales are 1 in these scenes)."""
    mesh = body["mesh"]
    assert body.get("scale", [1, 1, 1]) == [1, 1, 1]
    R = rotation(body.get("rotation_deg", [0, 0, 0]))
    c = body.get("position", [0, 0, 0])
    kind = mesh["primitive"]
    if kind in ("box", "plane"):
        return ("box", c, R, [s / 2 for s in mesh["size"]])
    if kind == "cylinder":
        return ("box", c, R, [mesh["radius"], mesh["height"] / 2, mesh["radius"]])
    if kind == "sphere":  # the mesh's vertices lie on the sphere, its faces inside
        return ("sphere", c, R, mesh["radius"])
    if kind == "torus":
        return ("torus", c, R, (mesh["radius"], mesh["minor_radius"], mesh.get("resolution", 16)))
    raise ValueError(kind)


def bounding_radius(shape):
    kind, _, _, p = shape
    if kind == "box":
        return norm(p)
    if kind == "sphere":
        return p
    return p[0] + p[1]


def box_box(a, b):
    """Largest separation over the 15 SAT axes: a lower bound on the distance."""
    _, ca, Ra, ha = a
    _, cb, Rb, hb = b
    axes_a = [[Ra[i][k] for i in range(3)] for k in range(3)]
    axes_b = [[Rb[i][k] for i in range(3)] for k in range(3)]
    axes = axes_a + axes_b
    for u in axes_a:
        for v in axes_b:
            w = cross(u, v)
            if norm(w) > 1e-9:
                axes.append([x / norm(w) for x in w])
    d = sub(cb, ca)
    best = -math.inf
    for n in axes:
        ra = sum(ha[k] * abs(dot(axes_a[k], n)) for k in range(3))
        rb = sum(hb[k] * abs(dot(axes_b[k], n)) for k in range(3))
        best = max(best, abs(dot(d, n)) - ra - rb)
    return best


def point_box(p, b):
    _, c, R, h = b
    local = apply(transpose(R), sub(p, c))
    outside = [max(0.0, abs(local[i]) - h[i]) for i in range(3)]
    return norm(outside)


def point_circle(p, c, axis, R):
    v = sub(p, c)
    h = dot(v, axis)
    rho = norm([v[i] - h * axis[i] for i in range(3)])
    return math.sqrt(h * h + (rho - R) ** 2)


def torus_circle(t):
    _, c, Rm, (R, r, n) = t
    axis = [Rm[i][1] for i in range(3)]  # primitives have their symmetry axis along y
    u = [Rm[i][0] for i in range(3)]
    w = [Rm[i][2] for i in range(3)]
    # The faceted inner equator lies up to (R - r)(1 - cos(pi / n)) inside the hole.
    sag = (R - r) * (1 - math.cos(math.pi / n))
    return c, axis, u, w, R, r + sag


def torus_torus(a, b, samples=4000):
    ca, axa, ua, wa, Ra, ra = torus_circle(a)
    cb, axb, _, _, Rb, rb = torus_circle(b)
    best = math.inf
    for k in range(samples):
        t = 2 * math.pi * k / samples
        p = [ca[i] + Ra * (math.cos(t) * ua[i] + math.sin(t) * wa[i]) for i in range(3)]
        best = min(best, point_circle(p, cb, axb, Rb))
    # sampling error of the centre-line distance is at most Ra * pi / samples
    return best - Ra * math.pi / samples - ra - rb


def distance_lower_bound(a, b):
    ka, kb = a[0], b[0]
    if ka == "box" and kb == "box":
        return box_box(a, b)
    if ka == "sphere" and kb == "box":
        return point_box(a[1], b) - a[3]
    if ka == "box" and kb == "sphere":
        return point_box(b[1], a) - b[3]
    if ka == "sphere" and kb == "sphere":
        return norm(sub(a[1], b[1])) - a[3] - b[3]
    if ka == "torus" and kb == "torus":
        return torus_torus(a, b)
    if ka == "torus" or kb == "torus":
        t, o = (a, b) if ka == "torus" else (b, a)
        if o[0] == "box":  # centre-line samples against the box, minus the tube
            c, _, u, w, R, r = torus_circle(t)
            samples = 2000
            best = min(point_box([c[i] + R * (math.cos(2 * math.pi * k / samples) * u[i] +
                                              math.sin(2 * math.pi * k / samples) * w[i]) for i in range(3)], o)
                       for k in range(samples))
            return best - R * math.pi / samples - r
        c, axis, _, _, R, r = torus_circle(t)
        return point_circle(o[1], c, axis, R) - r - bounding_radius(o)
    raise ValueError((ka, kb))


def check_scene(name, scene):
    shapes = [shape_of(b) for b in scene["bodies"]]
    def half_extent(s, i):  # of the world AABB: exact for boxes, bounding sphere otherwise
        return sum(abs(s[2][i][k]) * s[3][k] for k in range(3)) if s[0] == "box" else bounding_radius(s)
    lo = [min(s[1][i] - half_extent(s, i) for s in shapes) for i in range(3)]
    hi = [max(s[1][i] + half_extent(s, i) for s in shapes) for i in range(3)]
    diagonal = norm(sub(hi, lo))  # never below the true diagonal, so neither is d̂
    dhat = scene.get("contact", {}).get("dhat") or 1e-3 * diagonal
    need = max(MIN_GAP, 2 * dhat)
    worst = (math.inf, None)
    for i in range(len(shapes)):
        for j in range(i + 1, len(shapes)):
            a, b = shapes[i], shapes[j]
            if norm(sub(a[1], b[1])) - bounding_radius(a) - bounding_radius(b) > need:
                continue
            d = distance_lower_bound(a, b)
            if d < worst[0]:
                worst = (d, (scene["bodies"][i]["name"], scene["bodies"][j]["name"]))
            if d < need:
                raise SystemExit(f"{name}: {scene['bodies'][i]['name']} and {scene['bodies'][j]['name']} "
                                 f"are closer than {need:.4g} m (lower bound {d:.4g} m)")
    names = [b["name"] for b in scene["bodies"]]
    assert len(set(names)) == len(names), name
    return dhat, worst


# ---------------------------------------------------------------- scenes

def run_line(name):
    return f"Run: stiffsoft run scenes/{name}.json -o out/{name}"


def fixed(name, mesh, position, rotation_deg=(0, 0, 0)):
    return {"name": name, "kind": "fixed", "mesh": mesh, "position": list(position),
            "rotation_deg": list(rotation_deg)}


def body(name, mesh, position, rotation_deg=(0, 0, 0), **extra):
    b = {"name": name, "mesh": mesh, "position": list(position), "rotation_deg": list(rotation_deg)}
    b.update(extra)
    return b


def rounded(x):
    if isinstance(x, float):
        return round(x, 9)
    if isinstance(x, list):
        return [rounded(v) for v in x]
    if isinstance(x, dict):
        return {k: rounded(v) for k, v in x.items()}
    return x


PILES = {
    # name: (grid nx = nz, falling bodies, description head)
    "light": (2, 11, "Bullet comparison 'Light' (seed 001): 16 bodies (11 falling + a 5-piece container)"),
    "medium": (5, 137, "Bullet comparison 'Medium' (seed 001): 142 bodies (137 falling + a 5-piece container)"),
    "full": (8, 557, "Bullet comparison 'Full' (seed 001): 562 bodies (557 falling + a 5-piece container)"),
}

# The shape mix per pile, chosen so the total triangle count lands near the seed's
# (1.2K, 3.5K, 11K): the piles differ in how many bodies there are and how fine they are.
PILE_SHAPES = {
    "light": [box(0.1, 0.1, 0.1), sphere(0.05, 16), cylinder(0.04, 0.1, 20)],
    "medium": [box(0.1, 0.1, 0.1), sphere(0.05, 8), box(0.12, 0.08, 0.06), cylinder(0.04, 0.1, 6)],
    "full": [box(0.1, 0.1, 0.1), sphere(0.05, 6), cylinder(0.04, 0.1, 6)],
}
TARGET_TRIANGLES = {"light": 1200, "medium": 3500, "full": 11000}


def container(inner, wall_height, thickness=0.05, gap=0.005):
    """A fixed open box: a floor (top at y = 0) and four walls standing 5 mm above it,
    with 5 mm gaps at the corners, so no two fixed pieces touch."""
    half = inner / 2
    outer = inner + 2 * thickness
    y = gap + wall_height / 2
    return [
        fixed("floor", box(outer + 2 * gap, thickness, outer + 2 * gap), (0, -thickness / 2, 0)),
        fixed("wall_x_neg", box(thickness, wall_height, inner), (-half - thickness / 2, y, 0)),
        fixed("wall_x_pos", box(thickness, wall_height, inner), (half + thickness / 2, y, 0)),
        fixed("wall_z_neg", box(outer, wall_height, thickness), (0, y, -half - thickness / 2 - gap)),
        fixed("wall_z_pos", box(outer, wall_height, thickness), (0, y, half + thickness / 2 + gap)),
    ]


def make_pile(name):
    nx, count, head = PILES[name]
    return grid_pile(name, nx, count, PILE_SHAPES[name], head)


def make_wide_pile(name, nx, count):
    """A pile of full's kind (its shapes, grid pitch, drop and container walls) nx × nx bodies
    wide: issue 22's ~5,000-body pile of the seed's kind, for the scaling study of
    docs/benchmarks.md (not a shipped scene). Returns the scene."""
    head = f"A pile of full's kind, {count + 5} bodies ({count} falling + a 5-piece container)"
    return grid_pile(name, nx, count, PILE_SHAPES["full"], head)[0]


def grid_pile(name, nx, count, shapes, head):
    """count bodies of the given shapes, nx × nx a layer, randomly turned above an open box."""
    pitch = 0.2  # grid cell; every shape's bounding sphere has radius < 0.087 m
    inner = nx * pitch + 0.1
    rng = random.Random(20240601 + nx)  # deterministic per pile
    bodies = container(inner, wall_height=0.5)
    for k in range(count):
        layer, rest = divmod(k, nx * nx)
        i, j = divmod(rest, nx)
        position = ((i - (nx - 1) / 2) * pitch, 0.15 + layer * pitch, (j - (nx - 1) / 2) * pitch)
        mesh = shapes[k % len(shapes)]
        angles = [rng.uniform(0, 360) for _ in range(3)]
        bodies.append(body(f"{mesh['primitive']}_{k:03d}", dict(mesh), position, angles, density=1000.0))
    tris = sum(triangles(b["mesh"]) for b in bodies)
    scene = {
        "description": f"{head}, {tris} triangles: boxes, low-resolution spheres and cylinders in a "
                       f"{nx}x{nx} grid, randomly turned, dropped into a fixed open box. dt = 1/240 s, 1 s. "
                       f"Generated by scripts/make_piles.py. " + run_line(name),
        "time": {"dt": 1 / 240, "duration": 1.0},
        "contact": {"dhat": 1e-3, "mu": 0.3},
        "bodies": bodies,
    }
    return scene, tris


def make_brick_pile(name, n, layers):
    """Larger rigid piles for the linear-solver benchmark: 0.1 m cubes in a staggered bond,
    n × n on even layers and (n − 1) × (n − 1) on odd ones (each resting on four), 4 mm apart
    sideways and 3.5 mm apart vertically, on a fixed floor: they settle within a few steps and
    stay in contact, a 3D contact graph whose Hessian fills in as a FEM mesh's does."""
    size, side_gap, up_gap = 0.1, 0.004, 0.0035
    pitch = size + side_gap
    bodies = [fixed("floor", box(n * pitch + 0.5, 0.05, n * pitch + 0.5), (0, -0.025, 0))]
    for layer in range(layers):
        m = n - layer % 2
        y = up_gap + size / 2 + layer * (size + up_gap)
        for i in range(m):
            for j in range(m):
                x = (i - (m - 1) / 2) * pitch
                z = (j - (m - 1) / 2) * pitch
                bodies.append(body(f"brick_{layer}_{i}_{j}", box(size, size, size), (x, y, z), density=1000.0))
    count = len(bodies) - 1
    return {
        "description": f"{count} cubes (0.1 m) in a staggered bond, {layers} layers of {n}x{n} and "
                       f"{n - 1}x{n - 1}, 3.5 mm above one another, settling on a fixed floor, mu = 0.3: a "
                       f"large rigid pile in contact within a few steps (linear-solver benchmark, "
                       f"docs/linear_solvers.md). dt = 1/240 s, 0.5 s. Generated by scripts/make_piles.py. "
                       + run_line(name),
        "time": {"dt": 1 / 240, "duration": 0.5},
        "contact": {"dhat": 1e-3, "mu": 0.3},
        "bodies": bodies,
    }


def make_box_stack():
    size, gap = 0.2, 0.01
    bodies = [fixed("ground", box(1.8, 0.1, 1.8), (0, -0.05, 0))]
    for i in range(10):
        bodies.append(body(f"box_{i}", box(size, size, size), (0, gap + size / 2 + i * (size + gap), 0)))
    return {
        "description": "A stack of 10 cubes (0.2 m, 1 cm apart) settling on a fixed ground under gravity, "
                       "mu = 0.3; the stack must stay upright and intersection-free. " + run_line("box_stack"),
        "time": {"dt": 0.01, "duration": 2.0},
        "contact": {"mu": 0.3},
        "bodies": bodies,
    }


def make_incline(name, mu, outcome):
    theta = math.atan(0.5)  # 26.565°, tan θ = 0.5
    deg = math.degrees(theta)
    slab_thickness, cube, gap = 0.1, 0.2, 0.003
    normal = [-math.sin(theta), math.cos(theta), 0.0]
    # Centre of the cube: on the slab's normal through its centre, a hair above the top face.
    offset = slab_thickness / 2 + gap + cube / 2
    return {
        "description": f"A 0.2 m cube resting on a fixed slab tilted {deg:.3f} deg (tan = 0.5), aligned with the "
                       f"slope and 3 mm above it, mu = {mu}: {outcome} Friction is resolved within each step "
                       f"(contact.friction_iterations: 3): lagged again at the result while its lag error exceeds "
                       f"eps_v / 10, and Newton does not stop while a direction moves a sticking contact by more "
                       f"than eps_v h / 10. Lagged once, at the step's start, friction misses the landing step's "
                       f"contact and the block slides on at 0.045 m/s; with the default Newton tolerance alone "
                       f"(1e-2 x diagonal / s, far above the per-step velocity change a*h ~ 1e-3 m/s) Newton would "
                       f"stop while static friction's stiff first direction still holds the block. " + run_line(name),
        "time": {"dt": 0.01, "duration": 2.5},
        "contact": {"dhat": 1e-3, "mu": mu, "friction_iterations": 3},
        "bodies": [
            fixed("slab", box(2.0, slab_thickness, 1.0), (0, 0, 0), (0, 0, deg)),
            body("block", box(cube, cube, cube), [offset * n for n in normal], (0, 0, deg)),
        ],
    }


def make_house_of_cards():
    L, w, t = 0.1, 0.07, 0.005      # leaning card: length, width (z), thickness (m)
    theta = math.radians(20.0)       # lean from vertical
    g_top, g = 0.004, 0.004          # gap between the two tops of an A; gap below each card
    foot_gap, flat_gap = 0.01, 0.004  # between neighbouring A feet; between flats end to end
    # A-frame of two cards tilted ±θ about z; corner extents of one card (rotated by -θ).
    R = rotation((0, 0, -math.degrees(theta)))
    corners = [apply(R, [sx * t / 2, sy * L / 2, 0]) for sx in (-1, 1) for sy in (-1, 1)]
    x_right = max(c[0] for c in corners)
    y_low = min(c[1] for c in corners)
    y_high = max(c[1] for c in corners)
    x_low = min(c[0] for c in corners)
    half_width = x_right + g_top / 2 - x_low  # from the A's axis to its outer foot
    pitch = 2 * half_width + foot_gap

    bodies = [fixed("table", box(0.6, 0.05, 0.3), (0, -0.025, 0))]

    def a_frame(tag, x, y_base):
        cx = x_right + g_top / 2
        cy = y_base + g - y_low
        bodies.append(body(f"{tag}_left", box(t, L, w), (x - cx, cy, 0), (0, 0, -math.degrees(theta))))
        bodies.append(body(f"{tag}_right", box(t, L, w), (x + cx, cy, 0), (0, 0, math.degrees(theta))))
        return cy + y_high  # top of the A

    def flat(tag, x, y_base, length):
        bodies.append(body(tag, box(length, t, w), (x, y_base + g + t / 2, 0)))
        return y_base + g + t

    # level 1: three A-frames, two flats meeting over the middle apex
    top = max(a_frame(f"l1_a{i}", (i - 1) * pitch, 0.0) for i in range(3))
    flat_length = pitch - flat_gap
    assert flat_length > 2 * half_width + 0.004, "level-2 A-frames must fit on a level-1 flat"
    y = max(flat(f"l1_flat{i}", (i - 0.5) * pitch, top, flat_length) for i in range(2))
    # level 2: two A-frames, one on each flat, one flat across both
    top = max(a_frame(f"l2_a{i}", (i - 0.5) * pitch, y) for i in range(2))
    y = flat("l2_flat", 0.0, top, pitch + 0.012)
    # level 3: one A-frame
    a_frame("l3_a", 0.0, y)
    return {
        "description": "A 3-level house of cards (like Rigid-IPC's): 15 cards (0.1 x 0.07 x 0.005 m boxes) leaning "
                       "in A-frames at 20 deg with flat cards on top, mu = 0.5, on a fixed table. Friction must hold "
                       "it up; a few mm gaps close in the first steps. Generated by scripts/make_piles.py. "
                       + run_line("house_of_cards"),
        "time": {"dt": 0.01, "duration": 2.0},
        "contact": {"dhat": 5e-4, "mu": 0.5},
        "bodies": bodies,
    }


def make_wrecking_ball():
    R, r, n = 0.07, 0.012, 16          # chain link: centre-line radius, tube radius, resolution
    spacing = 0.105                    # link to link along the chain (interlocked: 2r < spacing < 2R - 2r)
    Rb, rb = 0.06, 0.03                # the "ball": a fat, heavy torus the last link passes through
    ball_offset = 0.08                 # last link centre to ball centre
    pivot = [0.0, 0.75, 0.0]
    swing = math.radians(65.0)         # released from 65 deg off vertical, towards -x
    down = [-math.sin(swing), -math.cos(swing), 0.0]
    tilt = rot_z(-swing)               # turns the chain's axis from -y to `down`
    links = 5
    bodies = [fixed("ground", box(2.0, 0.1, 1.2), (0, -0.05, 0))]
    for i in range(links):
        centre = [pivot[k] + i * spacing * down[k] for k in range(3)]
        # Ring planes contain the chain axis (y before the tilt); alternate between xy and yz.
        local = rot_x(math.pi / 2) if i % 2 == 0 else matmul(rot_y(math.pi / 2), rot_x(math.pi / 2))
        bodies.append({"name": f"link_{i}", "kind": "fixed" if i == 0 else "dynamic", "mesh": torus(R, r, n),
                       "position": centre, "rotation_deg": euler_deg(matmul(tilt, local)), "density": 7800.0})
    centre = [pivot[k] + ((links - 1) * spacing + ball_offset) * down[k] for k in range(3)]
    local = rot_x(math.pi / 2) if links % 2 == 0 else matmul(rot_y(math.pi / 2), rot_x(math.pi / 2))
    bodies.append({"name": "ball", "mesh": torus(Rb, rb, 16), "position": centre,
                   "rotation_deg": euler_deg(matmul(tilt, local)), "density": 20000.0})
    # A wall of 4 x 4 boxes just past the bottom of the swing, across the ball's path.
    size, gap = 0.1, 0.004
    for layer in range(4):
        for k in range(4):
            bodies.append(body(f"brick_{layer}_{k}", box(size, size, size),
                               (0.16, gap + size / 2 + layer * (size + gap), (k - 1.5) * (size + gap)),
                               density=400.0))
    return {
        "description": "A small wrecking ball: 5 interlocked torus links (link_0 fixed at the top) holding a heavy "
                       "fat torus (20000 kg/m3; a sphere cannot hang from a chain without joints), released from "
                       "65 deg and swinging into a wall of 16 light boxes on a fixed ground, mu = 0.2. Generated by "
                       "scripts/make_piles.py. " + run_line("wrecking_ball"),
        "time": {"dt": 0.01, "duration": 2.0},
        "contact": {"dhat": 1e-3, "mu": 0.2},
        "bodies": bodies,
    }


def ring_centre_line(body, samples=64):
    """The centre circle of a torus body, as a closed polygon of `samples` points (world)."""
    _, c, Rm, (R, _, _) = shape_of(body)
    u = [Rm[i][0] for i in range(3)]
    w = [Rm[i][2] for i in range(3)]
    return [[c[i] + R * (math.cos(2 * math.pi * k / samples) * u[i] + math.sin(2 * math.pi * k / samples) * w[i])
             for i in range(3)] for k in range(samples)]


def linking_number(A, B):
    """Linking number of the closed polygons A (planar, convex) and B: the signed number of
    times B's segments cross the flat disc bounded by A (bench/peers/ring_links.cpp does the same)."""
    n = len(A)
    c = [sum(p[i] for p in A) / n for i in range(3)]
    normal = [0.0, 0.0, 0.0]
    for i in range(n):
        normal = [normal[k] + cross(sub(A[i], c), sub(A[(i + 1) % n], c))[k] for k in range(3)]
    normal = [x / norm(normal) for x in normal]
    crossings = 0
    for k in range(len(B)):
        p, q = B[k], B[(k + 1) % len(B)]
        dp, dq = dot(normal, sub(p, c)), dot(normal, sub(q, c))
        if (dp > 0) == (dq > 0) or dp == dq:
            continue
        x = [p[i] + dp / (dp - dq) * (q[i] - p[i]) for i in range(3)]
        if all(dot(normal, cross(sub(A[(i + 1) % n], A[i]), sub(x, A[i]))) > 0 for i in range(n)):
            crossings += 1 if dp < 0 else -1
    return crossings


def make_chain_net():
    """An 8 x 8 net of rings woven as European 4-in-1 chain mail: 8 rows along x, neighbouring
    rows shifted by half a pitch and tilted +-35 deg about x, so that every ring passes through
    two rings of the row before and two of the row after. Held by its four corner rings."""
    R, r, n = 0.04, 0.005, 12          # ring: centre-line radius, tube radius, resolution
    rows, cols = 8, 8
    pitch = 2 * (R + r) + 0.007        # along a row: rings side by side, 7 mm apart
    row_pitch = 0.03                   # between rows (z)
    tilt = 35.0                        # degrees about x, alternating per row
    height = 0.5                       # the net's plane (y)
    bodies = [fixed("ground", box(1.2, 0.1, 0.6), (0, -0.05, 0))]
    corners = {(0, 0), (0, cols - 1), (rows - 1, 0), (rows - 1, cols - 1)}
    for k in range(rows):
        for i in range(cols):
            x = (i + 0.5 * (k % 2) - (cols - 1) / 2 - 0.25) * pitch
            z = (k - (rows - 1) / 2) * row_pitch
            angles = (tilt if k % 2 == 0 else -tilt, 0, 0)
            if (k, i) in corners:
                bodies.append(fixed(f"ring_{k}_{i}", torus(R, r, n), (x, height, z), angles))
            else:
                bodies.append(body(f"ring_{k}_{i}", torus(R, r, n), (x, height, z), angles, density=7800.0))
    bodies.append(body("ball", sphere(0.05, 12), (0.0, height + 0.15, 0.0), density=1000.0))
    # Every ring is linked with exactly the rings of the neighbouring rows it should be.
    rings = [b for b in bodies if b["mesh"]["primitive"] == "torus"]
    lines = [ring_centre_line(b) for b in rings]
    for a in range(len(rings)):
        for b in range(a + 1, len(rings)):
            ka, ia = divmod(a, cols)
            kb, ib = divmod(b, cols)
            # ring (k, i) of an even row sits between rings (k±1, i−1) and (k±1, i) of the odd rows
            shift = ib - ia if ka % 2 == 0 else ia - ib
            expected = abs(kb - ka) == 1 and shift in ((-1, 0) if ka % 2 == 0 else (0, -1))
            linked = linking_number(lines[a], lines[b]) != 0
            assert linked == expected, (rings[a]["name"], rings[b]["name"], linked)
    return {
        "description": "An 8 x 8 chain net: 64 steel rings (R = 4 cm, tube 5 mm) woven as European 4-in-1 chain "
                       "mail, held by its 4 corner rings (fixed), sagging under gravity while a 5 cm ball lands on "
                       "it, mu = 0.2. Generated by scripts/make_piles.py. " + run_line("chain_net"),
        "time": {"dt": 0.01, "duration": 2.0},
        "contact": {"dhat": 1e-3, "mu": 0.2},
        "bodies": bodies,
    }


def main():
    only_check = "--check" in sys.argv
    verify = "--verify" in sys.argv
    scenes = {}
    for name in PILES:
        scene, tris = make_pile(name)
        target = TARGET_TRIANGLES[name]
        print(f"{name}: {len(scene['bodies'])} bodies, {tris} triangles "
              f"({100 * (tris - target) / target:+.1f} % vs {target})")
        scenes[name] = scene
    scenes["box_stack"] = make_box_stack()
    scenes["incline_stick"] = make_incline(
        "incline_stick", 0.5, "mu = tan(theta), so the block must stick (it may creep below eps_v; "
        "accept s <= eps_v * t).")
    scenes["incline_slide"] = make_incline(
        "incline_slide", 0.49, "mu < tan(theta), so the block slides with a = g (sin - mu cos) = 0.0877 m/s^2, "
        "s(2.5 s) = 0.274 m.")
    scenes["house_of_cards"] = make_house_of_cards()
    scenes["wrecking_ball"] = make_wrecking_ball()
    scenes["chain_net"] = make_chain_net()
    scenes["bricks_900"] = make_brick_pile("bricks_900", 10, 10)
    scenes["bricks_2400"] = make_brick_pile("bricks_2400", 16, 10)
    differing = []
    for name, scene in scenes.items():
        dhat, (worst, pair) = check_scene(name, scene)
        print(f"{name}: d̂ = {dhat:.3g} m, smallest gap (lower bound) {worst:.4g} m between {pair}")
        text = json.dumps(rounded(scene), indent=1, ensure_ascii=False) + "\n"
        path = os.path.join(SCENES, name + ".json")
        if verify:
            with open(path, encoding="utf-8") as f:
                if f.read() != text:
                    differing.append(path)
        elif not only_check:
            with open(path, "w", encoding="utf-8") as f:
                f.write(text)
    if differing:
        sys.exit("make_piles: these files differ from what the generator writes (edit the generator, "
                 "then run it): " + ", ".join(differing))


if __name__ == "__main__":
    main()
