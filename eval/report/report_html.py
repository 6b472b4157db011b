"""index.html: one static page, no scripts and no external resources, so it opens from a copied
folder or an archived CI artefact exactly as it was generated."""

from dataclasses import dataclass, field
from html import escape

from report_results import (IMAGE_KINDS, METRICS, backend_groups, format_metric,
                            metric_heading, metric_names, natural_key)

STYLE = """
body { font-family: sans-serif; font-size: 14px; margin: 1.5em auto; max-width: 1400px;
       padding: 0 1em; color: #222; }
h1 { font-size: 1.6em; } h2 { border-bottom: 2px solid #ccc; margin-top: 2em; }
h3 { margin-top: 1.6em; }
table { border-collapse: collapse; margin: 0.5em 0; }
th, td { border: 1px solid #ccc; padding: 2px 6px; }
th { background: #f0f0f0; font-weight: 600; }
td.num { text-align: right; font-variant-numeric: tabular-nums; }
td.na { text-align: center; color: #999; }
tr.front td:first-child { font-weight: bold; }
.scroll { overflow-x: auto; }
img.chart { max-width: 100%; border: 1px solid #eee; }
table.images td { vertical-align: top; text-align: center; }
table.images img { width: 240px; image-rendering: pixelated; }
dl.legend dt { font-family: monospace; font-weight: bold; float: left; clear: left;
               width: 17em; }
dl.legend dd { margin-left: 18em; margin-bottom: 0.25em; }
.notes { color: #7a4b00; }
.small { color: #666; font-size: 0.9em; }
"""


@dataclass
class SceneSection:
    name: str
    anchor: str
    runs: list
    subtitle: str
    charts: list = field(default_factory=list)   # (heading, file name, description)
    images: dict = field(default_factory=dict)   # run.key -> {kind: relative path or None}
    notes: list = field(default_factory=list)
    front: set = field(default_factory=set)      # keys of runs on a Pareto front


def _params_text(run):
    return ", ".join(f"{k}={v}" for k, v in sorted(run.params.items(), key=lambda kv:
                                                     natural_key(kv[0]))) or "(defaults)"


def _cell(name, value):
    if value is None:
        return '<td class="na" title="not measured or does not apply">–</td>'
    return f'<td class="num">{escape(format_metric(name, value))}</td>'


def _run_cells(run):
    return (f"<td>{escape(run.technique)}</td><td>{escape(_params_text(run))}</td>"
            f"<td>{escape(run.backend)}</td>")


def _metrics_table(section):
    names = metric_names(section.runs)
    head = "".join(f'<th title="{escape(name)}">{escape(metric_heading(name))}</th>'
                   for name in names)
    rows = []
    for run in section.runs:
        on_front = run.key in section.front
        cls = ' class="front"' if on_front else ""
        mark = '<td title="on its backend\'s Pareto front">✓</td>' if on_front else "<td></td>"
        rows.append(f"<tr{cls}>{_run_cells(run)}{mark}"
                    + "".join(_cell(name, run.metric(name)) for name in names) + "</tr>")
    return ('<div class="scroll"><table><tr><th>technique</th><th>params</th><th>backend</th>'
            f'<th title="on the speed/accuracy Pareto front of its backend">front</th>{head}</tr>'
            + "\n".join(rows) + "</table></div>")


COST_METRICS = ["gpu_ms.shadow", "gpu_ms.lit", "gpu_ms.analysis", "gpu_ms.total", "cpu_ms",
                "shadow_memory_bytes", "shadow_triangles"]


def _cost_table(section):
    head = "".join(f"<th>{escape(metric_heading(n))}</th>" for n in COST_METRICS)
    rows = [f"<tr>{_run_cells(run)}" + "".join(_cell(n, run.metric(n)) for n in COST_METRICS)
            + "</tr>" for run in section.runs]
    return ('<div class="scroll"><table><tr><th>technique</th><th>params</th><th>backend</th>'
            f"{head}</tr>" + "\n".join(rows) + "</table></div>")


def _difference_cell(name, base, other):
    a, b = base.metric(name), other.metric(name)
    if a is None or b is None:
        return '<td class="na" title="missing on one backend">–</td>'
    diff = b - a
    shown = format_metric(name, abs(diff))
    sign = "+" if diff > 0 else "−" if diff < 0 else "±"
    relative = (f" ({diff / abs(a) * 100:+.0f}%)".replace("-", "−")
                if a != 0 and diff != 0 else "")
    title = (f"{base.backend}: {format_metric(name, a)}, {other.backend}: "
             f"{format_metric(name, b)}")
    return f'<td class="num" title="{escape(title)}">{sign}{escape(shown)}{relative}</td>'


def _cross_backend_table(section):
    groups = backend_groups(section.runs)
    if not groups:
        return None
    names = metric_names([r for _, _, rs in groups for r in rs])
    head = "".join(f"<th>Δ {escape(metric_heading(n))}</th>" for n in names)
    rows = []
    for _, _, runs in groups:
        runs = sorted(runs, key=lambda r: natural_key(r.backend))
        base = runs[0]
        for other in runs[1:]:
            rows.append(f"<tr><td>{escape(base.technique)}</td><td>{escape(_params_text(base))}"
                        f"</td><td>{escape(other.backend)} − {escape(base.backend)}</td>"
                        + "".join(_difference_cell(n, base, other) for n in names) + "</tr>")
    return ('<p class="small">The same technique and parameters measured on more than one backend. '
            "Each cell is the difference the backends column names (relative change in brackets; "
            "hover for both values). Accuracy metrics should agree closely, as both backends run "
            "the same shaders; GPU times are expected to differ.</p>"
            '<div class="scroll"><table><tr><th>technique</th><th>params</th><th>backends</th>'
            f"{head}</tr>" + "\n".join(rows) + "</table></div>")


def _images_table(section, labels):
    kinds = [k for k, _ in IMAGE_KINDS]
    extra = sorted({k for imgs in section.images.values() for k in imgs} - set(kinds),
                   key=natural_key)
    kinds += extra
    names = dict(IMAGE_KINDS)
    runs = [r for r in section.runs if section.images.get(r.key)]
    if not runs:
        return None
    used = [k for k in kinds if any(k in section.images[r.key] for r in runs)]
    head = "".join(f"<th>{escape(names.get(k, k))}</th>" for k in used)
    rows = []
    for run in runs:
        cells = []
        for kind in used:
            images = section.images[run.key]
            rel = images.get(kind)
            if kind not in images:
                cells.append('<td class="na">–</td>')
            elif rel is None:
                cells.append('<td class="na">missing file</td>')
            else:
                alt = f"{names.get(kind, kind)}: {labels[run.key]}"
                cells.append(f'<td><a href="{escape(rel)}"><img src="{escape(rel)}" '
                             f'alt="{escape(alt)}" loading="lazy"></a></td>')
        rows.append(f"<tr><th>{escape(labels[run.key])}</th>{''.join(cells)}</tr>")
    return (f'<div class="scroll"><table class="images"><tr><th>run</th>{head}</tr>'
            + "\n".join(rows) + "</table></div>")


def _legend():
    # The four GPU timings share one line; every other metric has its own.
    items = []
    for m in METRICS:
        if m.name == "gpu_ms.shadow":
            items.append(("gpu_ms.*", "GPU time per frame of the shadow passes, the lit pass and "
                                      "the analysis pass, and of the whole frame (total), in ms"))
        elif not m.name.startswith("gpu_ms."):
            items.append((m.name, m.meaning))
    return ('<dl class="legend">' + "".join(f"<dt>{escape(n)}</dt><dd>{escape(d)}</dd>"
                                            for n, d in items) + "</dl>")


def _notes(notes):
    if not notes:
        return ""
    return ('<ul class="notes">' + "".join(f"<li>{escape(n)}</li>" for n in notes) + "</ul>")


def render_page(title, inputs, sections, global_notes, labels_of):
    """The whole page. `inputs` is [(file name, run count)]; `labels_of(section)` gives
    {run.key: label} for a section's runs."""
    out = ["<!DOCTYPE html>", '<html lang="en"><head><meta charset="utf-8">',
           '<meta name="viewport" content="width=device-width, initial-scale=1">',
           f"<title>{escape(title)}</title><style>{STYLE}</style></head><body>",
           f"<h1>{escape(title)}</h1>"]
    total = sum(len(s.runs) for s in sections)
    out.append(f"<p>{total} runs in {len(sections)} scene(s), from "
               + ", ".join(f"<code>{escape(name)}</code> ({count} runs)" for name, count in inputs)
               + ".</p>")
    if sections:
        out.append("<p>Scenes: " + " · ".join(
            f'<a href="#{s.anchor}">{escape(s.name)}</a>' for s in sections) + "</p>")
    out.append("<h2 id=\"metrics\">What the metrics mean</h2>")
    out.append("<p>Accuracy is measured against a ray-traced reference of the same frame. "
               "A technique that does not apply leaves a metric empty (–).</p>")
    out.append(_legend())
    if global_notes:
        out.append("<h2>Notes</h2>" + _notes(global_notes))
    if not sections:
        out.append("<p>The input holds no runs.</p>")

    for s in sections:
        labels = labels_of(s)
        out.append(f'<section id="{s.anchor}"><h2>Scene: {escape(s.name)}</h2>')
        out.append(f"<p class=\"small\">{escape(s.subtitle)}; {len(s.runs)} runs.</p>")
        for heading, file_name, description in s.charts:
            out.append(f"<h3>{escape(heading)}</h3><p class=\"small\">{escape(description)}</p>"
                       f'<img class="chart" src="{escape(file_name)}" alt="{escape(heading)}: '
                       f'{escape(s.name)}">')
        out.append("<h3>Cost</h3>" + _cost_table(s))
        out.append("<h3>All metrics</h3><p class=\"small\">Bold rows (✓) are on their backend's "
                   "speed/accuracy Pareto front.</p>" + _metrics_table(s))
        cross = _cross_backend_table(s)
        if cross:
            out.append("<h3>Cross-backend</h3>" + cross)
        images = _images_table(s, labels)
        if images:
            out.append("<h3>Images</h3><p class=\"small\">Click an image for full size. Error map: "
                       "where the shadow term differs from the reference. Texel density: shadow "
                       "texels per pixel (undersampled areas are the blocky ones).</p>" + images)
        if s.notes:
            out.append("<h3>Notes: data left out</h3>" + _notes(s.notes))
        out.append("</section>")
    out.append("</body></html>\n")
    return "\n".join(out)
