#!/usr/bin/env python3
"""Writes the boxes of a check_sample_image.py scene as a glTF 2.0 file (+ .bin), so a sample
that loads glTF draws exactly what the checker ray-traces, and prints the sample's arguments
for the scene's camera and light.

    make_boxes_gltf.py SCENE.json OUT.gltf
"""
import json
import os
import struct
import sys


def box_faces(lo, hi):
    """Six faces, four corners each, counter-clockwise seen from outside (glTF's front faces)."""
    c = [(a + b) / 2 for a, b in zip(lo, hi)]
    h = [(b - a) / 2 for a, b in zip(lo, hi)]
    for axis in range(3):
        for sign in (1, -1):
            f = [0, 0, 0]
            f[axis] = sign
            u = [0, 1, 0] if axis == 0 else [1, 0, 0]
            w = [f[1] * u[2] - f[2] * u[1], f[2] * u[0] - f[0] * u[2], f[0] * u[1] - f[1] * u[0]]
            corners = [[c[i] + h[i] * (f[i] + sx * u[i] + sy * w[i]) for i in range(3)]
                       for sx, sy in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
            yield corners, f


def main():
    scene = json.load(open(sys.argv[1]))
    out = sys.argv[2]
    positions, normals, indices = [], [], []
    for b in scene["boxes"]:
        for corners, f in box_faces(b["min"], b["max"]):
            base = len(positions)
            positions += corners
            normals += [f] * 4
            indices += [base + k for k in (0, 1, 2, 0, 2, 3)]
    pos_bytes = b"".join(struct.pack("<3f", *p) for p in positions)
    nrm_bytes = b"".join(struct.pack("<3f", *n) for n in normals)
    idx_bytes = b"".join(struct.pack("<I", i) for i in indices)
    bin_name = os.path.splitext(os.path.basename(out))[0] + ".bin"
    with open(os.path.join(os.path.dirname(out) or ".", bin_name), "wb") as f:
        f.write(pos_bytes + nrm_bytes + idx_bytes)
    n = len(positions)
    lo = [min(p[i] for p in positions) for i in range(3)]
    hi = [max(p[i] for p in positions) for i in range(3)]
    gltf = {
        "asset": {"version": "2.0", "generator": "ShadowPort tests/samples/make_boxes_gltf.py"},
        "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2}]}],
        "buffers": [{"uri": bin_name, "byteLength": len(pos_bytes) + len(nrm_bytes) + len(idx_bytes)}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": len(pos_bytes), "target": 34962},
            {"buffer": 0, "byteOffset": len(pos_bytes), "byteLength": len(nrm_bytes), "target": 34962},
            {"buffer": 0, "byteOffset": len(pos_bytes) + len(nrm_bytes), "byteLength": len(idx_bytes), "target": 34963},
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": n, "type": "VEC3", "min": lo, "max": hi},
            {"bufferView": 1, "componentType": 5126, "count": n, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5125, "count": len(indices), "type": "SCALAR"},
        ],
    }
    with open(out, "w") as f:
        json.dump(gltf, f, indent=1)
    fmt = lambda v: ",".join(repr(float(x)) for x in v)
    light = [-x for x in scene["to_light"]]  # the sample takes the direction the light travels
    print(f"--eye {fmt(scene['eye'])} --target {fmt(scene['target'])} --light {fmt(light)}")


if __name__ == "__main__":
    main()
