# SPDX-License-Identifier: BSD-3-Clause
# voxlink.convert(): the same bytes as the CLI, NumPy arrays in the right axis order, and
# clear errors for what it cannot take.
import hashlib
import json
import pathlib
import subprocess

import numpy as np
import pytest

import voxlink

SKIN_BONE = pathlib.Path(__file__).resolve().parents[2] / "samples" / "headsq" / "skin-bone.tf.json"

def md5(path):
    return hashlib.md5(path.read_bytes()).hexdigest()


def ball(n=40, dtype=np.uint8):
    z, y, x = np.mgrid[0:n, 0:n, 0:n].astype(np.float64)
    r = np.sqrt((x - 0.45 * n) ** 2 + (y - 0.5 * n) ** 2 + (z - 0.55 * n) ** 2)
    # Anisotropic on purpose (x, y, z differ) so a transposed axis order cannot pass.
    a = 200.0 * np.exp(-((r / (0.3 * n)) ** 2)) + 0.2 * x
    return a.astype(dtype)


@pytest.mark.parametrize("options,cli_args", [
    (dict(threshold=60), ["--threshold", "60"]),
    (dict(threshold="60,200", brick=16, axis="x"),
     ["--threshold", "60,200", "--brick", "16", "--axis", "x"]),
    (dict(tf=SKIN_BONE, value_type="f16"), ["--tf", str(SKIN_BONE), "--value-type", "f16"]),
    (dict(keep_outside=(20, 200), threads=1, slab=16),
     ["--keep-outside", "20,200", "--threads", "1", "--slab", "16"]),
    (dict(threshold=[(40, 80), 200]), ["--threshold", "40,80", "--threshold", "200"]),
])
def test_foot_byte_identical_to_cli(tmp_path, foot_nrrd, cli, options, cli_args):
    by_cli = tmp_path / "cli.vxl"
    by_module = tmp_path / "module.vxl"
    subprocess.run([cli, "convert", str(foot_nrrd), "-o", str(by_cli), "-q", *cli_args],
                   check=True, stdout=subprocess.DEVNULL)
    f = voxlink.convert(str(foot_nrrd), output=str(by_module), **options)
    assert f.path == str(by_module)
    assert md5(by_module) == md5(by_cli)


def test_info_is_the_cli_json(tmp_path, foot_nrrd, cli):
    out = tmp_path / "foot.vxl"
    f = voxlink.convert(foot_nrrd, output=out, threshold=60)
    printed = subprocess.run([cli, "info", str(out), "--json", "--no-vdb"], check=True,
                             capture_output=True, text=True).stdout
    assert f.info(vdb=False) == json.loads(printed)
    with_peer = f.info()
    assert with_peer["peer"]["bytes"] > 0
    assert with_peer["voxels"] == f.voxels()[0].shape[0]


def test_array_matches_npy_file_through_cli(tmp_path, cli):
    a = ball()
    np.save(tmp_path / "ball.npy", a)
    subprocess.run([cli, "convert", str(tmp_path / "ball.npy"), "-o", str(tmp_path / "c.vxl"),
                    "-q", "--threshold", "60"], check=True, stdout=subprocess.DEVNULL)
    by_cli = voxlink.open(tmp_path / "c.vxl")
    by_array = voxlink.convert(a, threshold=60)
    for x, y in zip(by_cli.voxels(), by_array.voxels()):
        np.testing.assert_array_equal(x, y)


def test_voxels_and_dense_match_the_array():
    a = ball(dtype=np.int16) - 20
    f = voxlink.convert(a, threshold=(60, 150), spacing=(1, 2, 3), origin=(-1, 0, 5))
    assert f.spacing == (1, 2, 3) and f.origin == (-1, 0, 5)
    ijk, values, gradients = f.voxels()
    kept = (a >= 60) & (a <= 150)
    assert ijk.dtype == np.int32 and values.dtype == np.float64 and gradients.dtype == np.float32
    assert len(values) == kept.sum() > 0
    np.testing.assert_array_equal(values, a[ijk[:, 2], ijk[:, 1], ijk[:, 0]])
    assert kept[ijk[:, 2], ijk[:, 1], ijk[:, 0]].all()
    norms = np.linalg.norm(gradients, axis=1)
    np.testing.assert_allclose(norms[norms > 0], 1, atol=1e-5)
    dense = f.to_dense(fill=-7)
    assert dense.dtype == np.int16 and dense.shape == a.shape
    np.testing.assert_array_equal(dense, np.where(kept, a, -7))
    assert f.info(vdb=False)["dims"] == [40, 40, 40]


def test_float_values_in_source_units():
    a = ball(dtype=np.float32) / 7.0
    f = voxlink.convert(a, keep_all=True)
    ijk, values, _ = f.voxels()
    assert len(values) == a.size
    np.testing.assert_allclose(values, a[ijk[:, 2], ijk[:, 1], ijk[:, 0]], rtol=0, atol=1e-6)
    np.testing.assert_array_equal(f.to_dense(), a)


@pytest.mark.parametrize("array,error,text", [
    (ball()[:, :, ::2], ValueError, "not C-contiguous"),
    (ball().astype(np.float16), TypeError, "float16"),
    (ball().astype(np.complex64), TypeError, "complex64"),
    (ball()[0], ValueError, "2 dimensions"),
    (ball().astype(">u2"), TypeError, "native order"),
])
def test_bad_arrays(array, error, text):
    with pytest.raises(error, match=text):
        voxlink.convert(array, threshold=60)


def test_bad_options(tmp_path):
    with pytest.raises(ValueError, match="exactly one"):
        voxlink.convert(ball())
    with pytest.raises(ValueError, match="exactly one"):
        voxlink.convert(ball(), threshold=60, keep_all=True)
    with pytest.raises(ValueError, match="brick"):
        voxlink.convert(ball(), threshold=60, brick=5)
    with pytest.raises(voxlink.Error, match="threshold"):
        voxlink.convert(ball(), threshold="sixty")
    with pytest.raises(voxlink.Error, match="missing.nrrd"):
        voxlink.convert(tmp_path / "missing.nrrd", threshold=60)
    # Refused before any thread starts: 100000 threads exhausted this machine's tasks.
    with pytest.raises(voxlink.Error, match="threads 100000 is more than 1024"):
        voxlink.convert(ball(), threshold=60, threads=100000)


def test_unwritable_output_leaves_nothing(tmp_path):
    target = tmp_path / "no-such-dir" / "out.vxl"
    with pytest.raises(voxlink.Error, match="no-such-dir"):
        voxlink.convert(ball(), threshold=60, output=target)
    assert not target.parent.exists()
    bad = ball(dtype=np.float32)
    bad[3, 4, 5] = np.nan
    with pytest.raises(voxlink.Error, match=r"nan at voxel \(5, 4, 3\)"):
        voxlink.convert(bad, threshold=60, output=tmp_path / "nan.vxl")
    assert list(tmp_path.iterdir()) == []  # no output, no temporary file
