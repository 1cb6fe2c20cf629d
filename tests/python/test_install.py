"""Installed like other software: `cmake --install` to a prefix, a CMake project of one's own
built against that prefix's libtex, and the Debian package unpacked into a scratch root.
Each installed program must give the bytes of the build folder's."""
import configparser
import os
import pathlib
import shutil
import subprocess

import pytest

from conftest import ROOT, SAMPLE, SAMPLE_SW_QUARTER, build_dir

VERSION = "0.1.0"
SONAME = "0.1"
WINDOW = ",".join(str(v) for v in SAMPLE_SW_QUARTER)


def run(cmd, env=None, **kw):
    """A command; by default with tool_env() (CMake, cpack, dpkg, the compilers, ldd)."""
    r = subprocess.run([str(c) for c in cmd], capture_output=True, text=True, env=env or tool_env(), **kw)
    assert r.returncode == 0, f"{cmd} failed ({r.returncode}):\n{r.stdout}\n{r.stderr}"
    return r


def clean_env(**extra):
    """The environment of a user's shell: no loader or Python paths pointing into the build."""
    env = {k: v for k, v in os.environ.items() if k not in ("LD_LIBRARY_PATH", "PYTHONPATH")}
    env.update(extra)
    return env


def tool_env():
    """For the system's tools: without the sanitizer pass's LD_PRELOAD of the ASan runtime,
    under which cpack, not instrumented, hung in a lock while writing the package."""
    return {k: v for k, v in clean_env().items() if k != "LD_PRELOAD"}


def python_dir(root: pathlib.Path) -> pathlib.Path:
    found = sorted(root.glob("lib/python3*/dist-packages"))
    assert len(found) == 1, f"one Python package folder under {root}/lib, found {found}"
    return found[0]


def resolved_libraries(program: pathlib.Path) -> dict:
    """name -> path of the shared libraries the loader picks for the program (ldd)."""
    out = run(["ldd", program]).stdout
    libs = {}
    for line in out.splitlines():
        parts = line.split()
        if "=>" in parts and parts[parts.index("=>") + 1] != "not":
            libs[parts[0]] = pathlib.Path(parts[parts.index("=>") + 1]).resolve()
    return libs


def draw_sample(exe, out_dir: pathlib.Path, stem: str, *extra) -> list:
    outs = [out_dir / f"{stem}.gpkg", out_dir / f"{stem}.svg"]
    cmd = [exe, "--dem", SAMPLE / "dem.tif", "--partition", SAMPLE / "partition.gpkg", "--window", WINDOW, "-q",
           *extra]
    for o in outs:
        cmd += ["-o", o]
    run(cmd, env=clean_env())
    return outs


INSTALLED = {}  # prefix -> the files `cmake --install` reported writing there


@pytest.fixture(scope="module")
def prefix(tmp_path_factory) -> pathlib.Path:
    p = tmp_path_factory.mktemp("install") / "prefix"
    out = run(["cmake", "--install", build_dir(), "--prefix", p]).stdout
    # Its own report, not the build folder's install_manifest.txt, which another pytest
    # worker installing at the same time may rewrite.
    INSTALLED[p] = [line.split(": ", 1)[1] for line in out.splitlines()
                    if line.startswith(("-- Installing: ", "-- Up-to-date: "))]
    return p


def test_the_prefix_holds_the_whole_tool_and_nothing_is_written_outside_it(prefix):
    manifest = INSTALLED[prefix]
    outside = [f for f in manifest if not f.startswith(str(prefix) + "/")]
    assert manifest and not outside, f"installed outside {prefix}: {outside[:5]}"
    lib = prefix / "lib"
    for name in ("tex", "carto"):
        real = lib / f"lib{name}.so.{VERSION}"
        assert real.is_file() and not real.is_symlink()
        assert (lib / f"lib{name}.so.{SONAME}").resolve() == real
        assert (lib / f"lib{name}.so").resolve() == real
        dyn = run(["objdump", "-p", real]).stdout
        assert f"SONAME               lib{name}.so.{SONAME}" in dyn
    # The public headers, all of them and only them.
    headers = sorted(p.name for p in (prefix / "include" / "libtex").iterdir())
    assert headers == sorted(p.name for p in (ROOT / "libtex" / "include" / "libtex").iterdir())
    assert (prefix / "lib" / "cmake" / "libtex" / "libtexConfig.cmake").is_file()
    pkg = python_dir(prefix) / "rockhatch"
    assert (pkg / "__init__.py").is_file() and list(pkg.glob("_rockhatch.cpython-*.so"))
    share = prefix / "share" / "rockhatch"
    assert (share / "qgis_plugin" / "rockhatch_qgis" / "metadata.txt").is_file()
    assert os.access(share / "qgis_plugin" / "install_qgis_plugin.sh", os.X_OK)
    assert sorted(p.name for p in (share / "styles").glob("*.py")) == sorted(p.name for p in (ROOT / "styles").glob("*.py"))
    for f in ("dem.tif", "partition.gpkg"):
        assert (share / "data" / "sample_montblanc" / f).read_bytes() == (SAMPLE / f).read_bytes()
    assert (prefix / "share" / "man" / "man1" / "rockhatch.1").is_file()
    assert (prefix / "share" / "bash-completion" / "completions" / "rockhatch").is_file()


def test_the_installed_command_runs_from_the_prefix_and_draws_the_build_folders_bytes(prefix, tmp_path,
                                                                                        rockhatch_exe):
    exe = prefix / "bin" / "rockhatch"
    # The command carries its own libtex and carto (the static archives): it loads nothing of
    # the build folder, and no libtex.so or libcarto.so.
    libs = resolved_libraries(exe)
    build = str(build_dir().resolve())
    assert not [p for p in libs.values() if str(p).startswith(build)], libs
    assert not [n for n in libs if n.startswith(("libtex", "libcarto"))], libs
    mine = draw_sample(exe, tmp_path, "installed")
    built = draw_sample(rockhatch_exe, tmp_path, "built")
    for a, b in zip(mine, built):
        assert a.read_bytes() == b.read_bytes(), f"{a.name} differs from the build folder's"


def test_a_moved_prefix_still_runs(prefix, tmp_path, rockhatch_exe):
    # RPATHs relative to the programs: a copied prefix finds its own libraries.
    moved = tmp_path / "elsewhere"
    shutil.copytree(prefix, moved, symlinks=True)
    out = draw_sample(moved / "bin" / "rockhatch", tmp_path, "moved")[1]
    built = draw_sample(rockhatch_exe, tmp_path, "built")[1]
    assert out.read_bytes() == built.read_bytes()
    # The shared libraries find each other in the moved prefix: libcarto.so needs libtex.so.
    carto = moved / "lib" / f"libcarto.so.{VERSION}"
    assert str(resolved_libraries(carto)[f"libtex.so.{SONAME}"]).startswith(str(moved.resolve()))


def test_script_runs_of_the_installed_command_use_the_installed_python_package(prefix, tmp_path):
    # RH_PYTHON names the interpreter the command hands over to: a wrapper that records the
    # PYTHONPATH it was given.
    seen = tmp_path / "pythonpath.txt"
    wrapper = tmp_path / "python3"
    wrapper.write_text(f'#!/bin/sh\nprintf "%s" "$PYTHONPATH" > "{seen}"\nexec /usr/bin/python3 "$@"\n')
    wrapper.chmod(0o755)
    exe = prefix / "bin" / "rockhatch"
    env = clean_env(RH_PYTHON=str(wrapper))
    out = tmp_path / "script.svg"
    run([exe, "--script", prefix / "share" / "rockhatch" / "styles" / "rock.py", "--dem", SAMPLE / "dem.tif",
         "--partition", SAMPLE / "partition.gpkg", "--window", WINDOW, "-q", "-o", out], env=env)
    first = pathlib.Path(seen.read_text().split(":")[0])
    assert first.resolve() == python_dir(prefix).resolve()
    builtin = draw_sample(exe, tmp_path, "builtin")[1]
    assert out.read_bytes() == builtin.read_bytes(), "the installed rock.py draws what the built-in rock draws"


def test_the_installed_python_module_finds_the_installed_web_page(prefix):
    """`rockhatch serve` of a prefix serves share/rockhatch/web: the page and MapLibre GL JS."""
    web = prefix / "share" / "rockhatch" / "web"
    for f in ("index.html", "app.js", "style.css", "node_modules/maplibre-gl/dist/maplibre-gl.js"):
        assert (web / f).read_bytes() == (ROOT / "web" / f).read_bytes(), f
    code = "from rockhatch.serve import find_web_dir\nprint(find_web_dir())\n"
    out = run(["/usr/bin/python3", "-c", code], env=clean_env(PYTHONPATH=str(python_dir(prefix)))).stdout.strip()
    assert pathlib.Path(out) == web.resolve()


def test_the_installed_python_module_imports_from_the_prefix(prefix):
    pydir = python_dir(prefix)
    code = ("import rockhatch, rockhatch.carto, rockhatch.tex\n"
            "from rockhatch import _rockhatch, _rockhatch_image\n"
            "print(rockhatch.__file__); print(_rockhatch.__file__); print(_rockhatch_image.__file__)\n"
            "print(len(rockhatch.carto.styles()))\n")
    out = run(["/usr/bin/python3", "-c", code], env=clean_env(PYTHONPATH=str(pydir))).stdout.split()
    for f in out[:3]:
        assert f.startswith(str(pydir)), f"{f} is not the prefix's module"
    assert int(out[3]) > 5


def test_the_man_page_and_the_completion_are_made_from_the_option_table(prefix, rockhatch_exe):
    help_text = run([rockhatch_exe, "--help"]).stdout
    options = [line.split()[0] for line in help_text.split("\n\n")[2].splitlines()[1:] if line.startswith("  -")]
    assert len(options) > 25
    man = (prefix / "share" / "man" / "man1" / "rockhatch.1").read_text()
    assert man.startswith(".TH ROCKHATCH 1") and f"rockhatch {VERSION}" in man.splitlines()[0]
    for o in options:
        assert f".B {o.replace('-', chr(92) + '-')}" in man, f"{o} is missing from the man page"
    assert "ROCKHATCH PARTITION" in man and "\\-\\-min\\-slope" not in man  # preformatted usage, not options
    completion = prefix / "share" / "bash-completion" / "completions" / "rockhatch"
    script = (f"source {completion}; COMP_WORDS=(rockhatch --sty); COMP_CWORD=1; _rockhatch; echo ${{COMPREPLY[@]}};"
              f"COMP_WORDS=(rockhatch --style ro); COMP_CWORD=2; _rockhatch; echo ${{COMPREPLY[@]}};"
              f"COMP_WORDS=(rockhatch partition --min-sl); COMP_CWORD=2; _rockhatch; echo ${{COMPREPLY[@]}}")
    lines = run(["bash", "-c", script]).stdout.splitlines()
    assert lines == ["--style", "rock", "--min-slope"]


def test_a_cmake_project_of_ones_own_builds_against_the_installed_libtex(prefix, tmp_path):
    in_tree = build_dir() / "rh_stones"
    if not in_tree.exists():
        pytest.fail(f"{in_tree} is missing (configure with RH_BUILD_EXAMPLES=ON)")
    out = tmp_path / "build"
    run(["cmake", "-S", ROOT / "examples" / "downstream", "-B", out, f"-DCMAKE_PREFIX_PATH={prefix}",
         "-DCMAKE_BUILD_TYPE=Release"])
    run(["cmake", "--build", out])
    program = out / "stones"
    assert str(resolved_libraries(program)[f"libtex.so.{SONAME}"]).startswith(str(prefix.resolve()))
    run([program, tmp_path / "mine.svg", "7"], env=clean_env())
    run([in_tree, tmp_path / "tree.svg", "7"], env=clean_env())
    svg = (tmp_path / "mine.svg").read_bytes()
    assert svg == (tmp_path / "tree.svg").read_bytes() and svg.count(b"<poly") > 400


def test_the_qgis_plugin_installs_from_the_prefix(prefix, tmp_path):
    profiles = tmp_path / "profiles"
    run([prefix / "share" / "rockhatch" / "qgis_plugin" / "install_qgis_plugin.sh", "--profiles-path", profiles,
         "--copy"], env=clean_env())
    plugin = profiles / "default" / "python" / "plugins" / "rockhatch_qgis"
    assert (plugin / "metadata.txt").read_bytes() == (ROOT / "qgis_plugin" / "rockhatch_qgis" / "metadata.txt").read_bytes()
    ini = configparser.ConfigParser()
    ini.read(profiles / "default" / "QGIS" / "QGIS3.ini")
    assert ini["PythonPlugins"]["rockhatch_qgis"] == "true"


def test_the_debian_package_declares_its_dependencies_and_runs_unpacked(tmp_path, rockhatch_exe):
    run(["cpack", "--config", build_dir() / "CPackConfig.cmake", "-B", tmp_path / "deb"])
    deb = tmp_path / "deb" / f"rockhatch_{VERSION}_amd64.deb"
    assert deb.is_file()
    info = run(["dpkg-deb", "--info", deb]).stdout
    fields = {}
    for line in info.splitlines():
        if line.startswith(" ") and ":" in line and not line.startswith("  "):
            k, v = line.strip().split(":", 1)
            fields[k] = v.strip()
    assert fields["Package"] == "rockhatch" and fields["Version"] == VERSION and fields["Architecture"] == "amd64"
    depends = fields["Depends"]
    for needed in ("libgdal", "libgeographiclib", "libgmp10", "libmpfr6", "libtinyxml2", "libopenimageio",
                   "python3 (>= 3.11)", "python3-numpy"):
        assert needed in depends, f"Depends lacks {needed}: {depends}"
    assert "python3-distributed" in fields["Recommends"] and "qgis" in fields["Suggests"]
    contents = run(["dpkg-deb", "--contents", deb]).stdout
    for path in ("./usr/bin/rockhatch", f"./usr/lib/libtex.so.{VERSION}", "./usr/include/libtex/tex.hpp",
                 "./usr/lib/cmake/libtex/libtexConfig.cmake", "./usr/share/man/man1/rockhatch.1",
                 "./usr/share/rockhatch/qgis_plugin/rockhatch_qgis/metadata.txt"):
        assert path in contents, f"{path} is not in the package"
    root = tmp_path / "root"
    run(["dpkg", "-x", deb, root])
    exe = root / "usr" / "bin" / "rockhatch"
    lib = root / "usr" / "lib" / f"libcarto.so.{VERSION}"
    assert str(resolved_libraries(lib)[f"libtex.so.{SONAME}"]).startswith(str(root.resolve()))
    mine = draw_sample(exe, tmp_path, "unpacked")
    built = draw_sample(rockhatch_exe, tmp_path, "built")
    for a, b in zip(mine, built):
        assert a.read_bytes() == b.read_bytes(), f"{a.name} differs from the build folder's"
    pydir = python_dir(root / "usr")
    out = run(["/usr/bin/python3", "-c", "import rockhatch.carto as c; print(c.__file__)"],
              env=clean_env(PYTHONPATH=str(pydir))).stdout.strip()
    assert out.startswith(str(pydir))
