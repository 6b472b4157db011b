#!/usr/bin/env python3
"""Checks a `shadowport hlslc --survey` report: its counts, causes and per-file rows.

  check_survey_report.py report.md [--entries N] [--ok N] [--failed N] [--causes N]
      [--cause COUNT TEXT]... [--row FILE ENTRY TARGET RESULT]... [--no-entry ENTRY]...
      [--include-only FILE]... [--annotated DIR] [--contains TEXT]... [--stdout TEXT]
      [-- COMMAND...]

With `-- COMMAND...` (the survey, writing report.md), runs it first: it must exit 0, and print
the --stdout text when given.

--row matches FILE without the report's ":line", and RESULT as the start of the result cell
("ok", "**failed**: broken.hlsl:6"); --annotated DIR expects every `//! <target> <entry>` line
of DIR's .hlsl files (the tree's own list of its entry points) as a row that compiled.
Prints every mismatch, naming what was expected and what the report says; exits 1 on any.
"""
import argparse
import pathlib
import re
import subprocess
import sys


def cells(line):
    parts = re.split(r"(?<!\\)\|", line.strip())[1:-1]
    return [p.strip().replace("\\|", "|") for p in parts]


def parse(text):
    summary = next((l for l in text.splitlines() if l.startswith("- **")), "")
    m = re.search(r"\*\*(\d+) entry points?\*\*.*\*\*(\d+) compile .*?, (\d+) fail", summary)
    counts = tuple(int(g) for g in m.groups()) if m else None
    causes = [(int(c), t) for c, t in re.findall(r"^### (\d+) x `(.*)`$", text, re.M)]
    rows, in_table = [], False
    for line in text.splitlines():
        if line.startswith("## "):
            in_table = line == "## Per file"
        elif in_table and line.startswith("| ") and not line.startswith("| File |"):
            c = cells(line)
            if len(c) == 4:
                c[0] = re.sub(r":\d+$", "", c[0])
                rows.append(c)
    return summary, counts, causes, rows


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("report")
    ap.add_argument("--entries", type=int)
    ap.add_argument("--ok", type=int)
    ap.add_argument("--failed", type=int)
    ap.add_argument("--causes", type=int)
    ap.add_argument("--cause", nargs=2, action="append", default=[], metavar=("COUNT", "TEXT"))
    ap.add_argument("--row", nargs=4, action="append", default=[], metavar=("FILE", "ENTRY", "TARGET", "RESULT"))
    ap.add_argument("--no-entry", action="append", default=[])
    ap.add_argument("--include-only", action="append", default=[])
    ap.add_argument("--annotated")
    ap.add_argument("--contains", action="append", default=[])
    ap.add_argument("--stdout")
    argv = sys.argv[1:]
    command = argv[argv.index("--") + 1:] if "--" in argv else []
    a = ap.parse_args(argv[:len(argv) - len(command) - (1 if command else 0)])

    if command:
        pathlib.Path(a.report).unlink(missing_ok=True)
        pathlib.Path(a.report).parent.mkdir(parents=True, exist_ok=True)
        run = subprocess.run(command, capture_output=True, text=True)
        print(run.stdout, end="")
        if run.returncode != 0:
            print(run.stderr, end="")
            print(f"{a.report}: the survey exited with {run.returncode}: {' '.join(command)}")
            return 1
        if a.stdout is not None and a.stdout not in run.stdout:
            print(f"{a.report}: expected {a.stdout!r} on stdout")
            return 1
    text = pathlib.Path(a.report).read_text()
    summary, counts, causes, rows = parse(text)
    errors = []
    if counts is None:
        errors.append(f"no summary line with the counts (got {summary!r})")
    else:
        for name, want, got in (("entries", a.entries, counts[0]), ("ok", a.ok, counts[1]), ("failed", a.failed, counts[2])):
            if want is not None and want != got:
                errors.append(f"{name}: expected {want}, the summary says {got} ({summary})")
    if a.causes is not None and a.causes != len(causes):
        errors.append(f"causes: expected {a.causes}, the report has {len(causes)}: {causes}")
    for count, cause in a.cause:
        if (int(count), cause) not in causes:
            errors.append(f"cause: expected {count} x `{cause}`, the report has {causes}")

    def find(file, entry, target):
        return [r for r in rows if r[0] == file and r[1] == entry and r[2] == target]

    for file, entry, target, result in a.row:
        found = find(file, entry, target)
        if not found:
            errors.append(f"row: no row for {file} {entry} {target}")
        elif not any(r[3].startswith(result) for r in found):
            errors.append(f"row: {file} {entry} {target}: expected a result starting {result!r}, got {[r[3] for r in found]}")
    for entry in a.no_entry:
        if any(r[1] == entry for r in rows):
            errors.append(f"no-entry: {entry} is listed as an entry point")
    for file in a.include_only:
        if not any(r[0] == file and r[3].startswith("include-only") for r in rows):
            errors.append(f"include-only: {file} is not listed as include-only")
    if a.annotated:
        root = pathlib.Path(a.annotated)
        annotated = 0
        for f in sorted(root.rglob("*.hlsl")):
            for target, entry in re.findall(r"^//!\s+(\w+)\s+(\w+)\s*$", f.read_text(), re.M):
                annotated += 1
                rel = f.relative_to(root).as_posix()
                found = find(rel, entry, target)
                if not found or found[0][3] != "ok":
                    errors.append(f"annotated: {rel} declares //! {target} {entry}; the report has {found or 'no such row'}")
        if annotated == 0:
            errors.append(f"annotated: no //! lines under {root}")
    for t in a.contains:
        if t not in text:
            errors.append(f"contains: {t!r} is not in the report")

    for e in errors:
        print(f"{a.report}: {e}")
    if not errors:
        print(f"{a.report}: ok ({summary[2:]})")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
