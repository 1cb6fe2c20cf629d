"""Runs bench_tiled over the sizes of the thesis's Table 4.1 and beyond, one process per size
and engine (so that each peak memory is its own), and writes the table between the
`<!-- bench:tiled -->` markers of docs/tiled.md (or those --marker names). The environment is
passed on: run it with GLIBC_TUNABLES=glibc.malloc.hugetlb=1 for large pages under malloc.

usage: bench_tiled.py BENCH_TILED [--runs N] [--planar-timeout S] [--markdown docs/tiled.md] [--marker M]
"""
import argparse
import re
import subprocess
import sys

SIZES = [350, 1400, 2100, 4200, 9000, 100000, 1000000]
PLANAR_UP_TO = 100000  # the planar-map engine is not tried beyond (minutes, gigabytes)


def run(exe, cells, engine, runs, timeout):
    try:
        out = subprocess.run([exe, "--cells", str(cells), "--engine", engine, "--runs", str(runs)],
                             capture_output=True, text=True, timeout=timeout, check=True).stdout
    except subprocess.TimeoutExpired:
        return None
    return out.split()


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("exe")
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--planar-timeout", type=float, default=120)
    ap.add_argument("--markdown")
    ap.add_argument("--marker", default="bench:tiled", help="the table goes between <!-- MARKER --> and <!-- /MARKER -->")
    a = ap.parse_args()
    rows = []
    for cells in SIZES:
        runs = a.runs if cells <= 100000 else max(3, a.runs // 2)
        t = run(a.exe, cells, "tiled", runs, None)
        p = None
        if cells <= PLANAR_UP_TO:
            p = run(a.exe, cells, "planar", 3 if cells <= 9000 else 1, a.planar_timeout)
        planar = "not run" if cells > PLANAR_UP_TO else (
            f"> {a.planar_timeout:.0f} s" if p is None else f"{float(p[4]):.3f} s, {int(p[5]) / 1024:.0f} MiB")
        row = (f"| {cells:,} | {int(t[1]):,} | {float(t[2]) * 1000:.2f} ms | {float(t[3]):.4f} s | "
               f"{float(t[4]):.4f} s | {int(t[5]) / 1024:.0f} MiB | {planar} |")
        print(row, flush=True)
        rows.append(row)
    table = "\n".join([
        "| cells | curves out | operators | conversion, 1 thread | conversion, 2 threads | peak memory | "
        "planar-map engine (2 threads) |",
        "|---:|---:|---:|---:|---:|---:|---|",
        *rows,
    ])
    if a.markdown:
        with open(a.markdown) as f:
            text = f.read()
        mk = re.escape(a.marker)
        new = re.sub(r"(<!-- %s -->\n).*?(<!-- /%s -->)" % (mk, mk), lambda m: m.group(1) + table + "\n" + m.group(2),
                     text, flags=re.S)
        with open(a.markdown, "w") as f:
            f.write(new)
    return 0


if __name__ == "__main__":
    sys.exit(main())
