#!/usr/bin/env python3
"""Prints the sp/raw table from bench-rhi's JSON output (--benchmark_out=FILE --benchmark_out_format=json).

CPU time per draw (or dispatch) of each case on each backend, through sp:: and raw, and their
ratio. With repetitions the medians are used; without, the single run.
"""
import json
import sys

UNIT_NS = {"ns": 1.0, "us": 1e3, "ms": 1e6, "s": 1e9}


def main(path):
    with open(path) as f:
        data = json.load(f)
    rows = {}  # (case, backend) -> {side: ns per draw}
    order = []
    have_median = any(b.get("aggregate_name") == "median" for b in data["benchmarks"])
    for b in data["benchmarks"]:
        if have_median and b.get("aggregate_name") != "median":
            continue
        if b.get("error_occurred"):
            continue
        name = b.get("run_name", b["name"]).split("/iterations:")[0]
        case, backend, side = name.split("/")[:3]
        per_draw = b["cpu_time"] * UNIT_NS[b["time_unit"]] / b["draws"]
        key = (case, backend)
        if key not in rows:
            rows[key] = {}
            order.append(key)
        rows[key][side] = per_draw
    ctx = data.get("context", {})
    reps = max((b.get("repetitions", 1) for b in data["benchmarks"]), default=1)
    print(f"bench-rhi: CPU ns per draw (dispatch), {'median of ' + str(reps) + ' repetitions' if have_median else 'one run'};"
          f" load average {', '.join(f'{x:.1f}' for x in ctx.get('load_avg', []))}")
    print(f"{'case':<9} {'backend':<7} {'sp ns':>10} {'raw ns':>10} {'sp/raw':>7}")
    for case, backend in order:
        r = rows[(case, backend)]
        sp, raw = r.get("sp"), r.get("raw")
        ratio = f"{sp / raw:7.2f}" if sp and raw else "      -"
        fmt = lambda v: f"{v:10.0f}" if v is not None else "         -"
        print(f"{case:<9} {backend:<7} {fmt(sp)} {fmt(raw)} {ratio}")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: rhi-table.py BENCH.json")
    main(sys.argv[1])
