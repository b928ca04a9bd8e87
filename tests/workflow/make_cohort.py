#!/usr/bin/env python3
"""The test cohort from the shipped data, as a folder of scans and as a CSV sheet of the same scans.

    make_cohort.py TESTDATA OUT   writes OUT/scans/ (the folder) and OUT/cohort.csv (the sheet)

  ct            the abdomen-pelvis CT with its TotalSegmentator v1 labels (ct.organs.nii.gz, .tsv)
  ct-cropflip   the same CT, slices 20 to 99 only, stored flipped left-right: another voxel order and
                field of view of the same body (the affine says where each voxel is, so the body is not
                mirrored)
  dicom-ct      the 20-file JPEG 2000 DICOM series (a folder)
  mr-abdomen    the abdominal MRI of another subject with its TotalSegmentator MR labels
  broken        a NIfTI file cut short (testdata/bad/scan_truncated.nii.gz)

The crop and flip are done here on the NIfTI-1 file itself (header fields, voxel bytes), stdlib only.
"""
import array
import gzip
import os
import shutil
import struct
import sys

CROP = (20, 100)  # slices kept, [first, last)


def crop_flip_nifti(src: str, dst: str, first: int, last: int) -> None:
    with gzip.open(src, "rb") as f:
        data = f.read()
    if struct.unpack_from("<i", data, 0)[0] != 348:
        raise SystemExit(f"{src}: not a little-endian NIfTI-1 file")
    dim = list(struct.unpack_from("<8h", data, 40))
    bitpix = struct.unpack_from("<h", data, 72)[0]
    vox_offset = int(struct.unpack_from("<f", data, 108)[0])
    sform_code = struct.unpack_from("<h", data, 254)[0]
    if dim[0] != 3 or sform_code <= 0:
        raise SystemExit(f"{src}: expected a 3-D image with an sform")
    nx, ny, nz = dim[1:4]
    if not 0 <= first < last <= nz:
        raise SystemExit(f"{src}: slices {first}..{last} outside 0..{nz}")
    rows = [list(struct.unpack_from("<4f", data, 280 + 16 * r)) for r in range(3)]
    bpv = bitpix // 8
    typecode = {1: "B", 2: "H", 4: "I", 8: "Q"}[bpv]
    slice_bytes = nx * ny * bpv
    body = data[vox_offset + first * slice_bytes: vox_offset + last * slice_bytes]
    voxels = array.array(typecode)
    voxels.frombytes(body)
    flipped = array.array(typecode)
    for start in range(0, len(voxels), nx):  # each row along i reversed
        row = voxels[start: start + nx]
        row.reverse()
        flipped.extend(row)
    header = bytearray(data[:vox_offset])
    dim[3] = last - first
    struct.pack_into("<8h", header, 40, *dim)
    for r in range(3):
        a, b, c, t = rows[r]
        # world = A (i, j, k) + t; the voxel i' = nx-1-i of slice k' = k-first is that world point
        t = t + a * (nx - 1) + c * first
        struct.pack_into("<4f", header, 280 + 16 * r, -a, b, c, t)
    struct.pack_into("<h", header, 252, 0)  # qform_code 0: the sform alone places the voxels
    with gzip.open(dst, "wb") as f:
        f.write(bytes(header))
        f.write(flipped.tobytes())


def main(argv) -> int:
    if len(argv) != 3:
        print(__doc__.strip().splitlines()[2].strip(), file=sys.stderr)
        return 2
    testdata, out = (os.path.abspath(a) for a in argv[1:])
    scans = os.path.join(out, "scans")
    if os.path.exists(scans):
        shutil.rmtree(scans)
    os.makedirs(scans)
    ct = os.path.join(testdata, "ct-abdomen-pelvis")
    links = {
        "ct.nii.gz": os.path.join(ct, "example_ct.nii.gz"),
        "ct.organs.nii.gz": os.path.join(ct, "example_seg_total_v1_for_example_ct.nii.gz"),
        "ct.organs.tsv": os.path.join(ct, "labels_total_v1.tsv"),
        "dicom-ct": os.path.join(testdata, "dicom", "ct-series-jpeg2000"),
        "mr-abdomen.nii.gz": os.path.join(testdata, "mr-abdomen", "example_mr_sm.nii.gz"),
        "mr-abdomen.organs.nii.gz": os.path.join(testdata, "mr-abdomen", "example_seg_mr.nii.gz"),
        "mr-abdomen.organs.tsv": os.path.join(testdata, "mr-abdomen", "labels_total_mr.tsv"),
    }
    for name, target in links.items():
        if not os.path.exists(target):
            raise SystemExit(f"{target}: missing from the test data")
        os.symlink(target, os.path.join(scans, name))
    shutil.copyfile(os.path.join(testdata, "bad", "scan_truncated.nii.gz"), os.path.join(scans, "broken.nii.gz"))
    crop_flip_nifti(links["ct.nii.gz"], os.path.join(scans, "ct-cropflip.nii.gz"), *CROP)
    with open(os.path.join(out, "cohort.csv"), "w") as f:
        f.write("# the same scans as scans/, as a sheet\nscan,path,organs,organ_table\n")
        f.write("ct,scans/ct.nii.gz,scans/ct.organs.nii.gz,scans/ct.organs.tsv\n")
        f.write("mr-abdomen,scans/mr-abdomen.nii.gz,scans/mr-abdomen.organs.nii.gz,scans/mr-abdomen.organs.tsv\n")
        for name in ("ct-cropflip,scans/ct-cropflip.nii.gz", "dicom-ct,scans/dicom-ct", "broken,scans/broken.nii.gz"):
            f.write(name + ",,\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
