# SPDX-License-Identifier: BSD-3-Clause
"""The plots of bench/report.py: one function per section, each taking what the section
measured and returning a matplotlib figure. Each figure carries the run's caption (machine,
load, commit, date) at its foot, so a PNG shown alone still says where it came from."""
import matplotlib

matplotlib.use("Agg")  # headless: CI has no display
import matplotlib.pyplot as plt  # noqa: E402


def _figure(caption, panels=1):
    fig, axes = plt.subplots(1, panels, figsize=(6.4 * panels, 4.8), squeeze=False)
    fig.text(0.01, 0.01, caption, fontsize=7, color="0.35")
    fig.subplots_adjust(bottom=0.2, wspace=0.3)
    return fig, list(axes[0])


def points(fig):
    """Data points drawn in `fig` (line vertices and scatter offsets): the report's check that
    no plot came out empty."""
    n = 0
    for ax in fig.axes:
        # A horizontal reference line (axhline: x 0 to 1 in axes units) is not a data point.
        n += sum(len(line.get_xdata()) for line in ax.get_lines()
                 if line.get_transform() is not ax.get_yaxis_transform())
        n += sum(len(c.get_offsets()) for c in ax.collections)
    return n


def render(rows, caption):
    """rows: dicts with renderer, sampling, step, ms, psnr (one per bench-render row)."""
    fig, (ax,) = _figure(caption)
    styles = {("voxlink", "trilinear"): "o-", ("voxlink", "voxel"): "s",
              ("dense", "trilinear"): "o--", ("dense", "voxel"): "D"}
    for (renderer, sampling), style in styles.items():
        sel = sorted((r for r in rows if r["renderer"] == renderer and r["sampling"] == sampling),
                     key=lambda r: r["step"])
        if not sel:
            continue
        own = " (the project's dense 3D-texture caster)" if renderer == "dense" else ""
        ax.plot([r["ms"] for r in sel], [r["psnr"] for r in sel], style,
                label=f"{renderer} {sampling}{own}")
        if sampling == "trilinear":
            for r in sel:
                ax.annotate(f"step {r['step']:g}", (r["ms"], r["psnr"]), fontsize=7,
                            textcoords="offset points", xytext=(4, 4))
    peer = sorted((r for r in rows if r["renderer"] == "paraview"), key=lambda r: r["step"])
    for i, r in enumerate(peer):
        ax.axvline(r["ms"], color="0.4", linestyle=":", linewidth=1,
                   label="ParaView 5.11 trilinear (time only)" if i == 0 else None)
        ax.annotate(f"ParaView step {r['step']:g}", (r["ms"], 0.02),
                    xycoords=("data", "axes fraction"), rotation=90, fontsize=7, color="0.3",
                    textcoords="offset points", xytext=(-9, 0))
    ax.set_xscale("log")
    ax.set_xlabel("mean frame time, ms (log)")
    ax.set_ylabel("PSNR vs float64 reference, dB")
    ax.set_title("Render time vs image error (llvmpipe)")
    ax.legend(fontsize=8)
    ax.grid(True, alpha=0.3)
    return fig


def shadows(rows, caption):
    """rows: one per data set and sampling, with ms and psnr per variant (none, per-sample,
    per-voxel, still). One panel per sampling: frame time against PSNR vs exact shadow rays."""
    samplings = [s for s in ("voxel", "trilinear") if any(r["sampling"] == s for r in rows)]
    fig, axes = _figure(caption, len(samplings))
    markers = {"none": ("x", "no shadows"), "per-sample": ("o", "per-sample rays (exact)"),
               "per-voxel": ("^", "per-voxel cache, filled"),
               "still": ("v", "per-voxel cache, reused (still frame)")}
    colours = {}
    for ax, sampling in zip(axes, samplings):
        for r in (r for r in rows if r["sampling"] == sampling):
            colour = colours.setdefault(r["data"], f"C{len(colours)}")
            for k, (marker, _) in markers.items():
                ax.scatter([r["ms"][k]], [r["psnr"][k]], marker=marker, color=colour)
        for data, colour in colours.items():
            ax.plot([], [], "-", color=colour, label=data)
        for marker, label in markers.values():
            ax.scatter([], [], marker=marker, color="0.3", label=label)
        ax.set_xscale("log")
        ax.set_xlabel("median frame time, ms (log)")
        ax.set_ylabel("PSNR vs float64 exact shadow rays, dB")
        ax.set_title(f"Shadow rays, {sampling} sampling (llvmpipe)")
        ax.legend(fontsize=7)
        ax.grid(True, alpha=0.3)
    return fig


def convert(rows, caption):
    """rows: convert_bench.py's rows. Left: conversion time against B/voxel per case (marker:
    stored value type), with OpenVDB's B/voxel and its job time where it ran. Right: the
    random field's value error and gradient error against B/voxel per value type / bound."""
    fig, (left, right) = _figure(caption, 2)
    markers = {"u8": "o", "u16": "s", "f16": "^", "f32": "D"}
    for vt, marker in markers.items():
        sel = [r for r in rows if r["stored"] == vt]
        if sel:
            left.scatter([r["sec"] for r in sel], [r["bpv"] for r in sel], marker=marker,
                         label=f"voxlink, stored {vt}")
    for r in rows:
        left.annotate(r["name"], (r["sec"], r["bpv"]), fontsize=6, textcoords="offset points",
                      xytext=(3, 3))
    peer = [r for r in rows if r.get("peer_sec")]
    if peer:
        left.scatter([r["peer_sec"] for r in peer], [r["vdb_bpv"] for r in peer], marker="x",
                     color="k", label="OpenVDB FloatGrid job (same input)")
    left.set_xscale("log")
    left.set_yscale("log")
    left.set_xlabel("conversion time, s (median, log)")
    left.set_ylabel("bytes per stored voxel (log)")
    left.set_title("Conversion time vs size")
    left.legend(fontsize=7)
    left.grid(True, alpha=0.3)
    field = [r for r in rows if r["name"].startswith("grf")]
    if field:
        right.scatter([r["bpv"] for r in field], [max(r["verr"], 1e-12) for r in field],
                      label="max abs value error")
        for r in field:
            right.annotate(f"{r['stored']} ({r['name'].split('-', 1)[-1]})",
                           (r["bpv"], max(r["verr"], 1e-12)), fontsize=7,
                           textcoords="offset points", xytext=(3, 3))
        right.set_yscale("log")
        right.set_ylabel("max abs value error (field sd 1, log)")
    grad = right.twinx()
    grad.plot([r["bpv"] for r in rows], [r["gmean"] for r in rows], "r+",
              label="gradient error mean, deg (every case)")
    grad.plot([r["bpv"] for r in rows], [r["gmax"] for r in rows], "rx",
              label="gradient error max, deg")
    grad.set_ylabel("gradient error, deg", color="r")
    grad.set_ylim(0, 1.0)
    right.set_xlabel("bytes per stored voxel")
    right.set_title("Value type / error bound vs error")
    right.legend(fontsize=7, loc="upper left")
    grad.legend(fontsize=7, loc="upper right")
    right.grid(True, alpha=0.3)
    return fig


def kriging(rows, caption):
    """rows: kriging_vs_gstat.py's rows (neighbours, voxlink_s, gstat_s, rmse, gstat_rmse)."""
    fig, (ax,) = _figure(caption)
    ax.plot([r["voxlink_s"] for r in rows], [r["rmse"] for r in rows], "o-",
            label="voxlink krige (solve)")
    ax.plot([r["gstat_s"] for r in rows], [r["gstat_rmse"] for r in rows], "s--",
            label="gstat krige() (R)")
    for r in rows:
        label = f"k={r['neighbours'] or 'all'}"
        for x, y in ((r["voxlink_s"], r["rmse"]), (r["gstat_s"], r["gstat_rmse"])):
            ax.annotate(label, (x, y), fontsize=7, textcoords="offset points", xytext=(4, 4))
    ax.set_xscale("log")
    ax.set_xlabel("Kriging time, s (median, log)")
    ax.set_ylabel("RMSE vs exhaustive Walker Lake V")
    ax.set_title("Kriging time vs error per neighbourhood size")
    ax.legend(fontsize=8)
    ax.grid(True, alpha=0.3)
    return fig


def voxelization(runs, caption):
    """runs: {surface mode: voxelization_cost.py's JSON}. Left: PSNR against the exact (Embree)
    image per resolution; right: B/voxel per resolution."""
    fig, (left, right) = _figure(caption, 2)
    for mode, run in runs.items():
        for scene in dict.fromkeys(r["scene"] for r in run["rows"]):
            sel = [r for r in run["rows"] if r["scene"] == scene]
            res = [r["resolution"] for r in sel]
            for key, style in (("plain", "o-"), ("effects", "^--")):
                left.plot(res, [float(r[key]["psnr"]) for r in sel], style,
                          label=f"{scene}, {mode}, {'plain' if key == 'plain' else 'all effects'}")
            right.plot(res, [r["bytes_per_voxel"] for r in sel], "o-", label=f"{scene}, {mode}")
    for ax in (left, right):
        ax.set_xscale("log", base=2)
        ax.set_xlabel("voxels along the longest axis (log2)")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    left.set_ylabel("PSNR vs exact tracer (Embree), dB")
    left.set_title("Voxelization resolution vs image error")
    right.set_ylabel("bytes per stored voxel")
    right.set_title("Voxelization resolution vs size")
    return fig


def pack(rows, caption):
    """rows: pack_bench.py's rows (file, bytes_per_voxel, make_s, load_s)."""
    fig, (ax,) = _figure(caption)
    made = [r for r in rows if r["make_s"] is not None]
    ax.scatter([r["bytes_per_voxel"] for r in made], [max(r["make_s"], 0.005) for r in made],
               marker="o", label="pack / compress time")
    # Times print with 2 decimals: a 0.00 is drawn at 0.005, not dropped by the log axis.
    ax.scatter([r["bytes_per_voxel"] for r in rows], [max(r["load_s"], 0.005) for r in rows],
               marker="s", label="load time")
    for r in rows:
        y = max(r["make_s"] if r["make_s"] is not None else r["load_s"], 0.005)
        ax.annotate(r["file"].replace("`", ""), (r["bytes_per_voxel"], y), fontsize=6,
                    textcoords="offset points", xytext=(3, 3))
    ax.set_yscale("log")
    ax.set_xlabel("bytes per stored voxel")
    ax.set_ylabel("seconds (median, log)")
    ax.set_title("Packed size vs pack / load time")
    ax.legend(fontsize=8)
    ax.grid(True, alpha=0.3)
    return fig


def against_paraview(volumes, sweep, sizes, caption):
    """volumes, sweep: render_vs_paraview.sh's summary rows (with "kept %"); sizes: the frame
    size of each, as (volumes, sweep). Left: speed-up over
    ParaView against the share of voxels kept, both samplings, with issue 29's goals. Right:
    the occupancy sweep's frame times: where sparsity stops paying."""
    fig, (left, right) = _figure(caption, 2)

    def speedup(r, sampling):  # the script's ratio of unrounded means, not of its ms cells
        return float(r[f"{sampling} speed-up"].rstrip("x"))

    for sampling, marker, goal in (("trilinear", "o", 10), ("voxel", "s", 20)):
        colour = "C0" if sampling == "trilinear" else "C1"
        left.scatter([r["kept %"] for r in volumes], [speedup(r, sampling) for r in volumes],
                     marker=marker, color=colour, label=f"{sampling}, CT volumes ({sizes[0]})")
        sel = sorted(sweep, key=lambda r: r["kept %"])
        left.plot([r["kept %"] for r in sel], [speedup(r, sampling) for r in sel], marker + "--",
                  color=colour, mfc="none",
                  label=f"{sampling}, tooth occupancy sweep ({sizes[1]})")
        left.axhline(goal, color=colour, linestyle=":", linewidth=1,
                     label=f"goal {sampling} >= {goal}x")
    for r in volumes:
        left.annotate(r["data"], (r["kept %"], speedup(r, "trilinear")), fontsize=7,
                      textcoords="offset points", xytext=(4, -8))
    left.axhline(1, color="0.3", linewidth=1)
    left.set_xscale("log")
    left.set_yscale("log")
    left.set_xlabel("voxels kept by the TF, % (log)")
    left.set_ylabel("ParaView frame time / voxlink frame time (log)")
    left.set_title("Speed-up over ParaView, matched settings (llvmpipe)")
    left.legend(fontsize=7, loc="lower left")  # the upper right holds the sparse scans' points
    left.grid(True, alpha=0.3)
    sel = sorted(sweep, key=lambda r: r["kept %"])
    kept = [r["kept %"] for r in sel]
    for column, style, label in (("voxlink voxel ms", "s-", "voxlink voxel"),
                                 ("voxlink trilinear ms", "o-", "voxlink trilinear"),
                                 ("ParaView ms", "D--", "ParaView 5.11 trilinear")):
        right.plot(kept, [float(r[column]) for r in sel], style, label=label)
    right.set_xscale("log")
    right.set_yscale("log")
    right.set_xlabel("tooth voxels kept, % (log)")
    right.set_ylabel("mean frame time, ms (log)")
    right.set_title(f"Frame time against occupancy ({sizes[1]})")
    right.legend(fontsize=8)
    right.grid(True, alpha=0.3)
    return fig
