#!/usr/bin/env python3
"""Checks the viewer's overlay screenshots (tests/CMakeLists.txt, samples.viewer_overlay_*).

  check_overlay.py layers WINDOW.png PLAIN.png LAB-color.png LAB-layer.png
      The layer-colour overlay from the lab buffers the viewer dumped (--dump-lab): the lab's
      colour must be the plain frame (the lab lit pass shades as the normal one), at least two
      layers must be read, and every pixel of the window must be, per channel on the sRGB bytes,
      (colour + tint[layer]) // 2 where the pixel read layer >= 0 (layer PNG = layer + 1) and the
      colour itself elsewhere. The tints are docs/viewer.md's table, written here independently.
  check_overlay.py differs WINDOW.png PLAIN.png MIN_FRACTION
      At least MIN_FRACTION of the pixels differ from the plain frame (the overlay was drawn).
"""
import os
import sys

import numpy as np

# The samples' PNG reader (numpy only, what the tests may rely on).
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "samples"))
from check_sample_image import read_png  # noqa: E402

# docs/viewer.md: layer k's tint is TINTS[k % 8].
TINTS = [(230, 40, 40), (40, 200, 40), (50, 90, 240), (230, 220, 40),
         (220, 50, 220), (40, 210, 220), (250, 140, 20), (140, 70, 220)]


def load(path):
    return np.rint(read_png(path) * 255.0).astype(np.int32)  # RGB, floats in [0, 1] -> bytes


def fail(msg):
    print("FAIL: " + msg)
    sys.exit(1)


def main():
    mode = sys.argv[1]
    window, plain = load(sys.argv[2]), load(sys.argv[3])
    if window.shape != plain.shape:
        fail(f"window {window.shape} and plain frame {plain.shape} differ in size")
    if mode == "differs":
        frac = float(np.mean(np.any(window != plain, axis=2)))
        print(f"{frac * 100:.1f} % of the pixels differ from the plain frame")
        if frac < float(sys.argv[4]):
            fail(f"the overlay changed {frac * 100:.1f} % of the pixels, expected at least {float(sys.argv[4]) * 100:.1f} %")
        return
    color, layer = load(sys.argv[4]), load(sys.argv[5])[..., 0] - 1
    if color.shape != window.shape:
        fail(f"lab colour {color.shape} and window {window.shape} differ in size")
    if not np.array_equal(color, plain):
        fail("the lab's colour is not the plain frame")
    layers = sorted(set(np.unique(layer).tolist()) - {-1})
    if len(layers) < 2:
        fail(f"the frame reads layers {layers}: too few to tell layer colours apart")
    expected = color.copy()
    for k in layers:
        mask = layer == k
        expected[mask] = (color[mask] + np.array(TINTS[k % 8])) // 2
    wrong = np.any(window != expected, axis=2)
    for k in [-1] + layers:
        n, bad = int(np.sum(layer == k)), int(np.sum(wrong & (layer == k)))
        print(f"layer {k:2d}: {n:6d} pixels, {bad} wrong")
    if wrong.any():
        y, x = np.argwhere(wrong)[0]
        fail(f"{int(wrong.sum())} pixels are not their layer's tint; first ({x}, {y}): layer {layer[y, x]}, "
             f"window {window[y, x].tolist()}, expected {expected[y, x].tolist()}")
    print("layer colours match the lab's lookup")


if __name__ == "__main__":
    main()
