#!/usr/bin/python3
"""Times the terrain styles (scree, slope-hachures) on the whole Chamonix DEM of ../shared
(rock from --partition auto, 1:25000): the whole command, medians of --runs, with 1 and 2
threads, and the count of elements drawn. With --baseline another rockhatch executable (the
version before a change) is timed the same way, run by run in turn with the first, so that
both see the same load. The load average is printed beside the table: on a shared machine
the wall times move with it, the CPU times (user + sys) less.

    bench/bench_terrain.py BUILD/carto/rockhatch [--baseline OTHER/rockhatch] [--runs N] [--threads 1,2]
"""
import argparse
import os
import pathlib
import re
import statistics
import subprocess
import sys
import tempfile

from osgeo import ogr

ogr.UseExceptions()

ROOT = pathlib.Path(__file__).resolve().parents[1]
DEM = ROOT.parent / "shared" / "data" / "montblanc" / "Chamonix.tif"
LAYERS = {"scree": "hatch_stone", "slope-hachures": "hatch_hachure"}


def one_run(exe, style, threads, out):
    """Wall seconds, CPU seconds and the count of the style's elements of one run."""
    cmd = ["/usr/bin/time", "-f", "RH_TIME %e %U %S", str(exe), "--dem", str(DEM), "--partition", "auto",
           "--style", style, "--scale", "25000", "--threads", str(threads), "-q", "--overwrite", "-o", str(out)]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"bench_terrain: {' '.join(cmd)} failed:\n{r.stderr}")
    wall, user, system = map(float, re.search(r"RH_TIME ([\d.]+) ([\d.]+) ([\d.]+)", r.stderr).groups())
    ds = ogr.Open(str(out))  # kept alive while its layer is read
    count = ds.GetLayerByName(LAYERS[style]).GetFeatureCount()
    return wall, user + system, count


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("rockhatch")
    ap.add_argument("--baseline")
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--threads", default="1,2")
    a = ap.parse_args()
    if not DEM.exists():
        sys.exit(f"bench_terrain: {DEM} is absent")
    exes = [("this build", a.rockhatch)] + ([("baseline", a.baseline)] if a.baseline else [])
    threads = [int(t) for t in a.threads.split(",")]
    print(f"load average before: {' '.join(f'{x:.1f}' for x in os.getloadavg())}")
    print("| style | build | threads | median wall s | median CPU s | elements | elements / s (wall) |")
    print("|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for style in LAYERS:
            for t in threads:
                times = {name: [] for name, _ in exes}
                counts = {}
                for _ in range(a.runs):
                    for name, exe in exes:  # in turn, so that both see the same load
                        wall, cpu, n = one_run(exe, style, t, pathlib.Path(tmp) / "out.gpkg")
                        times[name].append((wall, cpu))
                        counts[name] = n
                for name, _ in exes:
                    wall = statistics.median(w for w, _ in times[name])
                    cpu = statistics.median(c for _, c in times[name])
                    print(f"| {style} | {name} | {t} | {wall:.2f} | {cpu:.2f} | {counts[name]:,} | "
                          f"{counts[name] / wall:,.0f} |", flush=True)
    print(f"load average after: {' '.join(f'{x:.1f}' for x in os.getloadavg())}")


if __name__ == "__main__":
    main()
