# SPDX-License-Identifier: BSD-3-Clause
"""The Markdown tables of bench/surface_modes.py: one per surface mode, from its CSV rows, with
issue 28's goals marked per row and the paper's bytes per voxel beside the scenes it measured."""

FIELDS = ["scene", "resolution", "mode", "effects", "voxels", "surface_voxels",
          "fragments_per_surface_voxel", "bytes", "build_s", "build_rss_mib", "normal_p95", "psnr",
          "edge_psnr", "first_hit_pct", "fps_512", "fps_1000", "note"]

# The paper's Table 1 (Kohler et al., VoxLink): (10^3 voxels, memory MB) per scene and
# resolution, its bricks 8, 8, 16. Its dragon is another mesh (fewer voxels); its bunny scene is
# samples/scenes/bunny-glass. B/voxel below is MB * 10^6 / voxels (MB read as 10^6 bytes).
PAPER_TABLE1 = {
    "dragon": {256: (81.6, 9.4), 512: (326.2, 70.0), 1024: (1303.2, 277.0)},
    "house": {256: (560.0, 16.7), 512: (2319.3, 100.0), 1024: (9444.9, 401.0)},
    "bunny-glass": {256: (139.2, 10.2), 512: (557.3, 73.5), 1024: (2233.8, 291.0)},
}
PAPER_SCENE = {"dragon": "dragon", "sample dragon": "dragon", "sample house": "house",
               "sample bunny-glass": "bunny-glass"}


def paper_bytes_per_voxel(scene, resolution):
    entry = PAPER_TABLE1.get(PAPER_SCENE.get(scene, ""), {}).get(int(str(resolution).split()[0]))
    return f"{entry[1] * 1e6 / (entry[0] * 1e3):.1f}" if entry else ""


def as_float(text):
    return float("inf") if text == "inf" else float(text)


def goals(row):
    """Issue 28's goals (named for the dragon at 512; applied to every row as the same bar)."""
    if not row["psnr"] or row["mode"] == "mean":
        return "-"
    missed = []
    if row["mode"] == "planes":
        if as_float(row["psnr"]) < 35:
            missed.append(f"whole {row['psnr']} < 35")
        if as_float(row["edge_psnr"]) < 25:
            missed.append(f"edges {row['edge_psnr']} < 25")
        if float(row["normal_p95"]) > 2:
            missed.append(f"p95 {row['normal_p95']} > 2")
    elif as_float(row["psnr"]) < 50:
        missed.append(f"whole {row['psnr']} < 50")
    return "met" if not missed else "not met: " + ", ".join(missed)


def write_tables(rows, modes):
    """Markdown: a table per mode, each scene's rows together (scenes in the order first
    measured), by resolution."""
    first = {}
    for r in rows:
        first.setdefault(r["scene"], len(first))
    rows = sorted(rows, key=lambda r: (first[r["scene"]], int(r["resolution"].split()[0])))
    out = []
    for mode in modes:
        out.append(f"\n**{mode}**\n")
        out.append("| scene | res | effects | voxels | fragments per surface voxel | B/voxel |"
                   " paper B/voxel | MB | build s | build peak MiB | normal p95 deg | PSNR dB |"
                   " edge PSNR dB | first hit differs % | fps 512x512 (shared) |"
                   " fps 1000x1000 (shared) | goals | note |")
        out.append("|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
                   "---:|---|---|")
        for r in rows:
            if r["mode"] != mode:
                continue
            measured = bool(r["bytes"])
            bytes_per_voxel = f"{int(r['bytes']) / int(r['voxels']):.2f}" if measured else ""
            megabytes = f"{int(r['bytes']) / 1e6:.1f}" if measured else ""
            paper = paper_bytes_per_voxel(r["scene"], r["resolution"])
            cells = [r["scene"], r["resolution"], r["effects"], r["voxels"],
                     r["fragments_per_surface_voxel"], bytes_per_voxel, paper, megabytes,
                     r["build_s"], r["build_rss_mib"],
                     r["normal_p95"], r["psnr"], r["edge_psnr"], r["first_hit_pct"],
                     r["fps_512"], r["fps_1000"], goals(r), r["note"]]
            out.append("| " + " | ".join(str(c) if c != "" else "-" for c in cells) + " |")
    return "\n".join(out) + "\n"
