# SPDX-License-Identifier: BSD-3-Clause
# voxlink.open(), validate() and to_dense() on files: corrupt files refused with the
# validator's message, fills that do not fit the source type refused.
import os
import subprocess
import sys

import numpy as np
import pytest

import voxlink


@pytest.fixture
def small_file(tmp_path):
    a = np.zeros((20, 24, 28), np.uint8)
    a[5:15, 6:18, 7:21] = 100
    path = tmp_path / "box.vxl"
    voxlink.convert(a, threshold=50, output=path)
    return path, a


def test_open_validate_roundtrip(small_file):
    path, a = small_file
    f = voxlink.open(path)
    assert f.dims == (28, 24, 20)
    report = f.validate()
    assert report["voxels_checked"] == (a >= 50).sum()
    assert report["bytes_checked"] > 0
    np.testing.assert_array_equal(f.to_dense(fill=3), np.where(a >= 50, a, 3))


def test_file_changed_on_disk_does_not_affect_an_open_file(small_file):
    """A File holds a private copy: truncating or overwriting the .vxl in place afterwards (cp
    over it, a re-run writing in place) used to kill Python through the mapping (SIGBUS,
    SIGSEGV). Run in a child so that a crash fails this test instead of the whole session."""
    path, a = small_file
    other = path.parent / "other.vxl"
    voxlink.convert(np.where(a > 0, 200, 0).astype(np.uint8), threshold=150, output=other)
    script = f"""
import numpy as np, voxlink
f = voxlink.open({str(path)!r})
open({str(path)!r}, "r+b").truncate(4096)
assert f.validate()["voxels_checked"] == {int((a >= 50).sum())}
open({str(path)!r}, "wb").write(open({str(other)!r}, "rb").read())
ijk, values, _ = f.voxels()
assert len(values) == {int((a >= 50).sum())} and set(values.tolist()) == {{100}}
assert f.to_dense().shape == {a.shape}
print("ok")
"""
    r = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                       env=os.environ, timeout=120)
    assert r.returncode == 0 and r.stdout.strip() == "ok", (r.returncode, r.stderr)


def test_corrupt_file_refused(small_file):
    path, _ = small_file
    data = bytearray(path.read_bytes())
    data[-20] ^= 0xFF
    path.write_bytes(bytes(data))
    with pytest.raises(voxlink.Error, match="box.vxl"):
        voxlink.open(path)


def test_not_a_file(tmp_path):
    (tmp_path / "text.vxl").write_text("hello")
    with pytest.raises(voxlink.Error, match="text.vxl"):
        voxlink.open(tmp_path / "text.vxl")


def test_fill_must_fit(small_file):
    f = voxlink.open(small_file[0])
    with pytest.raises(voxlink.Error, match="fill"):
        f.to_dense(fill=300)
    with pytest.raises(voxlink.Error, match="fill"):
        f.to_dense(fill=float("nan"))
    # The command line's rule: an integer source takes whole numbers only (it rounded 1.5 to 2
    # where Python truncated it to 1).
    with pytest.raises(voxlink.Error, match="fill 1.5 is not a whole number"):
        f.to_dense(fill=1.5)


def test_pack_reads_back_the_same_voxels(small_file, tmp_path):
    path, a = small_file
    f = voxlink.open(path)
    report = f.pack(tmp_path / "box.packed.vxl")
    assert report["packed_bytes"] < report["bytes"]
    packed = voxlink.open(tmp_path / "box.packed.vxl")
    assert packed.info(vdb=False)["packed_bytes"] == report["packed_bytes"]
    for mine, theirs in zip(f.voxels(), packed.voxels()):
        np.testing.assert_array_equal(mine, theirs)
    with pytest.raises(voxlink.Error, match="box.vxl"):
        f.pack(path)  # the input itself


def test_path_arguments(small_file):
    """Paths are what the os module takes: str(None) no longer names a file "None", and a NUL
    no longer opens the part of the path before it."""
    path, _ = small_file
    assert voxlink.open(os.fsencode(path)).dims == voxlink.open(path).dims
    for bad in (None, 5, [path]):
        with pytest.raises(TypeError, match="os.PathLike"):
            voxlink.open(bad)
    with pytest.raises(TypeError, match="os.PathLike"):
        voxlink.convert(None, threshold=1)
    with pytest.raises(ValueError, match="NUL"):
        voxlink.open(str(path) + "\0.ignored")
    with pytest.raises(ValueError, match="NUL"):
        voxlink.render(str(path) + "\0", size="8x8")


def test_empty_output_path_is_refused_before_any_work(small_file, tmp_path):
    path, a = small_file
    with pytest.raises(voxlink.Error, match="output path is empty"):
        voxlink.convert(a, threshold=50, output="")
    with pytest.raises(voxlink.Error, match="output path is empty"):
        voxlink.open(path).pack("")
