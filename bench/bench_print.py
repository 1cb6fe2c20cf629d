#!/usr/bin/env python3
"""Times the print style against bidirectional (the thesis's final design) with the
rockhatch command: the sample (hand-drawn partition and --partition auto) and
../shared/data/montblanc/Chamonix.tif (--partition auto), 1:10000 and 1:25000, 2 threads,
SVG output; median of RUNS runs each.

    /usr/bin/python3 bench/bench_print.py BUILD_DIR [--runs 3]
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
SHARED_DEM = ROOT.parent / "shared" / "data" / "montblanc" / "Chamonix.tif"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("build", type=pathlib.Path)
    ap.add_argument("--runs", type=int, default=3)
    args = ap.parse_args()
    exe = args.build / "carto" / "rockhatch"
    cases = [("sample, hand-drawn partition", SAMPLE / "dem.tif", SAMPLE / "partition.gpkg"),
             ("sample, --partition auto", SAMPLE / "dem.tif", "auto")]
    if SHARED_DEM.exists():
        cases.append(("Chamonix.tif, --partition auto", SHARED_DEM, "auto"))
    print("| case | scale | style | wall time (median) | hatches |")
    print("|---|---|---|---:|---:|")
    with tempfile.TemporaryDirectory() as tmp:
        for label, dem, partition in cases:
            for scale in (10000, 25000):
                for style in ("bidirectional", "print"):
                    times, hatches = [], ""
                    for _ in range(args.runs):
                        t = time.perf_counter()
                        r = subprocess.run([str(exe), "--dem", str(dem), "--partition", str(partition), "--style", style,
                                            "--scale", str(scale), "--threads", "2", "--overwrite",
                                            "-o", f"{tmp}/o.svg"], capture_output=True, text=True, check=True)
                        times.append(time.perf_counter() - t)
                        hatches = r.stderr.strip().splitlines()[-1].split(",")[1].split()[0]
                    print(f"| {label} | 1:{scale} | {style} | {statistics.median(times):.2f} s | {hatches} |",
                          flush=True)


if __name__ == "__main__":
    sys.exit(main())
