#!/usr/bin/env python3
"""Writes fins.gltf and shells.gltf next to this script: scenes with the thin features and contact shadows a shadow
denoiser gets wrong first (same conventions and helpers as make_default.py: y up, metres, triangles only,
POSITION + NORMAL, buffers embedded).

fins.gltf:   a heat sink (a base plate with twelve 3 cm fins 15 cm apart) whose fins cast thin parallel shadows
             and hard contact shadows on the plate, next to a cube standing on the ground (a 90-degree crease
             between its lit and its shadowed faces, and a contact edge).
shells.gltf: open half-cylinder shells 2 cm thick at several angles: thin lit crescents on their rims, thin curved
             shadows, and shells that shadow each other.
"""
import json
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from make_default import Builder, cube, document, ground, look_at_quat, plain_materials, quat_y  # noqa: E402


def shell(radius, thickness, segments):
    """Half of a hollow cylinder: angle 0..pi, y from 0 to 1, inner and outer walls with radial normals and flat
    rims at both ends and on top and bottom."""
    positions, normals, indices = [], [], []

    def quad(a, b, c, d, n):
        base = len(positions)
        positions.extend([a, b, c, d])
        normals.extend([n] * 4)
        indices.extend([base, base + 1, base + 2, base, base + 2, base + 3])

    r_in, r_out = radius - thickness / 2, radius + thickness / 2
    for i in range(segments):
        a0, a1 = math.pi * i / segments, math.pi * (i + 1) / segments
        p = lambda r, a, y: (r * math.cos(a), y, r * math.sin(a))  # noqa: E731
        mid = (a0 + a1) / 2
        out_n, in_n = (math.cos(mid), 0, math.sin(mid)), (-math.cos(mid), 0, -math.sin(mid))
        quad(p(r_out, a0, 0), p(r_out, a0, 1), p(r_out, a1, 1), p(r_out, a1, 0), out_n)
        quad(p(r_in, a0, 0), p(r_in, a1, 0), p(r_in, a1, 1), p(r_in, a0, 1), in_n)
        quad(p(r_in, a0, 1), p(r_in, a1, 1), p(r_out, a1, 1), p(r_out, a0, 1), (0, 1, 0))
        quad(p(r_in, a0, 0), p(r_out, a0, 0), p(r_out, a1, 0), p(r_in, a1, 0), (0, -1, 0))
    for a, n in ((0.0, (0, 0, -1)), (math.pi, (0, 0, -1))):
        c, s = math.cos(a), math.sin(a)
        quad((r_in * c, 0, r_in * s), (r_in * c, 1, r_in * s), (r_out * c, 1, r_out * s), (r_out * c, 0, r_out * s), n)
    return positions, normals, indices


def scene(name, build_nodes, eye, target):
    b = Builder()
    materials = [("ground", [0.72, 0.72, 0.68, 1]), ("metal", [0.55, 0.56, 0.60, 1]), ("red", [0.80, 0.22, 0.18, 1])]
    mat = {n: i for i, (n, _) in enumerate(materials)}
    gp, gn = ground(20.0)
    meshes = [{"name": "ground", "primitives": [{"attributes": {"POSITION": b.vec3(gp), "NORMAL": b.vec3(gn)},
                                                  "mode": 4, "material": mat["ground"]}]}]

    def add_mesh(mesh_name, data, material):
        p, n, i = data
        meshes.append({"name": mesh_name, "primitives": [{"attributes": {"POSITION": b.vec3(p), "NORMAL": b.vec3(n)},
                                                          "indices": b.indices(i, 5125), "material": mat[material]}]})
        return len(meshes) - 1

    nodes = [{"name": "ground", "mesh": 0}]

    def node(**kw):
        nodes.append(kw)
        return len(nodes) - 1

    roots = [0] + build_nodes(add_mesh, node)
    roots.append(node(name="camera", camera=0, translation=eye, rotation=look_at_quat(eye, target)))
    return document("dnsr viewer scenes/make_thin.py", name, roots, nodes, 0.6, meshes, plain_materials(materials), b)


def fins(add_mesh, node):
    box = add_mesh("box", cube(), "metal")
    red = add_mesh("red_box", cube(), "red")
    children = [node(name="base", mesh=box, translation=[0, 0.05, 0], scale=[1.9, 0.1, 1.2])]
    for i in range(12):
        x = -0.825 + 0.15 * i
        children.append(node(name=f"fin_{i}", mesh=box, translation=[x, 0.1 + 0.35, 0], scale=[0.03, 0.7, 1.2]))
    sink = node(name="heat_sink", translation=[-0.6, 0, 0], rotation=quat_y(15), children=children)
    crease = node(name="crease_cube", mesh=red, translation=[1.7, 0.5, 0.6], rotation=quat_y(-30), scale=[1, 1, 1])
    return [sink, crease]


def shells(add_mesh, node):
    s = add_mesh("shell", shell(0.6, 0.02, 48), "metal")
    placed = [([-1.2, 0, 0.2], 0, [1, 1.0, 1]), ([0.2, 0, -0.4], 70, [1, 1.3, 1]), ([1.3, 0, 0.6], 150, [0.8, 0.8, 0.8]),
              ([0.0, 0, 1.3], -40, [0.7, 0.6, 0.7])]
    return [node(name=f"shell_{i}", mesh=s, translation=t, rotation=quat_y(a), scale=sc)
            for i, (t, a, sc) in enumerate(placed)]


def main():
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).parent
    for name, build_nodes, eye, target in (("fins", fins, [2.6, 2.8, 3.6], [0.2, 0.3, 0.2]),
                                           ("shells", shells, [2.8, 2.4, 3.8], [0.1, 0.4, 0.3])):
        path = out / f"{name}.gltf"
        path.write_text(json.dumps(scene(name, build_nodes, eye, target), indent=1) + "\n")
        print(f"wrote {path}")


if __name__ == "__main__":
    main()
