# SPDX-License-Identifier: BSD-3-Clause
"""Scene files for the bench scripts that rewrite them elsewhere (table1_vs_embree.py,
voxelization_cost.py): object file names made absolute, since a scene file's relative names
are relative to its own folder."""
import os


def absolute_paths(scene, folder):
    """`scene` (a parsed scene file from `folder`) with each object's relative file name joined
    to `folder`."""
    for o in scene.get("objects", []):
        if "file" in o and not os.path.isabs(o["file"]):
            o["file"] = os.path.normpath(os.path.join(folder, o["file"]))
    return scene
