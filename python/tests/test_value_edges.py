# SPDX-License-Identifier: BSD-3-Clause
# Values at the edges of their types, and VTK image data with vector arrays and reversed
# directions (issue 30, item 8): inputs written by numpy (raw NRRD) and by VTK's own writer,
# converted and exported by the CLI, the exports read back with numpy and compared by value.
import json
import subprocess

import numpy as np
import pytest

import voxlink

# The type names voxlink export writes (report/dense_export.cpp).
NRRD_TYPES = {"uint8": "<u1", "int8": "<i1", "uint16": "<u2", "int16": "<i2", "uint32": "<u4",
              "int32": "<i4", "float": "<f4", "double": "<f8"}


def write_nrrd(path, a):
    """numpy's bytes behind a hand-written attached header; a[z][y][x]."""
    name = {"i4": "int32", "u4": "uint32", "f4": "float", "f8": "double"}[a.dtype.str[1:]]
    nz, ny, nx = a.shape
    header = (f"NRRD0004\ntype: {name}\ndimension: 3\nsizes: {nx} {ny} {nz}\n"
              "endian: little\nencoding: raw\n\n")
    path.write_bytes(header.encode() + a.astype(a.dtype.newbyteorder("<")).tobytes())


def read_nrrd(path):
    """An attached raw NRRD as voxlink export writes it: (array[z][y][x], header fields)."""
    head, _, body = path.read_bytes().partition(b"\n\n")
    fields = dict(line.split(": ", 1) for line in head.decode().splitlines()[1:]
                  if not line.startswith("#"))
    nx, ny, nz = (int(s) for s in fields["sizes"].split())
    return np.frombuffer(body, NRRD_TYPES[fields["type"]]).reshape(nz, ny, nx), fields


def run(cli, *args):
    return subprocess.run([cli, *map(str, args)], capture_output=True, text=True, timeout=120)


def convert_and_export(cli, tmp_path, source, *options):
    vxl, back = tmp_path / "out.vxl", tmp_path / "back.nrrd"
    r = run(cli, "convert", source, "--keep-all", "-o", vxl, *options)
    assert r.returncode == 0, r.stderr
    r = run(cli, "export", vxl, "-o", back)
    assert r.returncode == 0, r.stderr
    info = json.loads(run(cli, "info", vxl, "--json").stdout)
    return read_nrrd(back)[0], info, vxl


@pytest.mark.parametrize("dtype, values", [
    ("<i4", [2147483647, 2147483600, -2147483648, -2147483000, 0, 5, -7, 16777217]),
    ("<u4", [4294967295, 4294967200, 0, 1, 16777217, 123456789, 7, 3000000000]),
])
def test_32_bit_integers_near_their_limits_come_back_clamped(tmp_path, cli, dtype, values):
    a = np.array(values, dtype).reshape(2, 2, 2)
    write_nrrd(tmp_path / "in.nrrd", a)
    back, info, vxl = convert_and_export(cli, tmp_path, tmp_path / "in.nrrd")
    assert info["value_type"] == "f32"
    assert back.dtype == a.dtype
    error = np.abs(back.astype(np.float64) - a.astype(np.float64))
    # The largest value comes back as the largest the type holds, not the opposite extreme,
    # and the reported error is the error really given back (47 for 2147483600, 95 for
    # 4294967200: f32 rounds both to 2^31 / 2^32, clamped to the type's maximum).
    assert back.max() == np.iinfo(a.dtype).max
    assert error.max() == info["value_error"]["max_abs"]
    assert error.max() <= info["value_error"]["bound"]
    np.testing.assert_array_equal(voxlink.open(vxl).to_dense(), back)


def test_f64_range_wider_than_f32_is_refused_with_the_numbers(tmp_path, cli):
    a = np.array([1e300, 1, 0.5, -12345.678, 0, 0, 0, 0]).reshape(2, 2, 2)
    write_nrrd(tmp_path / "in.nrrd", a)
    r = run(cli, "convert", tmp_path / "in.nrrd", "--keep-all", "-o", tmp_path / "out.vxl")
    assert r.returncode != 0
    message = r.stderr.strip()
    assert len(message.splitlines()) == 1, message
    for part in ("in.nrrd", "0.5", "1e+300", "--error-bound"):
        assert part in message, message
    assert not (tmp_path / "out.vxl").exists()
    # With an absolute bound the small values may go: the bound holds for every voxel.
    back, info, _ = convert_and_export(cli, tmp_path, tmp_path / "in.nrrd",
                                       "--error-bound", "1e293")
    assert np.abs(back - a).max() <= 1e293
    assert info["value_error"]["max_abs"] <= 1e293


def test_variable_is_refused_by_a_format_without_named_variables(tmp_path, cli):
    write_nrrd(tmp_path / "in.nrrd", np.arange(8, dtype="<i4").reshape(2, 2, 2))
    r = run(cli, "convert", tmp_path / "in.nrrd", "--keep-all", "--variable", "density",
            "-o", tmp_path / "out.vxl")
    assert r.returncode != 0
    message = r.stderr.strip()
    assert len(message.splitlines()) == 1, message
    assert "in.nrrd" in message and "--variable 'density'" in message, message
    assert not (tmp_path / "out.vxl").exists()


@pytest.mark.parametrize("dtype, values", [
    ("<f8", [1e-300, 3e-300, -7.5e-301, 1e-310, 2.5e-299, 0, 1e-305, -1e-300]),
    ("<f8", [1e260, 3e250, -1e300, 1e270, 2e299, 1e280, 5e290, 0]),
    ("<f4", [3e38, 1.4e-45, -3e38, 1, 0, -1e-40, 2.5e-38, 1e30]),
])
def test_float_extremes_keep_their_relative_error(tmp_path, cli, dtype, values):
    a = np.array(values, dtype).reshape(2, 2, 2)
    write_nrrd(tmp_path / "in.nrrd", a)
    back, info, _ = convert_and_export(cli, tmp_path, tmp_path / "in.nrrd")
    assert back.dtype == a.dtype
    if a.dtype == np.float32:
        np.testing.assert_array_equal(back, a)  # f32 sources are stored as they are
        assert info["value_error"]["max_abs"] == 0
    else:
        nonzero = a != 0
        rel = np.abs(back[nonzero] - a[nonzero]) / np.abs(a[nonzero])
        assert rel.max() <= 2.0 ** -24
        assert np.all(back[~nonzero] == 0)
        assert info["value_error"]["max_rel"] == rel.max()


vtk = pytest.importorskip("vtk", reason="VTK's Python module writes the .vti inputs")
from vtk.util import numpy_support  # noqa: E402


def write_vti(path, arrays, origin=(0, 0, 0), spacing=(1, 1, 1), direction=None, dims=(3, 4, 5)):
    """arrays: (name, numpy array of shape (voxels, components) or (voxels,)), x fastest."""
    image = vtk.vtkImageData()
    image.SetDimensions(*dims)
    image.SetOrigin(*origin)
    image.SetSpacing(*spacing)
    if direction is not None:
        image.SetDirectionMatrix(*direction)
    for name, values in arrays:
        array = numpy_support.numpy_to_vtk(values, deep=True)
        array.SetName(name)
        image.GetPointData().AddArray(array)
    writer = vtk.vtkXMLImageDataWriter()
    writer.SetFileName(str(path))
    writer.SetInputData(image)
    assert writer.Write() == 1
    return image


def test_vti_vector_array_first_and_variable_picks_the_array(tmp_path, cli):
    rng = np.random.default_rng(8)
    velocity = rng.standard_normal((60, 3)).astype(np.float32)
    density = rng.integers(-500, 500, 60).astype(np.int16)
    mass = rng.integers(0, 255, 60).astype(np.uint8)
    source = tmp_path / "flow.vti"
    write_vti(source, [("velocity", velocity), ("density", density), ("mass", mass)])
    r = run(cli, "convert", source, "--keep-all", "-o", tmp_path / "d.vxl")
    assert r.returncode == 0, r.stderr
    assert "reading 'density'" in r.stdout, r.stdout
    back, _, _ = convert_and_export(cli, tmp_path, source)
    np.testing.assert_array_equal(back.ravel(), density)
    back, _, _ = convert_and_export(cli, tmp_path, source, "--variable", "mass")
    np.testing.assert_array_equal(back.ravel(), mass)
    for name, part in (("velocity", "NumberOfComponents"), ("pressure", "'density', 'mass'")):
        r = run(cli, "convert", source, "--keep-all", "--variable", name, "-o", tmp_path / "x.vxl")
        assert r.returncode != 0 and part in r.stderr and "flow.vti" in r.stderr, r.stderr


@pytest.mark.parametrize("direction", [
    (-1, 0, 0, 0, 1, 0, 0, 0, -1),
    (1, 0, 0, 0, -1, 0, 0, 0, 1),
    (0, -1, 0, 1, 0, 0, 0, 0, 1),  # grid axis 0 along +y, axis 1 along -x
])
def test_vti_direction_keeps_every_voxels_world_position(tmp_path, cli, direction):
    values = np.arange(60, dtype=np.int16) * 3 + 1
    image = write_vti(tmp_path / "d.vti", [("v", values)], origin=(10, 20, 30),
                      spacing=(0.5, 1, 2), direction=direction)
    assert 'Direction="' in (tmp_path / "d.vti").read_text(errors="replace")
    vxl, nrrd = tmp_path / "d.vxl", tmp_path / "d.nrrd"
    assert run(cli, "convert", tmp_path / "d.vti", "--keep-all", "-o", vxl).returncode == 0
    assert run(cli, "export", vxl, "-o", nrrd).returncode == 0
    back, fields = read_nrrd(nrrd)
    origin = np.array([float(s) for s in fields["space origin"].strip("()").split(",")])
    steps = [float(v) for v in fields["space directions"].replace("(", " ").replace(")", " ")
             .replace(",", " ").split()]
    spacing = np.array([steps[0], steps[4], steps[8]])
    assert np.all(spacing > 0)
    # VTK's world position of every source voxel against the export's.
    expected = {}
    for k in range(5):
        for j in range(4):
            for i in range(3):
                p = [0.0, 0.0, 0.0]
                image.TransformIndexToPhysicalPoint(i, j, k, p)
                expected[tuple(np.round(p, 9))] = values[(k * 4 + j) * 3 + i]
    got = {}
    for (z, y, x), v in np.ndenumerate(back):
        got[tuple(np.round(origin + spacing * (x, y, z), 9))] = v
    assert got == expected
