#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Drags the dragon of samples/scenes/dragon-animated.scene.json with the mouse in `voxlink view`
# under xvfb-run (xdotool: Ctrl + left drag over it) with a screenshot (P) before and after, and
# quits (Q): the first must equal bench-render --animate's frame for the same time, the second
# differ from it. Exit 77 (skipped) without xvfb-run, xdotool, idiff or the mesh.
# usage: drag_smoke_test.sh VOXLINK DATA_DIR
set -euo pipefail
voxlink=$1
data=$2
scene="$(cd "$(dirname "$0")/../.." && pwd)/samples/scenes/dragon-animated.scene.json"
for tool in xvfb-run xdotool idiff; do
  command -v $tool >/dev/null || { echo "skipped: $tool missing"; exit 77; }
done
[[ -f $data/mesh/stanford_dragon_decimated.ply ]] || { echo "skipped: the dragon mesh missing"; exit 77; }
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
echo "viewer drag smoke test passed"
