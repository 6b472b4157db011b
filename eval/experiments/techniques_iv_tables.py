#!/usr/bin/python3
"""Markdown tables for docs/techniques.md ("Local lights") from the results techniques-iv.sh writes.

    techniques_iv_tables.py OUT_DIR > tables.md

The accuracy columns are the Vulkan run's; the script checks that the GL run of the same scene and
parameters gives the same values ("same on GL")."""
import json
import statistics
import sys
from pathlib import Path

# The same pairing of Vulkan and GL runs as part I (and its "same on GL" test over its accuracy metrics).
from techniques_i_tables import load


def table(rows, varying, title):
    print(f"\n**{title}**\n")
    head = ["scene"] + varying + ["judged light", "misclassified %", "false lit %", "false shadow %", "texels/px median", "p05",
                                  "memory MiB", "GPU ms Vulkan (shadow / lit)", "GPU ms GL (shadow / lit)", "same on GL"]
    print("| " + " | ".join(head) + " |")
    print("|" + "---|" * len(head))
    for vk, gl, same in rows:
        m = vk["metrics"]
        gv, gg = m["gpu_ms"], (gl["metrics"]["gpu_ms"] if gl else {})
        cells = [vk["scene"]] + [vk["params"].get(p, "") for p in varying]
        cells += [str(vk["checks"].get("judged_local_light", "sun")), f"{m['misclassified_pct']:.3f}", f"{m['false_lit_pct']:.3f}",
                  f"{m['false_shadow_pct']:.3f}", f"{m['texels_per_pixel_median']:.2f}", f"{m['texels_per_pixel_p05']:.2f}",
                  f"{m['shadow_memory_bytes'] / 2**20:.1f}", f"{gv.get('shadow', 0):.1f} / {gv.get('lit', 0):.1f}",
                  f"{gg.get('shadow', 0):.1f} / {gg.get('lit', 0):.1f}" if gg else "-", "yes" if same else "NO"]
        print("| " + " | ".join(cells) + " |")


def variant(r):
    """A run's technique and the parameters that tell it apart in these experiments."""
    p = r["params"]
    name = r["technique"]
    for k in ("storage", "filter", "kernel", "depth", "faces_pass", "cull_faces", "resolution_from", "max_lights", "guard"):
        if k in r.get("params_given", {}) or (k == "filter" and k in p):
            if k == "kernel" and p.get("filter") == "hw2x2":
                continue
            name += f" {k}={p[k]}"
    return name


def omni_table(rows):
    print("\n**The omni techniques side by side (slow pan)**\n")
    head = ["scene", "technique", "misclassified %", "false lit %", "false shadow %", "seam band misclassified % (pixels)",
            "elsewhere %", "texels/px median", "memory MiB", "faces drawn", "shadow triangles", "same on GL"]
    print("| " + " | ".join(head) + " |")
    print("|" + "---|" * len(head))
    for vk, gl, same in sorted(rows, key=lambda r: (r[0]["scene"], variant(r[0]))):
        m = vk["metrics"]
        seam, c = m.get("seam_misclassified_pct"), vk["checks"]
        cells = [vk["scene"], variant(vk), f"{m['misclassified_pct']:.3f}", f"{m['false_lit_pct']:.3f}", f"{m['false_shadow_pct']:.3f}",
                 f"{seam:.3f} ({c.get('seam_pixels', 0)})" if seam is not None else "-",
                 f"{m['off_seam_misclassified_pct']:.3f}" if "off_seam_misclassified_pct" in m else "-",
                 f"{m['texels_per_pixel_median']:.2f}", f"{m['shadow_memory_bytes'] / 2**20:.1f}", str(m.get("shadow_layers_rendered", "-")),
                 f"{m['shadow_triangles']:,}", "yes" if same else "NO"]
        print("| " + " | ".join(cells) + " |")


def timing_table(out, prefix, title, passes):
    """Median over the repetitions (files prefix-1.json, prefix-2.json, ...) of each pass's GPU ms."""
    files = sorted(Path(out).glob(f"{prefix}-*.json"))
    if not files:
        return
    times = {}
    for f in files:
        for r in json.loads(f.read_text())["runs"]:
            for ps in passes:
                times.setdefault((r["scene"], variant(r), r["backend"], ps), []).append(r["metrics"]["gpu_ms"].get(ps, 0.0))
    print(f"\n**{title}** (median of {len(files)} repetitions, GPU ms)\n")
    head = ["scene", "technique"] + [f"{ps} {b}" for ps in passes for b in ("Vulkan", "GL")]
    print("| " + " | ".join(head) + " |")
    print("|" + "---|" * len(head))
    keys = sorted({(k[0], k[1]) for k in times})
    for scene, v in keys:
        cells = [scene, v]
        for ps in passes:
            for b in ("vulkan", "gl"):
                t = times.get((scene, v, b, ps))
                cells.append(f"{statistics.median(t):.1f}" if t else "-")
        print("| " + " | ".join(cells) + " |")


def counts_table(rows, title):
    print(f"\n**{title}**\n")
    head = ["scene", "technique", "misclassified %", "memory MiB", "faces drawn", "shadow triangles", "GPU ms Vulkan (shadow / lit)",
            "GPU ms GL (shadow / lit)", "same on GL"]
    print("| " + " | ".join(head) + " |")
    print("|" + "---|" * len(head))
    for vk, gl, same in sorted(rows, key=lambda r: variant(r[0])):
        m = vk["metrics"]
        gv, gg = m["gpu_ms"], (gl["metrics"]["gpu_ms"] if gl else {})
        cells = [vk["scene"], variant(vk), f"{m['misclassified_pct']:.3f}", f"{m['shadow_memory_bytes'] / 2**20:.1f}",
                 str(m.get("shadow_layers_rendered", "-")), f"{m['shadow_triangles']:,}", f"{gv.get('shadow', 0):.1f} / {gv.get('lit', 0):.1f}",
                 f"{gg.get('shadow', 0):.1f} / {gg.get('lit', 0):.1f}" if gg else "-", "yes" if same else "NO"]
        print("| " + " | ".join(cells) + " |")


def main():
    out = sys.argv[1]

    def have(name):
        return (Path(out) / f"{name}.json").exists()

    if have("cube-storage"):
        rows = sorted(load(out, "cube-storage"), key=lambda r: (r[0]["params"]["light"], r[0]["params"]["storage"], int(r[0]["params"]["resolution"])))
        table(rows, ["light", "storage", "resolution"], "cube: depth vs radial storage, face resolution, per point light (point-light-room, walk)")
    if have("cube-seam"):
        rows = sorted(load(out, "cube-seam"), key=lambda r: (r[0]["params"]["storage"], int(r[0]["params"]["resolution"])))
        table(rows, ["storage", "resolution"], "cube on cube-seam: every shadow crosses a face edge (static camera)")
    if have("omni"):
        omni_table(load(out, "omni"))
    timing_table(out, "king", "King's claim: filtering cost, cube against vsdct", ["lit"])
    if have("paraboloid"):
        counts_table(load(out, "paraboloid"), "paraboloid on coarse and fine geometry")
    if have("street-culling"):
        counts_table(load(out, "street-culling"), "street: per-face culling and screen-sized resolution (lights=all)")
    if have("street-lights"):
        counts_table(load(out, "street-lights"), "street: cost against the number of shadowed lights")
    timing_table(out, "faces-pass", "The six faces: six passes against one (SV_RenderTargetArrayIndex from the vertex shader)", ["shadow"])


if __name__ == "__main__":
    main()
