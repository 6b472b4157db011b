#!/usr/bin/python3
"""Tables and charts for docs/techniques.md, part III, from what techniques-iii.sh writes.

    techniques_iii_tables.py OUT_DIR > tables.md

Runs of the angle sweep are scenes named <scene>-gamma<DEG> (bench --light-gamma). For each scene
and metric a table has one row per technique variant and one column per gamma; the charts
OUT_DIR/gamma-<scene>-<metric>.png draw the same, one line per technique. Figures are the Vulkan
run's; a variant whose GL run differs in an accuracy metric is marked."""
import re
import sys
from pathlib import Path

from techniques_i_tables import fmt, load

METRICS = [("misclassified_pct", "misclassified %"), ("texels_per_pixel_median", "texels/px median"),
           ("texels_per_pixel_p05", "texels/px p05"), ("max_aliasing_error", "max aliasing error (px)"),
           ("storage_factor", "storage factor"), ("flicker", "flicker"), ("gpu_ms.total", "GPU ms total (Vulkan)")]


def metric(run, key):
    # No lit receiver in view (a light at the horizon facing the camera): nothing was judged, so
    # there is no density and no accuracy to report (misclassified would read 0 %), only a time.
    if not key.startswith("gpu_ms") and not run["metrics"].get("texels_per_pixel_median"):
        return None
    m = run["metrics"]
    for part in key.split("."):
        m = m.get(part) if isinstance(m, dict) else None
    return m


def variant(run):
    given = run.get("params_given") or {}
    text = run["technique"] + "".join(f" {k}={v}" for k, v in sorted(given.items()))
    return text


def sweep(rows):
    """{scene: {variant: {gamma: (vk, same)}}}"""
    out = {}
    for vk, gl, same in rows:
        m = re.match(r"(.*)-gamma([0-9.]+)$", vk["scene"])
        if not m:
            continue
        # A variant measured on one backend only has nothing to differ from.
        out.setdefault(m.group(1), {}).setdefault(variant(vk), {})[float(m.group(2))] = (vk, same or gl is None)
    return out


def tables(name, rows, title):
    data = sweep(rows)
    for scene, variants in data.items():
        gammas = sorted({g for v in variants.values() for g in v})
        for key, label in METRICS:
            print(f"\n**{title}: {scene}, {label} against gamma (degrees)**\n")
            print("| technique | " + " | ".join(f"{g:g}" for g in gammas) + " |")
            print("|---|" + "---|" * len(gammas))
            for v, by in variants.items():
                cells = []
                for g in gammas:
                    run, same = by.get(g, (None, True))
                    value = metric(run, key) if run else None
                    cells.append("-" if value is None else fmt(value) + ("" if same else " (GL differs)"))
                print(f"| {v} | " + " | ".join(cells) + " |")
    return data


def charts(out, data, prefix):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("\n(matplotlib missing: no charts)", file=sys.stderr)
        return
    for scene, variants in data.items():
        for key, label in METRICS:
            fig, ax = plt.subplots(figsize=(7, 4))
            for v, by in variants.items():
                gs = [g for g in sorted(by) if metric(by[g][0], key) is not None]
                ys = [metric(by[g][0], key) for g in gs]
                ax.plot(gs, ys, marker="o", label=v)
            ax.set_xlabel("gamma: angle between view and light direction (degrees)")
            ax.set_ylabel(label)
            if key in ("max_aliasing_error", "storage_factor", "texels_per_pixel_median", "texels_per_pixel_p05"):
                ax.set_yscale("log")
            ax.set_title(f"{scene}: {label}")
            ax.legend(fontsize=7)
            fig.tight_layout()
            fig.savefig(Path(out) / f"{prefix}-{scene}-{key.replace('.', '-')}.png", dpi=110)
            plt.close(fig)


def main():
    out = sys.argv[1]
    for name, title in (("sweep", "Equal memory (4 Mi texels)"), ("depth", "Depth in warped space against linear depth"),
                        ("bias", "Receiver-plane bias (box 3x3)"),
                        ("psm-slide", "PSM slide-back"), ("lispsm-n", "LiSPSM n scale"), ("tsm-focus", "TSM focus line")):
        path = Path(out) / f"{name}.json"
        if not path.exists():
            print(f"\n({name}.json missing)")
            continue
        data = tables(name, load(out, name), title)
        charts(out, data, "gamma" if name == "sweep" else f"gamma-{name}")


if __name__ == "__main__":
    main()
