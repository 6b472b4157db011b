#!/usr/bin/env python3
"""Checks a sample's picture against a ray-traced expectation of the same scene.

    check_sample_image.py SCENE.json IMAGE.png [IMAGE2.png]

SCENE.json describes what the sample draws (axis-aligned boxes, the camera, the light and the
shading formula; the constants are the sample's own). Every pixel is ray-traced on the CPU: the
first box hit by the camera ray, its face normal, and whether a ray towards the light is blocked
(D3D11's rules do not enter here: a pixel is lit exactly when the light reaches its surface
point). The sample's colour must match the lit or the shadowed colour of that surface. Pixels
within a few pixels of a silhouette or a shadow edge are excused (rasterization, PCF and the
shadow map's texels blur them), and faces turned so that lit and shadowed colours are close are
not judged. Everything else must agree; a second image (the other backend) must agree with the
first. Exits non-zero and prints what differs.
"""
import json
import struct
import sys
import zlib

import numpy as np


def read_png(path):
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise SystemExit(f"{path}: not a PNG file")
    pos, idat, width = 8, b"", None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, ctype, _, _, interlace = struct.unpack(">IIBBBBB", body)
            if depth != 8 or ctype not in (2, 6) or interlace:
                raise SystemExit(f"{path}: only 8-bit RGB/RGBA non-interlaced PNGs are read here")
            channels = 4 if ctype == 6 else 3
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw = zlib.decompress(idat)
    stride = width * channels
    out = np.zeros((height, stride), np.int32)
    prev = np.zeros(stride, np.int32)
    for y in range(height):
        ftype = raw[y * (stride + 1)]
        line = np.frombuffer(raw, np.uint8, stride, y * (stride + 1) + 1).astype(np.int32)
        cur = np.zeros(stride, np.int32)
        if ftype in (0, 2):
            cur = (line + (prev if ftype == 2 else 0)) & 255
        else:  # Sub, Average and Paeth depend on the pixel to the left: one pass along the row.
            for x in range(stride):
                a = cur[x - channels] if x >= channels else 0
                b = prev[x]
                c = prev[x - channels] if x >= channels else 0
                if ftype == 1:
                    pred = a
                elif ftype == 3:
                    pred = (a + b) // 2
                else:
                    p = a + b - c
                    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                    pred = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                cur[x] = (line[x] + pred) & 255
        out[y] = cur
        prev = cur
    return out.reshape(height, width, channels)[:, :, :3].astype(np.float64) / 255.0


def trace(boxes, origins, dirs):
    """First hit of each ray against the boxes: (t, box index, normal); t = inf for misses."""
    n = len(dirs)
    best_t = np.full(n, np.inf)
    best_i = np.full(n, -1)
    best_n = np.zeros((n, 3))
    safe = np.where(np.abs(dirs) < 1e-12, 1e-12, dirs)
    for i, (lo, hi) in enumerate(boxes):
        t1 = (lo - origins) / safe
        t2 = (hi - origins) / safe
        tmin_axes = np.minimum(t1, t2)
        tnear = tmin_axes.max(axis=1)
        tfar = np.maximum(t1, t2).min(axis=1)
        hit = (tfar >= np.maximum(tnear, 0.0)) & (tnear > 1e-6) & (tnear < best_t)
        axis = tmin_axes.argmax(axis=1)
        normal = np.zeros((n, 3))
        normal[np.arange(n), axis] = -np.sign(safe[np.arange(n), axis])
        best_t = np.where(hit, tnear, best_t)
        best_i = np.where(hit, i, best_i)
        best_n = np.where(hit[:, None], normal, best_n)
    return best_t, best_i, best_n


def srgb_encode(c):
    c = np.clip(c, 0.0, 1.0)
    return np.where(c <= 0.0031308, c * 12.92, 1.055 * np.power(c, 1 / 2.4) - 0.055)


def expected_image(scene, width, height):
    boxes = [(np.array(b["min"], float), np.array(b["max"], float)) for b in scene["boxes"]]
    colors = np.array([b["color"] for b in scene["boxes"]], float)
    eye, target, up = (np.array(scene[k], float) for k in ("eye", "target", "up"))
    f = (target - eye) / np.linalg.norm(target - eye)
    s = np.cross(f, up)
    s /= np.linalg.norm(s)
    u = np.cross(s, f)
    th = np.tan(np.radians(scene["fov_y_deg"]) / 2)
    px, py = np.meshgrid(np.arange(width) + 0.5, np.arange(height) + 0.5)
    nx = (px / width * 2 - 1) * th * width / height
    ny = (1 - py / height * 2) * th
    dirs = f + nx.reshape(-1, 1) * s + ny.reshape(-1, 1) * u
    dirs /= np.linalg.norm(dirs, axis=1, keepdims=True)
    origins = np.broadcast_to(eye, dirs.shape)
    t, obj, normal = trace(boxes, origins, dirs)
    hit = obj >= 0
    points = origins + dirs * np.where(hit, t, 0)[:, None]
    to_light = np.array(scene["to_light"], float)
    to_light /= np.linalg.norm(to_light)
    st, _, _ = trace(boxes, points + normal * 1e-3, np.broadcast_to(to_light, dirs.shape))
    visible = ~np.isfinite(st)
    ndotl = np.clip(normal @ to_light, 0.0, 1.0)
    albedo = colors[np.maximum(obj, 0)]
    amb = scene["ambient"]
    light = np.array(scene.get("light_color", 1.0), float)
    if scene["shading"] == "ambient-lerp":      # c * (a + (1 - a) * ndotl * vis)
        lit = albedo * (amb + (1 - amb) * ndotl)[:, None]
        shadow = albedo * amb
    else:                                         # "lambert": c * (a + light * ndotl * vis)
        lit = albedo * (amb + light * ndotl[:, None])
        shadow = albedo * amb
    lit[~hit] = shadow[~hit] = np.array(scene["sky"], float)
    if scene.get("srgb"):  # an sRGB render target encodes on write
        lit, shadow = srgb_encode(lit), srgb_encode(shadow)
    shape = (height, width)
    return (lit.reshape(shape + (3,)), shadow.reshape(shape + (3,)), visible.reshape(shape),
            obj.reshape(shape), hit.reshape(shape))


def dilate(mask, r):
    out = mask.copy()
    for dy in range(-r, r + 1):
        for dx in range(-r, r + 1):
            out |= np.roll(np.roll(mask, dy, 0), dx, 1)
    return out


def main():
    if len(sys.argv) < 3:
        raise SystemExit(__doc__)
    scene = json.load(open(sys.argv[1]))
    images = [read_png(p) for p in sys.argv[2:]]
    h, w, _ = images[0].shape
    lit, shadow, visible, obj, hit = expected_image(scene, w, h)
    # Labels change at silhouettes and shadow edges; pixels near a change are not judged.
    label = np.where(hit, obj * 2 + visible, -1)
    edges = np.zeros((h, w), bool)
    for axis in (0, 1):
        change = np.diff(label, axis=axis) != 0
        pad = [(0, 0), (0, 0)]
        pad[axis] = (0, 1)
        edges |= np.pad(change, pad)
        pad[axis] = (1, 0)
        edges |= np.pad(change, pad)
    radius = scene.get("edge_radius", 2)
    excused = dilate(edges, radius)
    contrast = np.abs(lit - shadow).max(axis=2)
    judged = ~excused & ((contrast >= 0.08) | ~hit)
    tol = scene.get("color_tolerance", 0.06)
    failed = False
    for k, img in enumerate(images):
        d_lit = np.abs(img - lit).max(axis=2)
        d_shadow = np.abs(img - shadow).max(axis=2)
        expect = np.where(visible | ~hit, d_lit, d_shadow)
        other = np.where(visible | ~hit, d_shadow, d_lit)
        # Wrong when the colour is nearer the other case, or near neither (a wrong picture).
        wrong = judged & ((expect > other) | (expect > tol))
        acne = judged & hit & visible & (d_shadow < d_lit)
        lost = judged & hit & ~visible & (d_lit < d_shadow)
        n_judged, n_wrong = int(judged.sum()), int(wrong.sum())
        print(f"{sys.argv[2 + k]}: {n_judged} pixels judged, {n_wrong} wrong "
              f"(lit drawn as shadow {int(acne.sum())}, shadow drawn as lit {int(lost.sum())}, "
              f"other colour {n_wrong - int(acne.sum()) - int(lost.sum())}); "
              f"{int(hit.sum())} on geometry, {int((hit & ~visible).sum())} in shadow")
        limit = scene.get("max_wrong_fraction", 0.001) * n_judged
        if n_judged < 0.5 * w * h or n_wrong > limit:
            failed = True
            ys, xs = np.nonzero(wrong)
            for y, x in list(zip(ys, xs))[:5]:
                print(f"  ({x}, {y}): got {np.round(img[y, x] * 255)}, lit {np.round(lit[y, x] * 255)}, "
                      f"shadow {np.round(shadow[y, x] * 255)}, expected {'lit' if visible[y, x] else 'shadow'}")
    if len(images) == 2:
        diff = np.abs(images[0] - images[1]).max(axis=2)
        n = int((diff > 2.5 / 255).sum())
        print(f"backends: {n} pixels differ by more than 2/255, max difference {diff.max() * 255:.0f}/255")
        if n > scene.get("max_backend_diff_fraction", 0.002) * w * h:
            failed = True
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
