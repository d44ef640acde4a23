# SPDX-License-Identifier: BSD-3-Clause
# Python arguments take Python values (docs/python.md): every path argument takes str, bytes or
# any os.PathLike (not only pathlib), and render's size takes (width, height) as well as "WxH".
import os
import pathlib

import numpy as np
import pytest

import voxlink

SKIN_BONE = pathlib.Path(__file__).resolve().parents[2] / "samples" / "headsq" / "skin-bone.tf.json"
HEADSQ = SKIN_BONE.parent / "headsq.nrrd"


class OwnPath(os.PathLike):
    """An os.PathLike that is not a pathlib path: only __fspath__."""

    def __init__(self, path):
        self.path = str(path)

    def __fspath__(self):
        return self.path


@pytest.fixture
def box(tmp_path):
    a = np.zeros((12, 14, 16), np.uint8)
    a[3:9, 4:10, 5:11] = 100
    return a


@pytest.mark.parametrize("wrap", [str, os.fsencode, pathlib.Path, OwnPath])
def test_every_path_argument_takes_any_path_type(tmp_path, box, wrap):
    out = tmp_path / "box.vxl"
    f = voxlink.convert(box, threshold=50, output=wrap(out))
    assert f.path == str(out) and out.is_file()
    assert voxlink.open(wrap(out)).dims == (16, 14, 12)
    f.pack(wrap(tmp_path / "box.packed.vxl"))
    assert voxlink.open(wrap(tmp_path / "box.packed.vxl")).info(vdb=False)["packed_bytes"] > 0
    by_tf = voxlink.convert(wrap(HEADSQ), tf=wrap(SKIN_BONE), output=wrap(tmp_path / "h.vxl"))
    assert by_tf.dims == (64, 64, 93)
    if hasattr(voxlink, "render"):
        image = voxlink.render(wrap(out), size=(8, 6), tf=wrap(SKIN_BONE))
        assert image.shape == (6, 8, 4)


def test_info_reports_where_the_grid_is(tmp_path, box):
    f = voxlink.convert(box, threshold=50, output=tmp_path / "b.vxl", spacing=(0.5, 1, 2),
                        origin=(10, -4, 3), axis="y", brick=4)
    info = f.info(vdb=False)
    assert info["origin"] == list(f.origin) == [10, -4, 3]
    assert info["spacing"] == list(f.spacing) == [0.5, 1, 2]
    # Bounds: the outer faces of the corner voxels (centres at origin + index * spacing).
    assert info["world_bounds"] == {"min": [9.75, -4.5, 2.0], "max": [17.75, 9.5, 26.0]}
    assert info["axis"] == "y" and info["brick_size"] == 4
    assert info["brick_grid"] == [4, 4, 3]


render_only = pytest.mark.skipif(not hasattr(voxlink, "render"),
                                 reason="the module was built without the viewer")


@render_only
def test_size_as_tuple_list_or_string(tmp_path, box):
    f = voxlink.convert(box, threshold=50)
    by_string = voxlink.render(f, size="24x16", camera="30,20")
    assert by_string.shape == (16, 24, 4)
    np.testing.assert_array_equal(by_string, voxlink.render(f, size=(24, 16), camera="30,20"))
    np.testing.assert_array_equal(by_string, voxlink.render(f, size=[24, 16], camera="30,20"))
    # NumPy integers are integers too (operator.index takes them).
    np.testing.assert_array_equal(
        by_string, voxlink.render(f, size=(np.int64(24), np.uint16(16)), camera="30,20"))


@render_only
@pytest.mark.parametrize("bad", [(24,), (24, 16, 1), (24.0, 16), (True, 16), None, 24])
def test_size_of_the_wrong_type_is_a_type_error(box, bad):
    f = voxlink.convert(box, threshold=50)
    with pytest.raises(TypeError, match="size must be"):
        voxlink.render(f, size=bad)


@render_only
def test_size_out_of_range_names_size(box):
    f = voxlink.convert(box, threshold=50)
    with pytest.raises(voxlink.Error, match="size"):
        voxlink.render(f, size=(0, 16))
