# SPDX-License-Identifier: BSD-3-Clause
"""ctest driver for bench/report.py (tests/report/CMakeLists.txt).

usage: check_report.py quick|peer-missing OUT_DIR VOXLINK UPSAMPLE VDB_PEER SHADOW_BENCH
                       DATA_DIR

quick: runs the quick preset into OUT_DIR and checks that report.md and every plot it links are
written, that each link is a PNG, and that each plot drew data points (report/points.json,
counted from the figures). peer-missing: runs it with an Rscript that does not exist and checks
that it fails with one line naming gstat and leaves no report behind. Exits 77 (skip) when the
real data is missing, unless VOXLINK_REQUIRE_DATA=1.
"""
import json
import os
import re
import shutil
import subprocess
import sys

REPORT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "bench",
                      "report.py")


def fail(message):
    sys.exit(f"check_report: {message}")


def main():
    mode, out, voxlink, upsample, vdb_peer, shadow_bench, data = sys.argv[1:8]
    if not os.path.isdir(os.path.join(data, "ct")):
        if os.environ.get("VOXLINK_REQUIRE_DATA") == "1":
            fail(f"real data missing with VOXLINK_REQUIRE_DATA=1: {data}")
        print(f"skipped: real data missing: {data}")
        sys.exit(77)
    shutil.rmtree(out, ignore_errors=True)
    cmd = ["/usr/bin/python3", REPORT, voxlink, upsample, vdb_peer, shadow_bench, data,
           "--out", out, "--work", os.path.join(out, "work"), "--quick"]
    env = dict(os.environ)
    if mode == "peer-missing":
        env["VOXLINK_RSCRIPT"] = os.path.join(out, "no-such-Rscript")
    p = subprocess.run(cmd, capture_output=True, text=True, env=env)
    print(p.stdout, p.stderr, sep="")
    if mode == "peer-missing":
        if p.returncode == 0:
            fail("the report succeeded without gstat")
        if not re.search(r"^report: peer missing.*gstat", p.stderr, re.M):
            fail("the failure does not name the missing gstat peer")
        if os.path.exists(os.path.join(out, "report.md")):
            fail("a report was written although a peer is missing")
        return
    if p.returncode != 0:
        fail(f"report.py exited {p.returncode}")
    md = os.path.join(out, "report.md")
    if not os.path.isfile(md):
        fail(f"{md} not written")
    with open(md) as f:
        text = f.read()
    pngs = re.findall(r"\]\(report/([\w-]+\.png)\)", text)
    if len(pngs) < 7:
        fail(f"report.md links {len(pngs)} plots, expected one per section (7)")
    with open(os.path.join(out, "report", "points.json")) as f:
        points = json.load(f)
    for png in pngs:
        path = os.path.join(out, "report", png)
        with open(path, "rb") as f:
            if f.read(8) != b"\x89PNG\r\n\x1a\n":
                fail(f"{path} is not a PNG")
        if points.get(png, 0) <= 0:
            fail(f"{png} has no data points")
    print(f"ok: report.md and {len(pngs)} plots ({points})")


if __name__ == "__main__":
    main()
