#!/usr/bin/python3
"""shadowport report: charts and an HTML page from `shadowport bench` results.

    report.py results.json... --out DIR [--title TEXT] [--intro TEXT]

Writes DIR/index.html, one PNG per chart and scene, and DIR/images/ (the runs' images, copied so
the folder can be moved or archived). Exits 1 with a message naming the file and run when an
input cannot be used; data that is merely missing is left out with a note on the page.
"""

import argparse
import re
import shutil
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from report_html import SceneSection, render_page  # noqa: E402
from report_results import (InputError, describe, front_keys, group_by_scene,  # noqa: E402
                            load_results, merge_runs, run_labels, setup_summary)

DEFAULT_TITLE = "ShadowPort measurement report"


def slug(text):
    return re.sub(r"[^A-Za-z0-9._-]+", "-", text).strip("-.") or "scene"


def unique_slugs(names):
    """{name: file-name-safe slug}, distinct even where two names slug alike."""
    taken = {}
    result = {}
    for name in names:
        base = candidate = slug(name)
        n = 2
        while candidate.lower() in taken:
            candidate = f"{base}-{n}"
            n += 1
        taken[candidate.lower()] = name
        result[name] = candidate
    return result


class ImageCopier:
    """Copies each distinct source image once into out/images/ as <folder>-<file name>, numbered
    if another source already took that name."""

    def __init__(self, out_dir):
        self.dir = out_dir / "images"
        self.copied = {}   # source path -> relative destination
        self.names = set()

    def copy(self, source):
        if source in self.copied:
            return self.copied[source]
        if not source.is_file():
            return None
        # Bench writes one folder per scene: keep the scene in the name (default-basic-gl-color.png).
        stem = f"{source.parent.name}-{source.stem}" if source.parent.name else source.stem
        name, n = f"{stem}{source.suffix}", 2
        while name.lower() in self.names:
            name = f"{stem}-{n}{source.suffix}"
            n += 1
        self.names.add(name.lower())
        self.dir.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(source, self.dir / name)
        self.copied[source] = f"images/{name}"
        return self.copied[source]


# (file suffix, heading, description, chart function name)
CHARTS = [
    ("speed-accuracy", "Speed vs accuracy",
     "One point per technique and parameter set; marker and colour give the backend. The step "
     "line is the Pareto front of each backend: the runs that no other run on that backend beats "
     "on both GPU time and misclassified pixels.", "speed_accuracy_chart"),
    ("error-categories", "Error categories",
     "The misclassified pixels split into light leaks (false lit) and acne or over-darkening "
     "(false shadow).", "error_categories_chart"),
    ("texel-density", "Perspective aliasing",
     "Shadow-map texels per screen pixel: the median and the worst 5% of pixels. Bars pointing "
     "left of 1 are undersampled.", "texel_density_chart"),
    ("flicker-series", "Flicker over time",
     "The shadow term's mean absolute change per frame along the camera pan.",
     "flicker_series_chart"),
    ("flicker", "Flicker",
     "The flicker metric per run: how much shadows crawl or shimmer when the camera moves.",
     "flicker_chart"),
    ("gpu-passes", "GPU time per pass",
     "The frame's GPU time split by pass; \"other\" is what the total has beyond the named "
     "passes.", "gpu_passes_chart"),
]

MISSING_CHART = {
    "speed_accuracy_chart": "no run has both gpu_ms.total and misclassified_pct",
    "error_categories_chart": "no run has false_lit_pct or false_shadow_pct",
    "texel_density_chart": "no run has texels_per_pixel_median or texels_per_pixel_p05",
    "flicker_series_chart": "no run has a flicker series",
    "flicker_chart": "no run has the flicker metric",
    "gpu_passes_chart": "no run has gpu_ms",
}


def build_sections(runs, out_dir, report_charts):
    scenes = group_by_scene(runs)
    slugs = unique_slugs(scenes)
    copier = ImageCopier(out_dir)
    sections = []
    for scene, scene_runs in scenes.items():
        section = SceneSection(name=scene, anchor=f"scene-{slugs[scene]}", runs=scene_runs,
                               subtitle=setup_summary(scene_runs),
                               front=front_keys(scene_runs))
        for r in scene_runs:
            section.notes.extend(r.notes)
        for suffix, heading, description, function in CHARTS:
            file_name = f"{slugs[scene]}-{suffix}.png"
            notes = getattr(report_charts, function)(scene, scene_runs, out_dir / file_name)
            if notes is None:
                section.notes.append(f"{heading}: chart skipped, {MISSING_CHART[function]}")
            else:
                section.charts.append((heading, file_name, description))
                section.notes.extend(notes)
        for r in scene_runs:
            copies = {}
            for kind, source in r.images.items():
                try:
                    copies[kind] = copier.copy(source)
                    problem = "not found"
                except OSError as e:
                    copies[kind] = None
                    problem = f"not copied ({e.strerror or e})"
                if copies[kind] is None:
                    section.notes.append(f"Images: {kind} image of {describe(r)} on {r.backend} "
                                         f"({r.where}) {problem}: {source}")
            if copies:
                section.images[r.key] = copies
        sections.append(section)
    return sections


def parse_args(argv):
    parser = argparse.ArgumentParser(
        prog="report.py", description="Charts and an HTML page from shadowport bench results.")
    parser.add_argument("results", nargs="+", type=Path, help="results JSON written by "
                        "`shadowport bench`; several files are merged")
    parser.add_argument("--out", required=True, type=Path, help="output folder (created)")
    parser.add_argument("--title", default=DEFAULT_TITLE, help="page title")
    parser.add_argument("--intro", help="a paragraph under the title: what was run and why")
    return parser.parse_args(argv)


def main(argv=None):
    args = parse_args(sys.argv[1:] if argv is None else argv)
    try:
        loaded = [load_results(path) for path in args.results]
    except InputError as e:
        print(f"report: error: {e}", file=sys.stderr)
        return 1
    runs, merge_notes = merge_runs(loaded)
    # Imported only now so that input errors are reported even where matplotlib is missing.
    try:
        import report_charts
    except ImportError as e:
        print(f"report: error: matplotlib is needed for the charts ({e}); on Debian: "
              "apt-get install python3-matplotlib", file=sys.stderr)
        return 1

    out_dir = args.out
    try:
        out_dir.mkdir(parents=True, exist_ok=True)
        sections = build_sections(runs, out_dir, report_charts)
        page = render_page(args.title, [(str(p), len(r)) for p, r in zip(args.results, loaded)],
                           sections, merge_notes, lambda s: run_labels(s.runs), args.intro)
        (out_dir / "index.html").write_text(page, encoding="utf-8")
    except OSError as e:
        print(f"report: error: cannot write to {out_dir}: {e}", file=sys.stderr)
        return 1
    charts = sum(len(s.charts) for s in sections)
    print(f"report: {len(runs)} runs, {len(sections)} scenes, {charts} charts -> "
          f"{out_dir / 'index.html'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
