#!/usr/bin/python3
"""Markdown tables for docs/techniques.md ("Local lights") from the results techniques-iv.sh writes.

    techniques_iv_tables.py OUT_DIR > tables.md

The accuracy columns are the Vulkan run's; the script checks that the GL run of the same scene and
parameters gives the same values ("same on GL")."""
import sys

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


def main():
    out = sys.argv[1]
    rows = sorted(load(out, "cube-storage"), key=lambda r: (r[0]["params"]["light"], r[0]["params"]["storage"], int(r[0]["params"]["resolution"])))
    table(rows, ["light", "storage", "resolution"], "cube: depth vs radial storage, face resolution, per point light (point-light-room, walk)")
    rows = sorted(load(out, "cube-seam"), key=lambda r: (r[0]["params"]["storage"], int(r[0]["params"]["resolution"])))
    table(rows, ["storage", "resolution"], "cube on cube-seam: every shadow crosses a face edge (static camera)")


if __name__ == "__main__":
    main()
