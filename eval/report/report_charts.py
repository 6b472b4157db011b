"""The report's charts: one PNG per chart and scene, drawn with matplotlib's Agg backend.

Every chart function takes a scene's runs (already sorted) and writes one file, returning the notes
about data it had to leave out; it writes nothing and returns None when no run has the data.
"""

import math
import textwrap

import matplotlib
import matplotlib.ticker

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (the backend must be chosen first)
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.text import Text  # noqa: E402
from matplotlib.transforms import (Bbox, ScaledTranslation,  # noqa: E402
                                   blended_transform_factory)

from report_results import (describe, pareto_front, run_labels, setup_summary,  # noqa: E402
                            technique_labels)

DPI = 110
FONT_SIZE = 9

# Vulkan's red and OpenGL's blue, so the two read the same in every chart.
BACKEND_STYLES = {"vulkan": ("#c0392b", "o", "-"), "gl": ("#2471a3", "s", "--")}
EXTRA_STYLES = [("#239b56", "^", "-."), ("#7d3c98", "D", ":"), ("#b9770e", "v", "-")]

FALSE_LIT_COLOR = "#f5b041"     # leaks: light where there should be shadow
FALSE_SHADOW_COLOR = "#1f3a5f"  # acne: shadow where there should be light


def _apply_style():
    plt.rcParams.update({
        "font.size": FONT_SIZE, "axes.titlesize": FONT_SIZE + 2, "axes.labelsize": FONT_SIZE + 1,
        "legend.fontsize": FONT_SIZE, "figure.dpi": DPI, "savefig.dpi": DPI,
        "axes.spines.top": False, "axes.spines.right": False,
    })


_apply_style()


def backend_style(backend, backends):
    """(colour, marker, line style) for a backend; unknown backends take the extra styles in the
    order they appear in `backends`."""
    if backend in BACKEND_STYLES:
        return BACKEND_STYLES[backend]
    others = [b for b in backends if b not in BACKEND_STYLES]
    return EXTRA_STYLES[others.index(backend) % len(EXTRA_STYLES)]


def ordered_backends(runs):
    """The runs' backends, the known ones first in a fixed order so legends read alike."""
    present = list(dict.fromkeys(r.backend for r in runs))
    return [b for b in BACKEND_STYLES if b in present] + [b for b in present
                                                           if b not in BACKEND_STYLES]


def scene_subtitle(runs):
    return plain("\n".join(textwrap.wrap(setup_summary(runs), 110)))


class LeftOut:
    """The runs a chart could not show, by reason, as one note per reason."""

    def __init__(self, chart):
        self.chart = chart
        self.reasons = {}

    def add(self, reason, run):
        self.reasons.setdefault(reason, []).append(run)

    def notes(self):
        return [f"{self.chart}: {reason}: "
                + "; ".join(f"{describe(r)} on {r.backend} ({r.where})" for r in runs)
                for reason, runs in self.reasons.items()]


def plain(text):
    """Text from the results as matplotlib should print it: a '$' would otherwise start mathtext,
    and an unbalanced one stops the drawing with an error."""
    return str(text).replace("$", r"\$")


def plain_labels(labels):
    # Labels are always made from all of a scene's runs, so a run is named alike in every chart
    # even where some charts leave others out.
    return {key: plain(text) for key, text in labels.items()}


def _save(fig, path):
    fig.savefig(path, dpi=DPI, facecolor="white")
    plt.close(fig)


def _bar_figure(n_rows, width=9.0):
    """A figure whose height follows the number of bar rows, so labels never squeeze."""
    return plt.subplots(figsize=(width, 2.0 + 0.32 * max(n_rows, 2)), layout="constrained")


def _row_axis(ax, labels):
    ax.set_yticks(range(len(labels)), labels)
    ax.set_ylim(len(labels) - 0.5, -0.5)  # first run on top, in table order
    ax.grid(axis="x", alpha=0.3)
    ax.set_axisbelow(True)


def _legend_below(ax, columns):
    """Under the x axis label, where it cannot cover a bar; constrained layout makes room. The
    offset is in inches (tick labels plus axis label) so it holds whatever the figure's height."""
    # Centred on the figure rather than the axes: long run labels push the axes right, and a
    # legend centred on them would run off the figure's edge.
    fig = ax.figure
    below = (blended_transform_factory(fig.transFigure, ax.transAxes)
             + ScaledTranslation(0, -0.5, fig.dpi_scale_trans))
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, 0.0), bbox_transform=below, ncol=columns,
              frameon=False)


# --- speed vs accuracy


def _overlap(a, b):
    w = min(a.x1, b.x1) - max(a.x0, b.x0)
    h = min(a.y1, b.y1) - max(a.y0, b.y0)
    return w * h if w > 0 and h > 0 else 0.0


# Offsets (points) tried for a label: the four diagonal corners, then straight above, below and
# beside, on rings further and further out (where a leader line ties the label to its point).
_CANDIDATES = [(dx * r, dy * r) for r in (5, 14, 26, 40, 56)
               for dx, dy in ((1, 1), (1, -1), (-1, 1), (-1, -1), (0, 1.3), (0, -1.3), (1.3, 0),
                              (-1.3, 0))]
_LEADER_FROM = 10  # points: closer labels sit against their marker and need no line


def _sample_lines(lines, to_px, step_px=3.0):
    """Points every few pixels along polylines given in data coordinates, in pixels."""
    samples = []
    for line in lines:
        px = [to_px(p) for p in line]
        for (x0, y0), (x1, y1) in zip(px, px[1:]):
            n = max(1, int(math.hypot(x1 - x0, y1 - y0) / step_px))
            samples.extend((x0 + (x1 - x0) * t / n, y0 + (y1 - y0) * t / n) for t in range(n + 1))
    return samples


def place_labels(ax, xy, texts, lines=(), marker_radius_px=8):
    """Annotates each point with its text at the candidate offset of least cost: leaving the axes
    is ruled out, covering a marker, another label or a line (`lines`: polylines in data
    coordinates) is expensive, and distance from the point costs a little. No extra package
    (adjustText) is needed and the result is deterministic."""
    fig = ax.figure
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    axes_box = ax.get_window_extent(renderer)
    to_px = ax.transData.transform
    r = marker_radius_px
    markers = [Bbox.from_extents(px - r, py - r, px + r, py + r)
               for px, py in (to_px(p) for p in xy)]
    line_points = _sample_lines(lines, to_px)
    placed = []
    for i in sorted(range(len(xy)), key=lambda i: (xy[i][0], xy[i][1])):
        ann = ax.annotate(
            texts[i], xy[i], xytext=(0, 0), textcoords="offset points", fontsize=FONT_SIZE - 0.5,
            zorder=5, bbox=dict(boxstyle="round,pad=0.15", fc="white", ec="none", alpha=0.85),
            arrowprops=dict(arrowstyle="-", color="0.4", lw=0.7, shrinkA=0, shrinkB=4))
        best = None
        for dx, dy in _CANDIDATES:
            ann.xyann = (dx, dy)
            ann.set_ha("left" if dx > 0 else "right" if dx < 0 else "center")
            ann.set_va("bottom" if dy > 0 else "top" if dy < 0 else "center")
            ann.update_positions(renderer)
            # The text alone (the annotation's own extent would include its leader line).
            box = Text.get_window_extent(ann, renderer).padded(2)
            if (box.x0 < axes_box.x0 or box.x1 > axes_box.x1 or box.y0 < axes_box.y0
                    or box.y1 > axes_box.y1):
                cost = 1e9
            else:
                cost = (sum(_overlap(box, m) for m in markers)
                        + sum(_overlap(box, p) for p in placed)
                        + 20 * sum(1 for x, y in line_points
                                   if box.x0 <= x <= box.x1 and box.y0 <= y <= box.y1)
                        + 2 * math.hypot(dx, dy))
            if best is None or cost < best[0]:
                best = (cost, (dx, dy), ann.get_ha(), ann.get_va(), box)
        _, offset, ha, va, box = best
        ann.xyann = offset
        ann.set_ha(ha)
        ann.set_va(va)
        ann.arrow_patch.set_visible(math.hypot(*offset) > _LEADER_FROM)
        placed.append(box)


def _step_path(front):
    """The corners of the 'post' step line through the front's points."""
    path = [front[0]]
    for (x0, y0), (x1, y1) in zip(front, front[1:]):
        path += [(x1, y0), (x1, y1)]
    return path


def speed_accuracy_chart(scene, runs, path):
    left = LeftOut("Speed vs accuracy")
    points = []
    for r in runs:
        x, y = r.metric("gpu_ms.total"), r.metric("misclassified_pct")
        if x is None or y is None:
            missing = " and ".join(n for n, v in (("gpu_ms.total", x), ("misclassified_pct", y))
                                   if v is None)
            left.add(f"not plotted, no {missing}", r)
        else:
            points.append((r, x, y))
    if not points:
        return None

    labels = plain_labels(technique_labels(runs))
    backends = ordered_backends(r for r, _, _ in points)
    fig, ax = plt.subplots(figsize=(10, 6.2), layout="constrained")
    handles = []
    front_lines = []
    for backend in backends:
        color, marker, line = backend_style(backend, backends)
        mine = [(x, y) for r, x, y in points if r.backend == backend]
        ax.scatter([p[0] for p in mine], [p[1] for p in mine], s=42, marker=marker, color=color,
                   edgecolors="white", linewidths=0.6, zorder=4)
        handles.append(Line2D([], [], ls="none", marker=marker, color=color,
                              label=plain(backend)))
        # One front per backend: a GPU time is only comparable with others on the same API, and
        # someone on OpenGL needs the choices OpenGL offers.
        front = [mine[i] for i in pareto_front(mine)]
        front_lines.append(_step_path(front))
        ax.step([p[0] for p in front], [p[1] for p in front], where="post", color=color,
                ls=line, lw=1.4, alpha=0.75, zorder=3)
        # Rings mark the front's points, so a front of one point shows too.
        ax.scatter([p[0] for p in front], [p[1] for p in front], s=130, marker="o",
                   facecolors="none", edgecolors=color, linewidths=1.1, zorder=4)
        suffix = f" ({plain(backend)})" if len(backends) > 1 else ""
        handles.append(Line2D([], [], color=color, ls=line, lw=1.4, alpha=0.75, marker="o",
                              ms=10, mfc="none", label=f"Pareto front{suffix}"))

    xs = [x for _, x, _ in points]
    ys = [y for _, _, y in points]
    # Misclassified starts at 0 (a perfect match) so heights compare; GPU time keeps its data range
    # because a long empty stretch from 0 ms would squeeze the points together. Both lower limits
    # sit a hair below the data so markers at 0 are not cut in half.
    pad = 0.12 * (max(xs) - min(xs)) or 0.5 * max(xs) or 1.0
    ax.set_xlim(max(min(xs) - pad, -0.03 * (max(xs) + pad)), max(xs) + pad)
    top = max(ys) * 1.12 or 1.0
    ax.set_ylim(-0.03 * top, top)
    ax.grid(alpha=0.3)
    ax.set_axisbelow(True)
    ax.set_xlabel("GPU time per frame, gpu_ms.total (ms)  →  slower")
    ax.set_ylabel("misclassified pixels (% of lit-receiving pixels)  →  less accurate")
    ax.set_title(f"{plain(scene)}: speed vs accuracy (lower left is better)\n"
                 f"{scene_subtitle(runs)}")
    ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.01, 1.0), frameon=False,
              title="backend")
    place_labels(ax, [(x, y) for _, x, y in points],
                 [labels[(r.technique, r.params_key)] for r, _, _ in points], front_lines)
    _save(fig, path)
    return left.notes()


# --- error categories


def _annotate_ends(ax, texts, ends):
    """Writes each row's text just past the end of its bar."""
    for row, (text, end) in enumerate(zip(texts, ends)):
        ax.annotate(text, (end, row), xytext=(3, 0), textcoords="offset points", va="center",
                    fontsize=FONT_SIZE - 1)


def error_categories_chart(scene, runs, path):
    left = LeftOut("Error categories")
    rows = []
    for r in runs:
        lit, shadow = r.metric("false_lit_pct"), r.metric("false_shadow_pct")
        if lit is None and shadow is None:
            left.add("not plotted, no false_lit_pct or false_shadow_pct", r)
            continue
        gap = ""
        for name, value, short in (("false_lit_pct", lit, "false lit"),
                                   ("false_shadow_pct", shadow, "false shadow")):
            if value is None:
                left.add(f"no {name}, drawn as 0", r)
                gap = f" ({short} missing)"
        rows.append((r, lit or 0.0, shadow or 0.0, gap))
    if not rows:
        return None
    labels = plain_labels(run_labels(runs))
    fig, ax = _bar_figure(len(rows))
    y = range(len(rows))
    lit = [row[1] for row in rows]
    shadow = [row[2] for row in rows]
    ax.barh(y, lit, color=FALSE_LIT_COLOR, height=0.7,
            label="false lit: light leaks (peter-panning, light bleeding)")
    ax.barh(y, shadow, left=lit, color=FALSE_SHADOW_COLOR, height=0.7,
            label="false shadow: acne, over-darkening")
    totals = [a + b for a, b in zip(lit, shadow)]
    _annotate_ends(ax, [f"{t:.2f}%{row[3]}" for t, row in zip(totals, rows)], totals)
    _row_axis(ax, [labels[row[0].key] for row in rows])
    ax.set_xlim(0, max(max(totals) * 1.2, 0.1))
    ax.set_xlabel("misclassified pixels (% of lit-receiving pixels)")
    ax.set_title(f"{plain(scene)}: error categories per run\n{scene_subtitle(runs)}")
    _legend_below(ax, 2)
    _save(fig, path)
    return left.notes()


# --- perspective aliasing


def texel_density_chart(scene, runs, path):
    left = LeftOut("Perspective aliasing")
    rows = []
    for r in runs:
        med, p05 = r.metric("texels_per_pixel_median"), r.metric("texels_per_pixel_p05")
        usable = [v for v in (med, p05) if v is not None and v > 0]
        if not usable:
            left.add("not plotted, no positive texels_per_pixel_median or _p05", r)
            continue
        for name, value in (("texels_per_pixel_median", med), ("texels_per_pixel_p05", p05)):
            if value is None or value <= 0:
                left.add(f"no positive {name}, that bar left out", r)
        rows.append((r, med if med and med > 0 else None, p05 if p05 and p05 > 0 else None))
    if not rows:
        return None
    labels = plain_labels(run_labels(runs))
    fig, ax = _bar_figure(len(rows))
    # Bars grow from the 1 texel/pixel line, so the side they point to says under- or
    # oversampled and their length (on the log axis) says by what factor.
    h = 0.38
    bars = ((-h / 2, 1, "#5d6d7e", "median"),
            (h / 2, 2, "#e67e22", "5th percentile (worst 5% of pixels)"))
    for offset, index, color, name in bars:
        ys = [row + offset for row, item in enumerate(rows) if item[index] is not None]
        vals = [item[index] for item in rows if item[index] is not None]
        if not vals:
            continue
        ax.barh(ys, [v - 1.0 for v in vals], left=1.0, height=h, color=color, label=name)
        for yy, v in zip(ys, vals):
            ax.annotate(f"{v:.3g}", (v, yy), xytext=(3 if v >= 1 else -3, 0),
                        textcoords="offset points", va="center", ha="left" if v >= 1 else "right",
                        fontsize=FONT_SIZE - 1.5)
    ax.set_xscale("log")
    values = [v for _, a, b in rows for v in (a, b) if v is not None] + [1.0]
    ax.set_xlim(min(values) / 2.2, max(values) * 2.2)
    ax.axvline(1.0, color="black", lw=1.0, zorder=3)
    ax.annotate("← undersampled", (1.0, 1.0), xycoords=("data", "axes fraction"), xytext=(-6, 2),
                textcoords="offset points", ha="right", va="bottom", fontsize=FONT_SIZE - 0.5)
    ax.annotate("oversampled →", (1.0, 1.0), xycoords=("data", "axes fraction"), xytext=(6, 2),
                textcoords="offset points", ha="left", va="bottom", fontsize=FONT_SIZE - 0.5)
    ax.xaxis.set_major_locator(matplotlib.ticker.LogLocator(subs=(1.0, 2.0, 5.0)))
    ax.xaxis.set_major_formatter(matplotlib.ticker.FuncFormatter(lambda v, _: f"{v:g}"))
    ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    _row_axis(ax, [labels[r.key] for r, _, _ in rows])
    ax.set_xlabel("shadow-map texels per screen pixel (log scale; 1 = one texel per pixel)")
    ax.set_title(f"{plain(scene)}: perspective aliasing\n{scene_subtitle(runs)}", pad=16)
    _legend_below(ax, 2)
    _save(fig, path)
    return left.notes()


# --- flicker


def flicker_series_chart(scene, runs, path):
    series = [(r, r.series["flicker"]) for r in runs if "flicker" in r.series]
    if not series:
        return None
    labels = plain_labels(run_labels(runs))
    backends = ordered_backends(r for r, _ in series)
    # Colour says technique and parameters, line style says backend, so one variant measured on
    # two backends shows as two lines of one colour.
    variants = list(dict.fromkeys((r.technique, r.params_key) for r, _ in series))
    palette = plt.get_cmap("tab10" if len(variants) <= 10 else "tab20").colors
    colors = {k: palette[i % len(palette)] for i, k in enumerate(variants)}
    fig, ax = plt.subplots(figsize=(10, 5), layout="constrained")
    for r, values in series:
        _, marker, line = backend_style(r.backend, backends)
        ax.plot(range(len(values)), values, ls=line, color=colors[(r.technique, r.params_key)],
                lw=1.4, label=labels[r.key], marker=marker if len(values) <= 30 else None, ms=3)
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3)
    ax.set_xlabel("frame of the camera pan")
    ax.set_ylabel("flicker: mean |Δ shadow term| since the previous frame")
    ax.set_title(f"{plain(scene)}: flicker over time (0 = stable)\n{scene_subtitle(runs)}")
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), frameon=False)
    _save(fig, path)
    left = LeftOut("Flicker over time")
    for r in runs:
        if "flicker" not in r.series:
            left.add("no flicker series", r)
    return left.notes()


def flicker_chart(scene, runs, path):
    rows = [(r, r.metric("flicker")) for r in runs if r.metric("flicker") is not None]
    if not rows:
        return None
    labels = plain_labels(run_labels(runs))
    fig, ax = _bar_figure(len(rows))
    values = [v for _, v in rows]
    ax.barh(range(len(rows)), values, height=0.65, color="#8e44ad")
    # Values span orders of magnitude (stabilized cascades ~1e-5, SDSM ~1e-2): three significant
    # digits, so a small one does not print as 0.0000.
    _annotate_ends(ax, [f"{v:.3g}" for v in values], values)
    _row_axis(ax, [labels[r.key] for r, _ in rows])
    ax.set_xlim(0, max(max(values) * 1.18, 1e-4))
    ax.set_xlabel("flicker: mean |Δ shadow term| per frame at a fixed world point (0 = stable)")
    ax.set_title(f"{plain(scene)}: flicker per run (slow camera pan)\n{scene_subtitle(runs)}")
    _save(fig, path)
    left = LeftOut("Flicker")
    for r in runs:
        if r.metric("flicker") is None:
            left.add("not plotted, no flicker metric", r)
    return left.notes()


# --- cost

PASS_COLORS = [("gpu_ms.shadow", "shadow passes", "#34495e"), ("gpu_ms.lit", "lit pass", "#5dade2"),
               ("gpu_ms.analysis", "analysis", "#f1c40f")]
# Passes a technique names beyond those (moment resolve and blur, a depth pre-pass) in this order.
EXTRA_PASS_COLORS = ["#e67e22", "#16a085", "#c0392b", "#8e44ad", "#7f8c8d"]


def pass_styles(runs):
    """(metric name, legend label, colour) of every GPU pass the runs name."""
    known = {name for name, _, _ in PASS_COLORS}
    extra = sorted({n for r in runs for n in r.metrics if n.startswith("gpu_ms.")
                    and n != "gpu_ms.total" and n not in known})
    return PASS_COLORS + [(n, n[len("gpu_ms."):], EXTRA_PASS_COLORS[i % len(EXTRA_PASS_COLORS)])
                          for i, n in enumerate(extra)]


def gpu_passes_chart(scene, runs, path):
    left = LeftOut("GPU time per pass")
    rows = []
    passes = pass_styles(runs)
    for r in runs:
        parts = [r.metric(name) or 0.0 for name, _, _ in passes]
        total = r.metric("gpu_ms.total")
        if total is None and not any(parts):
            left.add("not plotted, no gpu_ms", r)
            continue
        # Whatever the total has beyond the named passes (clears, resolves, present) shows as
        # "other" so bar lengths stay equal to the measured totals.
        other = max(total - sum(parts), 0.0) if total is not None else 0.0
        rows.append((r, parts, other, total if total is not None else sum(parts)))
    if not rows:
        return None
    labels = plain_labels(run_labels(runs))
    fig, ax = _bar_figure(len(rows))
    starts = [0.0] * len(rows)
    for i, (_, name, color) in enumerate(passes):
        widths = [parts[i] for _, parts, _, _ in rows]
        if any(widths):
            ax.barh(range(len(rows)), widths, left=starts, height=0.65, color=color, label=name)
            starts = [a + b for a, b in zip(starts, widths)]
    # A run that timed only the whole frame gets its own hatched bar rather than an "other"
    # segment, which would read as time outside every pass.
    whole = [o if not any(parts) else 0.0 for _, parts, o, _ in rows]
    others = [o if any(parts) else 0.0 for _, parts, o, _ in rows]
    if any(o > 0.005 for o in others):
        ax.barh(range(len(rows)), others, left=starts, height=0.65, color="#d5d8dc",
                label="other (total − passes)")
    only = [i for i, w in enumerate(whole) if w > 0]
    if only:
        ax.barh(only, [whole[i] for i in only], height=0.65, color="white", edgecolor="#7f8c8d",
                hatch="///", label="total only (no per-pass times)")
    others = [a + b for a, b in zip(others, whole)]
    totals = [t for *_, t in rows]
    ends = [max(t, s + o) for t, s, o in zip(totals, starts, others)]
    _annotate_ends(ax, [f"{t:.2f} ms" for t in totals], ends)
    _row_axis(ax, [labels[r.key] for r, *_ in rows])
    ax.set_xlim(0, max(max(ends) * 1.18, 0.1))
    ax.set_xlabel("GPU time per frame (ms)")
    ax.set_title(f"{plain(scene)}: GPU time per pass\n{scene_subtitle(runs)}")
    if ax.get_legend_handles_labels()[0]:
        _legend_below(ax, 4)
    _save(fig, path)
    return left.notes()
