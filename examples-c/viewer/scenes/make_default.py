#!/usr/bin/env python3
"""Writes default.gltf, the viewer's built-in scene, next to this script (or to the path given as argument).

The scene is made to show what a shadow denoiser has to get right, lit by a light with an angular radius of a
few degrees (y up, metres):
  - a 20 x 20 m ground plane;
  - a table on thin legs: the top casts a wide soft shadow, each leg a thin line that fades with distance;
  - a thin pole: a shadow only a few pixels wide that a too-wide filter erases;
  - a box held 2 m above the ground by a thin stand: a wide penumbra;
  - a box standing on the ground: a hard contact edge that widens away from it.

It also exercises the loader: a non-indexed mesh (the ground), a u16-indexed box shared by several nodes with
per-node scale, a u32-indexed cylinder with smooth normals, TRS and matrix node transforms, a node hierarchy
(the table) and a perspective camera node the viewer starts from. Buffers are embedded as base64 data URIs so
the file stands alone. Triangles only, POSITION + NORMAL, as the viewer supports.
"""
import base64
import json
import math
import struct
import sys
from pathlib import Path


class Builder:
    """Accumulates one binary buffer and the bufferViews/accessors that describe it."""

    def __init__(self):
        self.data = bytearray()
        self.views = []
        self.accessors = []

    def _view(self, payload, target):
        while len(self.data) % 4:  # every view starts 4-byte aligned, as glTF requires for floats
            self.data.append(0)
        self.views.append({"buffer": 0, "byteOffset": len(self.data), "byteLength": len(payload), "target": target})
        self.data.extend(payload)
        return len(self.views) - 1

    def vec3(self, values):
        payload = b"".join(struct.pack("<3f", *v) for v in values)
        view = self._view(payload, 34962)  # ARRAY_BUFFER
        acc = {"bufferView": view, "componentType": 5126, "count": len(values), "type": "VEC3"}
        acc["min"] = [min(v[i] for v in values) for i in range(3)]
        acc["max"] = [max(v[i] for v in values) for i in range(3)]
        self.accessors.append(acc)
        return len(self.accessors) - 1

    def indices(self, values, component_type):
        fmt = {5123: "<H", 5125: "<I"}[component_type]
        payload = b"".join(struct.pack(fmt, i) for i in values)
        view = self._view(payload, 34963)  # ELEMENT_ARRAY_BUFFER
        self.accessors.append({"bufferView": view, "componentType": component_type, "count": len(values),
                               "type": "SCALAR"})
        return len(self.accessors) - 1


def ground(size):
    h = size / 2
    corners = [(-h, 0, -h), (-h, 0, h), (h, 0, h), (-h, 0, -h), (h, 0, h), (h, 0, -h)]  # counter-clockwise from +y
    return corners, [(0, 1, 0)] * 6


def cube():
    """Unit cube centred on the origin: 24 vertices (flat normals), 36 indices."""
    positions, normals, indices = [], [], []
    for axis in range(3):
        for sign in (-1, 1):
            n = [0, 0, 0]
            n[axis] = sign
            u = [0, 0, 0]
            v = [0, 0, 0]
            u[(axis + 1) % 3] = 1
            v[(axis + 2) % 3] = 1
            base = len(positions)
            for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                positions.append(tuple(0.5 * (n[i] + a * u[i] + b * v[i]) for i in range(3)))
                normals.append(tuple(n))
            quad = [0, 1, 2, 0, 2, 3] if sign > 0 else [0, 2, 1, 0, 3, 2]
            indices += [base + q for q in quad]
    return positions, normals, indices


def cylinder(segments):
    """Radius 1, y from 0 to 1, smooth side normals, flat caps."""
    positions, normals, indices = [], [], []
    for i in range(segments + 1):
        a = 2 * math.pi * i / segments
        c, s = math.cos(a), math.sin(a)
        positions += [(c, 0, s), (c, 1, s)]
        normals += [(c, 0, s), (c, 0, s)]
    for i in range(segments):
        b = 2 * i
        indices += [b, b + 1, b + 3, b, b + 3, b + 2]
    for y, ny in ((0, -1), (1, 1)):
        centre = len(positions)
        positions.append((0, y, 0))
        normals.append((0, ny, 0))
        for i in range(segments):
            a = 2 * math.pi * i / segments
            positions.append((math.cos(a), y, math.sin(a)))
            normals.append((0, ny, 0))
        for i in range(segments):
            j = (i + 1) % segments
            tri = [centre, centre + 1 + i, centre + 1 + j]
            indices += tri if ny < 0 else [tri[0], tri[2], tri[1]]
    return positions, normals, indices


def quat_y(degrees):
    a = math.radians(degrees) / 2
    return [0.0, math.sin(a), 0.0, math.cos(a)]


def look_at_quat(eye, target):
    """Rotation taking the glTF camera frame (looking down -z, +y up) to look from eye at target."""
    f = [t - e for t, e in zip(target, eye)]
    n = math.sqrt(sum(x * x for x in f))
    f = [x / n for x in f]
    z = [-x for x in f]  # camera +z points backwards
    up = [0.0, 1.0, 0.0]
    x = [up[1] * z[2] - up[2] * z[1], up[2] * z[0] - up[0] * z[2], up[0] * z[1] - up[1] * z[0]]
    n = math.sqrt(sum(c * c for c in x))
    x = [c / n for c in x]
    y = [z[1] * x[2] - z[2] * x[1], z[2] * x[0] - z[0] * x[2], z[0] * x[1] - z[1] * x[0]]
    m00, m01, m02 = x[0], y[0], z[0]  # columns are the camera axes
    m10, m11, m12 = x[1], y[1], z[1]
    m20, m21, m22 = x[2], y[2], z[2]
    trace = m00 + m11 + m22
    if trace > 0:
        s = 0.5 / math.sqrt(trace + 1)
        return [(m21 - m12) * s, (m02 - m20) * s, (m10 - m01) * s, 0.25 / s]
    if m00 > m11 and m00 > m22:
        s = 2 * math.sqrt(1 + m00 - m11 - m22)
        return [0.25 * s, (m01 + m10) / s, (m02 + m20) / s, (m21 - m12) / s]
    if m11 > m22:
        s = 2 * math.sqrt(1 + m11 - m00 - m22)
        return [(m01 + m10) / s, 0.25 * s, (m12 + m21) / s, (m02 - m20) / s]
    s = 2 * math.sqrt(1 + m22 - m00 - m11)
    return [(m02 + m20) / s, (m12 + m21) / s, 0.25 * s, (m10 - m01) / s]


def matrix_trs(t, degrees_y, s):
    """Column-major 4x4 matrix = T * Ry * S (the form glTF's node.matrix uses)."""
    c, sn = math.cos(math.radians(degrees_y)), math.sin(math.radians(degrees_y))
    return [c * s, 0, -sn * s, 0,
            0, s, 0, 0,
            sn * s, 0, c * s, 0,
            t[0], t[1], t[2], 1]


def build():
    b = Builder()
    materials = [
        ("ground", [0.72, 0.72, 0.68, 1]),
        ("wood", [0.62, 0.42, 0.26, 1]),
        ("red", [0.80, 0.22, 0.18, 1]),
        ("blue", [0.22, 0.38, 0.80, 1]),
        ("metal", [0.55, 0.56, 0.60, 1]),
    ]
    gltf_materials = [{"name": n, "pbrMetallicRoughness": {"baseColorFactor": c, "metallicFactor": 0.0}}
                      for n, c in materials]
    mat = {n: i for i, (n, _) in enumerate(materials)}

    gp, gn = ground(20.0)
    ground_prim = {"attributes": {"POSITION": b.vec3(gp), "NORMAL": b.vec3(gn)}, "mode": 4}

    cp, cn, ci = cube()
    cube_attrs = {"POSITION": b.vec3(cp), "NORMAL": b.vec3(cn)}
    cube_idx = b.indices(ci, 5123)  # u16

    yp, yn, yi = cylinder(16)
    cyl_attrs = {"POSITION": b.vec3(yp), "NORMAL": b.vec3(yn)}
    cyl_idx = b.indices(yi, 5125)  # u32

    meshes = [{"name": "ground", "primitives": [dict(ground_prim, material=mat["ground"])]}]
    mesh = {"ground": 0}
    for name in ("wood", "red", "blue"):
        meshes.append({"name": "box_" + name, "primitives": [
            {"attributes": dict(cube_attrs), "indices": cube_idx, "material": mat[name]}]})
        mesh["box_" + name] = len(meshes) - 1
    meshes.append({"name": "pole", "primitives": [
        {"attributes": dict(cyl_attrs), "indices": cyl_idx, "material": mat["metal"]}]})
    mesh["pole"] = len(meshes) - 1

    nodes = []

    def node(**kw):
        nodes.append(kw)
        return len(nodes) - 1

    leg_nodes = [node(name="leg", mesh=mesh["box_wood"], translation=[x * 0.92, 0.5, z * 0.52],
                      scale=[0.06, 1.0, 0.06]) for x in (-1, 1) for z in (-1, 1)]
    top = node(name="table_top", mesh=mesh["box_wood"], translation=[0, 1.04, 0], scale=[2.0, 0.08, 1.2])
    table = node(name="table", translation=[-1.8, 0, 0.2], rotation=quat_y(20), children=leg_nodes + [top])
    pole = node(name="thin_pole", mesh=mesh["pole"], translation=[1.2, 0, -1.6], scale=[0.025, 2.6, 0.025])
    stand = node(name="stand", mesh=mesh["pole"], scale=[0.03, 2.0, 0.03])
    raised_box = node(name="raised_box", mesh=mesh["box_blue"], translation=[0, 2.4, 0], scale=[0.8, 0.8, 0.8])
    raised = node(name="raised_box_on_stand", matrix=matrix_trs([2.2, 0, 1.4], 30, 1.0),
                  children=[stand, raised_box])
    contact = node(name="contact_box", mesh=mesh["box_red"], translation=[0.1, 0.4, 1.9], rotation=quat_y(35),
                   scale=[1.0, 0.8, 1.0])
    g = node(name="ground", mesh=mesh["ground"])
    eye, target = [3.4, 3.6, 5.6], [0.2, 0.3, 0.2]
    camera = node(name="camera", camera=0, translation=eye, rotation=look_at_quat(eye, target))

    return document("dnsr viewer scenes/make_default.py", "default", [g, table, pole, raised, contact, camera], nodes,
                    0.75, meshes, gltf_materials, b)


def document(generator, name, roots, nodes, yfov, meshes, materials, b):
    """The glTF document of one scene: its root nodes, one perspective camera, the builder's embedded buffer."""
    return {
        "asset": {"version": "2.0", "generator": generator},
        "scene": 0,
        "scenes": [{"name": name, "nodes": roots}],
        "nodes": nodes,
        "cameras": [{"type": "perspective", "perspective": {"yfov": yfov, "znear": 0.05, "zfar": 100.0}}],
        "meshes": meshes,
        "materials": materials,
        "accessors": b.accessors,
        "bufferViews": b.views,
        "buffers": [{"byteLength": len(b.data),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(b.data)).decode()}],
    }


def plain_materials(materials):
    """glTF materials from (name, base colour) pairs."""
    return [{"name": n, "pbrMetallicRoughness": {"baseColorFactor": c, "metallicFactor": 0.0}} for n, c in materials]


def main():
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).with_name("default.gltf")
    out.write_text(json.dumps(build(), indent=1) + "\n")
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
