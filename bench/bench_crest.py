#!/usr/bin/python3
"""Times the crest ornaments: carto.draw_crests over every ridge line of the bundled sample
and of the automatic partition of the Chamonix DEM in ../shared (when present), at 1 and 2
threads, medians of N runs; and the whole rockhatch command on the sample with and without
--crest-ornament. Writes a Markdown table.

    bench/bench_crest.py BUILD_DIR [--runs N] [--markdown FILE]
"""
import argparse
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
SAMPLE = ROOT / "data" / "sample_montblanc"
CHAMONIX = ROOT.parent / "shared" / "data" / "montblanc" / "Chamonix.tif"


def median_seconds(f, runs):
    times = []
    for _ in range(runs):
        t = time.perf_counter()
        f()
        times.append(time.perf_counter() - t)
    return statistics.median(times)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("build")
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--markdown")
    a = ap.parse_args()
    build = pathlib.Path(a.build)
    sys.path.insert(0, str(build / "python"))
    from rockhatch import carto, tex

    cases = [("sample", SAMPLE / "dem.tif", str(SAMPLE / "partition.gpkg"))]
    if CHAMONIX.exists():
        cases.append(("Chamonix.tif, --partition auto", CHAMONIX, "auto"))
    rows = ["| partition | ridge lines | drawn | band | 1 thread | 2 threads | vertices |",
            "|---|---:|---:|---:|---:|---:|---:|"]
    for name, dem, partition in cases:
        part = carto.prepare(str(dem), partition).partition
        ridges = sum(1 for line in part.lines if line.kind == carto.LineKind.RIDGE)
        band = 20.0  # 2 mm at 1:10000
        result = carto.draw_crests(part, "default", band)
        vertices = sum(len(r) for o in result.ornaments for r in o.rings)
        t = {}
        for threads in (1, 2):
            tex.SetThreads(threads)
            t[threads] = median_seconds(lambda: carto.draw_crests(part, "default", band), a.runs)
        tex.SetThreads(0)
        rows.append(f"| {name} | {ridges} | {len(result.ornaments)} | {band:g} m | {t[1]:.3f} s | {t[2]:.3f} s "
                    f"| {vertices} |")
        print(rows[-1], flush=True)

    exe = build / "carto" / "rockhatch"
    cmd_rows = ["| command on the sample (default style, 2 threads) | wall time |", "|---|---:|"]
    with tempfile.TemporaryDirectory() as d:
        base = [str(exe), "-q", "--overwrite", "--threads", "2", "--dem", str(SAMPLE / "dem.tif"), "--partition",
                str(SAMPLE / "partition.gpkg"), "-o", str(pathlib.Path(d) / "o.gpkg")]
        for label, extra in (("without crests", []), ("with --crest-ornament default", ["--crest-ornament", "default"])):
            s = median_seconds(lambda: subprocess.run(base + extra, check=True, capture_output=True), a.runs)
            cmd_rows.append(f"| {label} | {s:.2f} s |")
            print(cmd_rows[-1], flush=True)

    if a.markdown:
        text = ("# Crest ornaments: benchmark\n\n"
                f"`bench/bench_crest.py BUILD_DIR --markdown docs/benchmarks-crest.md`: medians of {a.runs} runs "
                "on this 2-core machine, shared with other builds while it ran (the small times are noisy).\n\n"
                "`carto.draw_crests` over every ridge line (the default exemplar, a 2 mm band at 1:10000; the "
                "partition read beforehand and not timed):\n\n" + "\n".join(rows) + "\n\n" +
                "\n".join(cmd_rows) + "\n")
        pathlib.Path(a.markdown).write_text(text)


if __name__ == "__main__":
    main()
