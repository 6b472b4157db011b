#!/usr/bin/env python3
"""Instructions per draw through sp:: and raw, counted by callgrind: the sp/raw table when time is too noisy.

Usage: rhi-instructions.py BENCH_RHI_BINARY [--backend vulkan|gl] [--out DIR]

On a shared machine the CPU time of one case moves by up to 2x between runs (docs/rhi-cost.md), more than
most changes to the per-draw path. The instructions the benchmark thread executes inside a case's Record()
move far less (docs/rhi-cost.md gives their spread), so a few runs show what a change did. The bench runs twice under callgrind (3 and 11
iterations, collecting only inside the cases' Record functions, which the two sides of a case implement in
Sp<Case> and Vk<Case>/Gl<Case> classes); the difference divided by 8 iterations and the case's draws
removes what happens once (pipeline creation, first use). Instructions are not time: a cache miss or a
syscall counts as one instruction, and work on the drivers' own threads is not counted.
"""
import argparse
import json
import os
import re
import subprocess
import sys

ITERATIONS = (3, 11)


def run(binary, backend, iterations, out):
    raw_class = "Vk" if backend == "vulkan" else "Gl"
    base = os.path.join(out, f"callgrind-{backend}-{iterations}")
    cmd = ["valgrind", "--tool=callgrind", f"--callgrind-out-file={base}.out", "--collect-atstart=no",
           "--toggle-collect=*::Sp*::Record()", f"--toggle-collect=*::{raw_class}*::Record()",
           binary, f"--benchmark_filter=/{backend}/", "--benchmark_repetitions=1",
           f"--benchmark_out={base}.json", "--benchmark_out_format=json"]
    env = dict(os.environ, SPBENCH_ITERATIONS=str(iterations))
    return subprocess.Popen(cmd, env=env, stdout=subprocess.DEVNULL, stderr=open(base + ".log", "w"))


def counts(path):
    """Inclusive instructions of each Record(), by (case class suffix, side)."""
    text = subprocess.run(["callgrind_annotate", "--inclusive=yes", path], capture_output=True, text=True, check=True).stdout
    found = {}
    for line in text.splitlines():
        m = re.match(r"\s*([\d,]+) .*::(Sp|Vk|Gl)(\w+)::Record\(\)", line)
        if m:
            found[(m.group(3).lower(), "sp" if m.group(2) == "Sp" else "raw")] = int(m.group(1).replace(",", ""))
    return found


def draws(path):
    with open(path) as f:
        data = json.load(f)
    return {b["run_name"].split("/")[0]: b["draws"] for b in data["benchmarks"] if b.get("draws")}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("binary")
    ap.add_argument("--backend", default="vulkan", choices=["vulkan", "gl"])
    ap.add_argument("--out", default="out/bench-rhi-instructions")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    procs = [run(args.binary, args.backend, n, args.out) for n in ITERATIONS]  # two processes, two cores
    if any(p.wait() for p in procs):
        sys.exit(f"valgrind failed; see {args.out}/callgrind-{args.backend}-*.log")
    lo, hi = (counts(os.path.join(args.out, f"callgrind-{args.backend}-{n}.out")) for n in ITERATIONS)
    per_iteration = draws(os.path.join(args.out, f"callgrind-{args.backend}-{ITERATIONS[0]}.json"))
    extra = ITERATIONS[1] - ITERATIONS[0]
    print(f"bench-rhi under callgrind: instructions per draw (dispatch) on the benchmark thread, {args.backend}")
    print(f"{'case':<9} {'sp':>8} {'raw':>8} {'sp/raw':>7}")
    for case, n in per_iteration.items():
        if (case, "sp") not in hi or (case, "raw") not in hi:
            continue
        sp = (hi[(case, "sp")] - lo[(case, "sp")]) / (extra * n)
        raw = (hi[(case, "raw")] - lo[(case, "raw")]) / (extra * n)
        print(f"{case:<9} {sp:8.0f} {raw:8.0f} {sp / raw:7.2f}")


if __name__ == "__main__":
    main()
