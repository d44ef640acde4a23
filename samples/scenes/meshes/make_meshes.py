#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Writes the small meshes the sample scenes use beside the real data: a unit quad, a unit box
and a house with glass windows (walls, gable roof, ground; materials in house.mtl).
Run from this folder: python3 make_meshes.py (the outputs are committed)."""

def quad(verts, faces, a, b, c, d):
    base = len(verts) + 1
    verts += [a, b, c, d]
    faces.append((base, base + 1, base + 2, base + 3))

def write(name, groups, mtl=None):
    verts, out = [], []
    for group, material, quads in groups:
        faces = []
        for q in quads:
            quad(verts, faces, *q)
        out.append((group, material, faces))
    with open(name, "w") as f:
        f.write("# written by make_meshes.py\n")
        if mtl:
            f.write(f"mtllib {mtl}\n")
        for v in verts:
            f.write("v %g %g %g\n" % v)
        for group, material, faces in out:
            f.write(f"g {group}\n")
            if material:
                f.write(f"usemtl {material}\n")
            for face in faces:
                f.write("f " + " ".join(str(i) for i in face) + "\n")

# Unit quad in the xz plane, normal +y (counter-clockwise seen from above).
write("quad.obj", [("quad", None, [((-1, 0, -1), (-1, 0, 1), (1, 0, 1), (1, 0, -1))])])

# Unit box [-1, 1]^3, outward normals.
box = [((-1, -1, 1), (1, -1, 1), (1, 1, 1), (-1, 1, 1)), ((1, -1, -1), (-1, -1, -1), (-1, 1, -1), (1, 1, -1)),
       ((1, -1, 1), (1, -1, -1), (1, 1, -1), (1, 1, 1)), ((-1, -1, -1), (-1, -1, 1), (-1, 1, 1), (-1, 1, -1)),
       ((-1, 1, 1), (1, 1, 1), (1, 1, -1), (-1, 1, -1)), ((-1, -1, -1), (1, -1, -1), (1, -1, 1), (-1, -1, 1))]
write("box.obj", [("box", None, box)])

# A house 3 x 2 x 1.2 (plus a 0.6 roof) on a ground plane, two windows in the front and back
# walls and one in each side wall, each closed by a glass pane.
W, D, H, RIDGE = 1.5, 1.0, 1.2, 1.8
WY0, WY1 = 0.4, 0.9
walls, glass = [], []

def wall_z(z, sign):
    # x segments between the windows at [-1.0, -0.4] and [0.4, 1.0].
    def q(x0, x1, y0, y1):
        a, b, c, d = (x0, y0, z), (x1, y0, z), (x1, y1, z), (x0, y1, z)
        return (a, b, c, d) if sign > 0 else (b, a, d, c)
    walls.extend([q(-W, W, 0, WY0), q(-W, W, WY1, H)])
    for x0, x1 in [(-W, -1.0), (-0.4, 0.4), (1.0, W)]:
        walls.append(q(x0, x1, WY0, WY1))
    for x0, x1 in [(-1.0, -0.4), (0.4, 1.0)]:
        glass.append(q(x0, x1, WY0, WY1))

def wall_x(x, sign):
    def q(z0, z1, y0, y1):
        a, b, c, d = (x, y0, z1), (x, y0, z0), (x, y1, z0), (x, y1, z1)
        return (a, b, c, d) if sign > 0 else (b, a, d, c)
    walls.extend([q(-D, D, 0, WY0), q(-D, D, WY1, H), q(-D, -0.3, WY0, WY1), q(0.3, D, WY0, WY1)])
    glass.append(q(-0.3, 0.3, WY0, WY1))
    # Gable: a degenerate quad (two corners equal) is a triangle.
    top = (x, RIDGE, 0)
    walls.append(((x, H, D), (x, H, -D), top, top) if sign > 0 else ((x, H, -D), (x, H, D), top, top))

wall_z(D, 1)
wall_z(-D, -1)
wall_x(W, 1)
wall_x(-W, -1)
roof = [((-W - 0.1, H - 0.05, D + 0.1), (W + 0.1, H - 0.05, D + 0.1), (W + 0.1, RIDGE, 0), (-W - 0.1, RIDGE, 0)),
        ((W + 0.1, H - 0.05, -D - 0.1), (-W - 0.1, H - 0.05, -D - 0.1), (-W - 0.1, RIDGE, 0), (W + 0.1, RIDGE, 0))]
ground = [((-3, 0, -3), (-3, 0, 3), (3, 0, 3), (3, 0, -3))]
write("house.obj", [("walls", "wall", walls), ("glass", "glass", glass), ("roof", "roof", roof),
                    ("ground", "ground", ground)], mtl="house.mtl")
with open("house.mtl", "w") as f:
    f.write("""# written by make_meshes.py; MTL mapping in docs/geometry.md
newmtl wall
Kd 0.85 0.8 0.7
illum 2
newmtl roof
Kd 0.6 0.15 0.1
illum 2
newmtl ground
Kd 0.35 0.5 0.3
illum 2
newmtl glass
Kd 0.8 0.9 1.0
Ks 0.1 0.1 0.1
Ni 1.5
illum 7
""")
