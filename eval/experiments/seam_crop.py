#!/usr/bin/python3
"""Crops the cascade seam out of two renderings of the same frame (without and with a blend band)
and writes them side by side, enlarged, with the difference between them.

    seam_crop.py without.png with.png out.png [--size 96] [--at-seam]

The seam is where the two images differ most: the blend band changes only the pixels inside it,
so the window centred on the largest box-filtered difference holds the seam.
"""
import argparse

import matplotlib
matplotlib.use("Agg")
import matplotlib.image as mpimg
import matplotlib.pyplot as plt
import numpy as np


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("without")
    ap.add_argument("with_blend")
    ap.add_argument("out")
    ap.add_argument("--size", type=int, default=96, help="crop width and height in pixels")
    ap.add_argument("--at-seam", action="store_true", help="centre the crop on the far edge of the band (the split)")
    a = ap.parse_args()
    img0 = mpimg.imread(a.without)[..., :3]
    img1 = mpimg.imread(a.with_blend)[..., :3]
    if img0.shape != img1.shape:
        raise SystemExit(f"seam_crop: {a.without} is {img0.shape[1]}x{img0.shape[0]} but {a.with_blend} is {img1.shape[1]}x{img1.shape[0]}")
    diff = np.abs(img0 - img1).sum(axis=2)
    h, w = diff.shape
    s = min(a.size, h, w)
    # Sum of differences in every s x s window, from an integral image.
    integral = np.pad(diff.cumsum(0).cumsum(1), ((1, 0), (1, 0)))
    windows = integral[s:, s:] - integral[:-s, s:] - integral[s:, :-s] + integral[:-s, :-s]
    y, x = np.unravel_index(np.argmax(windows), windows.shape)
    if a.at_seam:
        # The band lies just before the split, so the split is the band's far edge: on screen the
        # topmost rows (further away) in which the images still differ. Centre the crop there.
        rows = diff[:, x:x + s].sum(axis=1)
        differing = np.nonzero(rows > 0.1 * rows.max())[0]
        y = int(np.clip(differing.min() - s // 2, 0, h - s))
    crop0, crop1 = img0[y:y + s, x:x + s], img1[y:y + s, x:x + s]
    cropd = diff[y:y + s, x:x + s]
    fig, axes = plt.subplots(1, 3, figsize=(12, 4.4))
    for ax, im, title in ((axes[0], crop0, "blend = 0 (seam)"), (axes[1], crop1, "with blend band")):
        ax.imshow(im, interpolation="nearest")
        ax.set_title(title)
        ax.axis("off")
    shown = axes[2].imshow(cropd, cmap="magma", interpolation="nearest")
    axes[2].set_title("|difference| (sum of RGB)")
    axes[2].axis("off")
    fig.colorbar(shown, ax=axes[2], fraction=0.046)
    fig.suptitle(f"{s}x{s} crop at pixel ({x}, {y}) of {w}x{h}, enlarged; where the two differ most")
    fig.tight_layout()
    fig.savefig(a.out, dpi=100)
    print(f"seam_crop: {a.out}: crop at ({x}, {y}), {s}x{s}, mean |difference| {cropd.mean():.4f} (whole image {diff.mean():.5f})")


if __name__ == "__main__":
    main()
