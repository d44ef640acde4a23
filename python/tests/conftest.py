# SPDX-License-Identifier: BSD-3-Clause
# Fixtures for the voxlink module tests: the real data folder, the CLI beside the module.
import os
import pathlib

import pytest


@pytest.fixture(scope="session")
def data_dir():
    path = pathlib.Path(os.environ.get("VOXLINK_DATA_DIR", ""))
    if not path.is_dir():
        pytest.skip(f"real test data not found at '{path}' (set VOXLINK_DATA_DIR)")
    return path


@pytest.fixture(scope="session")
def foot_nrrd(data_dir):
    path = data_dir / "ct" / "openscivis_lossy" / "foot_256x256x256_uint8_lossy.nrrd"
    if not path.is_file():
        pytest.skip(f"{path} missing")
    return path


@pytest.fixture(scope="session")
def cli():
    path = os.environ.get("VOXLINK_CLI", "")
    if not os.access(path, os.X_OK):
        pytest.fail(f"VOXLINK_CLI='{path}' is not the voxlink executable")
    return path
