"""Checks a `shadowport bench` results file: every run has every field the report and users rely
on, with values of the right type and range, and its images exist. Used by the CLI tests.

    check_bench_results.py results.json EXPECTED_RUNS
"""
import json
import math
import sys
from pathlib import Path

METRICS = ["misclassified_pct", "false_lit_pct", "false_shadow_pct", "mean_abs_error",
           "texels_per_pixel_median", "texels_per_pixel_p05", "max_aliasing_error", "storage_factor", "utilization", "flicker", "gpu_ms",
           "cpu_ms", "shadow_memory_bytes", "shadow_triangles"]


def fail(message):
    print(f"check_bench_results: {message}", file=sys.stderr)
    sys.exit(1)


def number(value):
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)


def main(path, expected_runs):
    path = Path(path)
    data = json.loads(path.read_text(encoding="utf-8"))
    runs = data.get("runs")
    if not isinstance(runs, list) or len(runs) != expected_runs:
        fail(f"expected {expected_runs} runs, got {runs if not isinstance(runs, list) else len(runs)}")
    for i, run in enumerate(runs):
        where = f"runs[{i}]"
        for key, kind in [("scene", str), ("technique", str), ("params", dict), ("backend", str),
                          ("size", list), ("frames", int), ("device", str), ("metrics", dict),
                          ("series", dict), ("images", dict)]:
            if not isinstance(run.get(key), kind):
                fail(f"{where}: \"{key}\" missing or not {kind.__name__}: {run.get(key)!r}")
        m = run["metrics"]
        for key in METRICS:
            if key not in m:
                fail(f"{where}: metrics.{key} missing")
        for key in METRICS:
            if key != "gpu_ms" and not number(m[key]):
                fail(f"{where}: metrics.{key} = {m[key]!r} is not a number")
        for key in ["misclassified_pct", "false_lit_pct", "false_shadow_pct"]:
            if not 0 <= m[key] <= 100:
                fail(f"{where}: metrics.{key} = {m[key]} outside [0, 100]")
        if abs(m["false_lit_pct"] + m["false_shadow_pct"] - m["misclassified_pct"]) > 1e-3:
            fail(f"{where}: false lit + false shadow != misclassified")
        if not 0 <= m["utilization"] <= 1 or not 0 <= m["mean_abs_error"] <= 1:
            fail(f"{where}: utilization or mean_abs_error outside [0, 1]")
        if not 0 < m["texels_per_pixel_p05"] <= m["texels_per_pixel_median"]:
            fail(f"{where}: texels per pixel p05 {m['texels_per_pixel_p05']} vs median "
                 f"{m['texels_per_pixel_median']}")
        # The worst frame's error is at least that of the worst 5 % over all frames.
        if not m["max_aliasing_error"] >= 0.999 / m["texels_per_pixel_p05"] or not m["storage_factor"] > 0:
            fail(f"{where}: max aliasing error {m['max_aliasing_error']} (1 / p05 = {1 / m['texels_per_pixel_p05']}), "
                 f"storage factor {m['storage_factor']}")
        gpu = m["gpu_ms"]
        for key in ["shadow", "lit", "total"]:
            if not number(gpu.get(key)) or gpu[key] < 0:
                fail(f"{where}: metrics.gpu_ms.{key} = {gpu.get(key)!r}")
        if run["size"] != [160, 90] or run["frames"] != 3:
            fail(f"{where}: size {run['size']} frames {run['frames']}")
        if len(run["series"].get("flicker", [])) != run["frames"] - 1:
            fail(f"{where}: series.flicker should have one value per frame after the first")
        for kind in ["color", "error", "texel_density", "reference"]:
            image = path.parent / run["images"].get(kind, "")
            if not image.is_file():
                fail(f"{where}: image {kind} not found: {image}")
        if not isinstance(run.get("params_given"), dict):
            fail(f"{where}: \"params_given\" missing or not an object")
        if not isinstance(run["checks"].get("validation_enabled"), bool):
            fail(f"{where}: checks.validation_enabled missing or not a bool")
        # Every backend after the first is compared with the first one's picture.
        cross = run.get("cross_backend")
        first = runs[0]["backend"]
        if (cross is None) != (run["backend"] == first):
            fail(f"{where}: cross_backend {cross!r} on backend {run['backend']} (first: {first})")
        if cross is not None:
            w, h = run["size"]
            if cross.get("against") != first or cross.get("pixels") != w * h \
                    or not 0 <= cross.get("differing_pixels", -1) <= w * h \
                    or not 0 <= cross.get("max_difference", -1) <= 255:
                fail(f"{where}: cross_backend {cross!r}")
            if not (path.parent / run["images"].get("backend_diff", "")).is_file():
                fail(f"{where}: no backend_diff image")
    print(f"check_bench_results: {len(runs)} runs OK")


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]))
