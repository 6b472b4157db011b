#!/usr/bin/env python3
"""Instructions per draw through sp:: and raw, counted by callgrind: the sp/raw table when time is too noisy.

Usage: rhi-instructions.py BENCH_RHI_BINARY [--backend vulkan|gl] [--cases a,b] [--out DIR]

On a shared machine the CPU time of one case moves by up to 2x between runs (docs/rhi-cost.md), more than
most changes to the per-draw path. The instructions the benchmark thread executes inside a case's Record()
move far less (docs/rhi-cost.md gives their spread), so a few runs show what a change did. Each benchmark
(case and side) runs in a process of its own, twice under callgrind (3 and 11 iterations, collecting only
inside the case's Record function, which the two sides implement in Sp<Case> and Vk<Case>/Gl<Case>
classes); the difference divided by 8 iterations and the case's draws removes what happens once (pipeline
creation, first use). A process per benchmark because the drivers keep state across cases: llvmpipe's
per-draw work in one case depended on which cases ran before it in the same process. Instructions are not
time: a cache miss or a syscall counts as one instruction, and work on the drivers' own threads is not
counted.
"""
import argparse
import json
import os
import re
import subprocess
import sys

ITERATIONS = (3, 11)
CASES = ("cbuffer", "texture", "state", "compute", "shadow")


def start(binary, name, iterations, out):
    base = os.path.join(out, f"callgrind-{name.replace('/', '-')}-{iterations}")
    cmd = ["valgrind", "--tool=callgrind", f"--callgrind-out-file={base}.out", "--collect-atstart=no",
           "--toggle-collect=*::Sp*::Record()", "--toggle-collect=*::Vk*::Record()", "--toggle-collect=*::Gl*::Record()",
           binary, f"--benchmark_filter=^{name}/", "--benchmark_repetitions=1",
           f"--benchmark_out={base}.json", "--benchmark_out_format=json"]
    env = dict(os.environ, SPBENCH_ITERATIONS=str(iterations))
    return base, subprocess.Popen(cmd, env=env, stdout=subprocess.DEVNULL, stderr=open(base + ".log", "w"))


def record_instructions(base):
    """Inclusive instructions of the Record() that ran in this process."""
    text = subprocess.run(["callgrind_annotate", "--inclusive=yes", base + ".out"], capture_output=True, text=True,
                          check=True).stdout
    for line in text.splitlines():
        m = re.match(r"\s*([\d,]+) .*::(Sp|Vk|Gl)\w+::Record\(\)", line)
        if m:
            return int(m.group(1).replace(",", ""))
    sys.exit(f"no Record() in {base}.out; see {base}.log")


def draws(base):
    with open(base + ".json") as f:
        data = json.load(f)
    return next(b["draws"] for b in data["benchmarks"] if b.get("draws"))


def per_draw(binary, name, out):
    """(instructions per draw, draws per iteration) of one benchmark: two processes, two cores."""
    runs = [start(binary, name, n, out) for n in ITERATIONS]
    for base, proc in runs:
        if proc.wait():
            sys.exit(f"valgrind failed; see {base}.log")
    lo, hi = (record_instructions(base) for base, _ in runs)
    n = draws(runs[0][0])
    return (hi - lo) / ((ITERATIONS[1] - ITERATIONS[0]) * n)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("binary")
    ap.add_argument("--backend", default="vulkan", choices=["vulkan", "gl"])
    ap.add_argument("--cases", default=",".join(CASES), help="comma-separated subset of " + ", ".join(CASES))
    ap.add_argument("--out", default="out/bench-rhi-instructions")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    cases = [c for c in args.cases.split(",") if c]
    for c in cases:
        if c not in CASES:
            sys.exit(f"--cases: unknown case '{c}' (known: {', '.join(CASES)})")
    print(f"bench-rhi under callgrind: instructions per draw (dispatch) on the benchmark thread, {args.backend}")
    print(f"{'case':<9} {'sp':>8} {'raw':>8} {'sp-raw':>8} {'sp/raw':>7}", flush=True)
    for case in cases:
        sp = per_draw(args.binary, f"{case}/{args.backend}/sp", args.out)
        raw = per_draw(args.binary, f"{case}/{args.backend}/raw", args.out)
        print(f"{case:<9} {sp:8.0f} {raw:8.0f} {sp - raw:8.0f} {sp / raw:7.2f}", flush=True)


if __name__ == "__main__":
    main()
