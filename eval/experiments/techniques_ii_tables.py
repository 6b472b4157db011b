#!/usr/bin/python3
"""Markdown tables for docs/techniques.md, part II, from what techniques-ii.sh writes.

    techniques_ii_tables.py OUT_DIR > tables.md
"""
import json
import sys
from pathlib import Path

from techniques_i_tables import ACCURACY, fmt, load


def gpu_cell(run, passes):
    g = run["metrics"]["gpu_ms"] if run else {}
    return " / ".join(f"{g[p]:.1f}" if p in g else "-" for p in passes) if run else "-"


def table(rows, varying, title, extra=()):
    print(f"\n**{title}**\n")
    passes = []
    for vk, gl, _ in rows:
        for p in vk["metrics"]["gpu_ms"]:
            if p not in passes and p != "total":
                passes.append(p)
    passes.append("total")
    head = ["scene", "technique"] + varying + ["misclassified %", "false lit %", "false shadow %", "texels/px median", "p05",
                                              "utilization", "flicker", "shadow triangles"] + list(extra)
    head += [f"GPU ms Vulkan ({' / '.join(passes)})", "GPU ms GL", "same on GL"]
    print("| " + " | ".join(head) + " |")
    print("|" + "---|" * len(head))
    for vk, gl, same in rows:
        m = vk["metrics"]
        cells = [vk["scene"], vk["technique"]] + [vk["params"].get(p, "") for p in varying]
        cells += [fmt(m["misclassified_pct"]), fmt(m["false_lit_pct"]), fmt(m["false_shadow_pct"]), fmt(m["texels_per_pixel_median"]),
                  fmt(m["texels_per_pixel_p05"]), fmt(m["utilization"], 4), fmt(m["flicker"]), fmt(m["shadow_triangles"])]
        cells += [e(vk) for e in extra.values()] if isinstance(extra, dict) else []
        cells += [gpu_cell(vk, passes), gpu_cell(gl, passes), "yes" if same else "NO"]
        print("| " + " | ".join(str(c) for c in cells) + " |")


def growth(out):
    print("\n**Cost growth with scene size (terrain-city, `--triangles N`, 4 frames): GPU ms per frame (all passes), Vulkan / GL**\n")
    print("| triangles | csm | sdsm cull=conservative | sdsm cull=readback | sdsm cull=gpu | shadow triangles csm / conservative / readback / gpu |")
    print("|---|---|---|---|---|---|")
    for t in (10000, 100000, 1000000, 2500000):
        csm = load(out, f"growth-csm-{t}")
        sdsm = {r[0]["params"]["cull"]: r for r in load(out, f"growth-sdsm-{t}")}
        runs = [csm[0]] + [sdsm[c] for c in ("conservative", "readback", "gpu")]
        total = lambda r: f"{r[0]['metrics']['gpu_ms']['total']:.0f} / {r[1]['metrics']['gpu_ms']['total']:.0f}" if r[1] else "-"
        tris = " / ".join(fmt(r[0]["metrics"]["shadow_triangles"]) for r in runs)
        print(f"| {fmt(runs[0][0]['scene_triangles'])} | " + " | ".join(total(r) for r in runs) + f" | {tris} |")


def main():
    out = sys.argv[1]
    table(load(out, "pssm") + load(out, "sdsm"), ["lambda", "partition", "tight"],
          "SDSM (log, 4 partitions of 1024^2, cull=gpu) against PSSM (4 cascades of 1024^2) over lambda")
    table(load(out, "sdsm-cull"), ["cull"], "SDSM culling modes")
    table(load(out, "sdsm-quantize"), ["quantize"], "SDSM temporal quantization (slow pan)")
    growth(out)
    table(load(out, "partitions"), ["partition"], "Partition schemes")
    table(load(out, "bleeding") + load(out, "bleeding-sdsm"), ["filter"],
          "Light bleeding on overlapping-occluders (blur 0.04 world units, default light-bleeding reduction)")
    table(load(out, "bleeding-raw"), ["filter", "bleed"], "Light bleeding without reduction (bleed=0)")
    table(load(out, "msaa"), ["filter", "msaa"], "MSAA shadow rendering for moment maps")


if __name__ == "__main__":
    main()
