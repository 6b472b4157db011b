#!/usr/bin/python3
"""Markdown tables for docs/soft-shadows.md from the results techniques-v.sh writes.

    techniques_v_tables.py OUT_DIR > tables.md

Times are medians over the timed frames (the bench's gpu_ms), per backend. Fractions are the
counted run's (hpsm_decisions, last frame); "same on GL" checks that GL counted the same."""
import json
import sys
from pathlib import Path

import numpy as np
from PIL import Image

BACKENDS = ("vulkan", "gl")
UMBRA_LEAK = 0.1  # eval::kUmbraLeakThreshold


def runs(out, name):
    p = Path(out) / f"{name}.json"
    return json.loads(p.read_text())["runs"] if p.exists() else []


def refused(out, name):
    p = Path(out) / f"{name}.refused"
    if not p.exists():
        return None
    # The error line only (a refusal may follow a warning).
    lines = [ln for ln in p.read_text().splitlines() if "error:" in ln] or p.read_text().splitlines()
    return " ".join(lines).split("error: ", 1)[-1].replace("|", "/")


def row(cells):
    print("| " + " | ".join(str(c) for c in cells) + " |")


def header(cells):
    row(cells)
    print("|" + "---|" * len(cells))


def fmt_fracs(d):
    return f"{100 * d['minmax']:.1f} / {100 * d['plane']:.1f} / {100 * d['filtered']:.1f}" if d else "-"


def filter_label(r):
    p = r["params"]
    f = p.get("filter", "hw2x2")
    if f == "pcss":
        mk = p.get("pcss_max_kernel", "15")
        return f"pcss {p.get('light_size')} deg" + ("" if mk == "15" else f" max kernel {mk}")
    return f if f == "hw2x2" else f"{f} {p.get('kernel')}"


def collect(out, prefix):
    """(technique, filter, scene, accel) -> backend -> run, over OUT/prefix-*.json."""
    groups = {}
    for f in sorted(Path(out).glob(f"{prefix}-*.json")):
        for r in json.loads(f.read_text())["runs"]:
            key = (r["technique"], filter_label(r), r["scene"], r["params"].get("accel", "none"))
            groups.setdefault(key, {})[r["backend"]] = r
    return groups


def refusals(out):
    return {f.stem: refused(out, f.stem) for f in sorted(Path(out).glob("speed-*.refused"))}


ACCELS = ("none", "minmax", "hpsm")


def order(key):
    t, f, scene, a = key
    return (t, f.split()[0], float(f.split()[1]), scene, ACCELS.index(a))


def speed_tables(out):
    timed, counted = collect(out, "speed"), collect(out, "frac")
    if not timed:
        return
    print("\n**Lit-pass time against filter width, with and without a secondary map** (GPU ms, median "
          "over frames, hpsm_counters=0; build = the secondary map's pass; fractions min/max / plane / "
          "filtered % from a separate counted frame)\n")
    header(["technique", "filter", "scene", "accel", "lit Vulkan", "lit GL", "build Vulkan", "build GL",
            "min/max / plane / filtered %", "same on GL"])
    g = lambda r, ps: f"{r['metrics']['gpu_ms'][ps]:.1f}" if r and ps in r["metrics"]["gpu_ms"] else "-"
    for key in sorted(timed, key=order):
        vk, gl = timed[key].get("vulkan"), timed[key].get("gl")
        c = counted.get(key, {})
        fv = c.get("vulkan", {}).get("metrics", {}).get("hpsm_decisions")
        fg = c.get("gl", {}).get("metrics", {}).get("hpsm_decisions")
        fr = fmt_fracs(fv) if key[3] != "none" else "(all filtered)"
        same = ("yes" if fv == fg else "NO") if key[3] != "none" else ""
        row(list(key) + [g(vk, "lit"), g(gl, "lit"), g(vk, "hpsm"), g(gl, "hpsm"), fr, same])
    for name, why in refusals(out).items():
        row([name[len("speed-"):], "", "all", "", "refused: " + why, "", "", "", "", ""])


def png(path):
    return np.asarray(Image.open(path).convert("RGB"), dtype=np.int16)


def accuracy_table(out):
    """Acceleration's pixels against the plain filter's: the first frame's colour pictures, and
    the whole path's metrics (which would differ if any frame's visibility did)."""
    timed = collect(out, "speed")
    if not timed:
        return
    print("\n**Does acceleration change the picture?** (first frame's colour image against accel=none; "
          "misclassified % and MAE over all frames)\n")
    header(["technique", "filter", "scene", "backend", "minmax: differing px", "hpsm: differing px", "max diff (of 255)",
            "metrics equal"])
    for key in sorted(timed, key=order):
        if key[3] != "none":
            continue
        for backend, r0 in sorted(timed[key].items()):
            cells, maxd, same = [], 0, True
            for a in ("minmax", "hpsm"):
                r1 = timed.get(key[:3] + (a,), {}).get(backend)
                if not r1:
                    cells.append("refused")
                    continue
                d = np.abs(png(Path(out) / r0["images"]["color"]) - png(Path(out) / r1["images"]["color"])).max(axis=2)
                cells.append(f"{int((d > 0).sum())} of {d.size}")
                maxd = max(maxd, int(d.max()))
                m0, m1 = r0["metrics"], r1["metrics"]
                same = same and all(m0[k] == m1[k] for k in ("misclassified_pct", "mean_abs_error", "false_lit_pct", "false_shadow_pct"))
            if cells != ["refused", "refused"]:
                row(list(key[:3]) + [backend] + cells + [maxd, "yes" if same else "NO"])


def lowsun_table(out):
    rs = runs(out, "lowsun") + runs(out, "lowsun-gamma")
    if not rs:
        return
    print("\n**Flat receivers under low suns: planes against min/max** (one counted frame, basic)\n")
    header(["scene", "filter", "accel", "min/max / plane / filtered % (Vulkan)", "same on GL", "lit ms Vulkan", "build ms Vulkan"])
    groups = {}
    for r in rs:
        groups.setdefault((r["scene"], filter_label(r), r["params"]["accel"]), {})[r["backend"]] = r
    for key, b in sorted(groups.items(), key=lambda kv: [str(x) for x in kv[0]]):
        vk, gl = b.get("vulkan"), b.get("gl")
        fv = vk["metrics"].get("hpsm_decisions") if vk else None
        fg = gl["metrics"].get("hpsm_decisions") if gl else None
        gm = vk["metrics"]["gpu_ms"] if vk else {}
        row(list(key) + [fmt_fracs(fv), "yes" if fv == fg else "NO", f"{gm.get('lit', 0):.1f}", f"{gm.get('hpsm', 0):.1f}"])


def sweep_table(out, name, param, title):
    rs = runs(out, name) + runs(out, name + "-minmax")
    if not rs:
        return
    print(f"\n**{title}** (default scene, basic box 7, counters on; GPU ms median over frames)\n")
    header(["accel", param, "min/max / plane / filtered % (Vulkan)", "same on GL", "lit Vulkan", "lit GL", "build Vulkan", "build GL"])
    groups = {}
    for r in rs:
        groups.setdefault((r["params"]["accel"], r["params"][param]), {})[r["backend"]] = r
    for key, b in sorted(groups.items(), key=lambda kv: (kv[0][0], float(kv[0][1]))):
        vk, gl = b.get("vulkan"), b.get("gl")
        fv, fg = (x["metrics"].get("hpsm_decisions") if x else None for x in (vk, gl))
        g = lambda r, ps: f"{r['metrics']['gpu_ms'].get(ps, 0):.1f}" if r else "-"
        row(list(key) + [fmt_fracs(fv), "yes" if fv == fg else "NO", g(vk, "lit"), g(gl, "lit"), g(vk, "hpsm"), g(gl, "hpsm")])


def pcss_table(out):
    names = sorted(f.stem for f in Path(out).glob("pcss-*.json")) + sorted(f.stem for f in Path(out).glob("pcss-*.refused"))
    if not names:
        return
    print("\n**PCSS against the area-light reference** (256 reference rays per pixel; MAE = mean |visibility - "
          "reference| over receiving pixels; penumbra MAE = the same over the pixels whose reference is strictly "
          "between 0 and 1, with their count; accuracy columns Vulkan, checked on GL)\n")
    header(["sun (deg)", "scene", "technique", "bias", "filter", "MAE", "penumbra MAE (pixels)", "misclassified %", "false lit %",
            "false shadow %", "lit ms Vulkan / GL", "MAE on GL"])
    for name in names:
        why = refused(out, name)
        if why:
            row([name, "all", "", "", "", "refused: " + why] + [""] * 6)
            continue
        groups = {}
        for r in runs(out, name):
            groups.setdefault((r["scene"], r["technique"], json.dumps(r["params"], sort_keys=True)), {})[r["backend"]] = r
        for key, b in sorted(groups.items()):
            vk, gl = b.get("vulkan"), b.get("gl")
            r = vk or gl
            m = r["metrics"]
            bias = r["params"].get("bias", "slope " + r["params"].get("slope_bias", ""))
            pen = f"{m['penumbra_mean_abs_error']:.4f} ({m['penumbra_pixels']})" if "penumbra_pixels" in m else "-"
            row([f"{r['checks'].get('light_size', 0):.2f}", key[0], key[1], bias, filter_label(r), f"{m['mean_abs_error']:.4f}", pen,
                 f"{m['misclassified_pct']:.3f}", f"{m['false_lit_pct']:.3f}", f"{m['false_shadow_pct']:.3f}",
                 f"{m['gpu_ms'].get('lit', 0):.1f} / {gl['metrics']['gpu_ms'].get('lit', 0):.1f}" if gl else "-",
                 f"{gl['metrics']['mean_abs_error']:.4f}" if gl else "-"])


def regions_table(out):
    """Part 5c: per region of the plank scenes, the same pixels in stacked-planks and single-plank."""
    rs = runs(out, "planks-regions-sun3")
    why = refused(out, "planks-regions-sun3")
    if why:
        print(f"\n**Plank regions**: refused: {why}")
    if not rs:
        return
    groups = {}
    for r in rs:
        label = filter_label(r) + ("" if r["params"].get("pcss_search", "6") == "6" else f" search {r['params']['pcss_search']}")
        groups.setdefault(label, {}).setdefault(r["scene"], {})[r["backend"]] = r
    for region in ("under-high-penumbra", "beside-high-penumbra", "far"):
        print(f"\n**Region `{region}`** (csm receiver-plane; Vulkan; single-plank -> stacked-planks on the same pixels; "
              f"leak = fraction of the reference's umbra pixels above {UMBRA_LEAK}; GL column: every number equal on GL)\n")
        header(["filter", "pixels", "penumbra MAE (pixels)", "umbra pixels", "umbra leak", "umbra mean visibility", "MAE",
                "same on GL"])
        for label in sorted(groups, key=lambda l: (l.startswith("pcss"), l)):
            cells, same = [], True
            for scene in ("single-plank", "stacked-planks"):
                b = groups[label].get(scene, {})
                vk, gl = b.get("vulkan"), b.get("gl")
                reg = vk["metrics"].get("regions", {}).get(region) if vk else None
                same = same and gl is not None and reg == gl["metrics"].get("regions", {}).get(region)
                cells.append(reg)
            if None in cells:
                row([label] + ["-"] * 7)
                continue
            s, t = cells
            two = lambda k, f: f"{s[k]:{f}} -> {t[k]:{f}}"
            row([label, two("pixels", "d"), f"{s['penumbra_mean_abs_error']:.4f} ({s['penumbra_pixels']}) -> "
                 f"{t['penumbra_mean_abs_error']:.4f} ({t['penumbra_pixels']})", two("umbra_pixels", "d"),
                 two("umbra_leak_fraction", ".4f"), two("umbra_mean_visibility", ".4f"), two("mean_abs_error", ".4f"),
                 "yes" if same else "NO"])


def biased_table(out):
    """Part 1 again with a slope bias large enough for the kernel, in one counted run."""
    rs = runs(out, "biased")
    if not rs:
        return
    print("\n**With enough bias for the kernel** (basic, slope_bias raised with the kernel; counters on; "
          "MAE against the hard reference, all frames)\n")
    header(["scene", "filter", "slope_bias", "accel", "min/max / plane / filtered % (Vulkan)", "same on GL", "MAE",
            "lit Vulkan", "lit GL", "build Vulkan", "build GL"])
    groups = {}
    for r in rs:
        groups.setdefault((r["scene"], filter_label(r), r["params"]["slope_bias"], r["params"]["accel"]), {})[r["backend"]] = r
    g = lambda r, ps: f"{r['metrics']['gpu_ms'].get(ps, 0):.1f}" if r else "-"
    for key in sorted(groups, key=lambda k: (k[0], float(k[1].split()[1]), ACCELS.index(k[3]))):
        vk, gl = groups[key].get("vulkan"), groups[key].get("gl")
        fv, fg = (x["metrics"].get("hpsm_decisions") if x else None for x in (vk, gl))
        fr = fmt_fracs(fv) if key[3] != "none" else "(all filtered)"
        row(list(key) + [fr, "yes" if fv == fg else "NO", f"{vk['metrics']['mean_abs_error']:.4f}", g(vk, "lit"), g(gl, "lit"),
                         g(vk, "hpsm"), g(gl, "hpsm")])


def main():
    out = sys.argv[1]
    speed_tables(out)
    accuracy_table(out)
    biased_table(out)
    lowsun_table(out)
    sweep_table(out, "sweep-eps", "hpsm_eps", "hpsm_eps sweep")
    sweep_table(out, "sweep-block", "hpsm_block", "hpsm_block sweep")
    pcss_table(out)
    regions_table(out)


if __name__ == "__main__":
    main()
