#!/usr/bin/env python3
"""The page of `shadowport advise`: the Pareto front as a chart, the recommendation's pictures beside
the closest cheaper configuration that misses the budget, and every configuration measured.

usage: advise_report.py advise.json --out dir
"""
import argparse
import html
import json
import os
import shutil
import sys

os.environ.setdefault("MPLCONFIGDIR", os.path.join(os.environ.get("TMPDIR", "/tmp"), "shadowport-mpl"))
import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

COST_LABEL = {"ms": "GPU ms per frame (median)", "memory": "shadow memory (MiB)"}
ERROR_LABEL = {
    "misclassified": "misclassified pixels (%)",
    "false_lit": "false lit pixels (%)",
    "false_shadow": "false shadow pixels (%)",
    "mean_abs_error": "mean |visibility - reference|",
    "flicker": "flicker (mean change of the shadow term)",
    "ms": "GPU ms per frame (median)",
    "memory": "shadow memory (MiB)",
}


def chart(doc, path):
    cost = doc["minimize"]
    err = doc["budgets"][0]["metric"]
    limit = doc["budgets"][0]["limit"]
    confs = doc["configurations"]
    fig, ax = plt.subplots(figsize=(8, 5), dpi=100)
    techniques = sorted({c["technique"] for c in confs})
    for t in techniques:
        xs = [c["metrics"][cost] for c in confs if c["technique"] == t]
        ys = [c["metrics"][err] for c in confs if c["technique"] == t]
        ax.scatter(xs, ys, s=18, alpha=0.6, label=t)
    front = [confs[i] for i in doc["front"]]
    ax.plot([c["metrics"][cost] for c in front], [c["metrics"][err] for c in front], "k-", lw=1, label="Pareto front")
    ax.axhline(limit, color="red", ls="--", lw=1, label=f"budget {err} <= {limit:g}")
    if doc.get("recommendation") is not None:
        r = confs[doc["recommendation"]]
        ax.scatter([r["metrics"][cost]], [r["metrics"][err]], s=160, facecolors="none", edgecolors="green", lw=2,
                   label="recommendation: " + r["config"])
    if doc.get("cheaper_miss") is not None:
        r = confs[doc["cheaper_miss"]]
        ax.scatter([r["metrics"][cost]], [r["metrics"][err]], s=160, facecolors="none", edgecolors="orange", lw=2,
                   label="cheaper, misses: " + r["config"])
    # A few broken configurations (bias=const acne: 40 % misclassified) would flatten everything
    # near the budget into one line; they are left above the chart and counted.
    errors = [c["metrics"][err] for c in confs]
    top = max([4 * limit] + [c["metrics"][err] for c in front if c["metrics"][err] <= 8 * max(limit, 1e-9)]) * 1.1
    above = sum(1 for e in errors if e > top)
    if above and top > 0:
        ax.set_ylim(bottom=min(0, min(errors)), top=top)
        ax.text(0.01, 0.98, f"{above} configuration(s) above {top:.3g}, off the chart", transform=ax.transAxes,
                va="top", fontsize=8)
    ax.set_xlabel(COST_LABEL[cost])
    ax.set_ylabel(ERROR_LABEL[err])
    w, h = doc["size"]
    ax.set_title(f"{doc['scene']}: {len(confs)} configurations, {doc['backend']} {w}x{h}, {doc['frames']} frames")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def copy_images(conf, src_dir, out_dir, tag):
    """Copies a configuration's pictures next to the page; returns kind -> relative path."""
    out = {}
    for kind, rel in sorted(conf.get("images", {}).items()):
        src = os.path.normpath(os.path.join(src_dir, rel))
        if not os.path.exists(src):
            continue
        dst = os.path.join("images", f"{tag}-{kind}.png")
        os.makedirs(os.path.join(out_dir, "images"), exist_ok=True)
        shutil.copyfile(src, os.path.join(out_dir, dst))
        out[kind] = dst
    return out


def row(c, mark=""):
    m = c["metrics"]
    return (f"<tr><td>{html.escape(mark)}</td><td><code>{html.escape(c['config'])}</code></td><td>{m['ms']:.1f}</td>"
            f"<td>{m['memory']:.1f}</td><td>{m['misclassified']:.3f}</td><td>{m['false_lit']:.3f}</td>"
            f"<td>{m['false_shadow']:.3f}</td><td>{m['flicker']:.2g}</td><td>{'yes' if c['meets'] else 'no'}</td></tr>")


HEAD = ("<tr><th></th><th>configuration</th><th>GPU ms</th><th>memory MiB</th><th>misclassified %</th>"
        "<th>false lit %</th><th>false shadow %</th><th>flicker</th><th>meets budget</th></tr>")


def main(argv):
    ap = argparse.ArgumentParser()
    ap.add_argument("advise_json")
    ap.add_argument("--out", required=True)
    a = ap.parse_args(argv)
    with open(a.advise_json) as f:
        doc = json.load(f)
    src_dir = os.path.dirname(os.path.abspath(a.advise_json))
    os.makedirs(a.out, exist_ok=True)
    chart(doc, os.path.join(a.out, "front.png"))
    confs = doc["configurations"]
    budgets = ", ".join(f"{b['metric']} &lt;= {b['limit']:g}" for b in doc["budgets"])
    w, h = doc["size"]
    p = [f"<!doctype html><html><head><meta charset='utf-8'><title>advise: {html.escape(doc['scene'])}</title>",
         "<style>body{font-family:sans-serif;margin:2em}table{border-collapse:collapse}td,th{border:1px solid #ccc;"
         "padding:2px 6px}img{image-rendering:pixelated;width:480px;margin:2px}</style></head><body>",
         f"<h1>advise: {html.escape(doc['scene'])}</h1>",
         f"<p>{doc['backend']}, {w}x{h}, {doc['frames']} frames; budget {budgets}; minimizing {doc['minimize']}"
         f" (GPU ms within {doc['noise'] * 100:.0f} % are ties, less memory wins); {len(confs)} configurations"
         f" ({doc['new_measurements']} measured now, {doc['from_cache']} from the cache).</p>"]
    rec = doc.get("recommendation")
    if rec is not None:
        r = confs[rec]
        p.append(f"<h2>Recommendation: <code>{html.escape(r['config'])}</code></h2><table>{HEAD}{row(r, 'recommended')}")
        if doc.get("cheaper_miss") is not None:
            p.append(row(confs[doc["cheaper_miss"]], "cheaper, misses"))
        for d in doc.get("defaults", []):
            p.append(row(confs[d], f"{confs[d]['technique']} defaults"))
        p.append("</table>")
        p.append(f"<pre>--technique {html.escape(doc['technique_option'])}\n\n{html.escape(doc['cpp'])}</pre>")
        p.append("<h2>What the budget buys</h2><p>First frame of the path: colour, error (false lit red, false shadow blue), "
                 "texel density, reference.</p><table>")
        pairs = [("recommended", r)]
        if doc.get("cheaper_miss") is not None:
            pairs.append(("cheaper", confs[doc["cheaper_miss"]]))
        for tag, c in pairs:
            imgs = copy_images(c, src_dir, a.out, tag)
            cells = "".join(f"<img src='{html.escape(imgs[k])}' alt='{k}' title='{k}'>" for k in
                            ("color", "error", "texel_density", "reference") if k in imgs)
            p.append(f"<tr><td><code>{html.escape(c['config'])}</code><br>{html.escape(tag)}</td><td>{cells}</td></tr>")
        p.append("</table>")
    else:
        p.append("<h2>No configuration meets the budget</h2><p>The closest:</p><table>" + HEAD)
        p.extend(row(confs[i]) for i in doc.get("closest", []))
        p.append("</table>")
    p.append("<h2>Pareto front</h2><img src='front.png' style='width:800px' alt='front'><table>" + HEAD)
    p.extend(row(confs[i], "front") for i in doc["front"])
    p.append("</table><h2>Every configuration measured</h2><table>" + HEAD)
    p.extend(row(c) for c in sorted(confs, key=lambda c: c["metrics"][doc["minimize"]]))
    p.append("</table></body></html>")
    with open(os.path.join(a.out, "index.html"), "w") as f:
        f.write("\n".join(p))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
