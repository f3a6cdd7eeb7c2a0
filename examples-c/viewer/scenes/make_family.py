#!/usr/bin/env python3
"""Writes a seeded family of procedural scenes for the "do no harm" checks (family.py): random sets of boxes, thin
fins and grilles, poles and wires, thin shells, spheres, stairs and creases, with or without a ground plane
(without one, every object stands against the sky), and with each scene the light and camera it is viewed with:
a directional light of angular radius 0 to 10 degrees or a point light, at a random elevation and azimuth; a still,
slowly orbiting, fast orbiting or panning camera, near or far. Nothing here is committed: family.py writes the
scenes into its build folder.

usage: make_family.py OUT_DIR FIRST_SEED COUNT [OBJECTS]   -> OUT_DIR/family_<seed>.gltf and OUT_DIR/family.json,
       which lists per seed the scene file, what it holds and the viewer arguments that place its light and camera.

OBJECTS is `seen` (the default: the objects above, which dnsr's methods were developed on) or `unseen`: a second
vocabulary kept apart as a check of whether those methods carry over, never to tune them on: tori, faceted rocks
(flat-shaded, jittered), lattices (a screen of crossed bars, standing or overhead), tilted poles, stacks of boards
at random angles, and grids of small spheres. Lights, cameras and grounds are drawn as for `seen`.

Same conventions as make_default.py: y up, metres, triangles only, POSITION + NORMAL, buffers embedded.
"""
import json
import math
import random
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from make_default import Builder, cube, cylinder, document, ground, look_at_quat, plain_materials, quat_y  # noqa: E402
from make_thin import shell  # noqa: E402

LIGHT_ANGLES = [0.0, 0.0, 0.27, 1.0, 3.0, 6.0, 10.0]  # angular radius, degrees; 0: hard shadows only
CAMERAS = {"still": ["--orbit-speed", "0"], "orbit": ["--orbit-speed", "0.25"], "fast": ["--orbit-speed", "2"],
           "pan": ["--orbit-speed", "0", "--pan", "0.004"]}


def sphere(rings, segments):
    """Unit sphere, smooth normals."""
    positions, indices = [], []
    for r in range(rings + 1):
        t = math.pi * r / rings
        for s in range(segments + 1):
            a = 2 * math.pi * s / segments
            positions.append((math.sin(t) * math.cos(a), math.cos(t), math.sin(t) * math.sin(a)))
    for r in range(rings):
        for s in range(segments):
            a, b = r * (segments + 1) + s, (r + 1) * (segments + 1) + s
            indices += [a, a + 1, b + 1, a, b + 1, b]
    return positions, list(positions), indices


def torus(major, minor, rings, segments):
    """Torus around the y axis, smooth normals."""
    positions, normals, indices = [], [], []
    for r in range(rings + 1):
        u = 2 * math.pi * r / rings
        for k in range(segments + 1):
            v = 2 * math.pi * k / segments
            n = (math.cos(v) * math.cos(u), math.sin(v), math.cos(v) * math.sin(u))
            positions.append(((major + minor * math.cos(v)) * math.cos(u), minor * math.sin(v),
                              (major + minor * math.cos(v)) * math.sin(u)))
            normals.append(n)
    for r in range(rings):
        for k in range(segments):
            a, b = r * (segments + 1) + k, (r + 1) * (segments + 1) + k
            indices += [a, b + 1, a + 1, a, b, b + 1]
    return positions, normals, indices


def rock(rng):
    """A unit sphere of 80 facets with jittered corners, flat normals (each facet its own three vertices)."""
    t = (1 + math.sqrt(5)) / 2
    corners = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
               (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
             (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11),
             (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    points = [tuple(c / math.sqrt(1 + t * t) for c in p) for p in corners]
    mids, split = {}, []

    def mid(a, b):
        key = (min(a, b), max(a, b))
        if key not in mids:
            m = [(x + y) / 2 for x, y in zip(points[a], points[b])]
            n = math.sqrt(sum(c * c for c in m))
            points.append(tuple(c / n for c in m))
            mids[key] = len(points) - 1
        return mids[key]
    for a, b, c in faces:
        ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
        split += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
    points = [tuple(c * rng.uniform(0.8, 1.15) for c in p) for p in points]
    positions, normals, indices = [], [], []
    for a, b, c in split:
        pa, pb, pc = points[a], points[b], points[c]
        e1, e2 = [y - x for x, y in zip(pa, pb)], [y - x for x, y in zip(pa, pc)]
        n = (e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0])
        if sum(x * y for x, y in zip(n, pa)) < 0:  # outward, counter-clockwise
            pb, pc, n = pc, pb, tuple(-x for x in n)
        length = math.sqrt(sum(x * x for x in n))
        base = len(positions)
        positions += [pa, pb, pc]
        normals += [tuple(x / length for x in n)] * 3
        indices += [base, base + 1, base + 2]
    return positions, normals, indices


def quat_x(degrees):
    a = math.radians(degrees) / 2
    return [math.sin(a), 0.0, 0.0, math.cos(a)]


def place_unseen(rng, add_mesh, node, kind, children):
    """One object of the `unseen` vocabulary into children (its root's frame: y up, resting on y = 0)."""
    if kind == "torus":
        major = rng.uniform(0.2, 0.6)
        tor = add_mesh("torus", torus(1.0, rng.uniform(0.08, 0.3), 48, 16), "red")
        children.append(node(mesh=tor, translation=[0, major * 0.3, 0], rotation=quat_x(rng.uniform(0, 90)),
                             scale=[major, major, major]))
    elif kind == "rock":
        r = rng.uniform(0.2, 0.8)
        children.append(node(mesh=add_mesh("rock", rock(rng), "metal"), translation=[0, r * 0.7, 0], scale=[r, r, r]))
    elif kind == "lattice":  # crossed bars 1-3 cm thick, 5-15 cm apart: standing, or overhead on four legs
        n, t, gap = rng.randint(5, 12), rng.uniform(0.01, 0.03), rng.uniform(0.05, 0.15)
        span, overhead = n * gap, rng.random() < 0.5
        box = add_mesh("box", cube(), "metal")
        height = rng.uniform(0.8, 1.6)
        for k in range(n + 1):
            offset = (k - n / 2) * gap
            if overhead:
                children += [node(mesh=box, translation=[offset, height, 0], scale=[t, t, span]),
                             node(mesh=box, translation=[0, height, offset], scale=[span, t, t])]
            else:
                children += [node(mesh=box, translation=[offset, span / 2, 0], scale=[t, span, t]),
                             node(mesh=box, translation=[0, (k + 0.5) * gap, 0], scale=[span, t, t])]
        if overhead:
            for sx in (-1, 1):
                for sz in (-1, 1):
                    children.append(node(mesh=box, translation=[sx * span / 2, height / 2, sz * span / 2],
                                         scale=[0.03, height, 0.03]))
    elif kind == "tilted_pole":
        r, hgt = rng.uniform(0.01, 0.05), rng.uniform(0.8, 2.5)
        children.append(node(mesh=add_mesh("cylinder", cylinder(24), "metal"), rotation=quat_x(rng.uniform(15, 70)),
                             scale=[r, hgt, r]))
    elif kind == "boards":  # thin boards piled at random angles, overhanging and crossing each other
        box = add_mesh("box", cube(), "red")
        y = 0.0
        for _ in range(rng.randint(2, 6)):
            th = rng.uniform(0.02, 0.06)
            y += th
            children.append(node(mesh=box, translation=[rng.uniform(-0.2, 0.2), y - th / 2, rng.uniform(-0.2, 0.2)],
                                 rotation=quat_y(rng.uniform(0, 180)),
                                 scale=[rng.uniform(0.6, 1.4), th, rng.uniform(0.1, 0.3)]))
    else:  # sphere_grid: small spheres on a square grid
        ball = add_mesh("sphere", sphere(12, 24), "red")
        n, r = rng.randint(3, 5), rng.uniform(0.04, 0.12)
        gap = r * rng.uniform(2.2, 3.5)
        for i in range(n):
            for j in range(n):
                children.append(node(mesh=ball, translation=[(i - n / 2) * gap, r, (j - n / 2) * gap], scale=[r, r, r]))


UNSEEN = ["torus", "rock", "lattice", "tilted_pole", "boards", "sphere_grid"]


def place_objects(rng, add_mesh, node, has_ground, objects="seen"):
    """3-7 objects in a 4 x 4 m area; without a ground plane they float at random heights (all against the sky)."""
    if objects == "unseen":
        kinds, roots = [], []
        for i in range(rng.randint(3, 7)):
            kind = rng.choice(UNSEEN)
            kinds.append(kind)
            x, z = rng.uniform(-2, 2), rng.uniform(-2, 2)
            y = 0.0 if has_ground else rng.uniform(-1, 1)
            children = []
            place_unseen(rng, add_mesh, node, kind, children)
            roots.append(node(name=f"{kind}_{i}", translation=[x, y, z], rotation=quat_y(rng.uniform(0, 360)),
                              children=children))
        return roots, kinds
    box, metal = add_mesh("box", cube(), "metal"), add_mesh("red_box", cube(), "red")
    cyl, ball = add_mesh("cylinder", cylinder(24), "metal"), add_mesh("sphere", sphere(16, 32), "red")
    shl = add_mesh("shell", shell(0.5, rng.choice([0.01, 0.02, 0.04]), 40), "metal")
    kinds, roots = [], []
    for i in range(rng.randint(3, 7)):
        kind = rng.choice(["box", "fins", "pole", "wire", "shell", "sphere", "stairs", "crease"])
        kinds.append(kind)
        x, z = rng.uniform(-2, 2), rng.uniform(-2, 2)
        y = 0.0 if has_ground else rng.uniform(-1, 1)
        yaw = rng.uniform(0, 360)
        children = []
        if kind == "box":
            sx, sy, sz = rng.uniform(0.2, 1.2), rng.uniform(0.2, 1.2), rng.uniform(0.2, 1.2)
            children.append(node(mesh=box, translation=[0, sy / 2, 0], scale=[sx, sy, sz]))
        elif kind == "fins":  # a grille: parallel slabs 1-4 cm thick, a few cm apart
            n, t, gap, hgt = rng.randint(4, 12), rng.uniform(0.01, 0.04), rng.uniform(0.04, 0.15), rng.uniform(0.3, 1.0)
            for k in range(n):
                children.append(node(mesh=box, translation=[(k - n / 2) * gap, hgt / 2, 0], scale=[t, hgt, 0.8]))
        elif kind == "pole":
            r, hgt = rng.uniform(0.01, 0.05), rng.uniform(0.8, 2.5)
            children.append(node(mesh=cyl, scale=[r, hgt, r]))
        elif kind == "wire":  # a thin horizontal bar held up high
            t, length, hgt = rng.uniform(0.005, 0.03), rng.uniform(1.5, 4.0), rng.uniform(0.6, 2.0)
            children.append(node(mesh=box, translation=[0, hgt, 0], scale=[length, t, t]))
        elif kind == "shell":
            children.append(node(mesh=shl, scale=[rng.uniform(0.6, 1.4), rng.uniform(0.5, 1.5), rng.uniform(0.6, 1.4)]))
        elif kind == "sphere":
            r = rng.uniform(0.15, 0.7)
            children.append(node(mesh=ball, translation=[0, r, 0], scale=[r, r, r]))
        elif kind == "stairs":
            steps, rise, run = rng.randint(3, 8), rng.uniform(0.05, 0.2), rng.uniform(0.1, 0.3)
            for k in range(steps):
                children.append(node(mesh=box, translation=[0, rise * (k + 1) / 2, run * k],
                                     scale=[0.8, rise * (k + 1), run]))
        else:  # crease: two slabs meeting at an angle
            angle = rng.uniform(60, 150)
            children.append(node(mesh=metal, translation=[0, 0.4, 0], scale=[1.0, 0.8, 0.05]))
            children.append(node(mesh=metal, translation=[0.5, 0.4, 0], rotation=quat_y(angle), scale=[1.0, 0.8, 0.05]))
        roots.append(node(name=f"{kind}_{i}", translation=[x, y, z], rotation=quat_y(yaw), children=children))
    return roots, kinds


def family_scene(seed, objects="seen"):
    rng = random.Random(seed)
    has_ground = rng.random() < 0.6
    b = Builder()
    materials = [("ground", [0.72, 0.72, 0.68, 1]), ("metal", [0.55, 0.56, 0.60, 1]), ("red", [0.80, 0.22, 0.18, 1])]
    mat = {n: i for i, (n, _) in enumerate(materials)}
    meshes, nodes = [], []

    def add_mesh(name, data, material):
        p, n, i = data
        meshes.append({"name": name, "primitives": [{"attributes": {"POSITION": b.vec3(p), "NORMAL": b.vec3(n)},
                                                     "indices": b.indices(i, 5125), "material": mat[material]}]})
        return len(meshes) - 1

    def node(**kw):
        nodes.append(kw)
        return len(nodes) - 1

    roots = []
    if has_ground:
        gp, gn = ground(20.0)
        meshes.append({"name": "ground", "primitives": [{"attributes": {"POSITION": b.vec3(gp), "NORMAL": b.vec3(gn)},
                                                         "mode": 4, "material": mat["ground"]}]})
        roots.append(node(name="ground", mesh=len(meshes) - 1))
    placed, kinds = place_objects(rng, add_mesh, node, has_ground, objects)
    roots += placed
    # Camera: near (the objects fill the view) or far (small on screen), looking down at 10-45 degrees.
    distance = rng.choice([rng.uniform(3.0, 5.0), rng.uniform(7.0, 12.0)])
    yaw, pitch = math.radians(rng.uniform(0, 360)), math.radians(rng.uniform(10, 45))
    eye = [distance * math.cos(pitch) * math.sin(yaw), 0.5 + distance * math.sin(pitch),
           distance * math.cos(pitch) * math.cos(yaw)]
    roots.append(node(name="camera", camera=0, translation=eye, rotation=look_at_quat(eye, [0, 0.5, 0])))
    gltf = document(f"dnsr viewer scenes/make_family.py, seed {seed}", f"family_{seed}", roots, nodes, 0.7, meshes,
                    plain_materials(materials), b)
    point = rng.random() < 0.25
    angle = rng.choice(LIGHT_ANGLES)
    camera = rng.choice(list(CAMERAS))
    args = ["--light-angle", f"{angle}", "--light-elevation", f"{rng.uniform(15, 75):.1f}",
            "--light-azimuth", f"{rng.uniform(-180, 180):.1f}"] + (["--point-light"] if point else []) + CAMERAS[camera]
    info = {"seed": seed, "ground": has_ground, "objects": kinds, "light": "point" if point else "directional",
            "light_angle_deg": angle, "camera": camera, "distance": round(distance, 2), "viewer_args": args}
    return gltf, info


def main():
    out, first, count = Path(sys.argv[1]), int(sys.argv[2]), int(sys.argv[3])
    objects = sys.argv[4] if len(sys.argv) > 4 else "seen"
    if objects not in ("seen", "unseen"):
        raise SystemExit(f"make_family.py: OBJECTS is seen or unseen, not {objects!r}")
    out.mkdir(parents=True, exist_ok=True)
    listing = []
    for seed in range(first, first + count):
        gltf, info = family_scene(seed, objects)
        path = out / f"family_{seed}.gltf"
        path.write_text(json.dumps(gltf) + "\n")
        info["scene"] = str(path)
        listing.append(info)
    (out / "family.json").write_text(json.dumps(listing, indent=1) + "\n")
    print(f"wrote {count} scenes to {out}")


if __name__ == "__main__":
    main()
