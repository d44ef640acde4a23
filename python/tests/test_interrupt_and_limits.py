# SPDX-License-Identifier: BSD-3-Clause
# voxlink.convert() on arrays applies the command line's size limits before reading anything
# (a memmap of shape (512, 65536, 65536) ran for hours; `voxlink convert` refuses the same dims
# at once), and Ctrl-C (SIGINT) stops a long conversion between slabs with KeyboardInterrupt,
# writing nothing.
import os
import pathlib
import subprocess
import sys
import textwrap
import time

import numpy as np
import pytest

import voxlink


def huge(shape, dtype=np.uint8):
    """An array of `shape` that takes no memory: every element is the same byte."""
    return np.lib.stride_tricks.as_strided(np.zeros(1, dtype), shape=shape,
                                           strides=(0,) * len(shape))


@pytest.mark.parametrize("shape,text", [
    ((512, 65536, 65536), r"65536x65536x512 is more than 1099511627776 voxels"),
    ((2, 3, 65537), r"axis 0 has size 65537, more than 65536"),
    ((70000, 1, 1), r"axis 2 has size 70000, more than 65536"),
    ((0, 4, 4), r"axis 2 has size 0"),
])
def test_arrays_beyond_the_cli_limits_are_refused_at_once(shape, text):
    start = time.perf_counter()
    with pytest.raises(voxlink.Error, match="numpy array: .*" + text):
        voxlink.convert(huge(shape), threshold=1)
    assert time.perf_counter() - start < 1.0


def test_cli_refuses_the_same_dims(cli, tmp_path):
    raw = tmp_path / "empty.raw"
    raw.write_bytes(b"")
    r = subprocess.run([cli, "convert", str(raw), "--dims", "65536,65536,512", "--type", "u8",
                        "--threshold", "1", "-o", str(tmp_path / "o.vxl")],
                       capture_output=True, text=True)
    assert r.returncode != 0
    assert "65536x65536x512 is more than 1099511627776 voxels" in r.stderr


# The child converts a memmap of a sparse 16 GiB file (1024 slices of 4096 x 4096 u8, zeros:
# tens of seconds of reading) and sends itself SIGINT after half a second.
CHILD = textwrap.dedent("""
    import os, signal, sys, threading, time
    import numpy as np
    import voxlink
    source, output = sys.argv[1], sys.argv[2]
    a = np.memmap(source, dtype=np.uint8, mode="r", shape=(1024, 4096, 4096))
    threading.Timer(0.5, os.kill, (os.getpid(), signal.SIGINT)).start()
    start = time.perf_counter()
    try:
        voxlink.convert(a, threshold=1, slab=8, output=output)
    except KeyboardInterrupt:
        print("interrupted after %.3f s" % (time.perf_counter() - start))
        sys.exit(0)
    print("finished after %.3f s" % (time.perf_counter() - start))
    sys.exit(1)
""")


def test_ctrl_c_interrupts_a_long_conversion(tmp_path):
    source = tmp_path / "zeros.u8"
    with open(source, "wb") as f:
        f.truncate(1024 * 4096 * 4096)  # sparse: no disk blocks
    output = tmp_path / "out.vxl"
    env = dict(os.environ)
    start = time.perf_counter()
    r = subprocess.run([sys.executable, "-c", CHILD, str(source), str(output)],
                       capture_output=True, text=True, timeout=120, env=env)
    elapsed = time.perf_counter() - start
    assert r.returncode == 0, r.stdout + r.stderr
    assert r.stdout.startswith("interrupted after"), r.stdout
    # Stopped at the next slab (8 slices, 128 MiB), not at the end of the 16 GiB.
    assert float(r.stdout.split()[2]) < 5.0, r.stdout
    assert elapsed < 30.0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["zeros.u8"]
