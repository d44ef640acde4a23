#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Writes DICOM files that other libraries read differently, and what each one holds.

Usage: make_dicom_cases.py OUT_DIR DATA_DIR

Every file is built from the real data (DATA_DIR: ct/slicer_CTHeadAxialDicom, dicom_multiframe)
with pydicom and GDCM's gdcmconv, never with voxlink. For the files voxlink must read, the
expected values are written beside them as CASE.f64 (float64 little endian, x fastest, then y,
then frames): pydicom's pixel_array of the uncompressed little-endian original, through the
rescale by numpy, as the DICOM standard defines the values. The test (dicom_encodings_test.cpp)
compares every voxel with them. Exits non-zero with a message when a tool is missing.
"""
import pathlib
import shutil
import subprocess
import sys

import numpy as np
import pydicom
from pydicom.uid import ExplicitVRBigEndian, ExplicitVRLittleEndian

HTJ2K_LOSSLESS = "1.2.840.10008.1.2.4.201"
JPEG_LOSSLESS = "1.2.840.10008.1.2.4.70"


def gdcmconv(args, src, dst):
    subprocess.run(["gdcmconv", *args, str(src), str(dst)], check=True)


def expect(out, name, values):
    np.asarray(values, dtype="<f8").tofile(out / f"{name}.f64")


def explicit_little(ds):
    ds.file_meta.TransferSyntaxUID = ExplicitVRLittleEndian
    ds.is_little_endian = True
    ds.is_implicit_VR = False


def to_big_endian(ds, stored, dtype):
    ds.file_meta.TransferSyntaxUID = ExplicitVRBigEndian
    ds.is_little_endian = False
    ds.is_implicit_VR = False
    ds.PixelData = stored.astype(dtype).tobytes()  # every value most significant byte first
    ds["PixelData"].VR = "OW"


def big_endian(out, dose, ct_head):
    # The RT Dose (32-bit, 15 frames), its first frame alone, and a 16-bit CT slice in Explicit
    # VR Big Endian. pydicom reading them back must give the little-endian values.
    ds = pydicom.dcmread(dose)
    stored = ds.pixel_array.astype(np.uint32)
    scaling = float(ds.DoseGridScaling)
    to_big_endian(ds, stored, ">u4")
    ds.save_as(out / "dose_big_endian.dcm", write_like_original=False)
    expect(out, "dose_big_endian", stored * scaling)
    ds.NumberOfFrames = 1
    ds.GridFrameOffsetVector = [0.0]
    to_big_endian(ds, stored[0], ">u4")
    ds.save_as(out / "dose_one_frame_big_endian.dcm", write_like_original=False)
    expect(out, "dose_one_frame_big_endian", stored[0] * scaling)
    ds = pydicom.dcmread(ct_head)
    head = ds.pixel_array
    to_big_endian(ds, head, ">i2")
    ds.save_as(out / "head_big_endian.dcm", write_like_original=False)
    expect(out, "head_big_endian", head * float(ds.RescaleSlope) + float(ds.RescaleIntercept))
    for name in ("dose_big_endian", "dose_one_frame_big_endian", "head_big_endian"):
        check = pydicom.dcmread(out / f"{name}.dcm")
        assert not check.is_little_endian, name
        values = check.pixel_array * float(check.get("DoseGridScaling", 1))
        if "RescaleSlope" in check:
            values = values * float(check.RescaleSlope) + float(check.RescaleIntercept)
        assert np.array_equal(values.ravel(), np.fromfile(out / f"{name}.f64")), name


def signed_images(out, ct_head):
    # Signed pixels with BitsStored 12 and 15 (negative values). Uncompressed: 16-bit two's
    # complement. JPEG-LS has no signed samples: DICOM stores the low BitsStored bits of the two's
    # complement value as unsigned samples, so the codestreams here are GDCM's lossless encoding
    # of those bit patterns (PixelRepresentation 0), then marked PixelRepresentation 1. The JPEG
    # 2000 codestream built the same way says "unsigned" where the header says signed: DICOM's
    # PixelRepresentation decides. All must hold the uncompressed file's values.
    for bits in (12, 15):
        ds = pydicom.dcmread(ct_head)
        head = ds.pixel_array.astype(np.int32)
        values = head - 1000 if bits == 12 else head * 8 - 8000
        assert values.min() >= -(1 << (bits - 1)) and values.max() < (1 << (bits - 1))
        assert values.min() < 0
        explicit_little(ds)
        ds.BitsStored = bits
        ds.HighBit = bits - 1
        for tag in ("RescaleSlope", "RescaleIntercept"):
            if tag in ds:
                delattr(ds, tag)
        ds.PixelRepresentation = 1
        ds.PixelData = values.astype("<i2").tobytes()
        raw = out / f"signed{bits}_raw.dcm"
        ds.save_as(raw, write_like_original=False)
        assert np.array_equal(pydicom.dcmread(raw).pixel_array, values)
        ds.PixelRepresentation = 0
        ds.PixelData = (values & ((1 << bits) - 1)).astype("<u2").tobytes()
        pattern = out / f"signed{bits}_pattern.dcm"
        ds.save_as(pattern, write_like_original=False)
        for codec in ("jpegls", "j2k"):
            name = out / f"signed{bits}_{codec}.dcm"
            gdcmconv([f"--{codec}"], pattern, name)
            signed = pydicom.dcmread(name)
            signed.PixelRepresentation = 1
            signed.save_as(name)
        pattern.unlink()
        for codec in ("raw", "jpegls", "j2k"):
            expect(out, f"signed{bits}_{codec}", values)


def deflated(out, ct_head, dose):
    # Deflated Explicit VR Little Endian (1.2.840.10008.1.2.1.99): one slice and the RT Dose.
    gdcmconv(["--deflated"], ct_head, out / "head_deflated.dcm")
    ds = pydicom.dcmread(ct_head)
    expect(out, "head_deflated",
           ds.pixel_array * float(ds.RescaleSlope) + float(ds.RescaleIntercept))
    gdcmconv(["--deflated"], dose, out / "dose_deflated.dcm")
    ds = pydicom.dcmread(dose)
    expect(out, "dose_deflated", ds.pixel_array * float(ds.DoseGridScaling))
    for name in ("head_deflated", "dose_deflated"):
        check = pydicom.dcmread(out / f"{name}.dcm")
        assert check.file_meta.TransferSyntaxUID == "1.2.840.10008.1.2.1.99", name


def single_frame_dose(out, dose):
    # An RT Dose of one frame without NumberOfFrames (the Multi-frame Module is conditional).
    ds = pydicom.dcmread(dose)
    stored = ds.pixel_array[0].astype(np.uint32)
    explicit_little(ds)
    del ds.NumberOfFrames
    ds.GridFrameOffsetVector = [0.0]
    ds.PixelData = stored.astype("<u4").tobytes()
    ds.save_as(out / "dose_one_frame.dcm", write_like_original=False)
    expect(out, "dose_one_frame", stored * float(ds.DoseGridScaling))


def one_bit_segmentation(out, ct_head):
    ds = pydicom.dcmread(ct_head)
    mask = ds.pixel_array > 500
    explicit_little(ds)
    ds.SOPClassUID = "1.2.840.10008.5.1.4.1.1.66.4"  # Segmentation Storage
    ds.Modality = "SEG"
    ds.BitsAllocated = ds.BitsStored = 1
    ds.HighBit = 0
    ds.PixelRepresentation = 0
    for tag in ("RescaleSlope", "RescaleIntercept"):
        if tag in ds:
            delattr(ds, tag)
    ds.PixelData = np.packbits(mask.ravel(), bitorder="little").tobytes()
    ds["PixelData"].VR = "OB"
    ds.save_as(out / "seg_1bit.dcm", write_like_original=False)


def high_throughput_j2k(out):
    # HTJ2K: the JPEG 2000 file's fragments under the HTJ2K Lossless syntax UID.
    # pydicom 2.3 predates HTJ2K: tell it the UID is an (encapsulated) transfer syntax.
    pydicom._uid_dict.UID_dictionary.setdefault(
        HTJ2K_LOSSLESS, ("HTJ2K Lossless", "Transfer Syntax", "", "", "HTJ2KLossless"))
    ds = pydicom.dcmread(out / "signed12_j2k.dcm")
    ds.file_meta.TransferSyntaxUID = HTJ2K_LOSSLESS
    ds.save_as(out / "htj2k.dcm", write_like_original=False)


def rgb_jpeg(out, ct_head):
    ds = pydicom.dcmread(ct_head)
    gray = (ds.pixel_array.astype(np.int32) * 255 // 1951).astype(np.uint8)
    explicit_little(ds)
    ds.SamplesPerPixel = 3
    ds.PhotometricInterpretation = "RGB"
    ds.PlanarConfiguration = 0
    ds.BitsAllocated = ds.BitsStored = 8
    ds.HighBit = 7
    ds.PixelRepresentation = 0
    for tag in ("RescaleSlope", "RescaleIntercept"):
        if tag in ds:
            delattr(ds, tag)
    ds.PixelData = np.stack([gray, 255 - gray, gray // 2], axis=-1).tobytes()
    ds["PixelData"].VR = "OB"
    raw = out / "rgb_raw.dcm"
    ds.save_as(raw, write_like_original=False)
    gdcmconv(["--jpeg"], raw, out / "rgb_jpeg.dcm")
    raw.unlink()
    # The same small JPEG whose frame header (SOF3) and DICOM header say 12000 x 12000: GDCM
    # would allocate 432 MB and decode before the refusal, so it must be refused from the header.
    big = pydicom.dcmread(out / "rgb_jpeg.dcm")
    assert big.file_meta.TransferSyntaxUID == JPEG_LOSSLESS
    data = bytearray(big.PixelData)
    sof = data.find(b"\xff\xc3")  # marker, length (2), precision (1), lines (2), samples (2)
    assert sof > 0
    data[sof + 5:sof + 9] = (12000).to_bytes(2, "big") * 2
    big.PixelData = bytes(data)
    big.Rows = big.Columns = 12000
    big.save_as(out / "rgb_jpeg_large.dcm", write_like_original=False)


def modality_lut(out, ct_head):
    # A Modality LUT Sequence instead of RescaleSlope/Intercept.
    ds = pydicom.dcmread(ct_head)
    explicit_little(ds)
    for tag in ("RescaleSlope", "RescaleIntercept"):
        if tag in ds:
            delattr(ds, tag)
    item = pydicom.Dataset()
    item.LUTDescriptor = [2048, 0, 16]
    item.ModalityLUTType = "HU"
    item.add_new("LUTData", "OW", ((np.arange(2048) * 3) % 4096).astype("<u2").tobytes())
    ds.ModalityLUTSequence = [item]
    ds.save_as(out / "modality_lut.dcm", write_like_original=False)
    expect(out, "modality_lut", ds.pixel_array)  # the stored values: the LUT is not applied


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: make_dicom_cases.py OUT_DIR DATA_DIR")
    if shutil.which("gdcmconv") is None:
        sys.exit("gdcmconv not found (Debian package libgdcm-tools)")
    out, data = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
    out.mkdir(parents=True, exist_ok=True)
    ct_head = data / "ct/slicer_CTHeadAxialDicom/CTHead1.dcm"
    dose = data / "dicom_multiframe/pydicom_rtdose.dcm"
    big_endian(out, dose, ct_head)
    signed_images(out, ct_head)
    deflated(out, ct_head, dose)
    single_frame_dose(out, dose)
    one_bit_segmentation(out, ct_head)
    high_throughput_j2k(out)
    rgb_jpeg(out, ct_head)
    modality_lut(out, ct_head)


if __name__ == "__main__":
    main()
