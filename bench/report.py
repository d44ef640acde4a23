#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""One command for speed against error: runs the bench scripts of this folder on the real data
(rendering beside ParaView, ParaView matched on six CT volumes and an occupancy sweep, shadow
rays, conversion, Kriging beside gstat, voxelization beside the Embree exact tracer, packed
files beside zstd and OpenVDB), plots each with matplotlib and writes OUT/report.md and
OUT/report/*.png (docs/report.md describes the sections). Each plot's caption names the CPU,
its cores, the load, the commit and the date; the hand tables of docs/ that a section
reproduces are printed beside its own numbers.

usage: report.py VOXLINK UPSAMPLE VDB_PEER SHADOW_BENCH DATA_DIR [--quick] [--out DIR]
                 [--work DIR]

--quick: small inputs (about 2 minutes on 2 cores; the ctest `report_quick`); without it the
full preset of docs/report.md (about 15 minutes on 2 cores). A missing peer (gstat,
OpenVDB, zstd, Embree) or plotting library stops the report before it measures anything, with
one line naming it. Outputs appear only when every section succeeded.
"""
import argparse
import datetime
import json
import os
import shutil
import subprocess
import sys
import tempfile

import report_docs
import report_sections

HERE = os.path.dirname(os.path.abspath(__file__))


def peers_missing(voxlink, vdb_peer, shadow_bench):
    """One line per peer or tool the report cannot run without."""
    missing = []

    def works(cmd):
        try:
            return subprocess.run(cmd, capture_output=True).returncode == 0
        except OSError:
            return False

    rscript = os.environ.get("VOXLINK_RSCRIPT", "Rscript")
    if not works([rscript, "-e", "suppressPackageStartupMessages(library(gstat))"]):
        missing.append(f"gstat: `{rscript} -e 'library(gstat)'` failed (Debian: r-cran-gstat)")
    if not works(["/usr/bin/python3", "-c", "import pyopenvdb"]):
        missing.append("OpenVDB: /usr/bin/python3 cannot import pyopenvdb (python3-openvdb)")
    if not os.access(vdb_peer, os.X_OK):
        missing.append(f"OpenVDB: {vdb_peer} is not built (target voxlink_bench_vdb_peer)")
    if not os.access(shadow_bench, os.X_OK):
        missing.append(f"shadow bench: {shadow_bench} is not built "
                       "(target voxlink_bench_shadow_rays)")
    if not shutil.which("pvpython") or not shutil.which("xvfb-run"):
        missing.append("ParaView: pvpython or xvfb-run not on PATH (Debian: paraview, xvfb)")
    if not shutil.which("zstd"):
        missing.append("zstd: not on PATH (Debian: zstd)")
    if not works([voxlink, "render-exact", "--help"]):
        missing.append(f"Embree: `{voxlink} render-exact` is missing (build with the viewer)")
    if not works(["/usr/bin/python3", "-c", "import matplotlib"]):
        missing.append("matplotlib: /usr/bin/python3 cannot import it (python3-matplotlib)")
    return missing


def machine():
    cpu = "unknown CPU"
    with open("/proc/cpuinfo") as f:
        for line in f:
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    with open("/proc/loadavg") as f:
        load = " ".join(f.read().split()[:3])
    git = ["git", "-C", os.path.dirname(HERE)]
    commit = subprocess.run(git + ["rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True).stdout.strip() or "unknown"
    dirty = subprocess.run(git + ["status", "--porcelain", "--untracked-files=no"],
                           capture_output=True, text=True).stdout.strip()
    return {"cpu": cpu, "cores": os.cpu_count(), "load": load,
            "commit": commit + ("+changes" if dirty else ""),
            "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")}


def caption(m):
    return (f"{m['cpu']}, {m['cores']} cores, load {m['load']} at start / {m['load_end']} at "
            f"end; commit {m['commit']}; {m['date']}")


def is_time(quantity):
    return quantity.endswith(" s") or quantity.endswith(" ms")


def agreement(quantity, docs, ours):
    """Sizes and errors should be equal (same inputs); times are shown as this run / docs."""
    if is_time(quantity):
        d, o = report_docs.number(docs), report_docs.number(ours)
        return f"{o / d:.2f}x" if d and o is not None else "-"
    return "equal" if report_docs.numbers(docs) == report_docs.numbers(ours) else "**differs**"


def comparison_table(rows):
    if not rows:
        return "No row of the hand table matches this preset's inputs.\n"
    values = [r for r in rows if not is_time(r[1])]
    equal = sum(agreement(*r[1:4]) == "equal" for r in values)
    out = [f"{equal} of {len(values)} sizes and errors equal the docs'; times: this run / docs "
           "(the load differs).", "",
           "| hand table row | quantity | docs | this run | agreement |", "|---|---|---:|---:|---|"]
    out += [f"| {r[0]} | {r[1]} | {r[2]} | {r[3]} | {agreement(*r[1:4])} |" for r in rows]
    return "\n".join(out) + "\n"


def write_markdown(path, m, preset, sections):
    cap = caption(m)
    lines = [
        "# Speed against error: the report",
        "",
        f"Written by `bench/report.py` ({preset} preset) on {m['date']}, commit {m['commit']}: "
        f"{m['cpu']}, {m['cores']} cores, GL on Mesa llvmpipe (headless EGL), no GPU. "
        f"Load average (1, 5, 15 min) {m['load']} at the start, {m['load_end']} at the end: "
        "the machine was shared, so absolute times drift (up to 40 %); each peer was "
        "measured in the same run as voxlink, and the ratios are the numbers to read.",
        "",
        "Regenerate: `cmake --build build --target report` (this page and docs/report/*.png; "
        "`--target report-quick` writes the small preset to build/report-quick instead). "
        "The first rendering section measures ParaView (pvpython) and the project's dense "
        "3D-texture ray caster beside voxlink across step sizes; the second runs ParaView at "
        "fully matched settings on six CT volumes and an occupancy sweep "
        "(`bench/render_vs_paraview.sh`, docs/rendering-benchmark.md, \"Against ParaView\").",
        "",
    ]
    for s in sections:
        lines += [f"## {s['title']}", "", s["text"], "",
                  f"![{s['title']}](report/{s['png']})", "", f"*{cap}*", "",
                  s["table"], "", "Beside the hand table of " + s["doc"] + ":", "",
                  comparison_table(s["hand"]), "Commands:", ""]
        lines += [f"    {c}" for c in s["commands"]] + [""]
    with open(path, "w") as f:
        f.write("\n".join(lines))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("voxlink")
    ap.add_argument("upsample")
    ap.add_argument("vdb_peer")
    ap.add_argument("shadow_bench")
    ap.add_argument("data")
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--out", default=os.path.join(os.path.dirname(HERE), "docs"))
    ap.add_argument("--work", help="work files (default: a temporary folder)")
    a = ap.parse_args()
    missing = peers_missing(a.voxlink, a.vdb_peer, a.shadow_bench)
    if missing:
        sys.exit("report: peer missing, nothing measured: " + "; ".join(missing))
    m = machine()
    work = a.work or tempfile.mkdtemp(prefix="voxlink-report-")
    os.makedirs(work, exist_ok=True)
    tools = report_sections.Tools(a.voxlink, a.upsample, a.vdb_peer, a.shadow_bench,
                                  os.path.abspath(a.data), work, a.quick)
    docs = os.path.join(os.path.dirname(HERE), "docs")
    measured = [fn(tools, docs) for fn in report_sections.SECTIONS]
    with open("/proc/loadavg") as f:
        m["load_end"] = " ".join(f.read().split()[:3])
    import report_plots  # only now: a missing matplotlib is reported above, as a peer
    # Everything is drawn into a staging folder first: a failure leaves the old report whole.
    os.makedirs(a.out, exist_ok=True)
    staging = tempfile.mkdtemp(prefix="report-", dir=a.out)
    os.chmod(staging, 0o755)
    try:
        counts = {}
        for s in measured:
            fig = s["plot"](caption(m))
            counts[s["png"]] = report_plots.points(fig)
            if counts[s["png"]] == 0:
                sys.exit(f"report: the plot {s['png']} has no data points")
            fig.savefig(os.path.join(staging, s["png"]), dpi=100)
        with open(os.path.join(staging, "points.json"), "w") as f:
            json.dump(counts, f, indent=1)
        write_markdown(os.path.join(staging, "report.md"), m,
                       "quick" if a.quick else "full", measured)
        final = os.path.join(a.out, "report")
        if os.path.isdir(final):
            shutil.rmtree(final)
        os.rename(os.path.join(staging, "report.md"), os.path.join(a.out, "report.md"))
        os.rename(staging, final)
    finally:
        if os.path.isdir(staging):
            shutil.rmtree(staging)
    print(f"wrote {os.path.join(a.out, 'report.md')} and {len(counts)} plots in "
          f"{os.path.join(a.out, 'report')}")


if __name__ == "__main__":
    main()
