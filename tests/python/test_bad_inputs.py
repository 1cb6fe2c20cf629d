"""Every bad input of bad_inputs.CASES: the exit code, a one-line message naming the input,
no output left behind and every input unchanged; and docs/bad-input.md lists exactly these rows."""
import hashlib
import os
import re
import resource
import subprocess

import pytest

import bad_inputs
from conftest import ROOT, SANITIZED


# A refused run must refuse, not try: 8 GB is far more than any row needs to fail. The same
# rows in both passes; only the way memory is limited differs. Under ASan (scripts/sanitize.sh
# sets RH_SANITIZED=1) an address-space limit cannot be used at all: ASan reserves terabytes of
# address space for its shadow memory at start-up, so every program would fail there. The limit
# goes through ASan's allocator instead: no single allocation over 8 GB, and malloc returns null
# rather than aborting, as it would at the limit.


def _limit_memory():
    if not SANITIZED:
        resource.setrlimit(resource.RLIMIT_AS, (8 << 30, 8 << 30))


def _env():
    env = dict(os.environ)
    if SANITIZED:
        env["ASAN_OPTIONS"] = ":".join(filter(None, [env.get("ASAN_OPTIONS", ""), "max_allocation_size_mb=8192",
                                                      "allocator_may_return_null=1"]))
    return env


def run_case(exe, case, w, args=None):
    """Runs one row in scratch folder w (its inputs are made there unless `args` is given)."""
    args = case.args(w) if args is None else args
    argv = [str(exe)] + case.cmd.split()[1:] + [str(a) for a in args]
    return subprocess.run(argv, capture_output=True, text=True, timeout=120, preexec_fn=_limit_memory, env=_env())


def digest(folder):
    return {p.relative_to(folder): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(folder.rglob("*")) if p.is_file() and "out" not in p.relative_to(folder).parts}


@pytest.mark.parametrize("case", bad_inputs.CASES, ids=lambda c: c.id)
def test_bad_input(rockhatch_exe, tmp_path, case):
    w = tmp_path
    args = case.args(w)  # makes the inputs
    before = digest(w)
    r = run_case(rockhatch_exe, case, w, args)
    lines = [line for line in r.stderr.splitlines() if line.strip()]
    assert r.returncode == case.code, (r.returncode, r.stderr)
    assert len(lines) == 1, r.stderr
    assert lines[0].startswith(case.cmd + ": "), lines[0]
    for word in case.words:
        assert word in lines[0], (word, lines[0])
    out = w / "out"
    assert not out.exists() or not list(out.rglob("*")), list(out.rglob("*"))
    assert digest(w) == before, "an input changed"


def readme_rows():
    text = (ROOT / "docs" / "bad-input.md").read_text()
    m = re.search(r"<!-- bad-input-table:begin -->(.*?)<!-- bad-input-table:end -->", text, re.S)
    assert m, "docs/bad-input.md has no bad-input table (scripts/bad_input_table.py writes it)"
    rows = []
    for line in m.group(1).splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) >= 5 and cells[3].isdigit():
            rows.append((cells[0].strip("`"), cells[1].strip("`"), cells[2], int(cells[3])))
    return rows


def test_the_docs_list_every_case():
    expected = [(c.cmd, c.what, c.bad, c.code) for c in bad_inputs.CASES]
    assert readme_rows() == expected, "docs/bad-input.md is out of date: run scripts/bad_input_table.py"


def test_every_option_of_the_help_has_a_row(rockhatch_exe):
    """A new option must come with its bad cases."""
    covered = {(c.cmd, c.what) for c in bad_inputs.CASES}
    # Flags take no value, and --help / --list-styles / -q only print: nothing bad to give them.
    no_value = {"--overwrite", "-q", "--help", "--list-styles", "--no-repair", "--no-spatial-index",
                "--no-ridge-extension", "--no-outline-labels", "--smooth-edge", "--fixed-controls"}
    for cmd, argv in (("rockhatch", ["--help"]), ("rockhatch partition", ["partition", "--help"])):
        text = subprocess.run([str(rockhatch_exe), *argv], capture_output=True, text=True).stdout
        options = set(re.findall(r"^\s+(-{1,2}[a-z][a-z-]*)", text, re.M)) - no_value
        assert options, text
        missing = sorted(o for o in options if (cmd, o) not in covered)
        assert not missing, f"{cmd}: no bad-input row for {missing}"
