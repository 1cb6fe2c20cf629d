#!/usr/bin/python3
"""How close the partition extracted tile by tile (rockhatch tiles --partition auto) comes to
one whole extraction (rockhatch partition), per tile size and halo.

Each tile runs carto.extract_tile, the function a Dask worker runs for it (the scheduler
changes where a tile runs, not what it computes), one tile after another in this process;
the tiles are merged with carto.merge_partition_tiles, as the tiled command does.

    /usr/bin/python3 bench/bench_tiles_partition.py [--repeat 3] [--markdown FILE]

Inputs: the bundled sample (1:10000) and ../shared/data/montblanc/Chamonix.tif warped to UTM
32N at 30 m (1:25000; skipped with a message when absent). Per case: faces of the whole and
the tiled partition, faces bit for bit the same, the rock area that lies on another face than
its match (faces matched one to one by largest overlap) as a share of the rock, the area
covered twice and the rock left uncovered by the tiled faces, the largest number of windows a
tile extracted, the largest window, and the median (over --repeat runs) of the time of all
tiles and of the whole extraction.
"""
import argparse
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "build" / "python"))

from osgeo import gdal  # noqa: E402

from rockhatch import carto, tex  # noqa: E402
from rockhatch.tiles import partition_difference  # noqa: E402

gdal.UseExceptions()

SHARED = ROOT.parent / "shared" / "data" / "montblanc" / "Chamonix.tif"


def tiled(dem, scale, tile, halo, out_dir):
    grid = carto.tile_grid(carto.raster_info(str(dem)), tile)
    eo = carto.ExtractOptions()
    eo.dem, eo.scale = str(dem), scale
    parts, rounds, cells = [], [], []
    t0 = time.perf_counter()
    for i, b in enumerate(grid):
        p = out_dir / f"part_{i}.gpkg"
        r = carto.extract_tile(eo, tex.BBox(b.xmin, b.ymin, b.xmax, b.ymax), halo, str(p))
        parts.append(str(p))
        rounds.append(r.rounds)
        cells.append(r.dem_cells)
    carto.merge_partition_tiles(parts, str(out_dir / "merged.gpkg"), True)
    return time.perf_counter() - t0, len(grid), max(rounds), max(cells)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--markdown")
    a = ap.parse_args()
    exe = ROOT / "build" / "carto" / "rockhatch"
    tmp = pathlib.Path(tempfile.mkdtemp(prefix="rh_bench_tp_"))
    cases = [(ROOT / "data" / "sample_montblanc" / "dem.tif", "sample", 10000, [500, 800, 1300], [300, 600, 1000, 4000])]
    if SHARED.exists():
        cham = tmp / "chamonix_utm.tif"
        gdal.Warp(str(cham), str(SHARED), dstSRS="EPSG:32632", xRes=30, yRes=30, resampleAlg="bilinear")
        cases.append((cham, "Chamonix.tif (UTM 32N, 30 m)", 25000, [3000, 5000], [1000, 2000, 3000, 4000, 6000]))
    else:
        print(f"{SHARED} is absent: Chamonix skipped", file=sys.stderr)
    rows = ["| DEM | scale | tile (m) | halo (m) | tiles | faces whole / tiled | bit for bit | on another face | "
            "covered twice | uncovered | max windows per tile | largest window (cells) | tiles (s) | whole (s) |",
            "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for dem, name, scale, sizes, halos in cases:
        whole = tmp / "whole.gpkg"
        times = []
        for _ in range(a.repeat):
            t0 = time.perf_counter()
            subprocess.run([str(exe), "partition", "--dem", str(dem), "--scale", str(scale), "-o", str(whole),
                            "--overwrite", "-q"], check=True)
            times.append(time.perf_counter() - t0)
        whole_s = statistics.median(times)
        for tile in sizes:
            for halo in halos:
                out = tmp / f"t_{tile}_{halo}"
                out.mkdir(exist_ok=True)
                runs = [tiled(dem, scale, tile, halo, out) for _ in range(a.repeat)]
                secs = statistics.median(r[0] for r in runs)
                _, n, rounds, cells = runs[0]
                c = partition_difference(whole, out / "merged.gpkg")
                row = (f"| {name} | 1:{scale} | {tile} | {halo} | {n} | {c['faces'][0]} / {c['faces'][1]} | {c['same']} | "
                       f"{c['other']:.3%} | {c['twice']:.3%} | {c['uncovered']:.3%} | {rounds} | {cells:,} | "
                       f"{secs:.2f} | {whole_s:.2f} |")
                rows.append(row)
                print(row, flush=True)
    text = "\n".join(rows) + "\n"
    if a.markdown:
        pathlib.Path(a.markdown).write_text(text)


if __name__ == "__main__":
    main()
