"""The partition from the DEM alone, from Python: carto.partition_from_dem writes what
`rockhatch partition` writes, accepts in-memory rasters, and fails clearly."""
import subprocess

import numpy as np
import pytest

import rockhatch
from rockhatch import carto


def test_same_bytes_as_the_command_and_hatchable(rockhatch_exe, sample_dir, tmp_path):
    cli = tmp_path / "cli.gpkg"
    subprocess.run([str(rockhatch_exe), "partition", "-q", "--dem", str(sample_dir / "dem.tif"), "-o", str(cli)],
                   check=True)
    stages = []
    r = carto.partition_from_dem(sample_dir / "dem.tif", tmp_path / "py.gpkg",
                                 progress=lambda f, s: stages.append(s) or True)
    assert (tmp_path / "py.gpkg").read_bytes() == cli.read_bytes()
    assert len(r.partition.faces) > 10 and len(r.network) > 10 and stages
    kinds = {seg.kind for f in r.partition.faces for seg in f.boundary}
    assert {carto.LineKind.RIDGE, carto.LineKind.VALLEY} <= kinds
    assert all(f.orientation is not None and 0 <= f.density <= 1 for f in r.partition.faces)
    rock = r.rock.array
    assert rock.shape == (r.rock.height, r.rock.width) and np.nanmax(rock) == 1
    s = carto.run(sample_dir / "dem.tif", tmp_path / "py.gpkg", [tmp_path / "h.svg"])
    assert s.faces == len(r.partition.faces) and s.hatches > 1000


def test_in_memory_dem_and_errors(sample_dir, tmp_path):
    dem = carto.read_raster(str(sample_dir / "dem.tif"))
    r = carto.partition_from_dem(dem, min_slope=80)
    assert 0 < len(r.partition.faces)
    flat = carto.Raster.from_array(np.full((60, 60), 1500.0), [0, 5, 0, 300, 0, -5], "EPSG:2154")
    with pytest.raises(rockhatch.RockhatchError, match="no rock: no area") as e:
        carto.partition_from_dem(flat, tmp_path / "flat.gpkg")
    assert e.value.code == 6 and not (tmp_path / "flat.gpkg").exists()
    no_crs = carto.Raster.from_array(dem.array, dem.geotransform)
    with pytest.raises(rockhatch.RockhatchError) as e:
        carto.partition_from_dem(no_crs)
    assert e.value.code == 4
    with pytest.raises(rockhatch.RockhatchError) as e:
        carto.partition_from_dem(dem, progress=lambda f, s: False)
    assert e.value.code == 10
    with pytest.raises(TypeError, match="unknown option 'slope'"):
        carto.partition_from_dem(dem, slope=80)
