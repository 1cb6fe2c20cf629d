"""Tiled runs on Dask distributed: rock hatching for areas larger than one machine.

The area is cut into square tiles (carto::tile_grid). Each tile is a Dask task that hatches
the faces it owns (carto::run_tile: the faces whose anchor lies in its box, read with their
neighbourhood and the DEM window under them, never the whole DEM) and writes its own
GeoPackage in a work folder. Once every tile is there, they are merged, in tile order, into
the outputs (one GeoPackage with one R-tree per layer; SVG and PNG drawn from it).

- Same hatches as a whole run: a tile draws its faces from the same cells through the same
  pixel positions as a whole run, so every feature is the whole run's feature, bit for bit,
  whatever the tile size or the number of workers (tests/python/test_tiles.py checks it).
- Faults: a tile file appears only when complete (written to a temporary name, renamed);
  a task lost with its worker is run again by Dask; an interrupted job run again with the
  same options skips the tiles already done (resume). Partial files are never merged.
- Memory: a worker holds one tile (its faces, its DEM window and its hatches) at a time.
- ``--partition auto``: the partition is first extracted tile by tile on the same grid
  (carto::extract_tile: the faces whose anchor lies in the tile, from the DEM window under
  it plus a halo, grown while a kept face reaches the halo) and merged into one partition
  file in the work folder; the hatching tiles then read that file. Against one whole
  extraction the result is bounded, not exact: docs/tiles-partition.md.

Command line: ``rockhatch tiles --dem DEM --partition faces.gpkg --tile-size METRES
[--workers N | --scheduler tcp://HOST:8786] -o out.gpkg`` plus every option of rockhatch.
In Python: ``rockhatch.tiles.run(dem=..., partition=..., tile_size=..., outputs=[...])``.
"""
import hashlib
import json
import os
import shutil
import signal
import sys
import threading
import time

from . import carto
from ._rockhatch import RockhatchError, TexError

# With --partition auto, the DEM an extraction tile reads around its box, in ground units: the
# shortest halo measured with which Chamonix.tif's tiled partition has the whole one's faces
# (docs/tiles-partition.md, bench/bench_tiles_partition.py).
DEFAULT_EXTRACT_HALO = 4000.0

# Options of `rockhatch tiles` on top of the rockhatch option table: (flag, takes a value, help).
TILE_OPTIONS = [
    ("--tile-size", True, "METRES  side of a tile in ground units of the DEM's CRS (required)"),
    ("--workers", True, "N  worker processes of the local Dask cluster (default 1)"),
    ("--scheduler", True, "ADDRESS  an existing Dask scheduler (tcp://HOST:8786) instead of a local cluster"),
    ("--connect-timeout", True, "SECONDS  with --scheduler: how long to wait for it to answer (default 15)"),
    ("--workdir", True, "DIR  folder of the tile files (default: the first output + '.tiles')"),
    ("--restart", False, "start again: remove the tiles a previous run of this job left"),
    ("--keep-tiles", False, "keep the tile files after the merge"),
    ("--dashboard", True, "ADDRESS  serve the local cluster's Dask dashboard there (e.g. :8787)"),
    ("--extract-halo", True, "METRES  with --partition auto: DEM read around each extraction tile "
                             f"(default {DEFAULT_EXTRACT_HALO:g}; see docs/tiles-partition.md)"),
]


_MANIFEST = "job.json"


def _split_args(argv):
    """The tiled-run options, the extraction's tuning options (rockhatch partition's, for
    --partition auto) as (name, value) pairs in order, and the rest for the rockhatch option
    table."""
    mine, extract, rest = {}, [], []
    table = {flag: takes for flag, takes, _ in TILE_OPTIONS}
    extract_table = dict(carto.extract_option_names())
    i = 0
    while i < len(argv):
        a = argv[i]
        name, eq, value = a.partition("=")
        if name in table or name in extract_table:
            if table.get(name, extract_table.get(name)):
                if not eq:
                    if i + 1 >= len(argv):
                        raise carto.error(2, f"{name} needs a value")
                    i += 1
                    value = argv[i]
            else:
                value = True
            if name in table:
                mine[name] = value
            else:
                extract.append((name, "" if value is True else value))
        else:
            rest.append(a)
        i += 1
    return mine, extract, rest


def _extract_options(dem, scale, extract):
    """carto.ExtractOptions of a tiled extraction: the DEM, the scale and the tuning options."""
    eo = carto.ExtractOptions()
    eo.dem = dem
    eo.scale = scale
    for name, value in extract:
        carto.set_extract_option(eo, name, value)
    return eo


def _positive(name, value, kind=float):
    try:
        v = kind(value)
    except (TypeError, ValueError):
        raise carto.error(2, f"{name}: '{value}' is not a number") from None
    if not v > 0 or v != v or v == float("inf"):
        raise carto.error(2, f"{name}: {value} is not a positive number")
    return v


def _job_key(argv, tile_size):
    """What identifies a job's tiles: the options that change a tile's content (not the
    outputs, --overwrite, --quiet or the thread count), the tile size, and the inputs'
    sizes and times."""
    skip_value = {"-o", "--threads", "--png-size"}
    skip_flag = {"--overwrite", "-q", "--no-spatial-index"}
    kept, i = [], 0
    while i < len(argv):
        a = argv[i]
        name = a.split("=", 1)[0]
        if name in skip_value:
            i += 1 if "=" in a else 2
            continue
        if name not in skip_flag:
            kept.append(a)
        i += 1
    stamps = [_stamp(a) for a in kept if os.path.isfile(a)]
    return {"args": kept, "tile_size": tile_size, "inputs": stamps}


def _stamp(path):
    """An input file as a job knows it: path, size and modification time."""
    st = os.stat(path)
    return [os.path.abspath(path), st.st_size, st.st_mtime_ns]


def _extract_task(dem, scale, extract, box, halo, path):
    """One tile of the partition, in a worker process: the faces whose anchor lies in the box,
    extracted from the DEM window around it (carto::extract_tile), written to a tile file."""
    import resource

    from . import carto as c
    from . import tex

    if os.path.exists(path):
        return {"skipped": True, "faces": 0, "seconds": 0.0, "rounds": 0,
                "peak_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0}
    r = c.extract_tile(_extract_options(dem, scale, extract), tex.BBox(*box), halo, path)
    return {"skipped": False, "faces": r.faces, "seconds": r.seconds, "rounds": r.rounds, "dem_cells": r.dem_cells,
            "peak_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0}


def _with_partition(argv, path):
    """The arguments with --partition replaced by `path`."""
    out, i = [], 0
    while i < len(argv):
        a = argv[i]
        if a == "--partition":
            out += ["--partition", path]
            i += 2
            continue
        if a.startswith("--partition="):
            a = "--partition=" + path
        out.append(a)
        i += 1
    return out


def _tile_task(argv, box, path):
    """One tile, in a worker process: parse the options, hatch, write the tile file. A tile
    file that exists is complete (a retried task finds it and returns)."""
    import resource

    from . import carto as c

    if os.path.exists(path):
        return {"skipped": True, "faces": 0, "hatches": 0, "seconds": 0.0,
                "peak_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0}
    cl = c.parse_command_line(argv)
    options = cl.options
    if cl.script:
        options.style_file = cl.script
        options.custom_style = c.load_style(cl.script)
    options.overwrite = True  # the final outputs are written by the merge, not here
    from . import tex

    tile = tex.BBox(*box)
    r = c.run_tile(options, tile, path)
    return {"skipped": False, "faces": r.faces, "context_faces": r.context_faces, "hatches": r.hatches,
            "dem_cells": r.dem_cells, "seconds": r.seconds,
            "peak_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0}


class Summary:
    """What a tiled run did."""

    def __init__(self):
        self.tiles = 0          # tiles in the grid
        self.done_before = 0    # tiles found done (resume)
        self.faces = 0
        self.hatches = 0
        self.seconds = 0.0
        self.tile_seconds = []  # per tile computed in this run
        self.peak_mb = 0.0      # largest peak resident memory reported by a worker
        self.merge_seconds = 0.0  # merging the tiles and writing the outputs
        self.workers = 0
        self.partition_faces = 0      # --partition auto: face polygons of the merged partition
        self.partition_overlaps = 0   # --partition auto: pairs of faces of different tiles that overlap
        self.partition_overlap_area = 0.0  # their common area (ground units squared)
        self.warnings = []            # what the user should know about the result
        self.partition_seconds = 0.0  # --partition auto: extracting and merging the partition
        self.extract_rounds = []      # --partition auto: windows extracted per tile computed
        self.vector_tiles = None      # a vector-tile output: carto.TileStats

    def __repr__(self):
        return (f"Summary(tiles={self.tiles}, done_before={self.done_before}, faces={self.faces}, "
                f"hatches={self.hatches}, seconds={self.seconds:.2f}, peak_mb={self.peak_mb:.0f})")


def _eta(done, total, started, first_done):
    rate = (done - first_done) / max(1e-9, time.monotonic() - started)
    left = (total - done) / rate if rate > 0 else float("inf")
    return rate, left


def _is_vector_tiles(path):
    return path.lower().endswith(".mbtiles") or path.endswith("/")


def _without(args, flags):
    """args without the options in `flags` (each taking a value, as --flag V or --flag=V)."""
    out, i = [], 0
    while i < len(args):
        name = args[i].partition("=")[0]
        if name in flags:
            i += 1 if "=" in args[i] else 2
            continue
        out.append(args[i])
        i += 1
    return out


def _run_zoom_levels(argv, mine, options, progress, t0):
    """A vector-tile output (.mbtiles or DIR/): every zoom level of --zoom is a tiled run of
    its own at that level's scale (carto.zoom_scale at the DEM's latitude), on one cluster,
    into a GeoPackage per level; the levels are then written as one set of vector tiles by
    carto.write_vector_tiles, as the rockhatch command writes them."""
    outs = list(options.outputs)
    if len(outs) != 1:
        raise carto.error(2, "rockhatch tiles with a vector-tile output takes no other -o (run it once per output)")
    out = outs[0]
    zmin, zmax = carto.parse_zoom_range(options.zoom or "12-16")
    latitude = carto.dem_latitude(options.dem)
    workdir = mine.get("--workdir") or (out.rstrip("/") + ".tiles")
    os.makedirs(workdir, exist_ok=True)
    base = _without(list(argv), {"-o", "--zoom", "--scale", "--workdir", "--page"})
    base = [a for a in base if a != "--keep-tiles"]
    summary = Summary()
    levels, cluster = [], _Cluster(mine, _positive("--workers", mine.get("--workers", 1), int), summary)
    try:
        for k, z in enumerate(range(zmin, zmax + 1)):
            gpkg = os.path.join(workdir, f"z{z}.gpkg")
            sub = base + ["--scale", repr(carto.zoom_scale(z, latitude)), "-o", gpkg, "--overwrite",
                          "--workdir", os.path.join(workdir, f"z{z}"), "--keep-tiles"]
            n = zmax - zmin + 1

            def part(f, stage, k=k, z=z):
                return not progress or progress(0.9 * (k + f) / n, f"zoom {z}: {stage}")

            s = run_args(sub, part, cluster=cluster)
            summary.tiles += s.tiles
            summary.done_before += s.done_before
            summary.hatches += s.hatches
            summary.faces = s.faces
            summary.tile_seconds += s.tile_seconds
            summary.peak_mb = max(summary.peak_mb, s.peak_mb)
            summary.warnings += s.warnings
            levels.append((z, gpkg))
    finally:
        cluster.close()
    if progress:
        progress(0.9, "writing tiles")
    t_merge = time.monotonic()
    name = os.path.splitext(os.path.basename(options.dem))[0]
    summary.vector_tiles = carto.write_vector_tiles(levels, out, name)
    summary.merge_seconds = time.monotonic() - t_merge
    if not mine.get("--keep-tiles"):
        shutil.rmtree(workdir, ignore_errors=True)
    summary.seconds = time.monotonic() - t0
    if progress:
        progress(1.0, "done")
    return summary


def run_args(argv, progress=None, cluster=None):
    """A tiled run from command-line arguments (the rockhatch option table plus
    TILE_OPTIONS). progress(fraction, stage) is called as tiles finish; returning False
    cancels (the tiles done are kept for a resume). Returns a Summary. A vector-tile output
    (.mbtiles, DIR/) runs once per zoom level (--zoom). `cluster`: a running _Cluster to use
    (left running)."""
    t0 = time.monotonic()
    mine, extract, rest = _split_args(list(argv))
    if "--tile-size" not in mine:
        raise carto.error(2, "--tile-size is required (side of a tile, ground units of the DEM's CRS)")
    tile_size = _positive("--tile-size", mine["--tile-size"])
    if "--workers" in mine and "--scheduler" in mine:
        raise carto.error(2, "--workers and --scheduler exclude each other (the cluster behind a scheduler has its own)")
    workers = _positive("--workers", mine.get("--workers", 1), int)
    if "--connect-timeout" in mine:
        if "--scheduler" not in mine:
            raise carto.error(2, "--connect-timeout is for --scheduler (a local cluster is started, not reached)")
        _positive("--connect-timeout", mine["--connect-timeout"])
    cl = carto.parse_command_line(rest)
    options = cl.options
    if any(_is_vector_tiles(o) for o in options.outputs):
        carto.make_plan(options)  # every check of the options, before any work
        return _run_zoom_levels(argv, mine, options, progress, t0)
    if cl.script:
        options.style_file = cl.script
        carto.check_files(options)
        options.custom_style = carto.load_style(cl.script)
    carto.make_plan(options)
    carto.check_tiled_rasters(options)
    auto = options.partition.path == "auto"
    if extract and not auto:
        raise carto.error(2, f"{extract[0][0]}: an option of the extraction, for --partition auto only")
    if extract:
        # Checked before any work: the numbers and their ranges, the mask against the outputs.
        eo = _extract_options(options.dem, options.scale, extract)
        carto.check_extract_options(eo)
        if eo.mask and not os.path.exists(eo.mask):
            raise carto.error(3, f"--mask '{eo.mask}': no such file")
        for out in options.outputs:
            carto.check_extract_files(eo, out, "", True)
    halo = _positive("--extract-halo", mine["--extract-halo"]) if "--extract-halo" in mine else DEFAULT_EXTRACT_HALO
    # The tiles cut the grid the whole run works on (a geographic DEM's UTM grid).
    grid = carto.tile_grid(carto.working_grid(carto.raster_info(options.dem, "--dem")).grid, tile_size)
    workdir = mine.get("--workdir") or (options.outputs[0] + ".tiles")
    if os.path.abspath(workdir) in {os.path.abspath(p) for p in [options.dem, options.partition.path] if p}:
        raise carto.error(9, f"--workdir '{workdir}' is an input")
    os.makedirs(workdir, exist_ok=True)
    key = _job_key(rest, tile_size)
    if auto:
        key["extract_halo"] = halo
        key["extract"] = [list(e) for e in extract]
        mask = dict(extract).get("--mask")
        if mask:
            key["inputs"].append(_stamp(mask))
    manifest = os.path.join(workdir, _MANIFEST)
    if mine.get("--restart") and os.path.exists(manifest):
        for name in os.listdir(workdir):
            if name.startswith(("tile_", "partition")) and name.endswith(".gpkg"):
                os.remove(os.path.join(workdir, name))
        os.remove(manifest)
    if os.path.exists(manifest):
        with open(manifest) as f:
            previous = json.load(f)
        if previous != key:
            raise carto.error(9, f"--workdir '{workdir}' holds the tiles of another job (other options or inputs); "
                                 "pass --restart to discard them, or another --workdir")
    else:
        tmp = manifest + ".part"
        with open(tmp, "w") as f:
            json.dump(key, f)
        os.replace(tmp, manifest)
    # Temporary files of tiles interrupted in a previous run: never merged, removed.
    for name in os.listdir(workdir):
        if ".part-" in name:
            os.remove(os.path.join(workdir, name))

    paths = [os.path.join(workdir, "tile_%07d.gpkg" % i) for i in range(len(grid))]
    pending = [i for i, p in enumerate(paths) if not os.path.exists(p)]
    summary = Summary()
    summary.tiles = len(grid)
    summary.done_before = len(grid) - len(pending)
    # One hatching thread per core of the machine, shared by the local workers.
    task_args = list(rest)
    if "--threads" not in " ".join(rest) and "--scheduler" not in mine:
        task_args += ["--threads", str(max(1, (os.cpu_count() or 1) // workers))]
    job = hashlib.sha1(json.dumps(key).encode()).hexdigest()[:12]
    own_cluster = cluster is None
    if own_cluster:
        cluster = _Cluster(mine, workers, summary)
    try:
        # Hatching fractions of the progress: after the partition's share with --partition auto.
        span = (0.3, 0.99) if auto else (0.0, 0.99)
        if auto:
            # 1. The partition, tile by tile (the same grid), merged into one file that the
            # hatching tiles then read as any partition file: the hatching is a whole run's
            # for that partition.
            merged_partition = os.path.join(workdir, "partition.gpkg")
            if not os.path.exists(merged_partition):
                _extract_partition(options, extract, grid, workdir, halo, merged_partition, job, cluster, summary,
                                   progress)
            task_args = _with_partition(task_args, merged_partition)
        if progress and not progress(span[0] + (span[1] - span[0]) * summary.done_before / len(grid),
                                     f"tiles {summary.done_before}/{len(grid)}"):
            raise carto.error(10, "cancelled before the first tile")
        if pending:
            jobs = [(f"rockhatch-tile-{job}-{i}", _tile_task,
                     (task_args, (grid[i].xmin, grid[i].ymin, grid[i].xmax, grid[i].ymax), paths[i])) for i in pending]
            _compute(jobs, summary.done_before, len(grid), "tiles", span, cluster, summary, progress, _count_tile)
    finally:
        if own_cluster:
            cluster.close()
    missing = [p for p in paths if not os.path.exists(p)]
    if missing:
        raise carto.error(1, f"{len(missing)} tile(s) missing after the run (first: {missing[0]})")

    if progress:
        progress(0.99, "merging")
    t_merge = time.monotonic()
    gpkg = [o for o in options.outputs if o.lower().endswith(".gpkg")]
    merged = gpkg[0] if gpkg else os.path.join(workdir, "merged.gpkg")
    summary.hatches = carto.merge_gpkg(paths, merged, options.spatial_index)
    for extra in gpkg[1:]:
        carto.merge_gpkg(paths, extra, options.spatial_index)
    others = [o for o in options.outputs if not o.lower().endswith(".gpkg")]
    if others:
        drawing = carto.read_gpkg(merged, options.scale)
        for out in others:
            if out.lower().endswith(".svg"):
                carto.write_svg(drawing, out)
            elif out.lower().endswith(".pdf"):
                carto.write_pdf(drawing, out, options.page)
            else:
                carto.write_png(drawing, out, options.png_pixels)
    summary.merge_seconds = time.monotonic() - t_merge
    if not mine.get("--keep-tiles"):
        if not gpkg:
            os.remove(merged)
        shutil.rmtree(workdir, ignore_errors=True)
    summary.seconds = time.monotonic() - t0
    if progress:
        progress(1.0, "done")
    return summary


class _Cluster:
    """The Dask client of a run, started on first use: a local cluster (--workers) or the
    one behind --scheduler. close() stops a local cluster, so no worker outlives the run."""

    def __init__(self, mine, workers, summary):
        self.mine, self.workers, self.summary = mine, workers, summary
        self.client = self.local = None
        self.before = set()  # pids of this process's children before the local cluster started

    def get(self):
        if self.client is not None:
            return self.client
        from distributed import Client, LocalCluster

        mine = self.mine
        if "--scheduler" in mine:
            # Dask retries a refused connection until the timeout: a scheduler may be starting.
            self.client = Client(mine["--scheduler"], timeout=f"{float(mine.get('--connect-timeout', 15)):g}s")
        else:
            # The workers import this very module (the folder holding the package first on
            # their path, set in their environment only).
            here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
            path = os.pathsep.join([here] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p])
            self.before = {p.pid for p in _children()}
            self.local = LocalCluster(n_workers=self.workers, threads_per_worker=1, processes=True,
                                      # Unasked, the scheduler's HTTP server takes any free
                                      # port: with None it tries 8787 and warns on stderr
                                      # when another cluster holds it.
                                      dashboard_address=mine.get("--dashboard") or ":0", silence_logs=50,
                                      env={"PYTHONPATH": path})
            self.client = Client(self.local)
            if mine.get("--dashboard"):
                # Without bokeh (not packaged by Debian bookworm) this serves distributed's
                # information pages (/info/main/workers.html), not the graphical dashboard.
                sys.stderr.write(f"rockhatch tiles: Dask dashboard at {self.client.dashboard_link}\n")
        self.summary.workers = len(self.client.scheduler_info().get("workers", {}))
        return self.client

    def close(self):
        # The worker processes of the local cluster, listed now (a nanny, which lives in this
        # process, starts a new worker when one is killed): the children multiprocessing
        # spawned since the cluster started. The caller's own children are left alone.
        procs = [p for p in _children() if p.pid not in self.before and _spawned_worker(p)] if self.local else []
        if self.client is not None:
            self.client.close()
        if self.local is not None:
            self.local.close()
        # On a busy machine Dask's shutdown can time out and leave a worker computing: it could
        # then write a tile after the run has returned. None outlives close().
        if procs:
            import psutil

            for p in procs:
                try:
                    p.kill()  # psutil checks that the pid was not reused
                except psutil.Error:  # NoSuchProcess: stopped by close() as it should
                    pass
            psutil.wait_procs(procs, timeout=10)


def _children():
    """This process's child processes (psutil, a dependency of distributed)."""
    import psutil

    return psutil.Process().children()


def _spawned_worker(p):
    """Whether a child process is one multiprocessing spawned to run a function (a Dask
    worker), not its resource tracker, which outlives clusters and is shared by them."""
    import psutil

    try:
        return "spawn_main" in " ".join(p.cmdline())
    except psutil.Error:
        return False


def _count_tile(summary, r):
    summary.faces += r["faces"]
    if not r["skipped"]:
        summary.tile_seconds.append(r["seconds"])


def _count_partition_tile(summary, r):
    if not r["skipped"]:
        summary.extract_rounds.append(r["rounds"])


def _compute(jobs, done, total, label, span, cluster, summary, progress, count):
    """Runs jobs (key, function, args) on the cluster with Dask's retries; progress reports
    "<label> done/total" within the fraction span."""
    from distributed import as_completed

    client = cluster.get()
    futures = [client.submit(fn, *args, key=key, retries=2, pure=False) for key, fn, args in jobs]
    started, first = time.monotonic(), done
    for fut in as_completed(futures):
        try:
            r = fut.result()
        except (RockhatchError, TexError):
            for f in futures:
                f.cancel()
            raise
        done += 1
        summary.peak_mb = max(summary.peak_mb, r["peak_mb"])
        count(summary, r)
        if progress:
            rate, left = _eta(done, total, started, first)
            stage = f"{label} {done}/{total}, {rate:.2f}/s, {_duration(left)} left"
            if not progress(span[0] + (span[1] - span[0]) * done / total, stage):
                for f in futures:
                    f.cancel()
                raise carto.error(10, f"cancelled after {done} of {total} {label} (run again to resume)")


def _extract_partition(options, extract, grid, workdir, halo, out, job, cluster, summary, progress):
    """--partition auto: the partition extracted tile by tile on the cluster, then merged."""
    t0 = time.monotonic()
    paths = [os.path.join(workdir, "partition_%07d.gpkg" % i) for i in range(len(grid))]
    pending = [i for i, p in enumerate(paths) if not os.path.exists(p)]
    if pending:
        jobs = [(f"rockhatch-partition-{job}-{i}", _extract_task,
                 (options.dem, options.scale, extract, (grid[i].xmin, grid[i].ymin, grid[i].xmax, grid[i].ymax), halo,
                  paths[i])) for i in pending]
        _compute(jobs, len(grid) - len(pending), len(grid), "partition tiles", (0.0, 0.28), cluster, summary,
                 progress, _count_partition_tile)
    missing = [p for p in paths if not os.path.exists(p)]
    if missing:
        raise carto.error(1, f"{len(missing)} partition tile(s) missing after the run (first: {missing[0]})")
    if progress:
        progress(0.29, "merging the partition")
    merge = carto.merge_partition_tiles(paths, out, True)
    summary.partition_faces = merge.faces
    summary.partition_overlaps = merge.overlaps
    summary.partition_overlap_area = merge.overlap_area
    if merge.overlaps:
        share = 100.0 * merge.overlap_area / merge.area if merge.area > 0 else 0.0
        summary.warnings.append(
            f"the partition tiles disagree: {merge.overlaps} pair(s) of faces from neighbouring tiles overlap "
            f"({merge.overlap_area:.0f} square ground units, {share:.3f}% of the rock); a longer --extract-halo (now "
            f"{halo:g}) brings the tiled partition closer to the whole extraction (docs/tiles-partition.md)")
    if summary.partition_faces == 0:
        os.remove(out)
        raise carto.error(6, f"--dem '{options.dem}': no rock: no face was extracted at 1:{options.scale:g} with the "
                             f"{'given' if extract else 'default'} thresholds (rockhatch partition --help says which "
                             "to lower)")
    summary.partition_seconds = time.monotonic() - t0


def _duration(s):
    if s == float("inf"):
        return "?"
    s = int(s + 0.5)
    return f"{s // 3600}h{s % 3600 // 60:02d}m" if s >= 3600 else f"{s // 60}m{s % 60:02d}s"


def run(dem, partition, tile_size, outputs, *, style=None, script=None, params=None, scale=None, seed=None,
        workers=None, scheduler=None, connect_timeout=None, workdir=None, restart=False, keep_tiles=False, overwrite=False,
        extract_halo=None, args=(), progress=None):
    """A tiled run from Python: the same as `rockhatch tiles`. partition: a file, or "auto"
    (extracted tile by tile, with `extract_halo` ground units of DEM around each tile);
    params: {name: value}; args: any other option of the rockhatch command, as on its
    command line."""
    argv = ["--dem", os.fspath(dem), "--partition", os.fspath(partition), "--tile-size", str(tile_size)]
    for out in ([outputs] if isinstance(outputs, (str, os.PathLike)) else outputs):
        argv += ["-o", os.fspath(out)]
    if style:
        argv += ["--style", style]
    if script:
        argv += ["--script", os.fspath(script)]
    for k, v in (params or {}).items():
        argv += ["--param", f"{k}={v}"]
    if scale is not None:
        argv += ["--scale", str(scale)]
    if seed is not None:
        argv += ["--seed", str(seed)]
    if workers is not None:
        argv += ["--workers", str(workers)]
    if scheduler:
        argv += ["--scheduler", scheduler]
    if connect_timeout is not None:
        argv += ["--connect-timeout", str(connect_timeout)]
    if workdir:
        argv += ["--workdir", os.fspath(workdir)]
    if restart:
        argv.append("--restart")
    if keep_tiles:
        argv.append("--keep-tiles")
    if extract_halo is not None:
        argv += ["--extract-halo", str(extract_halo)]
    if overwrite:
        argv.append("--overwrite")
    return run_args(argv + list(args), progress)


def partition_difference(whole, tiled):
    """How far a partition extracted tile by tile is from the whole extraction: a dict of
    faces (whole, tiled), same (faces bit for bit the same), other (rock area of `whole` lying on
    another face of `tiled` than its match, faces matched one to one by largest overlap),
    twice (area covered by two tiled faces), uncovered (rock of `whole` no tiled face
    covers), the last three as shares of the rock area, rock_m2, and places: (area, x, y) of
    each piece uncovered or covered twice, largest first. Both are partition GeoPackages
    (layer faces); reads them with GDAL's Python bindings."""
    from osgeo import gdal, ogr

    def polys(path):
        ds = ogr.Open(str(path))  # kept open while its layer is read
        return [f.GetGeometryRef().Clone() for f in ds.GetLayerByName("faces")]

    def union(gs):
        u = ogr.Geometry(ogr.wkbMultiPolygon)
        for g in gs:
            u.AddGeometry(g)
        return u.UnionCascaded()

    a, b = polys(whole), polys(tiled)
    gdal.PushErrorHandler("CPLQuietErrorHandler")  # areas of the point and line parts of intersections
    try:
        pairs = []
        for i, g in enumerate(a):
            ea = g.GetEnvelope()
            for j, h in enumerate(b):
                eb = h.GetEnvelope()
                if eb[0] > ea[1] or eb[1] < ea[0] or eb[2] > ea[3] or eb[3] < ea[2]:
                    continue
                x = g.Intersection(h)
                if x is not None and x.GetArea() > 0:
                    pairs.append((x.GetArea(), i, j))
        pairs.sort(reverse=True)
        used_a, used_b, matched = set(), set(), 0.0
        for x, i, j in pairs:
            if i not in used_a and j not in used_b:
                used_a.add(i)
                used_b.add(j)
                matched += x
        rock = sum(g.GetArea() for g in a)
        tiled_union = union(b)
        twice = sum(g.GetArea() for g in b) - tiled_union.GetArea()
        gap = union(a).Difference(tiled_union)
        uncovered = gap.GetArea()
        pieces = [gap.GetGeometryRef(k) for k in range(gap.GetGeometryCount())] if gap.GetGeometryCount() else []
        for i, g in enumerate(b):
            for h in b[i + 1:]:
                if g.Intersects(h):
                    x = g.Intersection(h)
                    if x is not None and x.GetGeometryType() == ogr.wkbPolygon:
                        pieces.append(x)
        places = sorted(((p.GetArea(), p.Centroid().GetX(), p.Centroid().GetY()) for p in pieces
                         if p.GetGeometryType() == ogr.wkbPolygon and p.GetArea() > 0), reverse=True)
    finally:
        gdal.PopErrorHandler()
    same = len({bytes(g.ExportToWkb()) for g in a} & {bytes(g.ExportToWkb()) for g in b})
    return {"faces": (len(a), len(b)), "same": same, "other": (rock - matched) / rock, "twice": twice / rock,
            "uncovered": uncovered / rock, "rock_m2": rock, "places": places}


def help_text():
    lines = ["usage: rockhatch tiles --dem DEM --partition FACES|auto|none --tile-size METRES -o OUT [options]",
             "",
             "Hatches the area tile by tile on a Dask cluster (a local one by default) and merges the",
             "tiles into the outputs; the result is the same as one whole run. Tiled-run options:"]
    for flag, _, text in TILE_OPTIONS:
        lines.append(f"  {flag:14s} {text}")
    names = " ".join(n for n, _ in carto.extract_option_names())
    lines += ["", "With --partition auto, the extraction's tuning options of rockhatch partition (see its --help):",
              f"  {names}", "", "and every option of the rockhatch command (rockhatch --help)."]
    return "\n".join(lines) + "\n"


def main(argv=None):
    """`rockhatch tiles`: returns the exit code."""
    from .cli import fail

    argv = sys.argv[1:] if argv is None else list(argv)
    if not argv or "--help" in argv or "-h" in argv:
        sys.stdout.write(help_text())
        return 0
    quiet = "-q" in argv
    bar = carto.ProgressBar(not quiet)
    # A terminate request (QGIS's Cancel, a job scheduler) stops the run in order: the local
    # cluster is closed, so no worker goes on computing, or writing a tile, after the command
    # has exited. Only the command's own process is affected; run() installs nothing.
    previous = signal.signal(signal.SIGTERM, _terminated) if _main_thread() else None
    try:
        s = run_args(argv, bar)
        bar.finish()
        sys.stderr.write(f"rockhatch tiles: {s.tiles} tiles ({s.done_before} done before), {s.faces} faces, "
                         f"{s.hatches} hatches, {s.seconds:.2f} s, peak {s.peak_mb:.0f} MB per worker\n")
        if s.vector_tiles is not None and s.vector_tiles.tiles:
            v = s.vector_tiles
            sys.stderr.write(f"rockhatch tiles: {v.tiles} vector tiles, {v.bytes / 1e6:.1f} MB, largest "
                             f"{v.largest / 1e3:.0f} kB ({'/'.join(map(str, v.largest_tile))})\n")
        if s.partition_faces:
            sys.stderr.write(f"rockhatch tiles: partition extracted tile by tile: {s.partition_faces} faces, "
                             f"{s.partition_seconds:.2f} s\n")
        for w in s.warnings:
            sys.stderr.write(f"rockhatch tiles: warning: {w}\n")
        return 0
    except (RockhatchError, TexError, OSError) as e:
        return fail(e, bar, "rockhatch tiles")
    except _Terminate:
        return fail(carto.error(10, "terminated: the finished tiles are kept (run again to resume)"), bar,
                    "rockhatch tiles")
    except Exception as e:  # the cluster's own failures (a task lost on every retry, a timeout)
        return fail(f"the Dask cluster failed: {type(e).__name__}: {e}", bar, "rockhatch tiles")
    finally:
        if previous is not None:
            signal.signal(signal.SIGTERM, previous)


class _Terminate(BaseException):
    """Raised in the main thread by SIGTERM; a BaseException so no `except Exception` swallows it."""


def _terminated(signum, frame):
    raise _Terminate()


def _main_thread():
    return threading.current_thread() is threading.main_thread()


if __name__ == "__main__":
    sys.exit(main())
