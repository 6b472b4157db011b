#!/usr/bin/python3
"""Tests of the report generator: the data rules (Pareto front, labels, merging), the handling of
malformed input, and whole runs of report.py on the fixtures in testdata/.

    /usr/bin/python3 eval/report/test_report.py [TestClass ...]
"""

import json
import struct
import subprocess
import sys
import tempfile
import unittest
import zlib
from html.parser import HTMLParser
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from report_results import (InputError, Run, backend_groups, front_keys,  # noqa: E402
                            load_results, merge_runs, pareto_front, run_labels, technique_labels)

REPORT = HERE / "report.py"
TESTDATA = HERE / "testdata"
VULKAN = TESTDATA / "results-vulkan.json"
GL = TESTDATA / "results-gl.json"
PARTIAL = TESTDATA / "results-partial.json"
CHART_KINDS = ["speed-accuracy", "error-categories", "texel-density", "flicker-series", "flicker",
               "gpu-passes"]


def make_run(technique="basic", params=None, backend="vulkan", scene="s", metrics=None, index=0):
    return Run(scene=scene, technique=technique, params=dict(params or {}), backend=backend,
               metrics=dict(metrics or {}), source=Path("x.json"), index=index)


def run_report(*args):
    return subprocess.run([sys.executable, str(REPORT), *map(str, args)], capture_output=True,
                          text=True, timeout=300)


def png_size(path):
    """(width, height) of a PNG after checking its signature, IHDR checksum and IEND trailer."""
    data = Path(path).read_bytes()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise AssertionError(f"{path}: not a PNG signature")
    length, kind = struct.unpack(">I4s", data[8:16])
    if kind != b"IHDR" or length != 13:
        raise AssertionError(f"{path}: first chunk is not IHDR")
    (crc,) = struct.unpack(">I", data[29:33])
    if zlib.crc32(data[12:29]) != crc:
        raise AssertionError(f"{path}: IHDR checksum mismatch")
    if data[-8:-4] != b"IEND":
        raise AssertionError(f"{path}: no IEND chunk at the end")
    return struct.unpack(">II", data[16:24])


class References(HTMLParser):
    """Every img src and a href of a page."""

    def __init__(self):
        super().__init__()
        self.images, self.links = [], []

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if tag == "img":
            self.images.append(attrs.get("src"))
        elif tag == "a":
            self.links.append(attrs.get("href"))


def references(html):
    parser = References()
    parser.feed(html)
    return parser


class ParetoFrontTest(unittest.TestCase):
    def test_known_front(self):
        points = [(5.0, 9.0),   # 0: fastest
                  (6.0, 4.0),   # 1: front
                  (7.0, 5.0),   # 2: dominated by 1
                  (8.0, 2.0),   # 3: front
                  (9.0, 2.0),   # 4: dominated by 3 (slower, same accuracy)
                  (6.0, 6.0),   # 5: dominated by 1 (same time, less accurate)
                  (12.0, 0.5)]  # 6: most accurate
        self.assertEqual(pareto_front(points), [0, 1, 3, 6])

    def test_identical_points_both_stay(self):
        self.assertEqual(pareto_front([(2.0, 2.0), (1.0, 3.0), (2.0, 2.0)]), [1, 0, 2])

    def test_order_is_by_time(self):
        self.assertEqual(pareto_front([(3.0, 1.0), (1.0, 3.0), (2.0, 2.0)]), [1, 2, 0])

    def test_one_point_dominating_all(self):
        self.assertEqual(pareto_front([(2.0, 2.0), (1.0, 1.0), (3.0, 1.5)]), [1])

    def test_empty_and_single(self):
        self.assertEqual(pareto_front([]), [])
        self.assertEqual(pareto_front([(4.0, 4.0)]), [0])

    def test_front_is_per_backend(self):
        def timed(technique, backend, ms, pct=None):
            metrics = {"gpu_ms.total": ms}
            if pct is not None:
                metrics["misclassified_pct"] = pct
            return make_run(technique, backend=backend, metrics=metrics)

        runs = [timed("a", "vulkan", 1, 5), timed("b", "vulkan", 2, 6), timed("a", "gl", 3, 7),
                timed("c", "gl", 4), timed("d", "gl", 5, 1)]
        fronts = {(k[1], k[3]) for k in front_keys(runs)}
        # gl's "a" is worse than vulkan's "a" but still on gl's own front; "c" has no accuracy.
        self.assertEqual(fronts, {("a", "vulkan"), ("a", "gl"), ("d", "gl")})


class LabelTest(unittest.TestCase):
    def test_only_varying_params_named(self):
        runs = [make_run("csm", {"cascades": "2", "split": "pssm", "size": "2048"}),
                make_run("csm", {"cascades": "4", "split": "pssm", "size": "2048"}),
                make_run("csm", {"cascades": "4", "split": "uniform", "size": "2048"})]
        labels = technique_labels(runs)
        self.assertEqual(sorted(labels.values()), ["csm cascades=2 split=pssm",
                                                   "csm cascades=4 split=pssm",
                                                   "csm cascades=4 split=uniform"])

    def test_single_variant_is_technique_alone(self):
        runs = [make_run("vsm", {"size": "2048", "blur": "5"}),
                make_run("pcf", {"kernel": "3"}), make_run("pcf", {"kernel": "5"})]
        labels = technique_labels(runs)
        self.assertEqual(labels[("vsm", runs[0].params_key)], "vsm")
        self.assertEqual(labels[("pcf", runs[1].params_key)], "pcf kernel=3")

    def test_numeric_params_sort_naturally_and_stay_distinct(self):
        runs = [make_run("basic", {"size": s}) for s in ("512", "1024", "4096")]
        labels = technique_labels(runs)
        self.assertEqual(len(set(labels.values())), 3)
        self.assertIn("basic size=1024", labels.values())

    def test_param_present_in_one_variant_only(self):
        runs = [make_run("sdsm", {}), make_run("sdsm", {"cascades": "8"})]
        labels = technique_labels(runs)
        self.assertEqual(sorted(labels.values()), ["sdsm", "sdsm cascades=8"])

    def test_backend_named_only_when_several(self):
        one = [make_run("pcf", {"kernel": "3"}), make_run("pcf", {"kernel": "5"})]
        self.assertEqual(sorted(run_labels(one).values()), ["pcf kernel=3", "pcf kernel=5"])
        two = one + [make_run("pcf", {"kernel": "3"}, backend="gl")]
        self.assertEqual(sorted(run_labels(two).values()),
                         ["pcf kernel=3 [gl]", "pcf kernel=3 [vulkan]", "pcf kernel=5 [vulkan]"])

    def test_variants_named_by_the_parameters_they_were_given(self):
        def csm(filter_, kernel, given):
            run = make_run("csm", {"filter": filter_, "kernel": kernel, "cascades": "4"})
            run.params_given = given
            return run
        runs = [csm("hw2x2", "3", {}), csm("gauss", "5", {"filter": "gauss", "kernel": "5"}),
                csm("msm", "3", {"filter": "msm"})]
        self.assertEqual([technique_labels(runs)[("csm", r.params_key)] for r in runs],
                         ["csm", "csm filter=gauss kernel=5", "csm filter=msm"])
        # Alone, a variant is named by everything it was given.
        self.assertEqual(technique_labels(runs[1:2])[("csm", runs[1].params_key)],
                         "csm filter=gauss kernel=5")
        self.assertEqual(technique_labels(runs[:1])[("csm", runs[0].params_key)], "csm")
        # Without that information every varying parameter is named.
        for r in runs:
            r.params_given = None
        self.assertIn("csm filter=msm kernel=3", technique_labels(runs).values())

    def test_given_parameters_that_name_two_variants_alike_are_not_used(self):
        a, b = make_run("t", {"a": "1", "b": "2"}), make_run("t", {"a": "1", "b": "3"})
        a.params_given = b.params_given = {"a": "1"}
        self.assertEqual(sorted(technique_labels([a, b]).values()), ["t b=2", "t b=3"])

    def test_fixture_labels_unique_per_scene(self):
        runs, _ = merge_runs([load_results(VULKAN), load_results(GL)])
        for scene in {r.scene for r in runs}:
            mine = [r for r in runs if r.scene == scene]
            labels = run_labels(mine)
            self.assertEqual(len(set(labels.values())), len(mine), scene)


class MergeTest(unittest.TestCase):
    def test_fixture_files_merge(self):
        vulkan, gl = load_results(VULKAN), load_results(GL)
        runs, notes = merge_runs([vulkan, gl])
        self.assertEqual(len(runs), len(vulkan) + len(gl))
        self.assertEqual(notes, [])
        self.assertEqual({r.backend for r in runs}, {"vulkan", "gl"})
        self.assertEqual(list(dict.fromkeys(r.scene for r in runs)),
                         ["ShadowColumns", "TankScene", "FlightHelmet"])
        columns = [r for r in runs if r.scene == "ShadowColumns"]
        pairs = {(t, dict(p).get("size")) for t, p, _ in backend_groups(columns)}
        self.assertIn(("basic", "2048"), pairs)
        self.assertEqual(len(backend_groups(columns)), 4)

    def test_later_measurement_replaces_earlier(self):
        with tempfile.TemporaryDirectory() as tmp:
            first, second = Path(tmp, "first.json"), Path(tmp, "second.json")
            run = {"scene": "s", "technique": "t", "params": {"k": "1"}, "backend": "vulkan"}
            first.write_text(json.dumps({"runs": [dict(run, metrics={"flicker": 1.0}),
                                                  dict(run, backend="gl", metrics={})]}))
            second.write_text(json.dumps({"runs": [dict(run, metrics={"flicker": 2.0})]}))
            runs, notes = merge_runs([load_results(first), load_results(second)])
        self.assertEqual(len(runs), 2)
        self.assertEqual(runs[0].metric("flicker"), 2.0)
        self.assertEqual(runs[0].source.name, "second.json")
        self.assertEqual(len(notes), 1)
        self.assertIn("second.json: runs[0] replaces first.json: runs[0]", notes[0])

    def test_params_differ_so_runs_kept_apart(self):
        a = make_run("csm", {"cascades": "2"})
        b = make_run("csm", {"cascades": "4"})
        runs, notes = merge_runs([[a], [b]])
        self.assertEqual((len(runs), notes), (2, []))

    def test_metrics_flattened_and_nulls_kept_missing(self):
        runs = load_results(GL)
        csm = [r for r in runs if r.scene == "TankScene" and r.technique == "csm"][0]
        self.assertIsNone(csm.metric("gpu_ms.total"))
        self.assertEqual(runs[0].metric("gpu_ms.total"), 5.83)
        self.assertEqual(runs[0].metric("shadow_triangles"), 16646.0)

    def test_image_paths_are_relative_to_the_results_file(self):
        run = [r for r in load_results(VULKAN) if r.images][0]
        for path in run.images.values():
            self.assertTrue(path.is_absolute())
            self.assertTrue(path.is_file(), path)
            self.assertEqual(path.parent, TESTDATA / "images")

    def test_partial_fixture_loads_with_notes(self):
        runs = load_results(PARTIAL)
        self.assertEqual(len(runs), 4)
        self.assertEqual(runs[0].params, {"size": "2048", "filter": "none"})
        self.assertEqual(runs[0].metric("contact_hardening_error"), 0.12)
        self.assertIsNone(runs[2].metric("misclassified_pct"))
        notes = " ".join(n for r in runs for n in r.notes)
        self.assertIn("misclassified_pct = \"n/a\" is not a number", notes)
        self.assertIn("series \"flicker\"", notes)
        self.assertIn("\"images\" is not an object", notes)


class MalformedInputTest(unittest.TestCase):
    """Unusable input: exit status 1 and one line naming the file (and the run), no traceback."""

    CASES = {
        "not-json": ("{\"runs\": [", r"not valid JSON"),
        "array": ("[1, 2]", "expected a JSON object with a \"runs\" array"),
        "no-runs": ("{\"results\": []}", "no \"runs\" array"),
        "runs-object": ("{\"runs\": {}}", "\"runs\" must be an array"),
        "run-not-object": ("{\"runs\": [\"csm\"]}", "runs[0]: expected an object"),
        "no-scene": (None, "runs[1]: missing \"scene\""),
        "no-technique": (None, "runs[1]: missing \"technique\""),
        "no-backend": (None, "runs[1]: missing \"backend\""),
        "no-metrics": (None, "runs[1]: missing \"metrics\""),
        "metrics-not-object": (None, "runs[1]: \"metrics\" must be an object"),
        "empty-scene": (None, "runs[1]: \"scene\" must be a non-empty string"),
        "params-not-object": (None, "runs[1]: \"params\" must be an object"),
    }

    @staticmethod
    def second_run_broken(case):
        good = {"scene": "s", "technique": "t", "backend": "vulkan", "metrics": {"flicker": 0.1}}
        bad = dict(good)
        if case.startswith("no-"):
            del bad[case[3:]]
        elif case == "metrics-not-object":
            bad["metrics"] = [1, 2]
        elif case == "empty-scene":
            bad["scene"] = ""
        elif case == "params-not-object":
            bad["params"] = "cascades=4"
        return json.dumps({"runs": [good, bad]})

    def check(self, text, expected, good_first=False):
        with tempfile.TemporaryDirectory() as tmp:
            bad = Path(tmp, "broken-results.json")
            bad.write_text(text)
            inputs = [VULKAN, bad] if good_first else [bad]
            result = run_report(*inputs, "--out", Path(tmp, "out"))
            self.assertEqual(result.returncode, 1, result.stderr)
            self.assertIn(str(bad), result.stderr)
            self.assertIn(expected, result.stderr)
            self.assertNotIn("Traceback", result.stderr)
            self.assertFalse(Path(tmp, "out", "index.html").exists())

    def test_cases(self):
        for case, (text, expected) in self.CASES.items():
            with self.subTest(case=case):
                self.check(text if text is not None else self.second_run_broken(case), expected)

    def test_second_file_named(self):
        self.check(self.second_run_broken("no-backend"), "runs[1]: missing \"backend\"",
                   good_first=True)

    def test_missing_file(self):
        with tempfile.TemporaryDirectory() as tmp:
            missing = Path(tmp, "nowhere.json")
            result = run_report(missing, "--out", Path(tmp, "out"))
        self.assertEqual(result.returncode, 1)
        self.assertIn(f"{missing}: cannot read", result.stderr)
        self.assertNotIn("Traceback", result.stderr)

    def test_load_results_raises_input_error(self):
        with tempfile.TemporaryDirectory() as tmp:
            path = Path(tmp, "r.json")
            path.write_text(self.second_run_broken("no-metrics"))
            with self.assertRaisesRegex(InputError, r"r\.json: runs\[1\]: missing \"metrics\""):
                load_results(path)


class EndToEndTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.out = Path(cls.tmp.name, "report")
        cls.result = run_report(VULKAN, GL, "--out", cls.out, "--title", "Fixture <lab> run")
        cls.html = (cls.out / "index.html").read_text(encoding="utf-8") \
            if (cls.out / "index.html").exists() else ""

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_exits_cleanly(self):
        self.assertEqual(self.result.returncode, 0, self.result.stderr)
        self.assertEqual(self.result.stderr, "")
        self.assertIn("26 runs, 3 scenes", self.result.stdout)

    def test_expected_charts_are_valid_pngs(self):
        scenes = ("ShadowColumns", "TankScene", "FlightHelmet")
        expected = {f"{scene}-{kind}.png" for scene in scenes for kind in CHART_KINDS}
        # TankScene has no run with a flicker series.
        expected.discard("TankScene-flicker-series.png")
        found = {p.name for p in self.out.glob("*.png")}
        self.assertEqual(found, expected)
        for name in expected:
            width, height = png_size(self.out / name)
            self.assertGreaterEqual(width, 600, name)
            self.assertGreaterEqual(height, 250, name)

    def test_page_references_every_chart_and_only_existing_files(self):
        refs = references(self.html)
        charts = {src for src in refs.images if not src.startswith("images/")}
        self.assertEqual(charts, {p.name for p in self.out.glob("*.png")})
        for ref in refs.images + refs.links:
            if ref.startswith("#"):
                continue
            self.assertNotIn("://", ref)
            self.assertTrue((self.out / ref).is_file(), ref)

    def test_run_images_are_copied(self):
        refs = references(self.html)
        copied = {src for src in refs.images if src.startswith("images/")}
        # 4 ShadowColumns runs and 1 TankScene run with 3 images each, and 2 references.
        self.assertEqual(len(copied), 17)
        for src in copied:
            png_size(self.out / src)

    def test_page_content(self):
        html = self.html
        self.assertTrue(html.startswith("<!DOCTYPE html>"))
        self.assertIn("<title>Fixture &lt;lab&gt; run</title>", html)
        self.assertNotIn("<script", html)
        for scene in ("ShadowColumns", "TankScene", "FlightHelmet"):
            self.assertIn(f"<h2>Scene: {scene}</h2>", html)
        for term in ("misclassified_pct", "false_lit_pct", "false_shadow_pct", "utilization",
                     "flicker", "texels_per_pixel_median", "the reference has zero"):
            self.assertIn(term, html)
        self.assertEqual(html.count("<h3>Cross-backend</h3>"), 2)  # not FlightHelmet: vulkan only
        self.assertEqual(html.count("<h3>Cost</h3>"), 3)
        self.assertIn("16.0</td>", html)  # 16 MiB shadow map in the cost table
        self.assertIn("Flicker over time: chart skipped, no run has a flicker series", html)
        self.assertIn("Speed vs accuracy: not plotted, no gpu_ms.total: csm cascades=4 "
                      "split=pssm on gl (results-gl.json: runs[5])", html)
        self.assertIn("not plotted, no misclassified_pct: csm cascades=4 split=uniform on vulkan",
                      html)

    def test_partial_input_gives_page_with_notes(self):
        with tempfile.TemporaryDirectory() as tmp:
            out = Path(tmp, "out")
            result = run_report(PARTIAL, "--out", out)
            self.assertEqual(result.returncode, 0, result.stderr)
            self.assertNotIn("Traceback", result.stderr)
            html = (out / "index.html").read_text(encoding="utf-8")
            # The scene name has a space and a slash; its files must still be plain names.
            self.assertTrue((out / "city-at-night-2-speed-accuracy.png").is_file())
            self.assertIn("does-not-exist.png", html)
            self.assertIn("missing file", html)
            self.assertIn("contact_hardening_error", html)
            self.assertIn("is not a number; treated as missing", html)
            for src in references(html).images:
                self.assertTrue((out / src).is_file(), src)

    def test_awkward_names(self):
        # '$' would start matplotlib's mathtext, '<' is HTML, and both scenes slug to "a-b".
        metrics = {"misclassified_pct": 1.0, "false_lit_pct": 0.4, "false_shadow_pct": 0.6,
                   "flicker": 0.01, "gpu_ms": {"total": 3.0}}
        runs = [{"scene": scene, "technique": "t_$x^", "params": {"k": "$1"}, "backend": "vulkan",
                 "device": "dev <b>", "metrics": metrics} for scene in ("a$b", "a b")]
        with tempfile.TemporaryDirectory() as tmp:
            path, out = Path(tmp, "r.json"), Path(tmp, "out")
            path.write_text(json.dumps({"runs": runs}))
            result = run_report(path, "--out", out)
            self.assertEqual(result.returncode, 0, result.stderr)
            self.assertTrue((out / "a-b-speed-accuracy.png").is_file())
            self.assertTrue((out / "a-b-2-speed-accuracy.png").is_file())
            html = (out / "index.html").read_text(encoding="utf-8")
            self.assertIn("dev &lt;b&gt;", html)
            self.assertNotIn("dev <b>", html)

    def test_no_runs_still_writes_a_page(self):
        with tempfile.TemporaryDirectory() as tmp:
            empty = Path(tmp, "empty.json")
            empty.write_text("{\"runs\": []}")
            result = run_report(empty, "--out", Path(tmp, "out"))
            self.assertEqual(result.returncode, 0, result.stderr)
            self.assertIn("holds no runs", Path(tmp, "out", "index.html").read_text())


def write_png(path, width, height, rgb=(128, 128, 128)):
    """A plain RGB PNG of one colour."""
    def chunk(kind, data):
        return (struct.pack(">I", len(data)) + kind + data
                + struct.pack(">I", zlib.crc32(kind + data)))
    raw = b"".join(b"\x00" + bytes(rgb) * width for _ in range(height))
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    Path(path).write_bytes(b"\x89PNG\r\n\x1a\n"
                           + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
                           + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def demo_runs(tmp, cross=None, checks=None):
    """Two techniques on two backends, with the images bench writes, as a results file; `cross`
    maps technique -> the gl run's cross_backend, `checks` (backend, technique) -> checks."""
    runs = []
    for technique, params in (("basic", {}), ("csm", {"filter": "gauss"})):
        for backend in ("vulkan", "gl"):
            stem = f"s/{technique}-{backend}"
            images = {"color": f"img/{stem}-color.png", "error": f"img/{stem}-error.png"}
            for rel in images.values():
                write_png(Path(tmp, rel), 50, 20)
            gpu = {"total": 2.0, "moments": 0.75} if technique == "csm" else {"total": 2.0}
            run = {"scene": "s", "technique": technique, "params": params, "backend": backend,
                   "device": "dev", "size": [50, 20],
                   "metrics": {"misclassified_pct": 1.0, "false_lit_pct": 0.5,
                               "false_shadow_pct": 0.5, "gpu_ms": gpu},
                   "images": images}
            if backend == "gl" and cross and technique in cross:
                run["cross_backend"] = cross[technique]
                run["images"]["backend_diff"] = f"img/{stem}-vs-vulkan-diff.png"
                write_png(Path(tmp, run["images"]["backend_diff"]), 50, 24, (200, 30, 30))
            if checks and (backend, technique) in checks:
                run["checks"] = checks[(backend, technique)]
            runs.append(run)
    path = Path(tmp, "results.json")
    path.write_text(json.dumps({"runs": runs}))
    return path


def page_of(results, *args):
    out = results.parent / "report"
    result = run_report(results, "--out", out, *args)
    if result.returncode != 0:
        raise AssertionError(result.stderr)
    return out, (out / "index.html").read_text(encoding="utf-8")


class CrossBackendTest(unittest.TestCase):
    SAME = {"against": "vulkan", "image": "color", "pixels": 1000, "differing_pixels": 0,
            "max_difference": 0}
    DIFFERENT = {"against": "vulkan", "image": "color", "pixels": 1000, "differing_pixels": 12,
                 "max_difference": 3}

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        results = demo_runs(cls.tmp.name, cross={"basic": cls.SAME, "csm": cls.DIFFERENT})
        cls.out, cls.html = page_of(results)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_section_shows_both_pictures_the_difference_and_the_counts(self):
        out, html = self.out, self.html
        page = references(html)
        self.assertEqual(html.count("<h3>Cross-backend</h3>"), 1)
        self.assertIn("<b>1 of 2</b> comparisons of gl against vulkan: bit-identical first "
                      "frame.", html)
        self.assertIn("0 of 1,000 pixels differ: <b>bit-identical</b>", html)
        self.assertIn("12 of 1,000 pixels differ (1.2 %), largest channel difference 3 of "
                      "255", html)
        diffs = [src for src in page.images if src.endswith("-diff.png")]
        self.assertEqual(len(diffs), 2)
        for src in page.images:
            png_size(out / src)
        # Difference images appear in the cross-backend section only, not as an images column.
        self.assertNotIn("<th>backend_diff</th>", html)
        # The order of the section: chart, figures, pictures, then the backends compared.
        order = [html.index(h) for h in ("<h3>Speed vs accuracy</h3>", "<h3>All metrics</h3>",
                                         "<h3>Images</h3>", "<h3>Cross-backend</h3>",
                                         "<h3>Cost</h3>")]
        self.assertEqual(order, sorted(order))

    def test_passes_a_technique_names_itself_are_costed(self):
        cost = self.html[self.html.index("<h3>Cost</h3>"):]
        self.assertIn("<th>GPU moments (ms)</th>", cost)
        self.assertIn('<td class="num">0.75</td>', cost)

    def test_bit_identical_runs_share_one_images_row(self):
        html = self.html
        images = html[html.index("<h3>Images</h3>"):html.index("<h3>Cross-backend</h3>")]
        self.assertIn("basic [vulkan = gl]", images)
        self.assertNotIn("basic [gl]", images)
        # Different pictures keep a row per backend.
        self.assertIn("csm [vulkan]", images)
        self.assertIn("csm [gl]", images)

    def test_malformed_comparison_is_noted_and_left_out(self):
        with tempfile.TemporaryDirectory() as tmp:
            bad = dict(self.DIFFERENT, differing_pixels=5000)   # more than there are pixels
            results = demo_runs(tmp, cross={"basic": {"against": "vulkan"}, "csm": bad})
            _, html = page_of(results)
            self.assertEqual(html.count("is not a comparison"), 2)
            self.assertNotIn("pixels differ", html)
            self.assertIn("basic [gl]", html)


class ValidationTest(unittest.TestCase):
    def test_clean_validated_runs_are_stated_and_the_intro_escaped(self):
        on = {"validation_enabled": True, "validation_errors": 0}
        with tempfile.TemporaryDirectory() as tmp:
            checks = {(b, t): on for b in ("vulkan", "gl") for t in ("basic", "csm")}
            _, html = page_of(demo_runs(tmp, checks=checks), "--title", "Demo", "--intro",
                              "4 <techniques>")
            self.assertIn("on in 4 of 4 runs; 0 errors.", html)
            self.assertNotIn('class="error"', html)
            self.assertIn("<h1>Demo</h1>\n<p>4 &lt;techniques&gt;</p>", html)

    def test_errors_are_shown_with_the_run_and_the_message(self):
        on = {"validation_enabled": True, "validation_errors": 0}
        failed = {"validation_enabled": True, "validation_errors": 3,
                  "last_validation_error": "vkCmdDraw: <bad> descriptor"}
        with tempfile.TemporaryDirectory() as tmp:
            checks = {("vulkan", "basic"): on, ("gl", "basic"): on, ("vulkan", "csm"): failed,
                      ("gl", "csm"): on}
            _, html = page_of(demo_runs(tmp, checks=checks))
            self.assertIn('class="error"', html)
            self.assertIn("3 validation error(s) in 1 run(s)", html)
            self.assertIn("csm filter=gauss on vulkan: 3 error(s); last: "
                          "<code>vkCmdDraw: &lt;bad&gt; descriptor</code>", html)
            self.assertLess(html.index('class="error"'), html.index("<h2>Scene: s</h2>"))

    def test_runs_without_validation_say_so_and_old_files_say_nothing(self):
        off = {"validation_enabled": False, "validation_errors": 0}
        with tempfile.TemporaryDirectory() as tmp:
            _, html = page_of(demo_runs(tmp, checks={("vulkan", "basic"): off}))
            self.assertIn("on in 0 of 1 runs (off:", html)
        with tempfile.TemporaryDirectory() as tmp:
            _, html = page_of(demo_runs(tmp))
            self.assertNotIn("Validation (", html)


if __name__ == "__main__":
    unittest.main(verbosity=2)
