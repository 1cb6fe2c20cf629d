"""Issue 17, reliability: no command writes onto one of its inputs (however the output is
spelt: ./x, a/../x, a symbolic or a hard link) nor twice onto one file, and a library call
leaves the process as it found it (GDAL configuration options, libtex's thread count and
seed). The QGIS algorithms: test_qgis_plugin.py."""
import hashlib
import os
import pathlib
import shutil
import subprocess

import pytest
from osgeo import gdal, ogr

import rockhatch
from rockhatch import carto, tex
from conftest import python_env

FRAMED_TILES = pathlib.Path(__file__).resolve().parent / "style_scripts" / "framed_tiles.py"
SPELLINGS = ["same", "dot", "dotdot", "symlink", "hardlink"]
# Every GDAL configuration option carto sets (scoped to its calls since issue 17).
GDAL_KEYS = ["OGR_CURRENT_DATE", "OGR_SQLITE_JOURNAL", "OGR_SQLITE_SYNCHRONOUS", "OGR_SQLITE_PRAGMA", "CPL_LOG"]
FIXED_DATE = "2000/01/01 00:00:00+00"  # carto's OGR_CURRENT_DATE, as OGR reads it back


def digest(path):
    return hashlib.sha256(pathlib.Path(path).read_bytes()).hexdigest()


@pytest.fixture
def data(sample_dir, tmp_path):
    """A copy of the sample, a style script and a mask in a folder of their own (with a
    subfolder for a/../x spellings); the files' digests."""
    d = tmp_path / "data"
    (d / "sub").mkdir(parents=True)
    shutil.copy(sample_dir / "dem.tif", d / "dem.tif")
    shutil.copy(sample_dir / "partition.gpkg", d / "partition.gpkg")
    shutil.copy(sample_dir / "partition.gpkg", d / "mask.gpkg")
    # A style script that leaves a mark when it runs: a refused run must not run it.
    (d / "style.py").write_text(
        "import pathlib, runpy\n"
        f"pathlib.Path({str(d / 'script_ran')!r}).touch()\n"
        f"_base = runpy.run_path({str(FRAMED_TILES)!r})\n"
        "NAME, PARAMS, style = 'marked', _base['PARAMS'], _base['style']\n")
    return d


def spelt(path, how):
    """Another name of `path` (to be used from the folder of `path`): itself, ./x, sub/../x,
    a symbolic link or a hard link to it (created here)."""
    path = pathlib.Path(path)
    if how == "same":
        return str(path)
    if how == "dot":
        return "./" + path.name
    if how == "dotdot":
        return "sub/../" + path.name
    link = path.with_name(how + path.suffix)
    if how == "symlink":
        link.symlink_to(path.name)
    else:
        os.link(path, link)
    return link.name


def snapshot(folder):
    return {p.name: digest(p) for p in folder.iterdir() if p.is_file()}


def assert_refused(r, *names):
    """Exit code 9 and one line naming the output and the input."""
    assert r.returncode == 9, (r.returncode, r.stderr)
    lines = [line for line in r.stderr.splitlines() if line.strip()]
    assert len(lines) == 1, r.stderr
    for name in names:
        assert name in lines[0], lines[0]


def run_in(folder, *args, env=None):
    return subprocess.run([str(a) for a in args], capture_output=True, text=True, timeout=120, cwd=folder, env=env)


# ---- the rockhatch command


@pytest.mark.parametrize("how", SPELLINGS)
@pytest.mark.parametrize("option", ["--partition", "--dem", "--script"])
def test_command_refuses_to_write_onto_an_input(rockhatch_exe, data, how, option):
    files = {"--dem": data / "dem.tif", "--partition": data / "partition.gpkg", "--script": data / "style.py"}
    args = ["--dem", files["--dem"], "--partition", files["--partition"]]
    if option == "--script":
        args += ["--script", files["--script"]]
    output = spelt(files[option], how)
    before = snapshot(data)
    r = run_in(data, rockhatch_exe, "-q", *args, "-o", output, "--overwrite", env=python_env())
    assert_refused(r, f"-o '{output}'", f"{option} '{files[option]}'", "onto an input")
    assert snapshot(data) == before  # the input byte for byte, and nothing else written
    assert not (data / "script_ran").exists()


def test_command_refuses_two_outputs_that_are_one_file(rockhatch_exe, data, tmp_path):
    r = run_in(data, rockhatch_exe, "-q", "--dem", "dem.tif", "--partition", "partition.gpkg",
               "-o", tmp_path / "h.svg", "-o", "../h.svg")
    assert_refused(r, str(tmp_path / "h.svg"), "'../h.svg'", "the same file")
    assert not list(tmp_path.glob("h.svg*"))


@pytest.mark.parametrize("how", SPELLINGS)
@pytest.mark.parametrize("target", ["-o dem", "--png dem", "-o mask"])
def test_partition_command_refuses_to_write_onto_an_input(rockhatch_exe, data, tmp_path, how, target):
    option, name = target.split()
    source = data / ("dem.tif" if name == "dem" else "mask.gpkg")
    output = spelt(source, how)
    outputs = ["-o", output] if option == "-o" else ["-o", tmp_path / "p.gpkg", "--png", output]
    before = snapshot(data)
    r = run_in(data, rockhatch_exe, "partition", "-q", "--dem", data / "dem.tif", "--mask", data / "mask.gpkg",
               *outputs, "--overwrite")
    input_option = "--dem" if name == "dem" else "--mask"
    assert_refused(r, f"{option} '{output}'", f"{input_option} '{source}'")
    assert r.stderr.startswith("rockhatch partition: ")
    assert snapshot(data) == before
    assert not (tmp_path / "p.gpkg").exists()


def test_partition_command_refuses_its_preview_onto_its_output(rockhatch_exe, data, tmp_path):
    r = run_in(data, rockhatch_exe, "partition", "-q", "--dem", "dem.tif", "-o", tmp_path / "p.gpkg",
               "--png", data / ".." / "p.gpkg")
    assert_refused(r, "--png", "-o", "the same file")


# ---- Python


@pytest.mark.parametrize("how", ["same", "dotdot", "symlink", "hardlink"])
def test_run_from_python_refuses_to_write_onto_an_input(data, how, monkeypatch):
    monkeypatch.chdir(data)
    output = spelt(data / "partition.gpkg", how)
    before = snapshot(data)
    with pytest.raises(rockhatch.RockhatchError, match="onto an input") as e:
        carto.run(data / "dem.tif", data / "partition.gpkg", [data / "h.svg", output], overwrite=True)
    assert e.value.code == 9 and output in str(e.value) and f"--partition '{data / 'partition.gpkg'}'" in str(e.value)
    # A style script is an input too, refused before it runs.
    with pytest.raises(rockhatch.RockhatchError, match="--script") as e:
        carto.run(data / "dem.tif", data / "partition.gpkg", [data / "sub" / ".." / "style.py"],
                  style=str(data / "style.py"), overwrite=True)
    assert e.value.code == 9 and not (data / "script_ran").exists()
    assert snapshot(data) == before


def test_partition_from_dem_refuses_to_write_onto_an_input(data, tmp_path):
    before = snapshot(data)
    for kwargs in ({"output": data / "sub" / ".." / "mask.gpkg", "mask": data / "mask.gpkg"},
                   {"output": tmp_path / "p.gpkg", "png": data / "dem.tif"},
                   {"output": tmp_path / "p.gpkg", "png": tmp_path / "p.gpkg"}):
        with pytest.raises(rockhatch.RockhatchError) as e:
            carto.partition_from_dem(data / "dem.tif", overwrite=True, **kwargs)
        assert e.value.code == 9, e.value
    assert snapshot(data) == before and not (tmp_path / "p.gpkg").exists()
    # The check itself, for front ends with inputs and outputs of their own (QGIS).
    with pytest.raises(rockhatch.RockhatchError, match="SLOPE .* is the input DEM"):
        carto.check_outputs([("DEM", str(data / "dem.tif"))], [("SLOPE", str(data / "sub/../dem.tif"))], True)
    carto.check_outputs([("DEM", str(data / "dem.tif"))], [("SLOPE", str(tmp_path / "slope.tif"))], True)


# ---- the host's settings


def gdal_settings():
    return {k: gdal.GetConfigOption(k) for k in GDAL_KEYS}


@pytest.fixture
def host_settings():
    """Values of the host program (QGIS, a user's script) that carto must keep."""
    gdal.SetConfigOption("OGR_SQLITE_JOURNAL", "WAL")
    yield gdal_settings()
    gdal.SetConfigOption("OGR_SQLITE_JOURNAL", None)


def last_change(gpkg):
    ds = ogr.Open(str(gpkg))
    rows = ds.ExecuteSQL("SELECT DISTINCT last_change FROM gpkg_contents")
    values = {f.GetField(0) for f in rows}
    ds.ReleaseResultSet(rows)
    return values


def test_gdal_options_are_the_hosts_after_every_call(sample_dir, tmp_path, host_settings):
    assert host_settings["OGR_SQLITE_JOURNAL"] == "WAL"
    carto.run(sample_dir / "dem.tif", sample_dir / "partition.gpkg", [tmp_path / "a.gpkg", tmp_path / "a.png"])
    assert gdal_settings() == host_settings
    carto.partition_from_dem(sample_dir / "dem.tif", tmp_path / "p.gpkg", png=tmp_path / "p.png")
    assert gdal_settings() == host_settings
    # Failed calls: a bad input, and a cancel while the GeoPackage is written.
    with pytest.raises(rockhatch.RockhatchError):
        carto.run(tmp_path / "none.tif", sample_dir / "partition.gpkg", [tmp_path / "x.gpkg"])
    assert gdal_settings() == host_settings
    with pytest.raises(rockhatch.RockhatchError) as e:
        carto.run(sample_dir / "dem.tif", sample_dir / "partition.gpkg", [tmp_path / "c.gpkg"],
                  progress=lambda f, stage: stage != "writing" or f <= 0.92)
    assert e.value.code == 10 and not (tmp_path / "c.gpkg").exists()
    assert gdal_settings() == host_settings
    # carto's GeoPackages keep the fixed date (same bytes every run) ...
    assert last_change(tmp_path / "a.gpkg") == last_change(tmp_path / "p.gpkg") == {FIXED_DATE}
    carto.run(sample_dir / "dem.tif", sample_dir / "partition.gpkg", [tmp_path / "b.gpkg"])
    assert (tmp_path / "b.gpkg").read_bytes() == (tmp_path / "a.gpkg").read_bytes()
    # ... and the host's own GeoPackages are dated again.
    ds = ogr.GetDriverByName("GPKG").CreateDataSource(str(tmp_path / "host.gpkg"))
    ds.CreateLayer("notes", geom_type=ogr.wkbPoint)
    ds = None
    assert not last_change(tmp_path / "host.gpkg") & {FIXED_DATE}


def test_threads_and_seed_are_the_processes_after_a_run(data, tmp_path):
    """A run with threads=1 and a style script calling SetSeed(123): GetThreads() and
    GetSeed() are what they were, and the drawing is the one without SetSeed."""
    script = tmp_path / "seeding.py"
    script.write_text(
        "import runpy\nfrom rockhatch.tex import SetSeed\nSetSeed(122)  # as the thesis's scripts start\n"
        f"_base = runpy.run_path({str(FRAMED_TILES)!r})\n"
        "NAME, PARAMS = _base['NAME'], _base['PARAMS']\n\n"
        "def style(fields, params):\n    SetSeed(123)\n    return _base['style'](fields, params)\n")
    saved = tex.GetThreads(), tex.GetSeed()
    try:
        tex.SetThreads(3)
        tex.SetSeed(9)
        carto.run(data / "dem.tif", data / "partition.gpkg", [tmp_path / "s.svg"], style=str(script), threads=1)
        assert (tex.GetThreads(), tex.GetSeed()) == (3, 9)
        carto.run(data / "dem.tif", data / "partition.gpkg", [tmp_path / "f.svg"], style=str(FRAMED_TILES),
                  threads=2)
        assert (tex.GetThreads(), tex.GetSeed()) == (3, 9)
        assert (tmp_path / "s.svg").read_bytes() == (tmp_path / "f.svg").read_bytes()
        # A script that fails after its SetSeed.
        script.write_text(script.read_text() + "\n\ndef style(fields, params):\n"
                          "    SetSeed(124)\n    raise ValueError('broken')\n")
        with pytest.raises(Exception, match="broken"):
            carto.run(data / "dem.tif", data / "partition.gpkg", [tmp_path / "x.svg"], style=str(script), threads=1)
        assert (tex.GetThreads(), tex.GetSeed()) == (3, 9)
    finally:
        tex.SetThreads(saved[0])
        tex.SetSeed(saved[1])
