#!/usr/bin/env python3
"""Writes docs/bad-input.md's table of bad inputs: every row of tests/python/bad_inputs.py, run
against the built command, with the message it really prints (scratch paths shortened).

usage: /usr/bin/python3 scripts/bad_input_table.py [BUILD_DIR]   (default: build)
"""
import pathlib
import re
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "python"))

import bad_inputs  # noqa: E402
from test_bad_inputs import run_case  # noqa: E402


def main():
    build = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ROOT / "build")
    exe = build / "carto" / "rockhatch"
    rows = ["| command | input or option | bad case | exit | message |", "|---|---|---|---:|---|"]
    for case in bad_inputs.CASES:
        with tempfile.TemporaryDirectory() as d:
            r = run_case(exe, case, pathlib.Path(d))
            msg = r.stderr.strip().replace(d + "/", "").replace(d, ".")
        if r.returncode != case.code:
            sys.exit(f"bad_input_table: {case.id}: exit {r.returncode}, expected {case.code}: {msg}")
        msg = msg.split(": ", 1)[1] if ": " in msg else msg
        if len(msg) > 160:
            msg = msg[:157] + "..."
        msg = msg.replace("|", "\\|")
        rows.append(f"| `{case.cmd}` | `{case.what}` | {case.bad} | {case.code} | {msg} |")
    readme = ROOT / "docs" / "bad-input.md"
    text = readme.read_text()
    table = "<!-- bad-input-table:begin -->\n" + "\n".join(rows) + "\n<!-- bad-input-table:end -->"
    new, n = re.subn(r"<!-- bad-input-table:begin -->.*?<!-- bad-input-table:end -->", lambda m: table, text, flags=re.S)
    if n != 1:
        sys.exit("bad_input_table: docs/bad-input.md has no <!-- bad-input-table:begin/end --> markers")
    readme.write_text(new)
    print(f"bad_input_table: {len(bad_inputs.CASES)} rows written to docs/bad-input.md")


if __name__ == "__main__":
    main()
