#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Installs the checkout with `pip install --no-build-isolation` into a new venv that sees the
# system's packages (docs/python.md), then, from a folder outside the checkout, converts
# samples/headsq through the installed module and compares its report with the executable's
# (build/cli/voxlink, built first). The installed module must load the OpenVDB plugin it carries
# (setup.py builds it without the build-tree fallback). Part of scripts/run-tests.sh;
# VOXLINK_CMAKE_ARGS is passed on to setup.py's CMake so that ccache reuses ./build's objects.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
cli=$root/build/cli/voxlink
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
/usr/bin/python3 -m venv --system-site-packages "$tmp/venv"
# --no-index: Debian's numpy satisfies the one requirement; nothing comes from PyPI.
"$tmp/venv/bin/pip" install --quiet --no-build-isolation --no-index "$root"
mkdir "$tmp/elsewhere"
cd "$tmp/elsewhere"
"$cli" convert "$root/samples/headsq/headsq.nrrd" --tf "$root/samples/headsq/skin-bone.tf.json" \
  -q -o by_cli.vxl
"$cli" info by_cli.vxl --json > cli_info.json
"$tmp/venv/bin/python" - "$root" <<'EOF'
import filecmp
import json
import pathlib
import sys

import voxlink

root = pathlib.Path(sys.argv[1])
where = pathlib.Path(voxlink.__file__).resolve()
assert where.is_relative_to(pathlib.Path(sys.prefix).resolve()), f"imported {where}, not the venv's"
f = voxlink.convert(str(root / "samples/headsq/headsq.nrrd"),
                    tf=str(root / "samples/headsq/skin-bone.tf.json"), output="by_module.vxl")
assert filecmp.cmp("by_module.vxl", "by_cli.vxl", shallow=False), "module and CLI files differ"
cli = json.load(open("cli_info.json"))
info = f.info()  # with the OpenVDB peer: the plugin installed beside the module
for report in (info, cli):
    report.pop("path")  # by_module.vxl, by_cli.vxl
    report["peer"].pop("seconds")  # the time it took to build the OpenVDB grid
assert info == cli, f"module info {info} != CLI info {cli}"
print(f"pip install: voxlink from {where.parent}: headsq {info['voxels']} voxels, "
      f"OpenVDB peer {info['peer']['bytes']} B, same as the CLI")
EOF
