#!/usr/bin/env python3
"""Writes a seeded family of procedural scenes for the "do no harm" checks (family.py): random sets of boxes, thin
fins and grilles, poles and wires, thin shells, spheres, stairs and creases, with or without a ground plane
(without one, every object stands against the sky), and with each scene the light and camera it is viewed with:
a directional light of angular radius 0 to 10 degrees or a point light, at a random elevation and azimuth; a still,
slowly orbiting, fast orbiting or panning camera, near or far. Nothing here is committed: family.py writes the
scenes into its build folder.

usage: make_family.py OUT_DIR FIRST_SEED COUNT   -> OUT_DIR/family_<seed>.gltf and OUT_DIR/family.json, which
       lists per seed the scene file, what it holds and the viewer arguments that place its light and camera.

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


def place_objects(rng, add_mesh, node, has_ground):
    """3-7 objects in a 4 x 4 m area; without a ground plane they float at random heights (all against the sky)."""
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


def family_scene(seed):
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
    objects, kinds = place_objects(rng, add_mesh, node, has_ground)
    roots += objects
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
    out.mkdir(parents=True, exist_ok=True)
    listing = []
    for seed in range(first, first + count):
        gltf, info = family_scene(seed)
        path = out / f"family_{seed}.gltf"
        path.write_text(json.dumps(gltf) + "\n")
        info["scene"] = str(path)
        listing.append(info)
    (out / "family.json").write_text(json.dumps(listing, indent=1) + "\n")
    print(f"wrote {count} scenes to {out}")


if __name__ == "__main__":
    main()
