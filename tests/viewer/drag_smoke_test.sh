#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Drags the dragon of samples/scenes/dragon-animated.scene.json with the mouse in `voxlink view`
# under xvfb-run (xdotool: Ctrl + left drag over it) with a screenshot (P) before and after, and
# quits (Q): the first must equal bench-render --animate's frame for the same time, the second
# differ from it. Then the same scene with nothing animated (the dragon static): a Ctrl + left
# drag over the dragon makes it move (the static part rebuilt without it) and drags it; the
# screenshot after differs from the one before. Then the same for a static protein (the 2XHE
# PDB's atoms as spheres, samples/scenes/protein-animated.scene.json without its animation).
# Exit 77 (skipped) without xvfb-run, xdotool, idiff, the mesh or the PDB file.
# usage: drag_smoke_test.sh VOXLINK DATA_DIR
set -euo pipefail
voxlink=$1
data=$2
samples="$(cd "$(dirname "$0")/../.." && pwd)/samples/scenes"
scene="$samples/dragon-animated.scene.json"
for tool in xvfb-run xdotool idiff; do
  command -v $tool >/dev/null || { echo "skipped: $tool missing"; exit 77; }
done
[[ -f $data/mesh/stanford_dragon_decimated.ply ]] || { echo "skipped: the dragon mesh missing"; exit 77; }
[[ -f $data/particles/biopython_2XHE.pdb ]] || { echo "skipped: the 2XHE PDB file missing"; exit 77; }
# The rest runs on a display of its own.
if [[ -z ${VOXLINK_DRAG_IN_XVFB:-} ]]; then
  VOXLINK_DRAG_IN_XVFB=1 exec xvfb-run -a -s "-screen 0 800x600x24" bash "$0" "$@"
fi
work=$(mktemp -d)
viewer=""
cleanup() {
  [[ -n $viewer ]] && kill "$viewer" 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT
cd "$work"
"$voxlink" bench-render --animate "$scene" --resolutions 64 --sizes 800x600 --frames 1 \
    --pictures bench >/dev/null
# The panels cover the window's left part; the drag happens right of them, over the dragon.
"$voxlink" view "$scene" --resolution 64 --window 800x600 --time 0 >view.log 2>&1 &
viewer=$!
# No window manager: the window sits at the screen's corner, and keys go to the window under
# the pointer. The viewer polls key states once a frame, so a key is held over several frames.
press() {
  xdotool keydown "$1"
  sleep 0.5
  xdotool keyup "$1"
}
# P until the viewer has written screenshot number $1 (a press while it still starts is lost).
shoot() {
  for _ in $(seq 1 60); do
    [[ -s voxlink-screenshot-$1.png ]] && return 0
    press p
    sleep 1
  done
  echo "no screenshot $1"
  cat view.log
  exit 1
}
xdotool search --sync --onlyvisible --name "VoxLink" >/dev/null
xdotool mousemove 530 400
shoot 1  # before the drag
sleep 2  # a press that came late may still write a second one
before=$(ls voxlink-screenshot-*.png | wc -l)
# Ctrl + left drag from over the dragon 60 pixels right, in steps.
xdotool keydown ctrl mousedown 1
for i in $(seq 1 6); do
  xdotool mousemove $((530 + 10 * i)) 400
  sleep 0.3
done
xdotool mouseup 1 keyup ctrl
sleep 2
after=$((before + 1))
shoot $after
press q
wait "$viewer" || { cat view.log; exit 1; }
viewer=""
# Not dragged yet: the same frame, pixel for pixel (docs/dynamic-scenes.md).
idiff -fail 0.004 voxlink-screenshot-1.png bench/animate_64_8_800x600.png
# Dragged: more than 1 % of the pixels differ.
if idiff -fail 0.004 -failpercent 1 voxlink-screenshot-$after.png bench/animate_64_8_800x600.png >diff.txt; then
  echo "the dragged frame equals the undragged one: the drag did not move the dragon"
  exit 1
fi
grep -E "pixels" diff.txt | head -1

# A Ctrl + left drag from (x, y) over a static object of SCENE makes it move and drags it 60
# pixels right: the screenshot after differs from the one before.
dragStatic() {
  local scene=$1 x=$2 y=$3 what=$4
  "$voxlink" view "$scene" --window 800x600 >view.log 2>&1 &
  viewer=$!
  xdotool search --sync --onlyvisible --name "VoxLink" >/dev/null
  xdotool mousemove "$x" "$y"
  shoot 1
  sleep 2
  before=$(ls voxlink-screenshot-*.png | wc -l)
  # The press makes the object move (its static part rebuilt on a thread); the drag starts from
  # the press once the new scene is swapped in, so the steps after it count from there.
  xdotool keydown ctrl mousedown 1
  sleep 1
  for i in $(seq 1 6); do
    xdotool mousemove $((x + 10 * i)) "$y"
    sleep 0.3
  done
  xdotool mouseup 1 keyup ctrl
  sleep 2
  after=$((before + 1))
  shoot $after
  press q
  wait "$viewer" || { cat view.log; exit 1; }
  viewer=""
  if idiff -fail 0.004 -failpercent 1 voxlink-screenshot-$after.png voxlink-screenshot-1.png >diff.txt; then
    echo "the static $what did not move under the drag"
    cat view.log
    exit 1
  fi
  grep -E "pixels" diff.txt | head -1
}

# A static dragon: dragon-animated's objects without the animation.
mkdir still && cd still
cat >still.scene.json <<EOF
{"grid": {"resolution": 64, "brick": 8},
 "materials": {"jade": {"color": [0.35, 0.65, 0.45], "specular": 0.5, "shininess": 40},
               "clay": {"color": [0.75, 0.6, 0.5]}},
 "objects": [
  {"type": "mesh", "file": "$samples/meshes/quad.obj", "material": "clay",
   "transform": {"scale": [47.5, 1, 77.55], "rotate": [90, 0, 0], "translate": [-2.5, -671.79, 235.92]}},
  {"type": "mesh", "file": "$samples/meshes/quad.obj", "material": "clay",
   "transform": {"scale": [77.55, 1, 72.6], "rotate": [0, 0, 90], "translate": [-50, -671.79, 308.5]}},
  {"type": "mesh", "file": "$data/mesh/stanford_dragon_decimated.ply", "material": "jade"}],
 "lights": [{"position": [200, -400, 600]}], "camera": {"azimuth": 60, "elevation": 20}}
EOF
dragStatic still.scene.json 530 400 dragon

# A static protein: protein-animated's objects without the animation, the floor longer to the
# left so that the protein shows right of the panels (x > 490), where the press is.
mkdir ../protein && cd ../protein
cat >protein.scene.json <<EOF
{"grid": {"resolution": 64, "brick": 8},
 "materials": {"jade": {"color": [0.35, 0.65, 0.45], "specular": 0.5, "shininess": 40},
               "clay": {"color": [0.75, 0.6, 0.5]}},
 "objects": [
  {"type": "mesh", "file": "$samples/meshes/quad.obj", "material": "clay",
   "transform": {"scale": [170, 1, 90], "translate": [-86, -95, 21]}},
  {"type": "mesh", "file": "$samples/meshes/quad.obj", "material": "clay",
   "transform": {"scale": [60, 1, 90], "rotate": [0, 0, 90], "translate": [-256, -35, 21]}},
  {"type": "particles", "file": "$data/particles/biopython_2XHE.pdb", "material": "jade"}],
 "lights": [{"position": [200, 150, 300]}], "camera": {"azimuth": 30, "elevation": 25, "up": "y"}}
EOF
dragStatic protein.scene.json 520 320 protein
echo "viewer drag smoke test passed"
