"""index.html: one static page, no scripts and no external resources, so it opens from a copied
folder or an archived CI artefact exactly as it was generated."""

from dataclasses import dataclass, field
from html import escape

from report_results import (BACKEND_DIFF, IMAGE_KINDS, METRICS, backend_groups, describe,
                            format_metric, metric_heading, metric_names, natural_key,
                            technique_labels)

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
table.images img { width: 280px; image-rendering: pixelated; }
table.images tr > th:first-child { min-width: 10em; }
dl.legend dt { font-family: monospace; font-weight: bold; float: left; clear: left;
               width: 17em; }
dl.legend dd { margin-left: 18em; margin-bottom: 0.25em; }
.notes { color: #7a4b00; }
.small { color: #666; font-size: 0.9em; }
.error { color: #a00; border: 2px solid #a00; padding: 0.3em 1em; background: #fff4f4; }
.ok { color: #1e6b30; }
table.images td.verdict { text-align: left; vertical-align: middle; max-width: 16em; }
td.num { white-space: nowrap; }
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


def _params_cell(run, tech):
    """The parameters the bench was given or, where the results do not say, those that tell this
    variant from the others (as in its label); all of them on hover and in the parameter list."""
    if run.params_given is not None:
        short = " ".join(f"{k}={v}" for k, v in sorted(run.params_given.items(),
                                                       key=lambda kv: natural_key(kv[0])))
        short = short or "(defaults)"
    else:
        short = tech[(run.technique, run.params_key)][len(run.technique):].strip()
    return f'<td title="{escape(_params_text(run))}">{escape(short)}</td>'


def _cell(name, value):
    if value is None:
        return '<td class="na" title="not measured or does not apply">–</td>'
    return f'<td class="num">{escape(format_metric(name, value))}</td>'


def _run_cells(run, tech):
    return (f"<td>{escape(run.technique)}</td>{_params_cell(run, tech)}"
            f"<td>{escape(run.backend)}</td>")


def _metrics_table(section):
    tech = technique_labels(section.runs)
    names = metric_names(section.runs)
    head = "".join(f'<th title="{escape(name)}">{escape(metric_heading(name))}</th>'
                   for name in names)
    rows = []
    for run in section.runs:
        on_front = run.key in section.front
        cls = ' class="front"' if on_front else ""
        mark = '<td title="on its backend\'s Pareto front">✓</td>' if on_front else "<td></td>"
        rows.append(f"<tr{cls}>{_run_cells(run, tech)}{mark}"
                    + "".join(_cell(name, run.metric(name)) for name in names) + "</tr>")
    return ('<div class="scroll"><table><tr><th>technique</th><th>params</th><th>backend</th>'
            f'<th title="on the speed/accuracy Pareto front of its backend">front</th>{head}</tr>'
            + "\n".join(rows) + "</table></div>")


COST_METRICS = ["gpu_ms.shadow", "gpu_ms.lit", "gpu_ms.analysis", "gpu_ms.total", "cpu_ms",
                "shadow_memory_bytes", "shadow_triangles"]


def _cost_table(section):
    tech = technique_labels(section.runs)
    # Passes a technique names beyond the usual ones (moments, depth prepass) go before the total.
    extra = sorted({n for r in section.runs for n in r.metrics if n.startswith("gpu_ms.")
                    and n not in COST_METRICS})
    names = COST_METRICS[:3] + extra + COST_METRICS[3:]
    head = "".join(f"<th>{escape(metric_heading(n))}</th>" for n in names)
    rows = [f"<tr>{_run_cells(run, tech)}" + "".join(_cell(n, run.metric(n)) for n in names)
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
    tech = technique_labels(section.runs)
    names = metric_names([r for _, _, rs in groups for r in rs])
    head = "".join(f"<th>Δ {escape(metric_heading(n))}</th>" for n in names)
    rows = []
    for _, _, runs in groups:
        runs = sorted(runs, key=lambda r: natural_key(r.backend))
        base = runs[0]
        for other in runs[1:]:
            rows.append(f"<tr><td>{escape(base.technique)}</td>{_params_cell(base, tech)}"
                        f"<td>{escape(other.backend)} − {escape(base.backend)}</td>"
                        + "".join(_difference_cell(n, base, other) for n in names) + "</tr>")
    return ('<p class="small">The same technique and parameters measured on more than one backend. '
            "Each cell is the difference the backends column names (relative change in brackets; "
            "hover for both values). Accuracy metrics should agree closely, as both backends run "
            "the same shaders; GPU times are expected to differ.</p>"
            '<div class="scroll"><table><tr><th>technique</th><th>params</th><th>backends</th>'
            f"{head}</tr>" + "\n".join(rows) + "</table></div>")


def _base_run(section, run):
    """The run a cross-backend comparison of `run` was made against, if it is in the section."""
    against = run.cross_backend["against"] if run.cross_backend else None
    return next((r for r in section.runs if r.backend == against and r.technique == run.technique
                 and r.params_key == run.params_key), None)


def _images_table(section, labels):
    kinds = [k for k, _ in IMAGE_KINDS]
    extra = sorted({k for imgs in section.images.values() for k in imgs} - set(kinds)
                   - {BACKEND_DIFF}, key=natural_key)
    kinds += extra
    names = dict(IMAGE_KINDS)
    runs = [r for r in section.runs if section.images.get(r.key)]
    if not runs:
        return None
    # A run whose colour image is bit-identical to its first backend's shows the same pictures:
    # one row for both, named "[vulkan = gl]".
    with_images = {r.key for r in runs}
    merged, hidden = {}, set()
    for run in runs:
        base = _base_run(section, run)
        if base is not None and base.key in with_images and run.cross_backend["differing_pixels"] == 0:
            merged.setdefault(base.key, []).append(run.backend)
            hidden.add(run.key)
    runs = [r for r in runs if r.key not in hidden]
    row_labels = dict(labels)
    tech = technique_labels(section.runs)
    for run in runs:
        if run.key in merged:
            row_labels[run.key] = (f"{tech[(run.technique, run.params_key)]} "
                                   f"[{' = '.join([run.backend] + merged[run.key])}]")
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
                cells.append(_image_cell(rel, alt))
        rows.append(f"<tr><th>{escape(row_labels[run.key])}</th>{''.join(cells)}</tr>")
    return (f'<div class="scroll"><table class="images"><tr><th>run</th>{head}</tr>'
            + "\n".join(rows) + "</table></div>")


def _parameter_list(section):
    """Every parameter of each technique variant, once: what the short labels leave out."""
    tech = technique_labels(section.runs)
    seen = {}
    for run in section.runs:
        seen.setdefault((run.technique, run.params_key), run)
    items = [f"<li><b>{escape(tech[key])}</b>: {escape(_params_text(run))}</li>"
             for key, run in seen.items() if run.params]
    if not items:
        return None
    return f'<ul class="small">{"".join(items)}</ul>'


def _image_cell(rel, alt):
    if rel is None:
        return '<td class="na">missing file</td>'
    return (f'<td><a href="{escape(rel)}"><img src="{escape(rel)}" alt="{escape(alt)}" '
            'loading="lazy"></a></td>')


def _cross_backend_images(section):
    """Per technique and parameter set: the first frame on the first backend and on each other
    one, where they differ, and the count of differing pixels."""
    tech = technique_labels(section.runs)
    rows = []
    for run in section.runs:
        c = run.cross_backend
        if c is None:
            continue
        base = _base_run(section, run)
        label = tech[(run.technique, run.params_key)]
        images = section.images.get(run.key, {})
        base_images = section.images.get(base.key, {}) if base else {}
        cells = []
        for owner, imgs, kind in ((c["against"], base_images, "color"), (run.backend, images, "color"),
                                  (f"{run.backend} vs {c['against']}", images, BACKEND_DIFF)):
            if kind in imgs:
                cells.append(_image_cell(imgs[kind], f"{label}: {owner}"))
            else:
                cells.append('<td class="na">–</td>')
        n, total = c["differing_pixels"], c["pixels"]
        verdict = (f"{n:,} of {total:,} pixels differ ({n / total * 100:.3g} %), largest channel "
                   f"difference {c['max_difference']} of 255" if total else "no pixels")
        if n == 0 and total:
            verdict = f"0 of {total:,} pixels differ: <b>bit-identical</b>"
        else:
            verdict = escape(verdict)
        rows.append(f"<tr><th>{escape(label)}</th>{''.join(cells)}"
                    f'<td class="verdict">{verdict}</td></tr>')
    if not rows:
        return None
    compared = [r for r in section.runs if r.cross_backend]
    against = sorted({r.cross_backend["against"] for r in compared})
    others = sorted({r.backend for r in compared}, key=natural_key)
    same = sum(1 for r in compared if r.cross_backend["differing_pixels"] == 0)
    summary = (f"<p><b>{same} of {len(compared)}</b> comparisons of {escape(', '.join(others))} "
               f"against {escape(', '.join(against))}: bit-identical first frame.</p>")
    return (summary + '<p class="small">The path\'s first frame rendered by each backend from the same HLSL, '
            "compared channel by channel. The difference image is the first backend's picture "
            "dimmed, with every differing pixel in red.</p>"
            '<div class="scroll"><table class="images"><tr><th>technique</th>'
            f"<th>{escape(', '.join(against))}</th><th>{escape(', '.join(others))}</th>"
            "<th>difference</th><th>pixels that differ</th></tr>"
            + "\n".join(rows) + "</table></div>")


def _validation_summary(runs):
    """One line on the validation layers / debug output of all runs, and every error."""
    known = [r for r in runs if r.validation_enabled is not None]
    if not known:
        return ""
    on = [r for r in known if r.validation_enabled]
    failed = [r for r in runs if r.validation_errors]
    text = (f"Validation (Vulkan validation layers, OpenGL debug output): on in {len(on)} of "
            f"{len(known)} runs")
    if len(on) < len(known):
        text += " (off: bench without --validate, or the layers are not installed)"
    if not failed:
        return f'<p class="ok">{escape(text)}; 0 errors.</p>'
    total = sum(r.validation_errors for r in failed)
    items = "".join(
        f"<li>{escape(r.scene)}, {escape(describe(r))} on {escape(r.backend)}: "
        f"{r.validation_errors} error(s)"
        + (f"; last: <code>{escape(r.last_validation_error)}</code>"
           if r.last_validation_error else "") + "</li>" for r in failed)
    return (f'<div class="error"><p><b>{escape(text)}: {total} validation error(s) in '
            f"{len(failed)} run(s).</b></p><ul>{items}</ul></div>")


def _legend():
    # The four GPU timings share one line; every other metric has its own.
    items = []
    for m in METRICS:
        if m.name == "gpu_ms.shadow":
            items.append(("gpu_ms.*", "GPU time per frame of the shadow passes, the lit pass, "
                                      "the analysis pass and any other pass a technique names "
                                      "(moments, depth prepass), and of the whole frame (total), "
                                      "in ms"))
        elif not m.name.startswith("gpu_ms."):
            items.append((m.name, m.meaning))
    return ('<dl class="legend">' + "".join(f"<dt>{escape(n)}</dt><dd>{escape(d)}</dd>"
                                            for n, d in items) + "</dl>")


def _notes(notes):
    if not notes:
        return ""
    return ('<ul class="notes">' + "".join(f"<li>{escape(n)}</li>" for n in notes) + "</ul>")


def render_page(title, inputs, sections, global_notes, labels_of, intro=None):
    """The whole page. `inputs` is [(file name, run count)]; `labels_of(section)` gives
    {run.key: label} for a section's runs. The speed/accuracy chart, the figures and the pictures
    come first in each scene; the other charts and the cost breakdown follow."""
    out = ["<!DOCTYPE html>", '<html lang="en"><head><meta charset="utf-8">',
           '<meta name="viewport" content="width=device-width, initial-scale=1">',
           f"<title>{escape(title)}</title><style>{STYLE}</style></head><body>",
           f"<h1>{escape(title)}</h1>"]
    if intro:
        out.append(f"<p>{escape(intro)}</p>")
    total = sum(len(s.runs) for s in sections)
    out.append(f"<p>{total} runs in {len(sections)} scene(s), from "
               + ", ".join(f"<code>{escape(name)}</code> ({count} runs)" for name, count in inputs)
               + '. <a href="#metrics">What the metrics mean</a>.</p>')
    out.append(_validation_summary([r for s in sections for r in s.runs]))
    if sections:
        out.append("<p>Scenes: " + " · ".join(
            f'<a href="#{s.anchor}">{escape(s.name)}</a>' for s in sections) + "</p>")
    if global_notes:
        out.append("<h2>Notes</h2>" + _notes(global_notes))
    if not sections:
        out.append("<p>The input holds no runs.</p>")

    for s in sections:
        labels = labels_of(s)
        out.append(f'<section id="{s.anchor}"><h2>Scene: {escape(s.name)}</h2>')
        out.append(f"<p class=\"small\">{escape(s.subtitle)}; {len(s.runs)} runs.</p>")
        charts = [_chart(s, *chart) for chart in s.charts]
        out.extend(charts[:1])
        out.append("<h3>All metrics</h3><p class=\"small\">Bold rows (✓) are on their backend's "
                   "speed/accuracy Pareto front.</p>" + _metrics_table(s))
        images = _images_table(s, labels)
        if images:
            out.append("<h3>Images</h3><p class=\"small\">The path's first frame; click an image "
                       "for full size. Error map: where the shadow term differs from the "
                       "reference. Texel density: shadow texels per pixel (undersampled areas are "
                       "the blocky ones).</p>" + images)
        cross_images = _cross_backend_images(s)
        cross = _cross_backend_table(s)
        if cross_images or cross:
            out.append("<h3>Cross-backend</h3>" + (cross_images or "") + (cross or ""))
        out.extend(charts[1:])
        out.append("<h3>Cost</h3>" + _cost_table(s))
        parameters = _parameter_list(s)
        if parameters:
            out.append("<h3>Parameters</h3>" + parameters)
        if s.notes:
            out.append("<h3>Notes: data left out</h3>" + _notes(s.notes))
        out.append("</section>")
    out.append("<h2 id=\"metrics\">What the metrics mean</h2>")
    out.append("<p>Accuracy is measured against a ray-traced reference of the same frame. "
               "A technique that does not apply leaves a metric empty (–).</p>")
    out.append(_legend())
    out.append("</body></html>\n")
    return "\n".join(out)


def _chart(section, heading, file_name, description):
    return (f"<h3>{escape(heading)}</h3><p class=\"small\">{escape(description)}</p>"
            f'<img class="chart" src="{escape(file_name)}" alt="{escape(heading)}: '
            f'{escape(section.name)}">')
