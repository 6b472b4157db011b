#!/usr/bin/python3
"""Markdown tables for docs/techniques.md (adaptive shadow maps) from the results asm.sh writes.

    asm_tables.py OUT_DIR > tables.md

Times are medians over the timed frames after warm-up (the bench's gpu_ms), per backend; the
refinement counters and accuracy are Vulkan's, with "GL same" saying whether GL's were identical."""
import json
import sys

from techniques_v_tables import header, row, runs

BACKENDS = ("vulkan", "gl")


def label(r):
    p = r["params"]
    if r["technique"] != "asm":
        extra = {"basic": f"{p.get('resolution')}^2", "csm": f"{p.get('cascades')} x {p.get('resolution')}^2",
                 "sdsm": f"{p.get('cascades')} x {p.get('resolution')}^2"}.get(r["technique"], "")
        return f"{r['technique']} {extra}".strip()
    return f"asm {p.get('allocation')}, mark={p.get('mark')}"


def pair(rs):
    """(label, extra key) -> {backend: run}."""
    groups = {}
    for r in rs:
        key = (label(r), json.dumps(r["params"], sort_keys=True))
        groups.setdefault(key, {})[r["backend"]] = r
    return groups


def ms(r, p):
    return r["metrics"]["gpu_ms"].get(p)


def fmt(v, digits=1):
    return "-" if v is None else f"{v:.{digits}f}"


def same_on_gl(b):
    if "vulkan" not in b or "gl" not in b:
        return "-"
    keys = ("misclassified_pct", "texels_per_pixel_median", "asm_refinement")
    return "yes" if all(b["vulkan"]["metrics"].get(k) == b["gl"]["metrics"].get(k) for k in keys) else "no"


def finest(r):
    levels = r["metrics"].get("asm_refinement", {}).get("pages_by_level", [])
    return max((i for i, n in enumerate(levels) if n), default=-1)


def equal_memory(out):
    for name, view in (("equal-default", "default scene, slow pan"), ("equal-close", "default scene, close-up A")):
        rs = runs(out, name)
        if not rs:
            continue
        print(f"\n**Equal memory, {view}** ({rs[0]['size'][0]}x{rs[0]['size'][1]}, {rs[0]['frames']} frames)\n")
        header(["technique", "misclassified %", "texels/px median", "memory MiB", "shadow ms vk / gl", "lit ms vk / gl",
                "total ms vk / gl", "finest level", "GL same"])
        for (lab, _), b in pair(rs).items():
            v = b.get("vulkan") or b.get("gl")
            m = v["metrics"]
            row([lab, fmt(m["misclassified_pct"], 3), fmt(m["texels_per_pixel_median"], 2), fmt(m["shadow_memory_bytes"] / 2**20, 1),
                 " / ".join(fmt(ms(b[k], "shadow")) if k in b else "-" for k in BACKENDS),
                 " / ".join(fmt(ms(b[k], "lit")) if k in b else "-" for k in BACKENDS),
                 " / ".join(fmt(ms(b[k], "total")) if k in b else "-" for k in BACKENDS),
                 finest(v) if v["technique"] == "asm" else "-", same_on_gl(b)])


def resolution(out):
    rs = runs(out, "resolution")
    if not rs:
        return
    base = {r["backend"]: ms(r, "lit") for r in runs(out, "resolution-basic")}
    print(f"\n**Effective resolution and the paper's figures, close-up A** ({rs[0]['size'][0]}x{rs[0]['size'][1]}, "
          f"{rs[0]['frames']} frames; lit pass against basic 2048^2's: the paper's 73-91 %)\n")
    header(["mode", "effective", "finest level (texels)", "resident pages", "memory MiB", "lit vs basic vk / gl",
            "analysis ms vk", "readback / allocation ms vk", "pages ms vk", "misclassified %", "GL same"])
    for (lab, _), b in pair([r for r in rs if r["technique"] == "asm"]).items():
        v = b["vulkan"]
        m, p = v["metrics"], v["params"]
        f = finest(v)
        page = int(p["page_size"])
        step = ms(v, "readback") if p["allocation"] == "readback" else ms(v, "allocation")
        lit = " / ".join(f"{100 * ms(b[k], 'lit') / base[k]:.0f} %" if k in b and base.get(k) else "-" for k in BACKENDS)
        row([p["allocation"], p["effective_resolution"], f"{f} ({page << f})", sum(m["asm_refinement"]["pages_by_level"]),
             fmt(m["shadow_memory_bytes"] / 2**20, 1), lit, fmt(ms(v, "analysis")), fmt(step, 2), fmt(ms(v, "pages")),
             fmt(m["misclassified_pct"], 3), same_on_gl(b)])


def steps(out):
    rs = runs(out, "compaction")
    if not rs:
        return
    print(f"\n**Each refinement step, sun turning (every frame refines from the resident levels), mark=visible, one iteration** "
          f"({rs[0]['size'][0]}x{rs[0]['size'][1]}, {rs[0]['frames']} frames; GPU ms, medians)\n")
    header(["mode", "compaction", "backend", "view + marking", "compaction pass", "readback", "allocation", "pages", "shadow (all)",
            "requests per frame", "pages per frame"])
    for r in rs:
        p, m = r["params"], r["metrics"]
        frames = m["asm_refinement"]["frames"]
        req = sorted(f["requests"] for f in frames)[len(frames) // 2]
        pages = sorted(f["pages_rendered"] for f in frames)[len(frames) // 2]
        # The timer's "analysis" pass holds the compaction pass (compaction=prefix runs inside it).
        view = ms(r, "analysis") - (ms(r, "compaction") or 0.0)
        row([p["allocation"], p["compaction"], r["backend"], fmt(view), fmt(ms(r, "compaction"), 2), fmt(ms(r, "readback"), 2),
             fmt(ms(r, "allocation"), 2), fmt(ms(r, "pages")), fmt(ms(r, "shadow")), req, pages])


def stability(out):
    for name, what in (("cut", "camera cut A -> B halfway"), ("pan", "fast pan, 90 degrees over the path"),
                       ("sun", "sun turning 20 degrees over the path"), ("small-pool", "fast pan, mark=visible, 64-texel pages: a pool of 6^2 or 16^2 pages, 3 resident levels"),
                       ("clipmap", "fast pan, mark=visible, 64-texel pages, clipmap of 0 (off), 4 or 8 pages per level")):
        rs = runs(out, name)
        if not rs:
            continue
        frames = rs[0]["frames"]
        print(f"\n**{what.capitalize()}** ({rs[0]['size'][0]}x{rs[0]['size'][1]}, {frames} frames)\n")
        header(["mode", "iterations", "pool", "clipmap", "pages rendered per frame", "unserved", "frames to converge after the cut" if name == "cut" else "frames converged",
                "misclassified % mean / max", "total ms vk / gl", "GL same"])
        for (lab, _), b in pair(rs).items():
            v = b["vulkan"]
            m, p = v["metrics"], v["params"]
            per = [f["pages_rendered"] for f in m["asm_refinement"]["frames"]]
            if name == "cut":
                after = per[frames // 2:]
                conv = next((i for i, n in enumerate(after) if n == 0), None)
                conv = "not within the path" if conv is None else str(conv)
            else:
                conv = f"{sum(1 for n in per if n == 0)} of {frames}"
            mis = v["series"]["misclassified_pct"]
            row([p["allocation"], p["iterations"], f"{p['pool_pages']}^2", p.get("clipmap", "0"), " ".join(map(str, per)), m["asm_refinement"]["unserved_total"], conv,
                 f"{sum(mis) / len(mis):.3f} / {max(mis):.3f}", " / ".join(fmt(ms(b[k], "total")) if k in b else "-" for k in BACKENDS),
                 same_on_gl(b)])


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "out/asm"
    equal_memory(out)
    resolution(out)
    steps(out)
    stability(out)


if __name__ == "__main__":
    main()
