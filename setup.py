# SPDX-License-Identifier: BSD-3-Clause
"""`pip install --no-build-isolation .`: builds the `voxlink` module with CMake (docs/python.md).

Debian 12 has no scikit-build, so setuptools drives CMake itself: it configures ./build-pip
(beside ./build, so that ccache reuses the objects of a ./build of the same checkout), builds
only the module and the plugins it loads, and copies them into the wheel: the module as a
top-level `voxlink` extension, the plugins into `voxlink.plugins/` beside it, where the loader
looks first (base/plugin_loader.h).
"""

import os
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent
# The plugins the module loads at run time: OpenVDB (.vdb inputs, info()'s peer, export) and
# DICOM; the OpenImageIO plugin writes image files, which only the executable does.
PLUGINS = ["voxlink_vdb", "voxlink_dicom"]
PLUGIN_FOLDER = "voxlink.plugins"


def project_version():
    for line in (ROOT / "CMakeLists.txt").read_text().splitlines():
        if line.startswith("project(VoxLink VERSION"):
            return line.split()[2]
    raise RuntimeError("CMakeLists.txt: no 'project(VoxLink VERSION ...)' line")


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build_dir = ROOT / "build-pip"
        configure = [
            "cmake", "-S", str(ROOT), "-B", str(build_dir), "-G", "Ninja",
            "-DCMAKE_BUILD_TYPE=Release",
            f"-DPython_EXECUTABLE={sys.executable}",
            # The loader's last fallback; nothing is installed there, only into the wheel.
            f"-DCMAKE_INSTALL_PREFIX={sys.prefix}",
            "-DVOXLINK_BUILD_PYTHON=ON", "-DVOXLINK_BUILD_TESTS=OFF",
            "-DVOXLINK_BUILD_BENCH=OFF", "-DVOXLINK_PLUGIN_SEARCH_BUILD_TREE=OFF",
        ]
        # Extra CMake options, e.g. the -DVOXLINK_WERROR=ON of scripts/run-tests.sh's ./build.
        configure += shlex.split(os.environ.get("VOXLINK_CMAKE_ARGS", ""))
        env = dict(os.environ)
        if shutil.which("ccache"):
            configure += ["-DCMAKE_CXX_COMPILER_LAUNCHER=ccache",
                          "-DCMAKE_C_COMPILER_LAUNCHER=ccache"]
            # As scripts/build.sh: paths hashed relative to the checkout's parent.
            env.setdefault("CCACHE_BASEDIR", str(ROOT.parent))
        subprocess.run(configure, check=True, env=env)
        subprocess.run(["cmake", "--build", str(build_dir), "--target", "voxlink_python",
                        *PLUGINS], check=True, env=env)

        module = Path(self.get_ext_fullpath(ext.name))
        module.parent.mkdir(parents=True, exist_ok=True)
        built = sorted((build_dir / "python").glob("voxlink*.so"))
        if len(built) != 1:
            raise RuntimeError(f"{build_dir / 'python'}: expected one voxlink*.so, found {built}")
        shutil.copy2(built[0], module)
        plugin_dir = module.parent / PLUGIN_FOLDER
        plugin_dir.mkdir(exist_ok=True)
        for name in PLUGINS:
            shutil.copy2(build_dir / "plugins" / f"lib{name}.so", plugin_dir)


setup(
    name="voxlink",
    version=project_version(),
    description="VoxLink sparse volumes: NumPy in and out, conversion, validation, rendering",
    ext_modules=[Extension("voxlink", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    # setuptools' own build folder, kept out of ./build (CMake's).
    options={"build": {"build_base": "build-pip/setuptools"}},
    install_requires=["numpy"],
    zip_safe=False,
    python_requires=">=3.9",
)
