# SPDX-License-Identifier: BSD-3-Clause
# `voxlink export -o out.vdb` checked with OpenVDB's own Python module (python3-openvdb):
# the grids, their values and gradients, transform and metadata; converting the export
# again with the same threshold gives the same voxels and values.
import json
import subprocess

import numpy as np
import pyopenvdb
import pytest

import voxlink


def export(cli, vxl, out):
    r = subprocess.run([cli, "export", str(vxl), "-o", str(out)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return r.stdout


def test_foot_grids_read_by_pyopenvdb(tmp_path, foot_nrrd, cli):
    f = voxlink.convert(foot_nrrd, threshold=60, output=tmp_path / "foot.vxl")
    export(cli, tmp_path / "foot.vxl", tmp_path / "foot.vdb")
    listing = subprocess.run(["vdb_print", "-l", str(tmp_path / "foot.vdb")], check=True,
                             capture_output=True, text=True).stdout
    for line in ["Name: values", "Name: gradient", "voxlink_meta:", "1,070,549"]:
        assert line in listing
    grids, _ = pyopenvdb.readAll(str(tmp_path / "foot.vdb"))
    by_name = {g.name: g for g in grids}
    assert set(by_name) == {"values", "gradient"}
    ijk, values, gradients = f.voxels()
    lo = ijk.min(axis=0)
    shape = tuple(ijk.max(axis=0) - lo + 1)
    for name, expected, dense in [("values", values, np.zeros(shape, np.float32)),
                                  ("gradient", gradients, np.zeros(shape + (3,), np.float32))]:
        grid = by_name[name]
        assert grid.activeVoxelCount() == len(values)
        grid.copyToArray(dense, ijk=tuple(int(v) for v in lo))
        local = ijk - lo
        np.testing.assert_array_equal(dense[local[:, 0], local[:, 1], local[:, 2]], expected)
        meta = json.loads(grid["voxlink_meta"])
        assert "classification" in json.dumps(meta)
        assert grid["voxlink_value_max_abs_error"] == 0


def test_transform_from_spacing_and_origin(tmp_path, cli):
    a = np.zeros((6, 5, 4), np.uint16)
    a[1:5, 1:4, 1:3] = 900
    voxlink.convert(a, threshold=100, spacing=(0.5, 1, 2), origin=(10, 20, 30),
                    output=tmp_path / "box.vxl")
    export(cli, tmp_path / "box.vxl", tmp_path / "box.vdb")
    grid = pyopenvdb.read(str(tmp_path / "box.vdb"), "values")
    assert grid.transform.indexToWorld((1, 1, 1)) == (10.5, 21.0, 32.0)
    assert grid.activeVoxelCount() == 4 * 3 * 2
    assert grid.evalActiveVoxelBoundingBox() == ((1, 1, 1), (2, 3, 4))


@pytest.mark.parametrize("keep", [["--keep-all"], ["--threshold", "60"]])
def test_round_trip_through_convert(tmp_path, foot_nrrd, cli, keep):
    f = voxlink.convert(foot_nrrd, threshold=60, output=tmp_path / "foot.vxl")
    export(cli, tmp_path / "foot.vxl", tmp_path / "foot.vdb")
    subprocess.run([cli, "convert", str(tmp_path / "foot.vdb"), *keep, "-o",
                    str(tmp_path / "again.vxl"), "-q"], check=True, stdout=subprocess.DEVNULL)
    ijk, values, _ = f.voxels()
    again = voxlink.open(tmp_path / "again.vxl")
    ijk2, values2, _ = again.voxels()
    # The reader's volume is the active bounding box: indices shift by its minimum, and the
    # bricks (so the file order) move with it; compare in index order. --keep-all keeps the
    # active voxels only, not the whole box.
    lo = ijk.min(axis=0)
    ijk = ijk - lo
    order, order2 = np.lexsort(ijk.T), np.lexsort(ijk2.T)
    np.testing.assert_array_equal(ijk[order], ijk2[order2])
    np.testing.assert_array_equal(values[order], values2[order2])
    # The same places in the world: the origin moved with the box.
    np.testing.assert_allclose(again.origin, np.array(f.origin) + lo * np.array(f.spacing))


def test_bad_export_paths(tmp_path, cli):
    a = np.full((4, 4, 4), 50, np.uint8)
    voxlink.convert(a, keep_all=True, output=tmp_path / "c.vxl")
    r = subprocess.run([cli, "export", str(tmp_path / "c.vxl"), "-o",
                        str(tmp_path / "no" / "c.vdb")], capture_output=True, text=True)
    assert r.returncode != 0 and "c.vdb" in r.stderr and r.stderr.count("\n") == 1
    assert sorted(p.name for p in tmp_path.iterdir()) == ["c.vxl"]
