# SPDX-License-Identifier: BSD-3-Clause
# The ParaView reader plugin (python/paraview/voxlink_reader.py) in ParaView's own pvpython,
# headless under Xvfb: .vxl is found by ParaView's file-type lookup and loads as vtkImageData
# with the values, a hidden-point ghost array for removed voxels and the gradient vectors; a
# contour of it renders.
import json
import os
import pathlib
import shutil
import subprocess

import numpy as np
import pytest

import voxlink

HERE = pathlib.Path(__file__).resolve().parent
PLUGIN = HERE.parent / "paraview" / "voxlink_reader.py"


@pytest.mark.parametrize("packed", [False, True], ids=["plain", "packed"])
def test_paraview_opens_and_renders_the_foot(tmp_path, foot_nrrd, packed):
    for tool in ("pvpython", "xvfb-run"):
        if not shutil.which(tool):
            pytest.fail(f"{tool} not found (scripts/install-deps.sh installs paraview, xvfb)")
    f = voxlink.convert(foot_nrrd, threshold=60, output=tmp_path / "foot.vxl")
    opened = tmp_path / "foot.vxl"
    if packed:  # a packed file opens the same way (voxlink.open unpacks it)
        opened = tmp_path / "foot.packed.vxl"
        f.pack(opened)
    ijk, values, _ = f.voxels()
    probes = [ijk[0].tolist(), ijk[len(ijk) // 2].tolist(), [0, 0, 0]]
    dense = f.to_dense()
    expected = [float(dense[z, y, x]) for x, y, z in probes]
    assert expected[2] == 0  # a removed voxel
    env = dict(os.environ, PYTHONPATH=os.environ.get("PYTHONPATH", ""))
    # -n 140: xvfb-run -a looks for a free display from there, not from 99 where the viewer
    # test's starts: two Xvfb racing for one display break the first one's socket.
    r = subprocess.run(["xvfb-run", "-a", "-n", "140", "pvpython", str(HERE / "paraview_load.py"), str(PLUGIN),
                        str(opened), str(tmp_path / "foot.png"),
                        json.dumps(probes)], capture_output=True, text=True, env=env, timeout=300)
    assert r.returncode == 0, r.stdout[-2000:] + r.stderr[:3000] + "\n...\n" + r.stderr[-1000:]
    out = json.loads(r.stdout.strip().splitlines()[-1])
    assert out["dialog_filters"] == ["VoxLink files (*.vxl)"]  # what the open dialog lists
    assert out["proxy"] == "VoxLinkReader" and out["class"] == "vtkImageData"
    assert out["dims"] == [256, 256, 256] and out["spacing"] == [1, 1, 1]
    assert out["scalars"] == "values" and out["vectors"] == "gradient"
    assert out["arrays"]["values"]["range"] == [0, 255]
    assert out["arrays"]["vtkGhostType"]["range"] == [0, 2]  # 2: vtkDataSetAttributes.HIDDENPOINT
    assert out["arrays"]["kept"]["range"] == [0, 1]
    assert out["arrays"]["gradient"]["components"] == 3
    assert out["sample"] == expected
    assert out["image_pixels"] == 128 * 128
    assert 0.02 * 128 * 128 < out["foreground_pixels"] < 0.9 * 128 * 128
    assert np.isclose(values.min(), 60)


def test_paraview_gui_opens_the_foot_through_the_open_dialog(tmp_path, foot_nrrd):
    """The ParaView GUI itself (under Xvfb) plays recorded events: File > Open, the foot picked in
    the open dialog, Apply. ParaView chooses the reader from the dialog's file types; the
    start-up script reports what the pipeline then holds."""
    voxlink.convert(foot_nrrd, threshold=60, output=tmp_path / "foot.vxl")
    events = (HERE / "paraview_gui_open.xml").read_text().replace(
        "VXL_PATH", str(tmp_path / "foot.vxl"))
    (tmp_path / "open.xml").write_text(events)
    report = tmp_path / "gui.json"
    env = dict(os.environ, HOME=str(tmp_path), VOXLINK_PLUGIN=str(PLUGIN), VOXLINK_OUT=str(report),
               PYTHONPATH=os.environ.get("PYTHONPATH", ""))
    # --dr: no user settings (and no start-up dialogs waiting for a click); --exit after the events.
    r = subprocess.run(["xvfb-run", "-a", "-n", "150", "paraview", "--dr",
                        "--script=" + str(HERE / "paraview_gui_startup.py"),
                        "--test-script=" + str(tmp_path / "open.xml"), "--exit"],
                       capture_output=True, text=True, env=env, timeout=300)
    assert r.returncode == 0, r.stdout[-2000:] + r.stderr[:3000]
    assert "Success =  true" in r.stdout + r.stderr
    out = json.loads(report.read_text())
    assert out["name"] == "foot.vxl" and out["proxy"] == "VoxLinkReader"
    assert out["class"] == "vtkImageData" and out["points"] == 256 ** 3
    assert out["arrays"] == ["gradient", "kept", "values", "vtkGhostType"]
    assert out["shown_in"] == ["RenderView"]


@pytest.mark.parametrize("ending", [".nrrd", ".nhdr"])
def test_paraview_reads_the_dense_export(tmp_path, foot_nrrd, cli, ending):
    """`voxlink export` to NRRD (and raw + detached header) opens in ParaView's own reader, no
    plugin: the source's type, shape and spacing, kept values and the fill elsewhere."""
    f = voxlink.convert(foot_nrrd, threshold=60, output=tmp_path / "foot.vxl")
    out = tmp_path / ("foot" + ending)
    r = subprocess.run([cli, "export", str(tmp_path / "foot.vxl"), "-o", str(out), "--fill", "7"],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    ijk, values, _ = f.voxels()
    probes = [ijk[0].tolist(), ijk[len(ijk) // 2].tolist(), [0, 0, 0]]
    r = subprocess.run(["xvfb-run", "-a", "-n", "160", "pvpython", str(HERE / "paraview_dense.py"),
                        str(out), json.dumps(probes)], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stdout[-2000:] + r.stderr[:3000]
    got = json.loads(r.stdout.strip().splitlines()[-1])
    assert got["proxy"] == "NrrdReader" and got["class"] == "vtkImageData"
    assert got["dims"] == [256, 256, 256]
    assert got["spacing"] == [1, 1, 1] and got["type"] == "unsigned char"
    assert got["sample"] == [float(values[0]), float(values[len(ijk) // 2]), 7.0]
