# SPDX-License-Identifier: BSD-3-Clause
"""The sections of bench/report.py. Each runs one of this folder's bench scripts with the
preset's sizes (the scripts do the measuring; this only picks inputs and reads their --json or
Markdown output), and returns what the report needs: its text, a table of its own numbers, the
plot (a function of the caption), the docs' hand-table rows it reproduces, and the commands."""
import json
import os
import re
import subprocess
import sys

import report_docs
import report_plots

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PY = "/usr/bin/python3"  # Debian's: numpy, matplotlib and pyopenvdb are its packages


class Tools:
    def __init__(self, voxlink, upsample, vdb_peer, shadow_bench, data, work, quick):
        self.voxlink, self.upsample, self.vdb_peer = voxlink, upsample, vdb_peer
        self.shadow_bench = shadow_bench
        self.data, self.work, self.quick = data, work, quick
        self.env = dict(os.environ, VOXLINK_BENCH_DIR=work)

    def run(self, cmd, env=None):
        """Runs a bench script; its stdout. Stops the report with the script's output if it
        fails (a half-measured report is never written)."""
        p = subprocess.run(cmd, capture_output=True, text=True, env=dict(self.env, **(env or {})))
        if p.returncode != 0:
            sys.exit(f"report: failed: {' '.join(cmd)}\n{p.stdout[-2000:]}{p.stderr[-2000:]}")
        return p.stdout


def command_line(cmd, env=None):
    """A bench command as the shell line the report prints: the environment it was run with
    first, values and arguments that hold spaces quoted."""
    assignments = [f"{k}={v!r}" if " " in v else f"{k}={v}" for k, v in (env or {}).items()]
    return " ".join(assignments + [f"'{c}'" if " " in c else c for c in cmd])


def script(name):
    return os.path.join(os.path.dirname(os.path.abspath(__file__)), name)


def markdown_rows(text):
    """The rows of the first Markdown table in `text`, as dicts."""
    lines = [l for l in text.splitlines() if l.startswith("|")]
    header = [c.strip() for c in lines[0].strip("|").split("|")]
    return [dict(zip(header, (c.strip() for c in l.strip("|").split("|")))) for l in lines[2:]]


def table(header, rows):
    out = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    out += ["| " + " | ".join(str(c) for c in r) + " |" for r in rows]
    return "\n".join(out)


TF_OF = {"foot": "foot-bone.tf.json", "tooth": "tooth.tf.json", "lidc": "lidc-bone.tf.json"}


def paraview_frames(t, vxl, dataset, size, frames, steps, commands):
    """ParaView's mean frame (ms) per trilinear step, on `voxlink export` of the same file (the
    kept values) with the same TF, camera orbit, shading and sample distance
    (bench/paraview_render_bench.py in pvpython, under its own Xvfb)."""
    nrrd = os.path.splitext(vxl)[0] + ".nrrd"
    export = [t.voxlink, "export", vxl, "-o", nrrd, "-q"]
    t.run(export)
    commands.append(" ".join(export))
    times = {}
    for step in steps:
        cmd = ["xvfb-run", "-a", "-s", "-screen 0 1280x1024x24", "pvpython", "--no-mpi",
               script("paraview_render_bench.py"), nrrd,
               os.path.join(REPO, "bench", "tf", TF_OF[dataset]), "--size", size,
               "--frames-per-turn", frames, "--step", str(step)]
        m = re.search(r"mean ([\d.]+)", t.run(cmd))
        if not m:
            sys.exit(f"report: no frame time from {' '.join(cmd)}")
        times[step] = float(m.group(1))
        commands.append(command_line(cmd))
    return times


def render(t, docs):
    dataset, size, frames, steps = (("tooth", "128x128", "4", [0.5, 1.0, 2.0]) if t.quick else
                                    ("foot", "512x512", "4", [0.25, 0.5, 1.0, 2.0]))
    runs = [("voxel", 0.5)] + [("trilinear", s) for s in steps]
    rows, commands = [], []
    for sampling, step in runs:
        out = os.path.join(t.work, f"render-{sampling}-{step:g}")
        env = {"DATASETS": dataset, "SAMPLINGS": sampling, "STEP": str(step)}
        cmd = ["bash", script("render_bench.sh"), t.voxlink, t.data, out, frames, size]
        t.run(cmd, env)
        commands.append(command_line(cmd, env))
        with open(os.path.join(out, dataset + ".md")) as f:
            for r in markdown_rows(f.read()):
                rows.append({"renderer": r["renderer"], "sampling": r["sampling"],
                             "step": step, "ms": float(r["mean ms"]),
                             "psnr": float(r["PSNR dB"]), "gpu": r["GPU MiB"],
                             "speedup": r["speed-up"]})
    vxl = os.path.join(t.work, "render-voxel-0.5", dataset + ".vxl")
    paraview = paraview_frames(t, vxl, dataset, size, frames, steps, commands)
    for step, ms in paraview.items():
        ours = next(r for r in rows if r["renderer"] == "voxlink" and
                    r["sampling"] == "trilinear" and r["step"] == step)
        rows.append({"renderer": "paraview", "sampling": "trilinear", "step": step, "ms": ms,
                     "psnr": None, "gpu": "-",
                     "speedup": f"voxlink {ms / ours['ms']:.1f}x faster" if ms >= ours["ms"]
                     else f"ParaView {ours['ms'] / ms:.1f}x faster"})
    hand = []
    doc_rows = report_docs.first_table_after(os.path.join(docs, "rendering-benchmark.md"),
                                             rf"^{dataset.capitalize()}:")
    for r in (r for r in rows if r["step"] == 0.5 and r["renderer"] != "paraview"):
        d = next((d for d in doc_rows if d.get("renderer") == r["renderer"] and
                  d.get("sampling") == r["sampling"] and d.get("size") == size), None)
        if d:
            key = f"{dataset} {r['renderer']} {r['sampling']} {size} step 0.5"
            hand += [(key, "mean ms", d["mean ms"], f"{r['ms']:.1f}"),
                     (key, "PSNR dB", d["PSNR dB"], f"{r['psnr']:.2f}")]
    return {
        "title": "Render time vs image error", "png": "render.png",
        "text": f"`voxlink bench-render` through `bench/render_bench.sh` on the {dataset} CT "
                f"({size}, {frames} frames per turn, the paper's two turns, shading on): the "
                "VoxLink ray tracer and the dense 3D-texture ray caster interleaved frame by "
                "frame, voxel sampling and trilinear sampling at each step (voxels), PSNR of the "
                "first view against the float64 reference. ParaView 5.11 (the peer: "
                "`bench/paraview_render_bench.py` in pvpython, VTK's GPU ray caster on the same "
                "llvmpipe) renders the exported kept values at each step with the same TF, "
                "orbit and shading, just after: its times are the dotted lines (no PSNR: its "
                "colours differ from the model's, and its rays stop at opacity 1 - 1/255 where "
                "voxlink's default here is 0.99; the matched comparison is "
                "docs/rendering-benchmark.md, \"Against ParaView\"). The hand table below "
                "used 6 frames per turn.",
        "plot": lambda cap: report_plots.render(rows, cap),
        "table": table(["renderer", "sampling", "step", "mean ms", "PSNR dB", "GPU MiB",
                        "speed-up (same frames)"],
                       [(r["renderer"], r["sampling"], "-" if r["sampling"] == "voxel" else
                         f"{r['step']:g}", f"{r['ms']:.1f}",
                         "-" if r["psnr"] is None else f"{r['psnr']:.2f}", r["gpu"],
                         r["speedup"]) for r in rows]),
        "doc": "docs/rendering-benchmark.md", "hand": hand, "commands": commands}


def paraview_summary(t, out, env, size, frames):
    """Runs bench/render_vs_paraview.sh (with `env`: DATASETS or OCCUPANCY) into `out`; its
    summary rows, each with the kept percentage read from its "voxels kept" cell; the command."""
    cmd = ["bash", script("render_vs_paraview.sh"), t.voxlink, t.data, out, frames, size]
    t.run(cmd, env)
    with open(os.path.join(out, "summary.md")) as f:
        rows = markdown_rows(f.read())
    if not rows:
        sys.exit(f"report: {' '.join(cmd)} measured no data set (is {t.data}/ct there?)")
    for r in rows:
        m = re.search(r"([\d.]+) %", r["voxels kept"])
        if not m:
            sys.exit(f"report: no kept share in {r['data']}'s row of {out}/summary.md")
        r["kept %"] = float(m.group(1))
    return rows, command_line(cmd, env)


def against_paraview(t, docs):
    """ParaView at fully matched settings (sample distance, termination, shading, orbit) on the
    CT volumes, and the occupancy sweep: the two hand tables of rendering-benchmark.md's
    "Against ParaView" regenerated in one run."""
    if t.quick:
        datasets, size, occupancy_size, frames = "tooth", "128x128", "128x128", "1"
    else:
        datasets, size, occupancy_size, frames = ("foot lidc tooth engine carp beetle",
                                                  "1000x1000", "512x512", "2")
    volumes, volume_cmd = paraview_summary(t, os.path.join(t.work, "paraview-volumes"),
                                           {"DATASETS": datasets}, size, frames)
    sweep, sweep_cmd = paraview_summary(t, os.path.join(t.work, "paraview-occupancy"),
                                        {"OCCUPANCY": "1", "BENCH_FLAGS": "--no-reference"},
                                        occupancy_size, frames)
    page = os.path.join(docs, "rendering-benchmark.md")
    hand = []
    for rows, heading, hand_size in ((volumes, r"^### Six CT volumes, sample distance matched",
                                      "1000x1000"),
                                     (sweep, r"^### Frame time against occupancy", "512x512")):
        doc_rows = report_docs.first_table_after(page, heading)
        # Sizes hold at any frame size; times and PSNR only at the hand table's.
        quantities = ["voxels kept", "file MB", "GPU MiB"]
        if (size if rows is volumes else occupancy_size) == hand_size:
            quantities += ["PSNR voxel / trilinear dB", "voxlink voxel ms",
                           "voxlink trilinear ms", "ParaView ms"]
        for r in rows:
            d = next((d for d in doc_rows if d.get("data") == r["data"]), None)
            if d:
                hand += [(r["data"], q, d[q], r[q]) for q in quantities]
    columns = ["data", "voxels kept", "file MB", "GPU MiB", "voxlink voxel ms",
               "voxlink trilinear ms", "ParaView ms", "voxel speed-up", "trilinear speed-up",
               "PSNR voxel / trilinear dB"]
    return {
        "title": "Against ParaView at matched settings, and frame time against occupancy",
        "png": "paraview.png",
        "text": f"`bench/render_vs_paraview.sh`: each CT volume converted with its TF "
                "(bench/tf/), exported dense with the same kept values, then `voxlink "
                "bench-render` and ParaView 5.11's GPU ray caster (pvpython, driven directly: "
                "sample distance 0.5 voxel of the smallest spacing, shading on, rays stopped "
                f"at opacity 1 - 1/255 in both, the paper's orbit) at {size}, {frames} "
                "frames per turn; PSNR against the float64 reference. Then the occupancy "
                "sweep: the tooth kept at four thresholds (about 1, 6, 20 and 48 % of its "
                f"voxels, a ramp TF over what each keeps) at {occupancy_size}, no PSNR. Issue "
                "29's goals: trilinear >= 10x and voxel >= 20x ParaView's frame rate, GPU "
                "memory <= 2x the file (MiB against MB here), PSNR >= 45 dB.",
        "plot": lambda cap: report_plots.against_paraview(volumes, sweep, (size, occupancy_size),
                                                          cap),
        "table": table(columns, [[r[c] for c in columns] for r in volumes + sweep]),
        "doc": "docs/rendering-benchmark.md (\"Six CT volumes\" and \"Frame time against "
               "occupancy\")", "hand": hand, "commands": [volume_cmd, sweep_cmd]}


def shadows(t, docs):
    datasets, size, per_turn = (("tooth", "128x128", "1") if t.quick else
                                ("foot tooth lidc", "512x512", "2"))
    out = os.path.join(t.work, "shadows")
    env = {"DATASETS": datasets}
    cmd = ["bash", script("shadow_rays_bench.sh"), t.voxlink, t.shadow_bench, t.data, out, size,
           per_turn]
    rows = [{"data": r["data"], "sampling": r["sampling"],
             "ms": {k: float(r[f"{k} ms"]) for k in ("none", "per-sample", "per-voxel", "still")},
             "psnr": {"none": float(r["none vs ref-S"]),
                      "per-sample": float(r["per-sample vs ref-S"]),
                      "per-voxel": float(r["per-voxel vs ref-S"]),
                      "still": float(r["per-voxel vs ref-S"])},
             "model": float(r["ref-V vs ref-S"]), "own": float(r["per-voxel vs ref-V"]),
             "mib": r["cache MiB"]}
            for r in markdown_rows(t.run(cmd, env))]
    if not rows:
        sys.exit(f"report: {' '.join(cmd)} measured no data set (is {t.data}/ct there?)")
    doc_rows = report_docs.first_table_after(os.path.join(docs, "shadows.md"),
                                             rf"^{size}, 2 views per turn")
    hand = []
    for r in rows:
        d = next((d for d in doc_rows if d.get("data") == r["data"] and
                  d.get("sampling") == r["sampling"]), None)
        if d:
            key = f"{r['data']} {r['sampling']} {size}"
            hand += [(key, "none ms", d["none ms"], f"{r['ms']['none']:.1f}"),
                     (key, "per-voxel ms", d["per-voxel ms"], f"{r['ms']['per-voxel']:.1f}"),
                     (key, "per-voxel vs ref-S dB", d["per-voxel vs ref-S"],
                      f"{r['psnr']['per-voxel']:.2f}"),
                     (key, "ref-V vs ref-S dB", d["ref-V vs ref-S"], f"{r['model']:.2f}")]
    return {
        "title": "Shadow rays: frame time vs error against exact shadow rays", "png": "shadows.png",
        "text": f"`bench/shadow_rays_bench.sh` ({size}, {per_turn} views per turn, the paper's two "
                "turns, median frame): the GL frame without shadows, with a shadow ray per sample "
                "(exact), with the per-voxel cache (a ray per visible voxel centre, its fill pass "
                "included), and the per-voxel frame again from the same view (the still frame: the "
                "cache reused), interleaved view by view in one process. Error: PSNR of the first "
                "view against the float64 reference with exact per-sample shadow rays (ref-S), so "
                "the frame without shadows shows what leaving them out costs and the per-voxel "
                "frames the per-voxel model's error (docs/shadows.md).",
        "plot": lambda cap: report_plots.shadows(rows, cap),
        "table": table(["data", "sampling", "none ms", "per-sample ms", "per-voxel ms",
                        "still ms", "per-voxel / none", "still / none",
                        "PSNR vs ref-S: none / per-sample / per-voxel dB",
                        "per-voxel vs its own model dB", "cache MiB"],
                       [(r["data"], r["sampling"], f"{r['ms']['none']:.1f}",
                         f"{r['ms']['per-sample']:.1f}", f"{r['ms']['per-voxel']:.1f}",
                         f"{r['ms']['still']:.1f}",
                         f"{r['ms']['per-voxel'] / r['ms']['none']:.2f}x",
                         f"{r['ms']['still'] / r['ms']['none']:.2f}x",
                         f"{r['psnr']['none']:.2f} / {r['psnr']['per-sample']:.2f} / "
                         f"{r['psnr']['per-voxel']:.2f}", f"{r['own']:.2f}", r["mib"])
                        for r in rows]),
        "doc": "docs/shadows.md (\"Speed against error\")", "hand": hand,
        "commands": [command_line(cmd, env)]}


def convert(t, docs):
    out = os.path.join(t.work, "convert.json")
    cmd = [PY, script("convert_bench.py"), t.voxlink, t.upsample, t.vdb_peer, t.data,
           "--json", out]
    cmd += ["--quick", "--grf", "64", "--cases",
            "foot256,tooth,LIDC2,carp,grf64,grf64-f16,grf64-e1e-3,grf64-e0.02"] if t.quick else []
    t.run(cmd)
    with open(out) as f:
        result = json.load(f)
    rows = result["rows"]
    doc_rows = report_docs.first_table_after(os.path.join(docs, "benchmarks.md"), r"^## Result")
    hand = []
    for r in rows:
        d = next((d for d in doc_rows if d.get("case") == r["name"]), None)
        if d:
            hand += [(r["name"], "B/voxel", d["B/voxel"], f"{r['bpv']:.3f}"),
                     (r["name"], "convert s", d["convert s (min)"], f"{r['sec']:.2f}"),
                     (r["name"], "gradient error mean/max deg", d["gradient error mean/max deg"],
                      f"{r['gmean']:.3f} / {r['gmax']:.3f}")]
    return {
        "title": "Conversion time and B/voxel vs value type, error bound and gradient error",
        "png": "convert.png",
        "text": f"`bench/convert_bench.py` (median of {result['repeats']} runs from the page "
                "cache): real CT files with a threshold, and a Gaussian random field (float64) "
                "kept outside [-1.96, 1.96] stored as f32, f16, and at error bounds 1e-3 and 0.02 "
                "(the converter picks the smallest type within the bound: column stored). The "
                "gradient errors are the converter's (angle between the exact central difference "
                "and its 16-bit code, every 64th voxel). The OpenVDB job (copyFromDense + Blosc "
                "write) runs on the same foot input in the same script; OpenVDB's B/voxel is "
                "`voxlink info`'s FloatGrid estimate.",
        "plot": lambda cap: report_plots.convert(rows, cap),
        "table": table(["case", "stored", "convert s", "B/voxel", "OpenVDB B/voxel",
                        "max abs value error", "gradient error mean / max deg", "OpenVDB job s",
                        "OpenVDB / voxlink"],
                       [(r["name"], r["stored"], f"{r['sec']:.2f}", f"{r['bpv']:.3f}",
                         f"{r['vdb_bpv']:.3f}", f"{r['verr']:.3g}",
                         f"{r['gmean']:.3f} / {r['gmax']:.3f}",
                         f"{r['peer_sec']:.2f}" if r["peer_sec"] else "-",
                         f"{r['peer_sec'] / r['sec']:.1f}x" if r["peer_sec"] else "-")
                        for r in rows]),
        "doc": "docs/benchmarks.md (\"Result\")", "hand": hand, "commands": result["commands"]}


def kriging(t, docs):
    out = os.path.join(t.work, "kriging.json")
    neighbours, runs = ("8,32", "1") if t.quick else ("4,8,16,24,32,64,0", "3")
    cmd = [PY, script("kriging_vs_gstat.py"), t.voxlink, t.data, "--neighbours", neighbours,
           "--runs", runs, "--gstat-runs", "1", "--json", out]
    t.run(cmd)
    with open(out) as f:
        rows = json.load(f)
    hand = []
    speed = report_docs.first_table_after(os.path.join(docs, "kriging.md"),
                                          r"^Speed beside gstat")
    for r in rows:
        k = str(r["neighbours"] or "all")
        d = next((d for d in speed if d.get("kriging") == "ordinary (same session)" and
                  d.get("neighbours") == k), None)
        if d:
            hand += [(f"ordinary, {k}", "gstat s", d["gstat s"], f"{r['gstat_s']:.3f}"),
                     (f"ordinary, {k}", "voxlink s", d["voxlink s"], f"{r['voxlink_s']:.3f}")]
    accuracy = report_docs.tables_after(os.path.join(docs, "kriging.md"), r"^Speed beside gstat")
    d = next((d for tab in accuracy for d in tab if d.get("drift (24 nearest unless said)") ==
              "none (ordinary)"), None)
    r24 = next((r for r in rows if r["neighbours"] == 24), None)
    if d and r24:
        hand.append(("none (ordinary), 24 nearest", "RMSE vs exhaustive V",
                     d["RMSE vs exhaustive V"], f"{r24['rmse']:.2f}"))
    return {
        "title": "Kriging time vs error per neighbourhood size, beside gstat",
        "png": "kriging.png",
        "text": "`bench/kriging_vs_gstat.py`: Walker Lake, 470 samples of V onto the 260 x 300 "
                "grid, spherical model, ordinary kriging with k nearest samples (gstat's nmax; "
                "all: global), R's gstat `krige()` timed alone in the same run. Error: RMSE "
                "against the exhaustive V at all 78,000 nodes; voxlink's time is its grid solve "
                f"(median of {runs}), gstat's one run.",
        "plot": lambda cap: report_plots.kriging(rows, cap),
        "table": table(["neighbours", "voxlink s", "gstat s", "gstat / voxlink", "RMSE voxlink",
                        "RMSE gstat", "max rel. pred diff vs gstat"],
                       [(r["neighbours"] or "all", f"{r['voxlink_s']:.3f}", f"{r['gstat_s']:.3f}",
                         f"{r['gstat_s'] / r['voxlink_s']:.1f}", f"{r['rmse']:.2f}",
                         f"{r['gstat_rmse']:.2f}", f"{r['max_rel_pred']:.2e}") for r in rows]),
        "doc": "docs/kriging.md", "hand": hand, "commands": [" ".join(cmd)]}


def surface_modes(voxlink):
    """The surface modes `scene build --help` offers (an option named --surface... with a
    choice list); [None] (the one built-in mode) when it has none."""
    text = subprocess.run([voxlink, "scene", "build", "--help"], capture_output=True,
                          text=True).stdout
    m = re.search(r"--surface[\w-]*\s+\S*\{([^}]*)\}", text)
    return [c.strip() for c in m.group(1).split(",")] if m else [None]


def voxelization(t, docs):
    scenes, resolutions, size = (("bunny", "64,128", "128x128") if t.quick else
                                 ("bunny,dragon", "128,256,512,1024", "256x256"))
    runs, commands = {}, []
    for mode in surface_modes(t.voxlink):
        out = os.path.join(t.work, f"voxelization-{mode or 'default'}.json")
        cmd = [PY, script("voxelization_cost.py"), t.voxlink,
               os.path.join(REPO, "samples", "scenes"), t.data,
               "--scenes", scenes, "--resolutions", resolutions, "--size", size, "--json", out]
        cmd += ["--quick"] if t.quick else []
        cmd += ["--surface", mode] if mode else []
        t.run(cmd)
        with open(out) as f:
            runs[mode or "surface (the one mode)"] = json.load(f)
        commands.append(" ".join(cmd))
    doc_rows = report_docs.first_table_after(os.path.join(docs, "exact-tracer.md"),
                                             r"^## What voxelization costs")
    hand = []
    for mode, run in runs.items():
        if mode not in ("mean", "surface (the one mode)"):
            continue  # the hand table holds mean-mode (version 2.0) files only
        for r in run["rows"]:
            d = next((d for d in doc_rows if d.get("scene") == r["scene"] and
                      d.get("voxels") == str(r["resolution"])), None)
            if d and size == "256x256":
                key = f"{r['scene']} {r['resolution']} ({mode})"
                hand += [(key, "plain PSNR dB", d[next(k for k in d if k.startswith("plain: PSNR"))]
                          .split(" / ")[0], r["plain"]["psnr"]),
                         (key, "file MB", d["file MB"], f"{r['mb']:.1f}")]
    return {
        "title": "Voxelization resolution and surface mode vs image error (Embree) and B/voxel",
        "png": "voxelization.png",
        "text": f"`bench/voxelization_cost.py`: `voxlink scene build` of each mesh at each "
                f"resolution, then `voxlink render-exact --compare` at {size}: the same float64 "
                "tracer over the voxel scene and over the original triangles (Embree 3), plain "
                "and with every effect. Surface modes: those `voxlink scene build --help` lists ("
                + ", ".join(runs) + ").",
        "plot": lambda cap: report_plots.voxelization(runs, cap),
        "table": table(["mode", "scene", "resolution", "build s", "file MB", "B/voxel",
                        "PSNR plain / effects dB", "first hit differs %",
                        "voxel s / Embree s (plain)"],
                       [(mode, r["scene"], r["resolution"], f"{r['build_s']:.2f}",
                         f"{r['mb']:.1f}", f"{r['bytes_per_voxel']:.2f}",
                         f"{r['plain']['psnr']} / {r['effects']['psnr']}",
                         r["plain"]["mismatch"],
                         f"{r['plain']['voxel']:.3f} / {r['plain']['exact']:.3f}")
                        for mode, run in runs.items() for r in run["rows"]]),
        "doc": "docs/exact-tracer.md (\"What voxelization costs\")", "hand": hand,
        "commands": commands}


def pack(t, docs):
    out = os.path.join(t.work, "pack.json")
    cmd = [PY, script("pack_bench.py"), t.voxlink, t.upsample, t.vdb_peer, t.data, "--cases",
           "foot256", "--repeats", "1" if t.quick else "3", "--json", out]
    t.run(cmd)
    with open(out) as f:
        result = json.load(f)
    rows = result["rows"]
    doc_rows = report_docs.first_table_after(os.path.join(docs, "benchmarks.md"),
                                             r"^foot256 \(the real 256")
    hand = []
    for r in rows:
        d = next((d for d in doc_rows if d.get("file") == r["file"]), None)
        if d:
            hand += [(f"foot256 {r['file']}", "B/voxel", d["B/voxel"],
                      f"{r['bytes_per_voxel']:.3f}"),
                     (f"foot256 {r['file']}", "load s", d["load s"], f"{r['load_s']:.2f}")]
            if r["make_s"] is not None:
                hand.append((f"foot256 {r['file']}", "make s", d["make s median (min)"],
                             f"{r['make_s']:.2f}"))
    return {
        "title": "Packed size vs pack and load time", "png": "pack.png",
        "text": f"`bench/pack_bench.py` on the foot (256^3, threshold 60; median of "
                f"{result['repeats']}): `voxlink pack` at its levels beside `zstd` of the .vxl "
                "and the OpenVDB file of the same voxels, all lossless, made in the same run. "
                "Load: `voxlink validate` (read, unpack, check), `zstd -d`, pyopenvdb.readAll.",
        "plot": lambda cap: report_plots.pack(rows, cap),
        "table": table(["file", "B/voxel", "make s", "load s"],
                       [(r["file"], f"{r['bytes_per_voxel']:.3f}",
                         "-" if r["make_s"] is None else f"{r['make_s']:.2f}",
                         f"{r['load_s']:.2f}") for r in rows]),
        "doc": "docs/benchmarks.md (\"Packed files\", foot256)", "hand": hand,
        "commands": result["commands"]}


SECTIONS = [render, against_paraview, shadows, convert, kriging, voxelization, pack]
