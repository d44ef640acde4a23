#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Smoke test of the viewer's commands through the executable: convert the tooth CT, render PNG
# and EXR headless (EGL) with the reference comparison, a tiny benchmark, and the interactive
# viewer for a few frames under Xvfb (a .vxl, and a scene file against bench-render
# --animate). Exit 77 (skipped) when the data is missing.
# usage: cli_smoke_test.sh VOXLINK DATA_DIR
set -euo pipefail
voxlink=$1
data=$2
tooth="$data/ct/tooth_103x94x161_uint8.raw"
if [[ ! -f $tooth ]]; then echo "skipped: $tooth missing"; exit 77; fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

"$voxlink" convert "$tooth" --dims 103 94 161 --type u8 --threshold 121 -o tooth.vxl -q
out=$("$voxlink" render tooth.vxl -o tooth.png --size 64x48 --reference --reference-output ref.png)
echo "$out"
grep -q "PSNR" <<<"$out"
psnr=$(sed -n 's/.*PSNR \([0-9.]*\) dB.*/\1/p' <<<"$out")
awk -v p="$psnr" 'BEGIN { exit !(p >= 45) }' || { echo "PSNR $psnr below 45 dB"; exit 1; }
"$voxlink" render tooth.vxl -o tooth.exr --size 40x40 --sampling trilinear --camera 90,10,1.2 --shadows
[[ -s tooth.png && -s ref.png && -s tooth.exr ]]

# Bad input: one line, non-zero status, nothing written.
if "$voxlink" render tooth.vxl -o bad.png --size 0x10 2>err.txt; then exit 1; fi
[[ $(wc -l <err.txt) -eq 1 && ! -e bad.png ]]
if "$voxlink" render tooth.vxl -o bad.png --termination-alpha 1.5 2>err.txt; then exit 1; fi
[[ $(wc -l <err.txt) -eq 1 && ! -e bad.png ]] && grep -q "termination alpha" err.txt

# Early ray termination reaches the image: ParaView's threshold (1 - 1/255) still agrees with the
# reference at the same setting, and stopping rays at opacity 0.3 changes the picture.
out=$("$voxlink" render tooth.vxl -o late.png --size 64x48 --sampling trilinear \
    --termination-alpha 0.996078431 --reference)
psnr=$(sed -n 's/.*PSNR \([0-9.]*\) dB.*/\1/p' <<<"$out")
awk -v p="$psnr" 'BEGIN { exit !(p >= 45) }' || { echo "PSNR $psnr below 45 dB"; exit 1; }
"$voxlink" render tooth.vxl -o early.png --size 64x48 --sampling trilinear --termination-alpha 0.3
if cmp -s late.png early.png; then echo "--termination-alpha changed nothing"; exit 1; fi

"$voxlink" bench-render tooth.vxl --sizes 32x32 --frames-per-turn 2 --samplings voxel | tee bench.txt
grep -q "| voxlink | voxel | 32x32 |" bench.txt
grep -q "| dense | voxel | 32x32 |" bench.txt

# Scene build with the GL voxelizer (headless) gives the exact path's voxels on the Cornell box.
cornell="$data/mesh/mcguire_CornellBox-Original.obj"
if [[ -f $cornell ]]; then
  echo "{\"grid\": {\"resolution\": 96}, \"objects\": [{\"type\": \"mesh\", \"file\": \"$cornell\"}]}" \
      >cornell.scene.json
  exact=$("$voxlink" scene build cornell.scene.json -o exact.vxl)
  gl=$("$voxlink" scene build cornell.scene.json -o gl.vxl --voxelizer gl)
  echo "$gl"
  grep -q "(gl)" <<<"$gl"
  count() { sed 's/.*\], \([0-9]*\) voxels.*/\1/' <<<"$1"; }
  awk -v a="$(count "$exact")" -v b="$(count "$gl")" \
      'BEGIN { d = a - b; if (d < 0) d = -d; exit !(a > 10000 && d <= a / 1000) }' ||
      { echo "GL voxels $(count "$gl") vs exact $(count "$exact")"; exit 1; }
  "$voxlink" validate gl.vxl
fi

if command -v xvfb-run >/dev/null; then
  xvfb-run -a -s "-screen 0 800x600x24" "$voxlink" view tooth.vxl --window 320x240 --frames 3 \
      --screenshot-on-exit view.png --capture-window-on-exit window.png
  [[ -s view.png && -s window.png && ! -e imgui.ini ]]
  # A scene file with a moving mesh: its first frame (--time 0, paused) is the frame
  # bench-render --animate draws for time 0 (the same grid, camera and TF).
  scene="$(cd "$(dirname "$0")/../.." && pwd)/samples/scenes/dragon-animated.scene.json"
  if [[ -f $data/mesh/stanford_dragon_decimated.ply ]] && command -v idiff >/dev/null; then
    xvfb-run -a -s "-screen 0 800x600x24" "$voxlink" view "$scene" --resolution 64 \
        --window 160x120 --frames 2 --time 0 --screenshot-on-exit scene-view.png
    "$voxlink" bench-render --animate "$scene" --resolutions 64 --sizes 160x120 --frames 1 \
        --pictures scene-bench
    # The same frame, pixel for pixel (docs/dynamic-scenes.md).
    idiff -fail 0.004 scene-view.png scene-bench/animate_64_8_160x120.png
  else
    echo "the dragon mesh or idiff missing: a scene in the viewer not tested"
  fi
else
  echo "xvfb-run not found: interactive viewer not tested"
fi
# A bad scene file: one line and a non-zero status before any window (no display is asked for).
echo '{"objects": [{"type": "mesh", "file": "none.obj"}], "grid": {"resolution": 1}}' >bad.scene.json
if DISPLAY= "$voxlink" view bad.scene.json 2>err.txt; then exit 1; fi
cat err.txt
[[ $(wc -l <err.txt) -eq 1 ]] && grep -q "bad.scene.json" err.txt
echo "viewer CLI smoke test passed"
