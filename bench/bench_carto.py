#!/usr/bin/python3
"""Times the rockhatch pipeline: the bundled sample per style with 1 and 2 threads, a 4x
larger synthetic area, and the real DEM in ../shared (when present). Reports medians of
wall time, peak memory (GNU time) and hatches per second, and writes a Markdown table.
Then times `rockhatch partition` (the partition from the DEM alone) on the sample and the
real DEM, with the precision and recall of its lines against the sample's true lines.

    bench/bench_carto.py BUILD_DIR [--runs N] [--markdown FILE] [--only partition|styles|gpkg]
                         [--baseline EXE --baseline-label TEXT]...

With --only, only that section of the Markdown file is rewritten. The gpkg section times
Chamonix.tif at 1:10000 to a GeoPackage (print and rock) against ogr2ogr's copy of the
result. The styles section times
the built-in styles against their Python scripts (styles/*.py) and the whole runs the
style rewrite was budgeted on (`--style bidirectional`, and the default `print`); each
--baseline adds a column of another rockhatch executable's times (a version before a
change; `-` where it does not know the style).
"""
import argparse
import pathlib
import re
import statistics
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "python"))
from realdem import grid_partition  # noqa: E402  (shared with the tests)
from partition_quality import precision_recall  # noqa: E402
SAMPLE = ROOT / "data" / "sample_montblanc"
SHARED_DEM = ROOT.parent / "shared" / "data" / "montblanc" / "Chamonix.tif"
STYLES = ["noisy", "ridge-triangles", "density-cells", "fine-ridges", "balanced", "high-ridges", "bidirectional",
          "print"]


def time_command(cmd):
    """Wall seconds, peak RSS in MB and the standard error of one command (GNU time)."""
    r = subprocess.run(["/usr/bin/time", "-f", "RH_TIME %e %M", *map(str, cmd)], capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"bench_carto: {' '.join(map(str, cmd))} failed:\n{r.stderr}")
    wall, rss = re.search(r"RH_TIME ([\d.]+) (\d+)", r.stderr).groups()
    return float(wall), int(rss) / 1024, r.stderr


def timed(cmd):
    """Wall seconds, peak RSS in MB and hatch count of one run."""
    wall, rss, err = time_command(cmd)
    return wall, rss, int(re.search(r"(\d+) hatches", err).group(1))


def median_run(cmd, runs):
    results = [timed(cmd) for _ in range(runs)]
    wall = statistics.median(r[0] for r in results)
    return wall, max(r[1] for r in results), results[0][2]


PARTITION_MARK = "<!-- partition: written by bench/bench_carto.py -->"
STYLES_MARK = "<!-- styles: written by bench/bench_carto.py -->"
GPKG_MARK = "<!-- gpkg: written by bench/bench_carto.py -->"
PRINT_MARK = "<!-- print quality: copied by bench/bench_carto.py from docs/print-quality.md -->"


def print_quality_section():
    """Issue 16's print measures, as bench/print_quality.py last wrote them to
    docs/print-quality.md (it draws Chamonix.tif at three scales: run it on its own)."""
    source = ROOT / "docs" / "print-quality.md"
    if not source.exists():
        return ""
    lines = [line for line in source.read_text().splitlines()
             if not line.startswith("<!--") and not line.startswith("# ")]
    body = "\n".join(lines).strip()
    return (f"{PRINT_MARK}\n\n### Print quality (issue 16)\n\nFrom [print-quality.md](print-quality.md), "
            f"written by `bench/print_quality.py`.\n\n{body}\n")


def knows_style(exe, style):
    """Whether exe lists the style (a baseline may not know a newer one)."""
    r = subprocess.run([str(exe), "--list-styles"], capture_output=True, text=True)
    return r.returncode == 0 and re.search(rf"^\s*{re.escape(style)}\b", r.stdout, re.M) is not None


# The style the speed budget of issue 11 was set on (the default until `print`), then the
# default style.
BUDGET_STYLES = ["bidirectional", "print"]


def styles_section(build_dir, runs, tmp, baselines=()):
    """Markdown of the style programs' costs: the budgeted whole runs (Chamonix.tif with
    --partition auto, the sample) for the budget's style and the default one, beside each
    baseline executable (label, path), then each built-in style against its Python script."""
    exe = build_dir / "carto" / "rockhatch"
    env = dict(__import__("os").environ, PYTHONPATH=str(build_dir / "python"))
    load = pathlib.Path("/proc/loadavg").read_text().split()[:3] if pathlib.Path("/proc/loadavg").exists() else []
    lines = [STYLES_MARK, "", "### Style programs", "",
             f"Whole command runs, `--style` as given, 1:10000, 2 threads, median of {runs} runs"
             + "".join(f"; `{label}`: {path}" for label, path in baselines)
             + (f"; load average {' / '.join(load)} when the section started" if load else "") + ".", "",
             "| case | style | output | wall time (median) | " + "".join(f"{label} | " for label, _ in baselines)
             + "hatches |",
             "|---|---|---|---:|" + "---:|" * len(baselines) + "---:|"]
    cases = [("sample (20 faces)", ["--dem", SAMPLE / "dem.tif", "--partition", SAMPLE / "partition.gpkg"])]
    if SHARED_DEM.exists():
        cases.append(("Chamonix.tif, --partition auto", ["--dem", SHARED_DEM, "--partition", "auto"]))
    else:
        print(f"bench_carto: {SHARED_DEM} absent, real-DEM style rows skipped")
    for style in BUDGET_STYLES:
        for label, inputs in cases:
            for ext in (".gpkg", ".svg"):
                cmd = ["-q", "--overwrite", "--threads", "2", "--style", style, *inputs, "-o", tmp / f"style{ext}"]
                wall, _, hatches = median_run([exe, *cmd], runs)
                before = ""
                for _, path in baselines:
                    before += f" {median_run([path, *cmd], runs)[0]:.2f} s |" if knows_style(path, style) else " - |"
                print(f"styles {label:35s} {style:14s} {ext} {wall:6.2f} s{before} {hatches} hatches", flush=True)
                lines.append(f"| {label} | {style} | {ext[1:]} | {wall:.2f} s |{before} {hatches} |")
    lines += ["", f"Each built-in style (C++) against its script in styles/ (Python, same bytes), on the sample, "
              f"GeoPackage, 2 threads, median of {runs} runs (the script's time includes starting Python):", "",
              "| style | C++ built-in | Python script | ratio |", "|---|---:|---:|---:|"]
    inputs = ["--dem", SAMPLE / "dem.tif", "--partition", SAMPLE / "partition.gpkg", "--threads", "2", "-q",
              "--overwrite", "-o", tmp / "s.gpkg"]
    for style in STYLES:
        c = statistics.median(timed([exe, "--style", style, *inputs])[0] for _ in range(runs))
        script = ROOT / "styles" / (style.replace("-", "_") + ".py")
        py = []
        for _ in range(runs):
            r = subprocess.run(["/usr/bin/time", "-f", "RH_TIME %e", "/usr/bin/python3", str(script),
                                *map(str, inputs)], capture_output=True, text=True, env=env)
            if r.returncode != 0:
                sys.exit(f"bench_carto: {script} failed:\n{r.stderr}")
            py.append(float(re.search(r"RH_TIME ([\d.]+)", r.stderr).group(1)))
        p = statistics.median(py)
        print(f"styles {style:16s} C++ {c:5.2f} s  Python {p:5.2f} s  {p / c:4.2f}x", flush=True)
        lines.append(f"| {style} | {c:.2f} s | {p:.2f} s | {p / c:.2f}x |")
    return "\n".join(lines) + "\n"


def gpkg_section(build_dir, runs, tmp):
    """Chamonix.tif at 1:10000 (its partition saved once by `rockhatch partition`) drawn to a
    GeoPackage by print and rock on 2 threads, against GDAL's copy of the result without an
    index (issue 43's yardstick), in alternating rounds; medians and ranges."""
    if not SHARED_DEM.exists():
        print(f"bench_carto: {SHARED_DEM} absent, GeoPackage section skipped")
        return ""
    exe = build_dir / "carto" / "rockhatch"
    part = tmp / "chamonix_partition.gpkg"
    subprocess.run([exe, "partition", "-q", "--overwrite", "--dem", SHARED_DEM, "--scale", "10000", "-o", part],
                   check=True, capture_output=True)
    styles = ("print", "rock")
    runs_of = {s: [] for s in styles}
    copies = {s: [] for s in styles}
    for _ in range(runs):
        for style in styles:
            out, copy = tmp / f"{style}.gpkg", tmp / f"{style}_copy.gpkg"
            # Both write a new file: replacing one costs the file system a flush of it on rename.
            out.unlink(missing_ok=True)
            runs_of[style].append(timed([exe, "--overwrite", "--threads", "2", "--dem", SHARED_DEM, "--partition", part,
                                         "--scale", "10000", "--style", style, "-o", out]))
            copy.unlink(missing_ok=True)
            copies[style].append(time_command(["ogr2ogr", "-f", "GPKG", "-lco", "SPATIAL_INDEX=NO", copy, out])[0])
    lines = [GPKG_MARK, "", "### Drawing to a GeoPackage against GDAL's copy of it (issue 43)", "",
             f"Chamonix.tif at 1:10000, its partition saved once (`rockhatch partition --scale 10000`), the "
             f"whole command to a new GeoPackage (R-tree included), 2 threads; then "
             f"`ogr2ogr -f GPKG -lco SPATIAL_INDEX=NO` of the result; {runs} alternating rounds, medians "
             f"(range). How the writer works: [gpkg-writer.md](gpkg-writer.md).", "",
             "| style | wall time | peak memory | strokes | strokes / s | ogr2ogr copy of the result | run / copy |",
             "|---|---:|---:|---:|---:|---:|---:|"]
    for style in styles:
        walls = [w for w, _, _ in runs_of[style]]
        wall, copy = statistics.median(walls), statistics.median(copies[style])
        peak = [m for _, m, _ in runs_of[style]]
        strokes = runs_of[style][0][2]
        print(f"gpkg {style:6s} {wall:6.2f} s  copy {copy:6.2f} s  {wall / copy:4.2f}x  {max(peak):5.0f} MB", flush=True)
        lines.append(f"| {style} | {wall:.2f} s ({min(walls):.2f}-{max(walls):.2f}) | {min(peak):.0f}-{max(peak):.0f} MB "
                     f"| {strokes} | {strokes / wall:.0f} | {copy:.2f} s ({min(copies[style]):.2f}-"
                     f"{max(copies[style]):.2f}) | {wall / copy:.2f}x |")
    return "\n".join(lines) + "\n"


def rewrite_section(markdown, mark, section):
    """Replaces (or adds) the section that starts at `mark` in the report: the report is its
    head, then the styles section, then the partition section, then the print-quality section
    (copied again from docs/print-quality.md)."""
    old = markdown.read_text() if markdown.exists() else ""
    order = (STYLES_MARK, GPKG_MARK, PARTITION_MARK, PRINT_MARK)
    starts = sorted((old.index(m), m) for m in order if m in old)
    head = old[:starts[0][0]] if starts else old
    parts = {m: old[a:(starts[k + 1][0] if k + 1 < len(starts) else len(old))] for k, (a, m) in enumerate(starts)}
    parts[mark] = section
    quality = print_quality_section()
    if quality:
        parts[PRINT_MARK] = quality
    chunks = [head.strip("\n")] + [parts[m].strip("\n") for m in order if m in parts]
    markdown.write_text("\n\n".join(c for c in chunks if c) + "\n")


def partition_section(build_dir, runs, tmp):
    """Markdown of the `rockhatch partition` timings and quality."""
    exe = build_dir / "carto" / "rockhatch"
    lines = [PARTITION_MARK, "", "### Partition from the DEM alone (`rockhatch partition`)", "",
             f"Whole command runs (read, reproject, terrain, flow, faces, write), median of {runs} runs.", "",
             "| case | wall time (median) | peak memory | faces | ridge / valley borders |",
             "|---|---:|---:|---:|---:|"]
    cases = [("sample 2.4 km, 5 m cells (EPSG:2154)", SAMPLE / "dem.tif", [])]
    if SHARED_DEM.exists():
        cases.append(("real DEM Chamonix.tif (EPSG:4326 -> UTM 32N, 31 m cells), defaults", SHARED_DEM, []))
        cases.append(("real DEM Chamonix.tif (EPSG:4326 -> UTM 32N, 31 m cells), --scale 25000", SHARED_DEM,
                      ["--scale", "25000"]))
    else:
        print(f"bench_carto: {SHARED_DEM} absent, real-DEM partition row skipped")
    sample_out = None
    for label, dem, extra in cases:
        out = tmp / f"partition{len(lines)}.gpkg"
        walls, rss = [], 0
        for _ in range(runs):
            r = subprocess.run(["/usr/bin/time", "-f", "RH_TIME %e %M", str(exe), "partition", "--dem", str(dem),
                                "-o", str(out), "--overwrite", "-q", *extra], capture_output=True, text=True)
            if r.returncode != 0:
                sys.exit(f"bench_carto: rockhatch partition on {dem} failed:\n{r.stderr}")
            wall, mem = re.search(r"RH_TIME ([\d.]+) (\d+)", r.stderr).groups()
            walls.append(float(wall))
            rss = max(rss, int(mem) / 1024)
        faces, ridges, valleys = map(int, re.search(r"(\d+) faces, (\d+) ridge and (\d+) valley", r.stderr).groups())
        wall = statistics.median(walls)
        print(f"partition {label:70s} {wall:6.2f} s {rss:6.0f} MB {faces} faces", flush=True)
        lines.append(f"| {label} | {wall:.2f} s | {rss:.0f} MB | {faces} | {ridges} / {valleys} |")
        if sample_out is None:
            sample_out = tmp / "sample_partition.gpkg"
            out.rename(sample_out)
    lines += ["", "Quality on the sample against the generator's true lines (`truth.gpkg`), tolerance 10 m "
              "(two cells), measured inside the rock mask and the convex hull of the true lines "
              "(tests/python/partition_quality.py):", "",
              "| lines | kind | precision | recall | extracted | true |", "|---|---|---:|---:|---:|---:|"]
    for layer, what in (("network", "traced network (`network` layer)"), ("lines", "face borders (`lines` layer)")):
        for kind, (p, r, ext, true) in precision_recall(sample_out, SAMPLE / "truth.gpkg", layer).items():
            print(f"{what:34s} {kind:6s} precision {p:.3f} recall {r:.3f}")
            lines.append(f"| {what} | {kind} | {p:.3f} | {r:.3f} | {ext:.0f} m | {true:.0f} m |")
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("build_dir", type=pathlib.Path)
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--markdown", type=pathlib.Path)
    ap.add_argument("--only", choices=["partition", "styles", "gpkg"],
                    help="run only this section (the rest of the report is kept)")
    ap.add_argument("--baseline", type=pathlib.Path, action="append", default=[],
                    help="another rockhatch executable to compare in the styles section (repeatable)")
    ap.add_argument("--baseline-label", action="append", default=[],
                    help="what each baseline executable is, in the order of --baseline (column titles)")
    args = ap.parse_args()
    labels = args.baseline_label + [f"baseline {k + 1}" for k in range(len(args.baseline_label), len(args.baseline))]
    baselines = list(zip(labels, args.baseline))
    if args.only:
        with tempfile.TemporaryDirectory() as tmp:
            if args.only == "partition":
                mark, section = PARTITION_MARK, partition_section(args.build_dir, max(args.runs, 5), pathlib.Path(tmp))
            elif args.only == "gpkg":
                mark, section = GPKG_MARK, gpkg_section(args.build_dir, args.runs, pathlib.Path(tmp))
            else:
                mark, section = STYLES_MARK, styles_section(args.build_dir, args.runs, pathlib.Path(tmp), baselines)
        if args.markdown:
            rewrite_section(args.markdown, mark, section)
            print(f"report written to {args.markdown}")
        return
    exe = args.build_dir / "carto" / "rockhatch"
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)

        def case(label, dem, part, extra, threads, out_ext=".gpkg"):
            cmd = [exe, "-q", "--overwrite", "--threads", threads, "--dem", dem, "--partition", part, *extra,
                   "-o", tmp / f"out{out_ext}"]
            wall, rss, hatches = median_run(cmd, args.runs)
            rows.append((label, threads, wall, rss, hatches, hatches / wall))
            print(f"{label:58s} {threads}t {wall:7.2f} s {rss:7.0f} MB {hatches:9d} hatches {hatches / wall:10.0f}/s",
                  flush=True)
            return wall

        dem, part = SAMPLE / "dem.tif", SAMPLE / "partition.gpkg"
        for style in STYLES:
            for t in (1, 2):
                case(f"sample (20 faces), {style}, GeoPackage", dem, part, ["--style", style], t)
        # Scaling: the same massif four times (4x area, 80 faces).
        big = tmp / "big"
        subprocess.run([args.build_dir / "carto" / "rh_make_sample", "-o", big, "--size", "4800"], check=True,
                       capture_output=True)
        bidir = ["--style", "bidirectional"]
        base = case("sample 2.4 km (20 faces), bidirectional, GeoPackage", dem, part, bidir, 2)
        four = case("sample x4 4.8 km (80 faces), bidirectional, GeoPackage", big / "dem.tif",
                    big / "partition.gpkg", bidir, 2)
        print(f"4x area costs {four / base:.2f}x the time")
        rows.append(("4x area / 1x area time ratio", 2, four / base, 0, 0, 0))
        if SHARED_DEM.exists():
            grid = tmp / "grid.gpkg"
            n = grid_partition(SHARED_DEM, grid, 90)
            label = f"real DEM Chamonix.tif (EPSG:4326, {n} faces, slope >= 90%)"
            for style in STYLES:
                for t in (1, 2):
                    case(f"{label}, {style}, GeoPackage", SHARED_DEM, grid, ["--style", style], t)
            for t in (1, 2):
                case(f"{label}, bidirectional, GeoPackage without R-tree", SHARED_DEM, grid,
                     [*bidir, "--no-spatial-index"], t)
                case(f"{label}, bidirectional, SVG", SHARED_DEM, grid, bidir, t, ".svg")
        else:
            print(f"bench_carto: {SHARED_DEM} absent, real-DEM rows skipped")
        styles = styles_section(args.build_dir, args.runs, tmp, baselines)
        gpkg = gpkg_section(args.build_dir, args.runs, tmp)
        partition = partition_section(args.build_dir, max(args.runs, 5), tmp)
    if args.markdown:
        with open(args.markdown, "w") as f:
            f.write(f"<!-- written by bench/bench_carto.py; medians of {args.runs} runs; whole runs of the "
                    "rockhatch command (read, fields, hatching, write) -->\n")
            f.write("| case | threads | wall time (median) | peak memory | hatches | hatches / s |\n")
            f.write("|---|---:|---:|---:|---:|---:|\n")
            for label, t, wall, rss, hatches, rate in rows:
                if hatches == 0:
                    f.write(f"| {label} | {t} | {wall:.2f}x | | | |\n")
                else:
                    f.write(f"| {label} | {t} | {wall:.2f} s | {rss:.0f} MB | {hatches} | {rate:.0f} |\n")
            f.write("\n" + styles + ("\n" + gpkg if gpkg else "") + "\n" + partition)
            quality = print_quality_section()
            if quality:
                f.write("\n" + quality)
        print(f"report written to {args.markdown}")


if __name__ == "__main__":
    main()
