#!/usr/bin/env python3
"""Markdown table of several `shadowport advise` runs: the recommendation against a technique's
default configuration (docs/lab.md, "Advise").

usage: advise_table.py [--default csm] dir/advise.json...
"""
import argparse
import json
import sys


def verdict(rec, default, noise):
    """Is the recommendation cheaper than the default at equal or better error? The same rule as the
    choice: GPU ms within the noise margin are a tie, decided by memory."""
    r, d = rec["metrics"], default["metrics"]
    if rec["full_config"] == default["full_config"]:
        return "no: the default is the answer"
    better_error = r["misclassified"] <= d["misclassified"]
    if r["ms"] < d["ms"] * (1 - noise):
        how = f"yes: {d['ms'] / r['ms']:.1f}x faster"
        if r["memory"] < d["memory"]:
            how += f", {d['memory'] / r['memory']:.1f}x less memory"
        elif r["memory"] > d["memory"]:
            how += f", {r['memory'] / d['memory']:.1f}x more memory"
    elif r["ms"] <= d["ms"] / (1 - noise) and r["memory"] < d["memory"]:
        how = f"yes: same GPU ms within noise, {d['memory'] / r['memory']:.1f}x less memory"
    else:
        how = "no"
    return how if better_error else how + " (but higher error)"


def main(argv):
    ap = argparse.ArgumentParser()
    ap.add_argument("--default", default="csm")
    ap.add_argument("files", nargs="+")
    a = ap.parse_args(argv)
    print("| scene | budget: misclassified % <= | configurations measured | recommendation | GPU ms | MiB | misclassified % "
          f"| {a.default} defaults: GPU ms | MiB | misclassified % | cheaper at equal or better error? |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for f in a.files:
        with open(f) as fh:
            d = json.load(fh)
        confs = d["configurations"]
        default = next(confs[i] for i in d["defaults"] if confs[i]["technique"] == a.default)
        budget = d["budgets"][0]["limit"]
        n = len(confs)
        if d["recommendation"] is None:
            print(f"| {d['scene']} | {budget:g} | {n} | none meets it | | | | {default['metrics']['ms']:.1f} | "
                  f"{default['metrics']['memory']:.1f} | {default['metrics']['misclassified']:.3f} | - |")
            continue
        rec = confs[d["recommendation"]]
        r, dm = rec["metrics"], default["metrics"]
        print(f"| {d['scene']} | {budget:g} | {n} | `{rec['config']}` | {r['ms']:.1f} | {r['memory']:.1f} | {r['misclassified']:.3f} "
              f"| {dm['ms']:.1f} | {dm['memory']:.1f} | {dm['misclassified']:.3f} | {verdict(rec, default, d['noise'])} |")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
