#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Builds the fuzz seed corpora from ../shared/data (small files, or real headers cut down to a
few slices of real data) plus a few hand-made variants the data set lacks (LIST file lists,
appended VTI data, Fortran-order npy, ...). Nothing large is committed: scripts/fuzz.sh runs
this into the build dir. Usage: make_seeds.py DATA_DIR OUT_DIR [VOXLINK_EXE]"""
import base64
import gzip
import io
import os
import struct
import subprocess
import sys
import zipfile
import zlib

MARK = b"\n==> %s <==\n"


def bundle(main, *extra):
    """One fuzz input: the main file, then (name, bytes) files beside it (fuzz/fuzz_input.h)."""
    out = main
    for name, data in extra:
        out += MARK % name.encode() + data
    return out


class Seeds:
    def __init__(self, out):
        self.out = out

    def add(self, target, name, data):
        folder = os.path.join(self.out, target)
        os.makedirs(folder, exist_ok=True)
        with open(os.path.join(folder, name), "wb") as f:
            f.write(data)


def read(data_dir, rel, limit=None):
    with open(os.path.join(data_dir, rel), "rb") as f:
        return f.read() if limit is None else f.read(limit)


def nrrd_seeds(s, d):
    slice_bytes = 64 * 64 * 2
    slices = [read(d, "ct/vtk_headsq/quarter.%d" % i) for i in (1, 2, 3)]
    numbered = (b"NRRD0004\ndimension: 3\nsizes: 64 64 3\nspacings: 3.2 3.2 1.5\n"
                b"endian: little\ntype: short\nencoding: raw\ndata file: quarter.%d 1 3 1\n")
    s.add("nrrd", "headsq_numbered",
          bundle(numbered, *[("quarter.%d" % (i + 1), slices[i]) for i in range(3)]))
    listed = (b"NRRD0004\ndimension: 3\nsizes: 64 64 2\nendian: little\ntype: short\n"
              b"encoding: raw\ndata file: LIST 2\nquarter.1\nquarter.2\n")
    s.add("nrrd", "headsq_list", bundle(listed, ("quarter.1", slices[0]), ("quarter.2", slices[1])))
    data = b"".join(slices)[: 3 * slice_bytes]
    s.add("nrrd", "attached_raw",
          b"NRRD0004\ntype: short\ndimension: 3\nsizes: 64 64 3\nencoding: raw\n"
          b"endian: big\nspace: left-posterior-superior\nspace directions: (3,0,0) (0,3,0) (0,0,1.5)\nspace origin: (1,2,3)\n\n"
          + data)
    flair = read(d, "mri/niivue_FLAIR.nrrd")
    header = flair[: flair.index(b"\n\n") + 2].replace(b"sizes: 124 160 140", b"sizes: 124 160 2")
    raw = zlib.decompressobj(16 + zlib.MAX_WBITS).decompress(flair[flair.index(b"\n\n") + 2 :],
                                                             124 * 160 * 2)
    s.add("nrrd", "flair_gzip_oblique", header + gzip.compress(raw[: 124 * 160 * 2]))
    nucleon = read(d, "volume/voreen_nucleon/nucleon.nrrd")
    s.add("nrrd", "nucleon_detached",
          bundle(nucleon.replace(b"sizes: 41 41 41", b"sizes: 41 41 3"),
                 ("nucleon.raw", read(d, "volume/voreen_nucleon/nucleon.raw", 41 * 41 * 3))))
    lidc = read(d, "ct/vtkjs_LIDC2/LIDC2.nhdr").replace(b"sizes: 256 256 133", b"sizes: 32 32 4")
    s.add("nrrd", "lidc_gzip_detached",
          bundle(lidc, ("b1ad142a1ebc80f957fcdc329e876d51.gz", gzip.compress(bytes(range(256)) * 16))))


def metaimage_seeds(s, d):
    mhd = read(d, "mri/vtk_HeadMRVolume.mhd").replace(b"48 62 42", b"48 62 3")
    raw = read(d, "mri/vtk_HeadMRVolume.raw", 48 * 62 * 3)
    s.add("metaimage", "head_mr", bundle(mhd, ("HeadMRVolume.raw", raw)))
    mha = read(d, "mri/niivue_mha.mha")
    split = mha.index(b"ElementDataFile = LOCAL\n") + len(b"ElementDataFile = LOCAL\n")
    voxels = zlib.decompress(mha[split:])[: 64 * 64 * 2 * 2]
    packed = zlib.compress(voxels)
    header = mha[:split].replace(b"DimSize = 64 64 37", b"DimSize = 64 64 2").replace(
        b"CompressedDataSize = 131270", b"CompressedDataSize = %d" % len(packed))
    s.add("metaimage", "mha_zlib_local", header + packed)
    listed = (b"ObjectType = Image\nNDims = 3\nDimSize = 48 62 2\nElementType = MET_UCHAR\n"
              b"ElementDataFile = LIST\na.raw\nb.raw\n")
    s.add("metaimage", "list",
          bundle(listed, ("a.raw", raw[: 48 * 62]), ("b.raw", raw[48 * 62 : 2 * 48 * 62])))
    numbered = (b"NDims = 3\nDimSize = 48 62 2\nElementType = MET_USHORT\nElementByteOrderMSB = True\n"
                b"ElementDataFile = s%03d.raw 1 2 1\n")
    s.add("metaimage", "numbered",
          bundle(numbered, ("s001.raw", raw[: 48 * 62 * 2]), ("s002.raw", raw[: 48 * 62 * 2])))
    frog = read(d, "volume/vtk_frogtissue/frogtissue.mhd")
    s.add("metaimage", "frog_header_only", frog)


def nifti_seeds(s, d):
    nii = gzip.decompress(read(d, "mri/vtk_avg152T1_RL_nifti.nii.gz"))
    header = bytearray(nii[:352])
    order = "<" if struct.unpack("<i", nii[:4])[0] == 348 else ">"
    struct.pack_into(order + "h", header, 46, 2)  # dim[3]: two slices
    small = bytes(header) + nii[352 : 352 + 91 * 109 * 2]
    s.add("nifti", "avg152_plain", small)
    s.add("nifti", "avg152_gzip", gzip.compress(small))


def vvd_seeds(s, d):
    vvd = (b'<?xml version="1.0" ?>\n<VoreenData version="1">\n<Volumes>\n<Volume>\n'
           b'<RawData filename="walnut.raw" format="uint16" x="128" y="96" z="2" />\n'
           b'<MetaData>\n<MetaItem name="Offset" type="Vec3MetaData"><value x="-1" y="-0.75" '
           b'z="-0.89" /></MetaItem>\n<MetaItem name="Spacing" type="Vec3MetaData"><value '
           b'x="0.015625" y="0.015625" z="0.015625" /></MetaItem>\n</MetaData>\n</Volume>\n'
           b'</Volumes>\n</VoreenData>\n')
    raw = read(d, "ct/voreen_walnut/walnut.raw", 128 * 96 * 2 * 2)
    s.add("vvd", "walnut", bundle(vvd, ("walnut.raw", raw)))
    s.add("vvd", "walnut_header_prefix", read(d, "ct/voreen_walnut/walnut.vvd", 2048))


def vti_seeds(s, d):
    values = struct.pack("<64f", *[i * 0.25 for i in range(64)])
    head = (b'<?xml version="1.0"?>\n<VTKFile type="ImageData" version="0.1" '
            b'byte_order="LittleEndian" header_type="%s"%s>\n<ImageData WholeExtent="0 3 0 3 0 3" '
            b'Origin="0 0 0" Spacing="1 1 2">\n<Piece Extent="0 3 0 3 0 3">\n'
            b'<PointData Scalars="v">\n')
    tail = b"</PointData>\n</Piece>\n</ImageData>\n%s</VTKFile>\n"
    inline = base64.b64encode(struct.pack("<I", len(values)) + values)
    s.add("vti", "inline_base64",
          head % (b"UInt32", b"") + b'<DataArray type="Float32" Name="v" format="binary">'
          + inline + b"</DataArray>\n" + tail % b"")
    packed = zlib.compress(values)
    blocks = struct.pack("<QQQQ", 1, len(values), len(values), len(packed)) + packed
    s.add("vti", "zlib_uint64",
          head % (b"UInt64", b' compressor="vtkZLibDataCompressor"')
          + b'<DataArray type="Float32" Name="v" format="binary">'
          + base64.b64encode(blocks[:32]) + base64.b64encode(packed) + b"</DataArray>\n"
          + tail % b"")
    s.add("vti", "appended_raw",
          head % (b"UInt32", b"") + b'<DataArray type="Float32" Name="v" format="appended" '
          b'offset="0"/>\n' + tail % (b'<AppendedData encoding="raw">_'
                                      + struct.pack("<I", len(values)) + values
                                      + b"\n</AppendedData>\n"))
    s.add("vti", "hydrogen_prefix", read(d, "volume/vtk_hydrogen.vti", 4096))


def npy_header(descr, shape, fortran=False, version=1):
    text = "{'descr': '%s', 'fortran_order': %s, 'shape': %s, }" % (
        descr, "True" if fortran else "False", repr(tuple(shape)))
    size_bytes = 2 if version == 1 else 4
    total = 6 + 2 + size_bytes + len(text) + 1
    text += " " * ((64 - total % 64) % 64) + "\n"
    length = struct.pack("<H" if version == 1 else "<I", len(text))
    return b"\x93NUMPY" + bytes([version, 0]) + length + text.encode("latin1")


def npy_seeds(s, d):
    tooth = read(d, "ct/tooth_103x94x161_uint8.raw", 103 * 94 * 2)
    s.add("npy", "u1_c", npy_header("|u1", (2, 94, 103)) + tooth)
    s.add("npy", "f4_fortran", npy_header("<f4", (4, 3, 2), fortran=True) + struct.pack("<24f", *range(24)))
    s.add("npy", "i2_big_v2", npy_header(">i2", (3, 5), version=2) + struct.pack(">15h", *range(15)))
    s.add("npy", "f8_1d_v3", npy_header("<f8", (7,), version=3) + struct.pack("<7d", *range(7)))


def gslib_seeds(s, d):
    s.add("gslib", "sgems_small", b"3 2 2\n2\nporosity\nfacies\n" +
          b"".join(b"%d.5 %d\n" % (i, i % 2) for i in range(12)))
    s.add("gslib", "geoeas_dims_title", b"a grid\n1\nvalue\n" + b"".join(b"-999\n1e3\n" for _ in range(4)))
    packed = io.BytesIO()
    with zipfile.ZipFile(packed, "w", zipfile.ZIP_DEFLATED) as z:
        z.writestr("grid.sgems", b"2 2 2\n1\nv\n" + b"".join(b"%d\n" % i for i in range(8)))
    s.add("gslib", "zipped", packed.getvalue())


def raw_seeds(s, d):
    options = struct.pack("<HHHBB", 103, 94, 2, 0, 0)  # u8 (type byte 0 -> u8), little, no header
    s.add("raw", "tooth_u8", options + read(d, "ct/tooth_103x94x161_uint8.raw", 103 * 94 * 2))
    options = struct.pack("<HHHBB", 64, 64, 2, 3, 0x80 | 16)  # i16, big, 16 header bytes
    s.add("raw", "headsq_i16_big_header", options + bytes(16) + read(d, "ct/vtk_headsq/quarter.1") * 2)


def dicom_seeds(s, d):
    s.add("dicom", "ct_head_one", read(d, "ct/slicer_CTHeadAxialDicom/CTHead1.dcm"))
    s.add("dicom", "ct_head_two", bundle(read(d, "ct/slicer_CTHeadAxialDicom/CTHead1.dcm"),
                                         ("CTHead2.dcm", read(d, "ct/slicer_CTHeadAxialDicom/CTHead2.dcm"))))
    s.add("dicom", "rtdose_multiframe", read(d, "dicom_multiframe/pydicom_rtdose.dcm"))
    s.add("dicom", "enhanced_ct_multiframe", enhanced_ct(d))


def dicom_element(group, element, vr, value):
    """One explicit VR little endian element; SQ values are lists of item byte strings."""
    if vr == b"SQ":
        body = b"".join(struct.pack("<HHI", 0xFFFE, 0xE000, 0xFFFFFFFF) + item +
                        struct.pack("<HHI", 0xFFFE, 0xE00D, 0) for item in value)
        return (struct.pack("<HH", group, element) + vr + b"\0\0" + struct.pack("<I", 0xFFFFFFFF) +
                body + struct.pack("<HHI", 0xFFFE, 0xE0DD, 0))
    if isinstance(value, str):
        value = value.encode()
        value += b"\0" if vr == b"UI" and len(value) % 2 else b" " * (len(value) % 2)
    if vr in (b"OB", b"OW", b"UN"):
        return struct.pack("<HH", group, element) + vr + b"\0\0" + struct.pack("<I", len(value)) + value
    return struct.pack("<HH", group, element) + vr + struct.pack("<H", len(value)) + value


def enhanced_ct(d):
    """A 3-frame Enhanced CT file (8x4 pixels of the CT head's slices 40..42, frames in reverse
    position order) with shared and per-frame functional groups, written by hand."""
    e = dicom_element
    frames, pixels = [], b""
    for k, n in enumerate((42, 41, 40)):
        data = read(d, "ct/slicer_CTHeadAxialDicom/CTHead%d.dcm" % n)
        pixels += data[-8192 + 64 * 2 * 30: -8192 + 64 * 2 * 30 + 8 * 4 * 2]
        frames.append(e(0x0020, 0x9113, b"SQ", [e(0x0020, 0x0032, b"DS", "0\\0\\%g" % (1.5 * (n - 1)))]) +
                      e(0x0028, 0x9145, b"SQ", [e(0x0028, 0x1052, b"DS", str(-k)) +
                                               e(0x0028, 0x1053, b"DS", "1")]))
    shared = (e(0x0020, 0x9116, b"SQ", [e(0x0020, 0x0037, b"DS", "1\\0\\0\\0\\1\\0")]) +
              e(0x0028, 0x9110, b"SQ", [e(0x0028, 0x0030, b"DS", "3.2\\3.2") +
                                       e(0x0018, 0x0050, b"DS", "1.5")]))
    ts = "1.2.840.10008.1.2.1"
    meta_body = e(0x0002, 0x0001, b"OB", b"\0\1") + e(0x0002, 0x0010, b"UI", ts)
    meta = e(0x0002, 0x0000, b"UL", struct.pack("<I", len(meta_body))) + meta_body
    body = (e(0x0008, 0x0016, b"UI", "1.2.840.10008.5.1.4.1.1.2.1") +
            e(0x0008, 0x0060, b"CS", "CT") + e(0x0020, 0x000E, b"UI", "1.2.3.4.5.6") +
            e(0x0028, 0x0002, b"US", struct.pack("<H", 1)) +
            e(0x0028, 0x0004, b"CS", "MONOCHROME2") + e(0x0028, 0x0008, b"IS", "3") +
            e(0x0028, 0x0010, b"US", struct.pack("<H", 4)) +
            e(0x0028, 0x0011, b"US", struct.pack("<H", 8)) +
            e(0x0028, 0x0100, b"US", struct.pack("<H", 16)) +
            e(0x0028, 0x0101, b"US", struct.pack("<H", 16)) +
            e(0x0028, 0x0102, b"US", struct.pack("<H", 15)) +
            e(0x0028, 0x0103, b"US", struct.pack("<H", 1)) +
            e(0x5200, 0x9229, b"SQ", [shared]) + e(0x5200, 0x9230, b"SQ", frames) +
            e(0x7FE0, 0x0010, b"OW", pixels))
    return bytes(128) + b"DICM" + meta + body


def image_seeds(s, out):
    tmp = os.path.join(out, "tmp-images")
    os.makedirs(tmp, exist_ok=True)
    made = []
    for name, args in (("gray8.png", ["--pattern", "checker:width=4:height=4", "8x8", "1"]),
                       ("rgb16.tif", ["--pattern", "fill:top=0.1:bottom=0.9", "8x6", "3", "-d", "uint16"])):
        path = os.path.join(tmp, name)
        try:
            subprocess.run(["oiiotool"] + args + ["-o", path], check=True, capture_output=True)
        except (OSError, subprocess.CalledProcessError):
            continue
        made.append(path)
    for path in made:
        with open(path, "rb") as f:
            data = f.read()
        s.add("image_stack", os.path.basename(path), data)
    tiffs = [p for p in made if p.endswith(".tif")]
    if tiffs:
        multi = os.path.join(tmp, "pages.tif")
        if subprocess.run(["oiiotool", tiffs[0], tiffs[0], "--siappend", "-o", multi],
                          capture_output=True).returncode == 0:
            with open(multi, "rb") as f:
                s.add("image_stack", "multipage.tif", f.read())
    pngs = [p for p in made if p.endswith(".png")]
    if pngs:
        with open(pngs[0], "rb") as f:
            png = f.read()
        s.add("image_stack", "two_slices", bundle(png, ("slice1.png", png)))


def tf_seeds(s, root):
    for rel in ("samples/headsq/skin-bone.tf.json", "bench/tf/tooth.tf.json"):
        with open(os.path.join(root, rel), "rb") as f:
            s.add("transfer_function", os.path.basename(rel), f.read())
    s.add("transfer_function", "minimal",
          b'{"format":"voxlink-transfer-function","version":1,"opacity":[[0,0],[1,1]],'
          b'"color":[[0,0,0,0],[1,1,1,1]]}')


def paraview_seeds(s):
    s.add("paraview_preset", "cool_warm",
          b'[{"ColorSpace":"Diverging","Name":"Cool to Warm","NanColor":[1,1,0],'
          b'"RGBPoints":[0,0.23,0.299,0.754,0.5,0.865,0.865,0.865,1,0.706,0.016,0.15]}]')
    s.add("paraview_preset", "with_points",
          b'{"Name":"bone","RGBPoints":[-1000,0,0,0,500,1,0.9,0.8,3000,1,1,1],'
          b'"Points":[-1000,0,0.5,0,400,0,0.5,0,3000,0.8,0.5,0]}')


def kriging_seeds(s, d):
    s.add("kriging_points", "walker_head", b"".join(
        read(d, "geostat/gstat_csv/walker.csv").splitlines(keepends=True)[:40]))
    s.add("kriging_points", "meuse_quoted_na",
          b'"X","Y","V"\n181072,333611,1022\n181025,333558,NA\n"181165",333537,640\n')
    s.add("kriging_points", "xyz", b"X,Y,Z,V\n0,0,0,1\n1,0,2,3.5\n0,1,1,-2\n")
    geoeas = read(d, "geostat/vtk_b_100sampledatawl.sgems", 1200)
    geoeas = geoeas[: geoeas.rindex(b"\n") + 1]
    s.add("kriging_points", "geoeas", geoeas.replace(b"U-random-samplingtrans", b"V"))


def small_mesh(d, keep=200):
    """The first `keep` vertices of the npm bunny and the faces that use only them."""
    verts, faces = [], []
    for line in read(d, "mesh/bunny_npm.obj").decode().splitlines():
        f = line.split()
        if f and f[0] == "v" and len(verts) < keep:
            verts.append(tuple(float(x) for x in f[1:4]))
        elif f and f[0] == "f":
            idx = [int(x.split("/")[0]) - 1 for x in f[1:]]
            if all(0 <= i < keep for i in idx):
                faces.append(idx)
    return verts, faces


def mesh_seeds(s, d):
    verts, faces = small_mesh(d)
    obj = "".join("v %g %g %g\n" % v for v in verts) + "".join(
        "f %s\n" % " ".join(str(i + 1) for i in f) for f in faces)
    s.add("mesh", "bunny_part.obj", obj.encode())
    cornell = read(d, "mesh/mcguire_CornellBox-Original.obj")
    s.add("mesh", "cornell_with_mtl",
          bundle(cornell, ("CornellBox-Original.mtl", read(d, "mesh/mcguire_CornellBox-Original.mtl"))))
    s.add("mesh", "cornell_no_mtl", cornell)
    # PLY: ASCII from the real bunny's header, binary of both byte orders.
    head = ("ply\nformat %s 1.0\nelement vertex %d\nproperty float x\nproperty float y\n"
            "property float z\nelement face %d\nproperty list uchar int vertex_indices\nend_header\n")
    s.add("mesh", "bunny_part_ascii.ply",
          (head % ("ascii", len(verts), len(faces))).encode()
          + "".join("%g %g %g\n" % v for v in verts).encode()
          + "".join("%d %s\n" % (len(f), " ".join(map(str, f))) for f in faces).encode())
    for name, fmt, order in (("le", "binary_little_endian", "<"), ("be", "binary_big_endian", ">")):
        body = b"".join(struct.pack(order + "3f", *v) for v in verts)
        body += b"".join(struct.pack(order + "B%di" % len(f), len(f), *f) for f in faces)
        s.add("mesh", "bunny_part_%s.ply" % name,
              (head % (fmt, len(verts), len(faces))).encode() + body)
    # OFF (assimp's reader; the loader checks its counts and indices first).
    s.add("mesh", "bunny_part.off",
          ("OFF\n# bunny part\n%d %d 0\n" % (len(verts), len(faces))).encode()
          + "".join("%g %g %g\n" % v for v in verts).encode()
          + "".join("%d %s\n" % (len(f), " ".join(map(str, f))) for f in faces).encode())
    tris = [f for f in faces if len(f) == 3][:100]
    ascii_stl = "solid part\n" + "".join(
        "facet normal 0 0 0\nouter loop\n" + "".join("vertex %g %g %g\n" % verts[i] for i in t)
        + "endloop\nendfacet\n" for t in tris) + "endsolid part\n"
    s.add("mesh", "bunny_part_ascii.stl", ascii_stl.encode())
    binary = b"\0" * 80 + struct.pack("<I", len(tris)) + b"".join(
        struct.pack("<3f", 0, 0, 0) + b"".join(struct.pack("<3f", *verts[i]) for i in t)
        + b"\0\0" for t in tris)
    s.add("mesh", "bunny_part_binary.stl", binary)


def particle_seeds(s, d):
    for rel in ("particles/biopython_2XHE.pdb", "particles/biopython_7DDO.pdb"):
        lines = read(d, rel).splitlines(keepends=True)
        atoms = [l for l in lines if l.startswith((b"ATOM", b"HETATM"))]
        hetatm = [l for l in atoms if l.startswith(b"HETATM")][:20]
        s.add("particles", os.path.basename(rel), b"".join(lines[:10] + atoms[:150] + hetatm))
    atoms = [l for l in read(d, "particles/biopython_7DDO.pdb").splitlines()
             if l.startswith(b"ATOM")][:100]
    text = b"# x y z r material\n" + b"".join(
        b"%s %s %s 1.5 %s\n" % (a[30:38].strip(), a[38:46].strip(), a[46:54].strip(),
                                a[76:78].strip() or b"C") for a in atoms)
    s.add("particles", "atoms.txt", text)
    s.add("particles", "spheres.csv", b"x,y,z,r\n0,0,0,1\n2.5,0,0,0.5\n0,3,1e3,2\n")


def scene_seeds(s, root):
    folder = os.path.join(root, "samples", "scenes")
    for name in sorted(os.listdir(folder)):
        if name.endswith(".scene.json"):
            with open(os.path.join(folder, name), "rb") as f:
                s.add("scene", name, f.read())


def vxl_seeds(s, d, out, voxlink):
    if not voxlink:
        return
    tmp = os.path.join(out, "tmp-vxl")
    os.makedirs(tmp, exist_ok=True)
    neghip = read(d, "volume/neghip_64x64x64_uint8.raw")
    crop = b"".join(neghip[(z * 64 + y) * 64 + 24 : (z * 64 + y) * 64 + 40]
                    for z in range(24, 40) for y in range(24, 40))
    src = os.path.join(tmp, "crop.raw")
    with open(src, "wb") as f:
        f.write(crop)
    for name, extra in (("u8_b4", ["--brick", "4"]), ("f16_b8_x", ["--value-type", "f16", "--axis", "x"]),
                        ("u16_b8_y", ["--value-type", "u16", "--axis", "y"])):
        dst = os.path.join(tmp, name + ".vxl")
        cmd = [voxlink, "convert", src, "--dims", "16,16,16", "--type", "u8", "--threshold", "60",
               "-o", dst, "-q"] + extra
        if subprocess.run(cmd, capture_output=True).returncode == 0:
            with open(dst, "rb") as f:
                s.add("vxl", name, f.read())
            # The same file packed, with and without predicted gradients.
            for suffix, pack_args in (("packed", []), ("packed_fast", ["--fast"])):
                packed = os.path.join(tmp, name + "." + suffix + ".vxl")
                if subprocess.run([voxlink, "pack", dst, "-o", packed, "-q"] + pack_args,
                                  capture_output=True).returncode == 0:
                    with open(packed, "rb") as f:
                        s.add("vxl", name + "_" + suffix, f.read())
    # A 24^3 crop with brick 8: its middle brick lies away from the volume's faces, where
    # unpacking predicts gradients eight cells at a time (pack/detail/dense_brick_rows.h).
    # (this corner of neghip keeps 132 voxels in the middle brick, 696 in all)
    crop24 = b"".join(neghip[(z * 64 + y) * 64 : (z * 64 + y) * 64 + 24]
                      for z in range(16, 40) for y in range(32, 56))
    src24 = os.path.join(tmp, "crop24.raw")
    with open(src24, "wb") as f:
        f.write(crop24)
    dst = os.path.join(tmp, "u8_b8_z24.vxl")
    packed = os.path.join(tmp, "u8_b8_z24.packed.vxl")
    if (subprocess.run([voxlink, "convert", src24, "--dims", "24,24,24", "--type", "u8",
                        "--threshold", "60", "-o", dst, "-q"], capture_output=True).returncode == 0
            and subprocess.run([voxlink, "pack", dst, "-o", packed, "-q"],
                               capture_output=True).returncode == 0):
        with open(packed, "rb") as f:
            s.add("vxl", "u8_b8_z24_packed", f.read())
    # A scene (version 2) of the first volume and a sphere, plain and packed: the packed one's
    # GRAD is predicted over VMSK slots.
    volume = os.path.join(tmp, "u8_b4.vxl")
    if os.path.exists(volume):
        scene_json = os.path.join(tmp, "s.scene.json")
        with open(scene_json, "w") as f:
            f.write('{"objects": [{"type": "volume", "file": "u8_b4.vxl"}, '  # beside the scene
                    '{"type": "sphere", "center": [8, 8, 8], "radius": 3}]}')
        scene, packed = os.path.join(tmp, "scene.vxl"), os.path.join(tmp, "scene.packed.vxl")
        if (subprocess.run([voxlink, "scene", "build", scene_json, "-o", scene],
                           capture_output=True).returncode == 0 and
                subprocess.run([voxlink, "pack", scene, "-o", packed, "-q"],
                               capture_output=True).returncode == 0):
            for name, path in (("scene_sphere", scene), ("scene_sphere_packed", packed)):
                with open(path, "rb") as f:
                    s.add("vxl", name, f.read())
    # A small mesh scene in the two surface modes of format 2.1 (per-voxel fragment lists FROF/FRAG;
    # triangle references TRID/TRIS), so the fuzzer starts inside their validators.
    mesh = os.path.join(tmp, "box.obj")
    with open(mesh, "w") as f:
        f.write("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
                "f 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n")
    mesh_json = os.path.join(tmp, "box.scene.json")
    with open(mesh_json, "w") as f:
        f.write('{"grid": {"resolution": 12}, "objects": [{"type": "mesh", "file": "box.obj"}]}')
    for mode in ("planes", "triangles"):
        out = os.path.join(tmp, f"box_{mode}.vxl")
        if subprocess.run([voxlink, "scene", "build", mesh_json, "-o", out, "--surface", mode],
                          capture_output=True).returncode == 0:
            with open(out, "rb") as f:
                s.add("vxl", f"scene_box_{mode}", f.read())


def main():
    data_dir, out = sys.argv[1], sys.argv[2]
    voxlink = sys.argv[3] if len(sys.argv) > 3 else None
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    s = Seeds(out)
    nrrd_seeds(s, data_dir)
    metaimage_seeds(s, data_dir)
    nifti_seeds(s, data_dir)
    vvd_seeds(s, data_dir)
    vti_seeds(s, data_dir)
    npy_seeds(s, data_dir)
    gslib_seeds(s, data_dir)
    raw_seeds(s, data_dir)
    dicom_seeds(s, data_dir)
    image_seeds(s, out)
    tf_seeds(s, root)
    paraview_seeds(s)
    kriging_seeds(s, data_dir)
    vxl_seeds(s, data_dir, out, voxlink)
    mesh_seeds(s, data_dir)
    particle_seeds(s, data_dir)
    scene_seeds(s, root)


if __name__ == "__main__":
    main()
