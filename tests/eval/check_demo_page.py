"""Checks what `shadowport demo` wrote: index.html names every technique on both backends, has the
speed/accuracy chart, every technique's images and the cross-backend comparison, every picture it
shows exists, the terminal table lists every run, and nothing was written outside --out.

    check_demo_page.py --out DIR --stdout FILE --stderr FILE --scene NAME
        --techniques LABEL[,LABEL...] [--fallback-notice] [--empty DIR] [--home DIR]

A LABEL is a technique as the demo prints it (`csm filter=gauss kernel=5`). --fallback-notice:
the demo must have said that it fell back to a built-in scene. --empty: the working directory the
demo ran in, which must stay empty; --home: the HOME it ran with, which must hold none of the
project's files (no reference, shader or matplotlib cache).
"""
import argparse
import sys
from html.parser import HTMLParser
from pathlib import Path

BACKENDS = ("vulkan", "gl")


class Page(HTMLParser):
    """Headings, image sources, and the text of every table row."""

    def __init__(self):
        super().__init__()
        self.headings, self.images, self.rows = [], [], []
        self._tag, self._row = None, None

    def handle_starttag(self, tag, attrs):
        if tag == "img":
            self.images.append(dict(attrs).get("src"))
        elif tag == "tr":
            self._row = []
        elif tag in ("h1", "h2", "h3"):
            self.headings.append("")
        self._tag = tag

    def handle_endtag(self, tag):
        if tag == "tr" and self._row is not None:
            self.rows.append(" | ".join(t.strip() for t in self._row if t.strip()))
            self._row = None

    def handle_data(self, data):
        if self._tag in ("h1", "h2", "h3") and self.headings:
            self.headings[-1] += data
        if self._row is not None:
            self._row.append(data)


def fail(message):
    print(f"check_demo_page: {message}", file=sys.stderr)
    sys.exit(1)


def check_page(out, scene, techniques):
    index = out / "index.html"
    if not index.is_file():
        fail(f"{index} was not written")
    text = index.read_text(encoding="utf-8")
    page = Page()
    page.feed(text)
    for expected in (f"ShadowPort demo: {scene}", f"Scene: {scene}", "Speed vs accuracy",
                     "All metrics", "Images", "Cross-backend"):
        if expected not in [h.strip() for h in page.headings]:
            fail(f"no heading '{expected}' (headings: {page.headings})")
    runs = len(techniques) * len(BACKENDS)
    if f"on in {runs} of {runs} runs; 0 errors." not in text:
        fail("the page does not say that validation was on in every run without errors")
    for technique in techniques:
        name, _, params = technique.partition(" ")
        for backend in BACKENDS:
            # The metrics table's row: technique | params | backend | ...
            if not any(r.startswith(f"{name} | ") and f" | {backend} | " in r
                       and all(p in r for p in params.split()) for r in page.rows):
                fail(f"no metrics row for {technique} on {backend}")
        cross = [r for r in page.rows if r.startswith(technique + " |") and "pixels differ" in r]
        if len(cross) != 1:
            fail(f"expected one cross-backend row for {technique}, got {cross}")
    for src in page.images:
        if not (out / src).is_file():
            fail(f"the page shows {src}, which does not exist")
    if not any(src.endswith("-speed-accuracy.png") for src in page.images):
        fail("no speed/accuracy chart on the page")
    diffs = [src for src in page.images if src.endswith("-diff.png")]
    if len(diffs) != len(techniques):
        fail(f"expected {len(techniques)} cross-backend difference images, got {diffs}")
    return index


def check_terminal(index, printed, techniques):
    for technique in techniques:
        for backend in BACKENDS:
            if not any(line.startswith(technique + " ") and f" {backend} " in line
                       for line in printed.splitlines()):
                fail(f"the terminal table has no line for {technique} on {backend}")
        if f"cross-backend, {technique}: gl against vulkan" not in printed:
            fail(f"the terminal names no cross-backend result for {technique}")
    if f"report: open {index}" not in printed:
        fail("the terminal does not name the report")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--out", type=Path, required=True)
    parser.add_argument("--stdout", type=Path, required=True)
    parser.add_argument("--stderr", type=Path, required=True)
    parser.add_argument("--scene", required=True)
    parser.add_argument("--techniques", required=True)
    parser.add_argument("--fallback-notice", action="store_true")
    parser.add_argument("--empty", type=Path, help="must still be empty (the working directory)")
    parser.add_argument("--home", type=Path, help="must hold none of the project's files")
    args = parser.parse_args()
    techniques = args.techniques.split(",")
    index = check_page(args.out, args.scene, techniques)
    check_terminal(index, args.stdout.read_text(encoding="utf-8"), techniques)
    progress = args.stderr.read_text(encoding="utf-8")
    notices = [line for line in progress.splitlines() if "notice:" in line]
    if args.fallback_notice and not any(f"using the built-in scene {args.scene}" in line
                                        for line in notices):
        fail(f"no notice of the fallback to {args.scene} (notices: {notices})")
    if not args.fallback_notice and notices:
        fail(f"unexpected notice: {notices}")
    for phase in ("technique 1/", "frame 1/", "writing the report"):
        if phase not in progress:
            fail(f"the progress lines never say '{phase}'")
    if not list((args.out / "lab" / "reference-cache").glob("*.vis")):
        fail("no reference cache beside the results (out/lab/reference-cache)")
    if args.empty:
        written = list(args.empty.rglob("*"))
        if written:
            fail(f"the demo wrote into its working directory: {[str(p) for p in written[:5]]}")
    if args.home:
        # The GPU driver may keep its own shader cache there; the project's files may not be.
        written = [p for p in args.home.rglob("*")
                   if any(k in str(p.relative_to(args.home)) for k in ("shadowport", "matplotlib"))]
        if written:
            fail(f"the demo wrote into HOME: {[str(p) for p in written[:5]]}")


if __name__ == "__main__":
    main()
