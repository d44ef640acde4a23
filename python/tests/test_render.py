# SPDX-License-Identifier: BSD-3-Clause
# voxlink.render(): headless EGL frames, the same pixels as the CLI's EXR output.
import subprocess

import numpy as np
import pytest

import voxlink

if not hasattr(voxlink, "render"):
    pytest.skip("the module was built without the viewer", allow_module_level=True)


@pytest.fixture(scope="module")
def foot(tmp_path_factory, foot_nrrd):
    return voxlink.convert(foot_nrrd, threshold=60,
                           output=tmp_path_factory.mktemp("render") / "foot.vxl")


def test_render_shape_and_determinism(foot):
    image = voxlink.render(foot, size="96x64", camera="30,20")
    assert image.shape == (64, 96, 4) and image.dtype == np.float32
    assert 0.05 < (image[..., 3] > 0.5).mean() < 0.95  # the foot covers part of the frame
    np.testing.assert_array_equal(image, voxlink.render(foot.path, size="96x64", camera="30,20"))
    assert np.abs(image - voxlink.render(foot, size="96x64", camera="120,20")).max() > 0.1
    trilinear = voxlink.render(foot, size="96x64", camera="30,20", sampling="trilinear")
    assert np.abs(image - trilinear).max() > 0


def test_bad_render_options(foot):
    with pytest.raises(voxlink.Error, match="size"):
        voxlink.render(foot, size="big")
    with pytest.raises(ValueError, match="sampling"):
        voxlink.render(foot, sampling="cubic")
