"""Reading, checking and merging the results files written by `shadowport bench`.

Nothing here imports matplotlib, so the data rules can be tested (and reused by scripts) without
a plotting stack.
"""

import json
import math
import re
from dataclasses import dataclass, field
from pathlib import Path


class InputError(Exception):
    """A results file that cannot be used at all; the message names the file and the run."""


# The metrics the report knows, in the order tables show them. A flattened name joins nested
# objects with a dot ("gpu_ms.total"). `scale` turns the stored value into the shown unit.
@dataclass(frozen=True)
class Metric:
    name: str
    heading: str
    unit: str
    fmt: str
    meaning: str
    scale: float = 1.0


METRICS = [
    Metric("misclassified_pct", "misclassified", "%", "{:.2f}",
           "pixels that can receive light (facing the light) whose lit/shadowed state differs from "
           "the ray-traced reference, in % of those pixels; lower is better"),
    Metric("false_lit_pct", "false lit", "%", "{:.2f}",
           "% of lit-receiving pixels lit although the reference is in shadow: light leaks "
           "(peter-panning, light bleeding)"),
    Metric("false_shadow_pct", "false shadow", "%", "{:.2f}",
           "% of lit-receiving pixels in shadow although the reference is lit: shadow acne, "
           "over-darkening"),
    Metric("seam_misclassified_pct", "seam band misclassified", "%", "{:.2f}",
           "misclassified % of the judged pixels within one face texel of an edge between two "
           "faces of the judged point light's shadow cube (docs/local-lights.md, Seam metric)"),
    Metric("off_seam_misclassified_pct", "off-seam misclassified", "%", "{:.2f}",
           "misclassified % of the judged pixels away from the cube-face edges; a seam band "
           "figure above it points at errors of the seams themselves"),
    Metric("mean_abs_error", "mean |error|", "", "{:.4f}",
           "mean absolute difference of the shadow term (0 = shadow, 1 = lit) from the reference; "
           "with an area light (checks.light_size > 0) the reference is the fraction of the light "
           "visible, so this judges the penumbra's shape, not only which side of 0.5 a pixel is"),
    Metric("texels_per_pixel_median", "texels/px median", "", "{:.3g}",
           "shadow-map texels per screen pixel, median over receiving pixels; below 1 = "
           "undersampled (blocky, jagged shadow edges)"),
    Metric("texels_per_pixel_p05", "texels/px p05", "", "{:.3g}",
           "5th percentile of texels per pixel: how badly the worst-sampled 5% of pixels fare"),
    Metric("max_aliasing_error", "max aliasing error", "px", "{:.3g}",
           "largest projected size of a shadow texel in pixels over the visible receivers, worst "
           "frame (Lloyd et al.; 99.9th percentile over pixels); above 1 = visible texels"),
    Metric("storage_factor", "storage factor", "", "{:.3g}",
           "shadow-map texels needed, per screen pixel, for a maximum aliasing error of 1 "
           "(the map's texels times the error squared, over the pixels)"),
    Metric("utilization", "utilization", "", "{:.2f}",
           "fraction of shadow texels sampled by at least one pixel (1 = no texel wasted)"),
    Metric("flicker", "flicker", "", "{:.3g}",
           "mean absolute change of the shadow term at the same world point between consecutive "
           "frames on a slow camera pan; the reference has zero"),
    Metric("gpu_ms.shadow", "GPU shadow", "ms", "{:.2f}",
           "GPU time of the shadow passes per frame, in ms"),
    Metric("gpu_ms.lit", "GPU lit", "ms", "{:.2f}",
           "GPU time of the lit (shading) pass per frame, in ms"),
    Metric("gpu_ms.analysis", "GPU analysis", "ms", "{:.2f}",
           "GPU time of the technique's analysis pass (e.g. depth-range reduction) per "
           "frame, in ms"),
    Metric("gpu_ms.total", "GPU total", "ms", "{:.2f}", "GPU time of the whole frame, in ms"),
    Metric("cpu_ms", "CPU", "ms", "{:.2f}", "CPU time to record and submit a frame, in ms"),
    Metric("shadow_memory_bytes", "shadow memory", "MiB", "{:.1f}",
           "memory held by shadow maps and the technique's other resources, in MiB",
           1.0 / (1024 * 1024)),
    Metric("shadow_triangles", "shadow triangles", "", "{:,.0f}",
           "triangles submitted to the shadow passes per frame"),
]
METRIC_BY_NAME = {m.name: m for m in METRICS}

IMAGE_KINDS = [("color", "color"), ("error", "error heat map"),
               ("texel_density", "texel density"), ("reference", "reference")]
# Bench's picture of where a run's first frame differs from the same run on the first backend.
BACKEND_DIFF = "backend_diff"


@dataclass
class Run:
    scene: str
    technique: str
    params: dict
    backend: str
    metrics: dict              # flattened name -> float or None
    source: Path
    index: int
    device: str = None
    size: tuple = None
    frames: int = None
    series: dict = field(default_factory=dict)   # name -> list of float
    images: dict = field(default_factory=dict)   # kind -> absolute Path (may not exist)
    notes: list = field(default_factory=list)
    # Validation layers / GL debug output: None where the results do not say (older files).
    validation_enabled: bool = None
    validation_errors: int = None
    last_validation_error: str = None
    # {"against": backend, "pixels", "differing_pixels", "max_difference"} or None.
    cross_backend: dict = None
    # The parameters the bench was given (the rest are defaults); None where the file does not say.
    params_given: dict = None

    @property
    def params_key(self):
        return tuple(sorted(self.params.items()))

    @property
    def key(self):
        return (self.scene, self.technique, self.params_key, self.backend)

    @property
    def where(self):
        return f"{self.source.name}: runs[{self.index}]"

    def metric(self, name):
        return self.metrics.get(name)


def _number(value):
    """The value as a finite float, or None when it is not one (bools are not numbers here)."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return None
    value = float(value)
    return value if math.isfinite(value) else None


def _flatten_metrics(obj, prefix, out, notes, where):
    for name, value in obj.items():
        full = f"{prefix}{name}"
        if isinstance(value, dict):
            _flatten_metrics(value, full + ".", out, notes, where)
        elif value is None:
            out[full] = None
        else:
            number = _number(value)
            if number is None:
                notes.append(f"{where}: metric {full} = {json.dumps(value)} is not a number; "
                             "treated as missing")
            out[full] = number


def _param_text(value):
    if isinstance(value, str):
        return value
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float) and value.is_integer():
        return str(int(value))
    return json.dumps(value) if isinstance(value, (dict, list)) else str(value)


def _require_text(raw, name, where):
    value = raw.get(name)
    if value is None:
        raise InputError(f"{where}: missing \"{name}\"")
    if not isinstance(value, str) or not value.strip():
        raise InputError(f"{where}: \"{name}\" must be a non-empty string, got {json.dumps(value)}")
    return value


def parse_run(raw, source, index):
    """One element of "runs"; raises InputError for what the report cannot work without and notes
    (on the run) what it can do without."""
    where = f"{source}: runs[{index}]"
    if not isinstance(raw, dict):
        raise InputError(f"{where}: expected an object, got {type(raw).__name__}")
    scene = _require_text(raw, "scene", where)
    technique = _require_text(raw, "technique", where)
    backend = _require_text(raw, "backend", where)
    if "metrics" not in raw:
        raise InputError(f"{where}: missing \"metrics\"")
    if not isinstance(raw["metrics"], dict):
        raise InputError(f"{where}: \"metrics\" must be an object, "
                         f"got {json.dumps(raw['metrics'])}")
    params = raw.get("params") or {}
    if not isinstance(params, dict):
        raise InputError(f"{where}: \"params\" must be an object, got {json.dumps(params)}")

    run = Run(scene=scene, technique=technique, backend=backend,
              params={str(k): _param_text(v) for k, v in params.items()},
              metrics={}, source=Path(source), index=index)
    short = run.where
    given = raw.get("params_given")
    if isinstance(given, dict):
        run.params_given = {str(k): _param_text(v) for k, v in given.items()}
    elif given is not None:
        run.notes.append(f"{short}: \"params_given\" is not an object; ignored")
    _flatten_metrics(raw["metrics"], "", run.metrics, run.notes, short)

    device = raw.get("device")
    run.device = device if isinstance(device, str) and device else None
    size = raw.get("size")
    if isinstance(size, list) and len(size) == 2 and all(_number(v) for v in size):
        run.size = (int(size[0]), int(size[1]))
    elif size is not None:
        run.notes.append(f"{short}: \"size\" {json.dumps(size)} is not [width, height]; ignored")
    frames = _number(raw.get("frames"))
    run.frames = int(frames) if frames is not None else None

    series = raw.get("series")
    if isinstance(series, dict):
        for name, values in series.items():
            if isinstance(values, list) and values and all(_number(v) is not None for v in values):
                run.series[name] = [float(v) for v in values]
            else:
                run.notes.append(f"{short}: series \"{name}\" is not a non-empty list of numbers; "
                                 "ignored")
    elif series is not None:
        run.notes.append(f"{short}: \"series\" is not an object; ignored")

    images = raw.get("images")
    if isinstance(images, dict):
        base = Path(source).resolve().parent
        for kind, rel in images.items():
            if isinstance(rel, str) and rel:
                run.images[kind] = (base / rel).resolve()
            else:
                run.notes.append(f"{short}: image \"{kind}\" is not a path; ignored")
    elif images is not None:
        run.notes.append(f"{short}: \"images\" is not an object; ignored")
    _parse_checks(raw.get("checks"), run, short)
    _parse_cross_backend(raw.get("cross_backend"), run, short)
    return run


def _count(value):
    number = _number(value)
    return int(number) if number is not None and number >= 0 and number.is_integer() else None


def _parse_checks(checks, run, short):
    if checks is None:
        return
    if not isinstance(checks, dict):
        run.notes.append(f"{short}: \"checks\" is not an object; ignored")
        return
    enabled = checks.get("validation_enabled")
    if isinstance(enabled, bool):
        run.validation_enabled = enabled
    if "validation_errors" in checks:
        run.validation_errors = _count(checks["validation_errors"])
        if run.validation_errors is None:
            run.notes.append(f"{short}: checks.validation_errors = "
                             f"{json.dumps(checks['validation_errors'])} is not a count; ignored")
    message = checks.get("last_validation_error")
    if isinstance(message, str) and message:
        run.last_validation_error = message


def _parse_cross_backend(cross, run, short):
    if cross is None:
        return
    parsed = None
    if isinstance(cross, dict) and isinstance(cross.get("against"), str):
        counts = {k: _count(cross.get(k)) for k in ("pixels", "differing_pixels", "max_difference")}
        if all(v is not None for v in counts.values()) \
                and counts["differing_pixels"] <= counts["pixels"]:
            parsed = dict(counts, against=cross["against"])
    if parsed is None:
        run.notes.append(f"{short}: \"cross_backend\" {json.dumps(cross)} is not a comparison "
                         "(against, pixels, differing_pixels, max_difference); ignored")
    run.cross_backend = parsed


def load_results(path):
    """All runs of one results file. Raises InputError for unreadable or malformed files."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as e:
        raise InputError(f"{path}: cannot read: {e.strerror or e}") from None
    except UnicodeDecodeError as e:
        raise InputError(f"{path}: not UTF-8 text ({e.reason} at byte {e.start})") from None
    try:
        data = json.loads(text)
    except json.JSONDecodeError as e:
        raise InputError(f"{path}: not valid JSON: {e.msg} at line {e.lineno} column {e.colno}") \
            from None
    if not isinstance(data, dict):
        raise InputError(f"{path}: expected a JSON object with a \"runs\" array, "
                         f"got {type(data).__name__}")
    if "runs" not in data:
        raise InputError(f"{path}: no \"runs\" array")
    if not isinstance(data["runs"], list):
        raise InputError(f"{path}: \"runs\" must be an array, got {type(data['runs']).__name__}")
    return [parse_run(raw, path, i) for i, raw in enumerate(data["runs"])]


def merge_runs(run_lists):
    """Runs of several files in first-seen order. A run measured again (same scene, technique,
    params and backend) keeps the later measurement, as a re-run of the bench is meant to replace
    the old numbers; the replacement is noted."""
    merged = {}
    notes = []
    for runs in run_lists:
        for run in runs:
            old = merged.get(run.key)
            if old is not None:
                notes.append(f"{run.where} replaces {old.where} "
                             f"({run.scene}, {describe(run)}, {run.backend}): same scene, "
                             "technique, params and backend")
            merged[run.key] = run
    return list(merged.values()), notes


def describe(run):
    """Technique and every parameter: a full, unambiguous name for notes."""
    return " ".join([run.technique] + [f"{k}={v}" for k, v in sorted(run.params.items())])


def natural_key(text):
    """Sorts "cascades=10" after "cascades=4"."""
    return [(0, int(part), "") if part.isdigit() else (1, 0, part)
            for part in re.split(r"(\d+)", str(text)) if part]


def run_sort_key(run):
    return (natural_key(run.technique),
            [(natural_key(k), natural_key(v)) for k, v in sorted(run.params.items())],
            natural_key(run.backend))


def group_by_scene(runs):
    """{scene: runs sorted by technique, params, backend}, scenes in first-seen order."""
    scenes = {}
    for run in runs:
        scenes.setdefault(run.scene, []).append(run)
    return {scene: sorted(rs, key=run_sort_key) for scene, rs in scenes.items()}


def setup_summary(runs):
    """The device (or devices, with their backends) and resolution the runs were measured on."""
    devices = {}
    for r in runs:
        devices.setdefault(r.device or "unknown device", set()).add(r.backend)
    if len(devices) == 1:
        text = next(iter(devices))
    else:
        text = "; ".join(f"{'/'.join(sorted(b, key=natural_key))}: {d}"
                         for d, b in devices.items())
    sizes = sorted({r.size for r in runs if r.size})
    if len(sizes) == 1:
        text += f", {sizes[0][0]}×{sizes[0][1]}"
    elif sizes:
        text += ", " + " / ".join(f"{w}×{h}" for w, h in sizes)
    return text


def technique_labels(runs):
    """{(technique, params_key): label}: the technique followed by only the parameters that tell
    its variants among `runs` apart, so labels stay short where a technique has one setting.
    With many variants (sweeps of several parameters merged into one page) a parameter is named
    only where it differs from its most common value, which for one-parameter-at-a-time sweeps
    is the default: "csm cascades=1 resolution=2048" rather than every swept parameter."""
    variants, given = {}, {}
    for run in runs:
        variants.setdefault(run.technique, {})[run.params_key] = run.params
        given.setdefault(run.technique, {})[run.params_key] = run.params_given
    labels = {}
    for technique, by_params in variants.items():
        names = sorted({k for params in by_params.values() for k in params}, key=natural_key)
        varying = [k for k in names if len({params.get(k) for params in by_params.values()}) > 1]
        common = {}
        for k in varying:
            counts = {}
            for params in by_params.values():
                counts[params.get(k)] = counts.get(params.get(k), 0) + 1
            # Most frequent value; ties go to the first seen, so the choice is deterministic.
            common[k] = max(counts, key=counts.get)
        mine = {}
        for params_key, params in by_params.items():
            if len(by_params) > 4:
                parts = [f"{k}={params[k]}" for k in varying if k in params and params[k] != common[k]]
            else:
                parts = [f"{k}={params[k]}" for k in varying if k in params]
            mine[params_key] = " ".join([technique] + parts)
        # Where the bench says which parameters it was given, a variant is named by those alone
        # ("csm filter=msm", not "csm filter=msm kernel=3" beside a 5x5 Gaussian variant), unless
        # that would name two variants alike.
        # A technique run in one variant only is named by everything it was given.
        if all(g is not None for g in given[technique].values()):
            named = {}
            for params_key, params in by_params.items():
                set_here = given[technique][params_key]
                names = varying if len(by_params) > 1 else sorted(set_here, key=natural_key)
                parts = [f"{k}={params[k]}" for k in names if k in params and k in set_here]
                named[params_key] = " ".join([technique] + parts)
            if len(set(named.values())) == len(named):
                mine = named
        labels.update({(technique, k): v for k, v in mine.items()})
    return labels


def run_labels(runs):
    """{run.key: label} for charts with one row per run: the technique label, plus the backend
    when the runs use more than one."""
    tech = technique_labels(runs)
    several = len({r.backend for r in runs}) > 1
    return {r.key: tech[(r.technique, r.params_key)] + (f" [{r.backend}]" if several else "")
            for r in runs}


def pareto_front(points):
    """Indices of the points (x, y) that no other point dominates, lower being better on both
    axes, ordered by x. A point is dominated when another is no worse on both and better on one,
    so identical points all stay on the front."""
    front = []
    for i, (x, y) in enumerate(points):
        dominated = any(qx <= x and qy <= y and (qx < x or qy < y)
                        for j, (qx, qy) in enumerate(points) if j != i)
        if not dominated:
            front.append(i)
    return sorted(front, key=lambda i: (points[i][0], points[i][1]))


def front_keys(runs):
    """Keys of the runs on their backend's speed/accuracy Pareto front (gpu_ms.total against
    misclassified_pct). Fronts are per backend: GPU times are only comparable on one API."""
    keys = set()
    for backend in {r.backend for r in runs}:
        mine = [r for r in runs if r.backend == backend and r.metric("gpu_ms.total") is not None
                and r.metric("misclassified_pct") is not None]
        points = [(r.metric("gpu_ms.total"), r.metric("misclassified_pct")) for r in mine]
        keys.update(mine[i].key for i in pareto_front(points))
    return keys


def backend_groups(runs):
    """[(technique, params_key, [runs on different backends])] for runs measured on more than one
    backend, in run order."""
    groups = {}
    for run in runs:
        groups.setdefault((run.technique, run.params_key), []).append(run)
    return [(t, p, rs) for (t, p), rs in groups.items() if len({r.backend for r in rs}) > 1]


def metric_names(runs):
    """Known metrics first (catalogue order) then any others the runs carry, sorted."""
    present = {name for r in runs for name in r.metrics}
    known = [m.name for m in METRICS if m.name in present]
    extra = sorted(present - set(known), key=natural_key)
    return known + extra


def _metric(name):
    """The catalogue entry; a GPU pass a technique names itself (gpu_ms.moments) reads like the
    known passes."""
    metric = METRIC_BY_NAME.get(name)
    if metric is None and name.startswith("gpu_ms."):
        pass_name = name[len("gpu_ms."):]
        metric = Metric(name, f"GPU {pass_name}", "ms", "{:.2f}",
                        f"GPU time of the technique's {pass_name} pass per frame, in ms")
    return metric


def format_metric(name, value):
    if value is None:
        return "–"
    metric = _metric(name)
    if metric is None:
        return f"{value:.4g}"
    return metric.fmt.format(value * metric.scale)


def metric_heading(name):
    metric = _metric(name)
    if metric is None:
        return name
    return f"{metric.heading} ({metric.unit})" if metric.unit else metric.heading
