#!/usr/bin/env python3
"""End-to-end check of `shadowport advise` on a small case (default scene, 96x54, 2 frames, basic and
csm over resolution and cascades, --minimize memory, which is deterministic):
  1. the search, interrupted by SIGINT after a few measurements, exits 130 with the cache and
     state file whole;
  2. rerun, it resumes (the cached measurements are not measured again) and recommends;
  3. rerun once more, it measures nothing new and recommends the same;
  4. the exhaustive sweep over the same lattice (sharing the cache) finds the same optimum;
  5. an impossible budget says so and lists the closest configurations, exit 3;
  6. the page has the chart and the pictures of the recommendation and the cheaper miss.

usage: check_advise.py path/to/shadowport workdir
"""
import json
import os
import shutil
import signal
import subprocess
import sys
import time

BUDGET = "misclassified=0.1"


def fail(msg):
    print("FAIL: " + msg)
    sys.exit(1)


def main():
    exe, work = sys.argv[1], sys.argv[2]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    cache = os.path.join(work, "cache")
    env = dict(os.environ, SHADOWPORT_REFERENCE_CACHE=os.path.join(work, "reference-cache"))

    def args(out, budget=BUDGET, extra=()):
        return [exe, "advise", "--scene", "default", "--backend", "vulkan", "--size", "96x54", "--frames", "2",
                "--techniques", "basic,csm", "--axes", "resolution,cascades", "--max-resolution", "1024", "--minimize", "memory",
                "--budget", budget, "--cache", cache, "--out", os.path.join(work, out)] + list(extra)

    def run(name, a, expect_rc=0):
        t0 = time.time()
        p = subprocess.run(a, env=env, capture_output=True, text=True)
        print(f"--- {name}: rc {p.returncode}, {time.time() - t0:.1f} s\n{p.stdout}\n{p.stderr[-3000:]}")
        if p.returncode != expect_rc:
            fail(f"{name}: exit {p.returncode}, expected {expect_rc}")
        return p

    def doc(out):
        with open(os.path.join(work, out, "advise.json")) as f:
            return json.load(f)

    def entries():
        try:
            with open(os.path.join(cache, "advise-cache.json")) as f:
                return len(json.load(f)["entries"])
        except (OSError, ValueError):
            return 0

    # 1. Interrupted after at least three measurements.
    p = subprocess.Popen(args("search"), env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    deadline = time.time() + 120
    while entries() < 3 and p.poll() is None and time.time() < deadline:
        time.sleep(0.1)
    p.send_signal(signal.SIGINT)
    out, err = p.communicate(timeout=120)
    print(f"--- interrupted: rc {p.returncode}\n{err[-2000:]}")
    if p.returncode != 130:
        fail(f"interrupted search exited {p.returncode}, expected 130")
    if "run the same command again to resume" not in err:
        fail("the interrupted search does not say how to resume")
    cached = entries()  # parses: the cache is whole
    with open(os.path.join(work, "search", "advise-state.json")) as f:
        state = json.load(f)
    if state["complete"] or cached < 3:
        fail(f"after the interrupt: state {state}, {cached} cached measurements")

    # 2. Resumed.
    r = run("resumed search", args("search"))
    if "resuming an interrupted search" not in r.stderr:
        fail("the rerun does not say it resumes")
    d = doc("search")
    n_search = len(d["configurations"])
    if d["from_cache"] != cached or d["new_measurements"] != n_search - cached:
        fail(f"resumed: {d['from_cache']} from the cache, {d['new_measurements']} new of {n_search}; {cached} were cached")
    if d["recommendation"] is None:
        fail("no recommendation")
    rec = d["configurations"][d["recommendation"]]["config"]
    for needle in ["recommendation: " + rec, "--technique " + rec, "sp::tech::CreateTechnique(", "Pareto front", "measured "]:
        if needle not in r.stdout + r.stderr:
            fail(f"output lacks '{needle}'")

    # 3. Same arguments again: nothing measured.
    run("rerun", args("search"))
    d2 = doc("search")
    if d2["new_measurements"] != 0 or d2["configurations"][d2["recommendation"]]["config"] != rec:
        fail(f"rerun measured {d2['new_measurements']} new configurations")

    # 4. The exhaustive sweep over the same lattice.
    run("exhaustive", args("exhaustive", extra=["--exhaustive"]))
    e = doc("exhaustive")
    n_full = len(e["configurations"])
    erec = e["configurations"][e["recommendation"]]
    srec = d["configurations"][d["recommendation"]]
    print(f"search: {n_search} configurations, exhaustive: {n_full}; search optimum {rec} "
          f"({srec['metrics']['memory']:.3f} MiB, {srec['metrics']['misclassified']:.4f} %), exhaustive optimum "
          f"{erec['config']} ({erec['metrics']['memory']:.3f} MiB, {erec['metrics']['misclassified']:.4f} %)")
    if erec["config"] != rec:
        fail("the search and the exhaustive sweep disagree")
    if n_search >= n_full:
        fail("the search measured as much as the exhaustive sweep")

    # 5. An impossible budget.
    r = run("impossible", args("impossible", budget="misclassified=0", extra=["--exhaustive", "--no-report"]), expect_rc=3)
    if "no configuration meets the budget" not in r.stdout or "the closest" not in r.stdout:
        fail("an impossible budget is not reported with the closest configurations")

    # 6. The page.
    for f in ["index.html", "front.png", "images/recommended-color.png", "images/recommended-error.png"]:
        if not os.path.exists(os.path.join(work, "search", f)):
            fail(f"page lacks {f}")
    if d["cheaper_miss"] is not None and not os.path.exists(os.path.join(work, "search", "images", "cheaper-error.png")):
        fail("page lacks the cheaper miss's pictures")
    print("OK")


if __name__ == "__main__":
    main()
