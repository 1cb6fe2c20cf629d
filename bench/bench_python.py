#!/usr/bin/python3
"""What Python costs: the Appendix A gallery written in Python (bindings/examples/gallery.py)
against the same examples in C++ (rh_gallery), and the Python style scripts (styles/)
against the built-in C++ styles on the sample and on the real DEM. Reports medians and
where the Python time goes, as Markdown.

    bench/bench_python.py BUILD_DIR [--runs N] [--markdown FILE]
"""
import argparse
import cProfile
import pathlib
import pstats
import re
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
SAMPLE = ROOT / "data" / "sample_montblanc"
SHARED_DEM = ROOT.parent / "shared" / "data" / "montblanc" / "Chamonix.tif"
STYLE_CASES = ["noisy", "density-cells", "bidirectional"]


def median(xs):
    return statistics.median(xs)


def cpp_gallery_times(exe, name, threads, runs, out):
    """rh_gallery prints the seconds of build + evaluation + SVG writing of each example."""
    times = []
    for _ in range(runs + 1):  # the first run warms the caches
        r = subprocess.run([str(exe), "--only", name, "--threads", str(threads), "--out", str(out)],
                           capture_output=True, text=True, check=True)
        times.append(float(re.search(r"curves\s+([\d.]+) s", r.stdout).group(1)))
    return median(times[1:])


class Counter:
    """Wraps the MapTo* operators of the gallery module to count Python mapper calls."""

    def __init__(self, module, tex):
        self.calls = 0
        for op in ("MapToVertices", "MapToEdges", "MapToFaces"):
            setattr(module, op, self.wrap(getattr(tex, op)))

    def wrap(self, op):
        def counted(mapper, arrangement):
            def m(cell):
                self.calls += 1
                return mapper(cell)

            return op(m, arrangement)

        return counted


def gallery_rows(build, runs, tmp):
    sys.path.insert(0, str(ROOT / "bindings" / "examples"))
    import gallery
    from rockhatch import tex

    exe = build / "libtex" / "rh_gallery"
    rows = []
    for name, build_fn in gallery.EXAMPLES.items():
        row = {"name": name}
        for threads in (1, 2):
            tex.SetThreads(threads)
            py = []
            for _ in range(runs + 1):
                t0 = time.perf_counter()
                tex.ExportSVG(build_fn(gallery.ELEMENTS), gallery.SIZE, str(tmp / f"{name}.svg"))
                py.append(time.perf_counter() - t0)
            row[f"py{threads}"] = median(py[1:])
            row[f"cpp{threads}"] = cpp_gallery_times(exe, name, threads, runs, tmp / "cpp")
        tex.SetThreads(1)
        counter = Counter(gallery, tex)
        tex.ExportSVG(build_fn(gallery.ELEMENTS), gallery.SIZE, str(tmp / f"{name}.svg"))
        row["calls"] = counter.calls
        for op in ("MapToVertices", "MapToEdges", "MapToFaces"):
            setattr(gallery, op, getattr(tex, op))
        rows.append(row)
        print(f"{name:10s} C++ {row['cpp1'] * 1e3:8.1f} ms  Python {row['py1'] * 1e3:8.1f} ms  "
              f"x{row['py1'] / row['cpp1']:5.2f}  {row['calls']:6d} Python mapper calls", flush=True)
    tex.SetThreads(0)
    return rows


def style_run(carto, dem, part, style, threads, out, **extra):
    t0 = time.perf_counter()
    s = carto.run(dem, part, [out], style=style, threads=threads, overwrite=True, **extra)
    return time.perf_counter() - t0, s.hatches


def style_rows(runs, tmp, cases):
    from rockhatch import carto

    rows = []
    for label, dem, part, extra in cases:
        for name in STYLE_CASES:
            script = str(ROOT / "styles" / (name.replace("-", "_") + ".py"))
            row = {"case": label, "style": name}
            for threads in (1, 2):
                for kind, style in (("cpp", name), ("py", script)):
                    ts = []
                    for _ in range(runs + 1):
                        t, hatches = style_run(carto, dem, part, style, threads, tmp / "s.gpkg", **extra)
                        ts.append(t)
                    row[f"{kind}{threads}"] = median(ts[1:])
                    row["hatches"] = hatches
            rows.append(row)
            print(f"{label:12s} {name:14s} C++ {row['cpp1']:6.2f} s  Python {row['py1']:6.2f} s  "
                  f"x{row['py1'] / row['cpp1']:5.2f}  (2 threads: {row['cpp2']:6.2f} / {row['py2']:6.2f} s)",
                  flush=True)
    return rows


def profile_style(dem, part, name, tmp, extra):
    """Where the Python style's time goes (one thread, so cProfile sees the face calls)."""
    from rockhatch import carto

    script = str(ROOT / "styles" / (name.replace("-", "_") + ".py"))
    prof = cProfile.Profile()
    t0 = time.perf_counter()
    prof.enable()
    carto.run(dem, part, [tmp / "p.gpkg"], style=script, threads=1, overwrite=True, **extra)
    prof.disable()
    total = time.perf_counter() - t0
    st = pstats.Stats(prof)
    groups = {"pipeline (read, fields, write)": 0.0, "C++ building blocks": 0.0, "Python style code": 0.0}
    blocks = {}
    for (filename, _, func), (_, _, tottime, _, _) in st.stats.items():
        if filename == "~":  # built-in / extension functions
            if "run" in func:
                key = "pipeline (read, fields, write)"
            else:
                key = "C++ building blocks"
                m = re.search(r"'(\w+)'|method '(\w+)' of '(?:rockhatch\._rockhatch\.)?(?:carto\.)?(\w+)", func)
                label = func
                if m:
                    label = m.group(1) or f"{m.group(3)}.{m.group(2)}"
                blocks[label] = blocks.get(label, 0.0) + tottime
        else:
            key = "Python style code"
        groups[key] += tottime
    # The pipeline's own time is what carto.run spent outside the Python calls.
    inside = groups["C++ building blocks"] + groups["Python style code"]
    groups["pipeline (read, fields, write)"] = max(0.0, total - inside)
    top = sorted(blocks.items(), key=lambda kv: -kv[1])[:6]
    return total, groups, top


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("build_dir", type=pathlib.Path)
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--markdown", type=pathlib.Path)
    args = ap.parse_args()
    build = args.build_dir.resolve()
    sys.path.insert(0, str(build / "python"))
    sys.path.insert(0, str(ROOT / "tests" / "python"))
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        (tmp / "cpp").mkdir()
        grows = gallery_rows(build, args.runs, tmp)
        cases = [("sample", SAMPLE / "dem.tif", SAMPLE / "partition.gpkg", {})]
        if SHARED_DEM.exists():
            from realdem import grid_partition

            part = tmp / "real_partition.gpkg"
            grid_partition(SHARED_DEM, part)
            cases.append(("real DEM", SHARED_DEM, part, {}))
        else:
            print(f"bench_python: {SHARED_DEM} is absent: the real-DEM rows are skipped")
        srows = style_rows(max(3, args.runs // 2), tmp, cases)
        prof_case = cases[-1]
        total, groups, top = profile_style(prof_case[1], prof_case[2], "bidirectional", tmp, prof_case[3])

    lines = ["# Python against C++", "",
             "Written by `bench/bench_python.py` (`cmake --build build --target bench_python`). Medians after one "
             "warm-up run, on this project's 2-core machine.", "",
             "## Appendix A gallery: Python scripts against their C++ twins", "",
             "Both build the arrangement and write the SVG (the bytes are the same: a test checks it). The C++ "
             "time is what `rh_gallery` measures in-process; the Python time is measured around the same call in "
             "the interpreter. Overhead per call = (Python - C++) / Python mapper calls, one thread.", "",
             "| example | C++ 1 t (ms) | Python 1 t (ms) | ratio | C++ 2 t (ms) | Python 2 t (ms) | ratio "
             "| Python mapper calls | overhead per call (µs) |",
             "|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in grows:
        per_call = (r["py1"] - r["cpp1"]) / r["calls"] * 1e6 if r["calls"] else float("nan")
        lines.append(f"| {r['name']} | {r['cpp1'] * 1e3:.1f} | {r['py1'] * 1e3:.1f} | {r['py1'] / r['cpp1']:.2f} | "
                     f"{r['cpp2'] * 1e3:.1f} | {r['py2'] * 1e3:.1f} | {r['py2'] / r['cpp2']:.2f} | {r['calls']} | "
                     f"{per_call:.1f} |")
    tot_c = sum(r["cpp1"] for r in grows)
    tot_p = sum(r["py1"] for r in grows)
    lines += ["", f"All examples, one thread: C++ {tot_c * 1e3:.0f} ms, Python {tot_p * 1e3:.0f} ms "
              f"(x{tot_p / tot_c:.2f}).", "",
              "## Styles: Python scripts against the built-in C++ styles", "",
              "`carto.run` in one process with the built-in style and with `styles/NAME.py` (same hatches: a test "
              "compares the bytes). The real DEM is `../shared/data/montblanc/Chamonix.tif` with the grid partition "
              "of the carto benchmark.", "",
              "| area | style | hatches | C++ 1 t (s) | Python 1 t (s) | ratio | C++ 2 t (s) | Python 2 t (s) | ratio |",
              "|---|---|---:|---:|---:|---:|---:|---:|---:|"]
    for r in srows:
        lines.append(f"| {r['case']} | {r['style']} | {r['hatches']} | {r['cpp1']:.2f} | {r['py1']:.2f} | "
                     f"{r['py1'] / r['cpp1']:.2f} | {r['cpp2']:.2f} | {r['py2']:.2f} | {r['py2'] / r['cpp2']:.2f} |")
    lines += ["", f"## Where the Python style's time goes ({prof_case[0]}, bidirectional, one thread, cProfile)", "",
              f"Total {total:.2f} s (profiling adds its own overhead).", "", "| part | seconds | share |",
              "|---|---:|---:|"]
    for k, v in groups.items():
        lines.append(f"| {k} | {v:.2f} | {100 * v / total:.0f} % |")
    lines += ["", "Largest C++ building blocks called from Python:", "", "| call | seconds |", "|---|---:|"]
    for k, v in top:
        lines.append(f"| `{k}` | {v:.2f} |")
    text = "\n".join(lines) + "\n"
    print(text)
    if args.markdown:
        args.markdown.write_text(text)


if __name__ == "__main__":
    main()
