#!/usr/bin/python3
"""Times the Python twins of the gallery (bindings/examples/gallery.py) in one interpreter:
build the arrangement, evaluate it on the 2000 x 2000 window and write the SVG, as
bench_gallery does for C++. Writes one line per example: name, 1-thread and 2-thread
medians in seconds (tab separated); bench_gallery --python-times reads it.

    bench/gallery_python_times.py BUILD_DIR --out times.tsv [--runs N] [--only NAME,...]
"""
import argparse
import pathlib
import statistics
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("build_dir", type=pathlib.Path)
    ap.add_argument("--out", type=pathlib.Path, required=True)
    ap.add_argument("--runs", type=int, default=7)
    ap.add_argument("--only", default="")
    a = ap.parse_args()
    sys.path.insert(0, str(a.build_dir.resolve() / "python"))
    sys.path.insert(0, str(ROOT / "bindings" / "examples"))
    import gallery
    from rockhatch import tex

    names = a.only.split(",") if a.only else list(gallery.EXAMPLES)
    lines = []
    with tempfile.TemporaryDirectory() as tmp:
        svg = str(pathlib.Path(tmp) / "x.svg")
        for name in names:
            build = gallery.EXAMPLES[name]
            medians = []
            for threads in (1, 2):
                tex.SetThreads(threads)
                times = []
                for _ in range(a.runs + 1):  # the first run warms up
                    t0 = time.perf_counter()
                    tex.SetSeed(0)  # each run numbers its partitions' streams from the start
                    tex.ExportSVG(build(gallery.ELEMENTS), gallery.SIZE, svg)
                    times.append(time.perf_counter() - t0)
                medians.append(statistics.median(times[1:]))
            lines.append(f"{name}\t{medians[0]:.6f}\t{medians[1]:.6f}")
            print(f"{name:10s} Python {medians[0] * 1e3:8.1f} ms (1 thread) {medians[1] * 1e3:8.1f} ms (2 threads)",
                  flush=True)
    tex.SetThreads(0)
    a.out.write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
