#!/usr/bin/python3
"""Markdown tables for docs/techniques.md from the results techniques-i.sh writes.

    techniques_i_tables.py OUT_DIR > tables.md

Every figure is read from OUT_DIR/<experiment>.json; the accuracy columns are the Vulkan run's and
the script checks that the GL run of the same scene and parameters gives the same values."""
import json
import sys
from pathlib import Path

ACCURACY = ["misclassified_pct", "false_lit_pct", "false_shadow_pct", "texels_per_pixel_median",
            "texels_per_pixel_p05", "utilization", "flicker", "shadow_triangles"]


def load(out, name):
    runs = json.loads((Path(out) / f"{name}.json").read_text())["runs"]
    pairs = {}
    for r in runs:
        key = (r["scene"], r["technique"], json.dumps(r["params"], sort_keys=True))
        pairs.setdefault(key, {})[r["backend"]] = r
    rows = []
    for key, by in pairs.items():
        vk, gl = by.get("vulkan"), by.get("gl")
        same = vk is not None and gl is not None and all(vk["metrics"][k] == gl["metrics"][k] for k in ACCURACY)
        rows.append((vk or gl, gl, same))
    return rows


def fmt(v, digits=3):
    if isinstance(v, int):
        return f"{v:,}".replace(",", " ")
    if v != 0 and abs(v) < 1e-2:
        return f"{v:.1e}"
    return f"{v:.{digits}f}"


def table(rows, varying, title):
    print(f"\n**{title}**\n")
    head = ["scene"] + varying + ["misclassified %", "false lit %", "false shadow %", "texels/px median", "p05",
                                  "utilization", "flicker", "GPU ms Vulkan (shadow / lit)", "GPU ms GL (shadow / lit)", "same on GL"]
    print("| " + " | ".join(head) + " |")
    print("|" + "---|" * len(head))
    for vk, gl, same in rows:
        m = vk["metrics"]
        gv, gg = vk["metrics"]["gpu_ms"], (gl["metrics"]["gpu_ms"] if gl else {})
        cells = [vk["scene"]] + [vk["params"].get(p, vk["technique"] if p == "technique" else "") for p in varying]
        cells += [fmt(m["misclassified_pct"]), fmt(m["false_lit_pct"]), fmt(m["false_shadow_pct"]),
                  fmt(m["texels_per_pixel_median"]), fmt(m["texels_per_pixel_p05"]), fmt(m["utilization"], 4), fmt(m["flicker"]),
                  f"{gv.get('shadow', 0):.1f} / {gv.get('lit', 0):.1f}",
                  f"{gg.get('shadow', 0):.1f} / {gg.get('lit', 0):.1f}" if gg else "-", "yes" if same else "NO"]
        print("| " + " | ".join(str(c) for c in cells) + " |")


def main():
    out = sys.argv[1]
    table(load(out, "cascades-vs-single") + load(out, "basic"), ["technique", "cascades", "resolution"],
          "4 PSSM cascades vs one focused map of the same texel count (basic: the scene-fitted 2048^2 map)")
    table(load(out, "stabilize"), ["stabilize"], "Stabilization along the slow pan")
    table(load(out, "bias-const") + load(out, "bias-receiver-plane"), ["bias", "depth_bias", "slope_bias"],
          "Bias on grazing-light, 7x7 box PCF")
    table(load(out, "blend"), ["blend"], "Blend band (5x5 box PCF)")
    table(load(out, "filters"), ["filter", "kernel"], "Filters (5x5 kernels)")
    table(load(out, "splits"), ["split"], "Split schemes (4 cascades)")
    table(load(out, "layout"), ["select", "storage"], "Cascade selection and storage")
    table(load(out, "fit"), ["fit", "focus"], "Fit and focus")
    table(load(out, "failure-scenes"), ["technique"], "Default csm on the failure scenes")


if __name__ == "__main__":
    main()
