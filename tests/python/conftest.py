"""Shared fixtures: where the built programs are."""
import os
import pathlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


def build_dir() -> pathlib.Path:
    return pathlib.Path(os.environ.get("RH_BUILD_DIR", ROOT / "build"))


@pytest.fixture(scope="session")
def gallery_exe() -> pathlib.Path:
    exe = build_dir() / "libtex" / "rh_gallery"
    if not exe.exists():
        pytest.fail(f"{exe} is missing: run scripts/setup.sh first (or set RH_BUILD_DIR)")
    return exe


SAMPLE = ROOT / "data" / "sample_montblanc"
SHARED_DEM = ROOT.parent / "shared" / "data" / "montblanc" / "Chamonix.tif"


@pytest.fixture(scope="session")
def rockhatch_exe() -> pathlib.Path:
    exe = build_dir() / "carto" / "rockhatch"
    if not exe.exists():
        pytest.fail(f"{exe} is missing: run scripts/setup.sh first (or set RH_BUILD_DIR)")
    return exe


@pytest.fixture(scope="session")
def sample_dir() -> pathlib.Path:
    return SAMPLE
