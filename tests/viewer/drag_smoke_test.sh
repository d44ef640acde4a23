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
"$voxlink" bench-render --animate "$scene" --resolutions 64 --sizes 400x300 --frames 1 \
    --pictures bench >/dev/null
"$voxlink" view "$scene" --resolution 64 --window 400x300 --time 0 >view.log 2>&1 &
viewer=$!
# No window manager: the window sits at the screen's corner, and keys go to the window under
# the pointer.
xdotool search --sync --onlyvisible --name "VoxLink" >/dev/null
sleep 3  # the first frames
xdotool mousemove 200 150
xdotool key h  # hide the panels: the whole window is the view
sleep 1
xdotool key p  # before the drag: voxlink-screenshot-1.png
for _ in $(seq 1 60); do [[ -s voxlink-screenshot-1.png ]] && break; sleep 1; done
# Ctrl + left drag from the middle (the dragon) 60 pixels right, in steps.
xdotool keydown ctrl mousedown 1
for i in $(seq 1 6); do
  xdotool mousemove $((200 + 10 * i)) 150
  sleep 0.3
done
xdotool mouseup 1 keyup ctrl
sleep 2
xdotool key p  # after it: voxlink-screenshot-2.png
for _ in $(seq 1 60); do [[ -s voxlink-screenshot-2.png ]] && break; sleep 1; done
xdotool key q
wait "$viewer" || { cat view.log; exit 1; }
viewer=""
[[ -s voxlink-screenshot-1.png && -s voxlink-screenshot-2.png ]] || { echo "no screenshots"; cat view.log; exit 1; }
idiff voxlink-screenshot-1.png bench/animate_64_8_400x300.png  # not dragged yet: the same frame
if idiff voxlink-screenshot-2.png bench/animate_64_8_400x300.png >diff.txt; then
  echo "the dragged frame equals the undragged one: the drag did not move the dragon"
  exit 1
fi
grep -E "pixels" diff.txt | head -1
echo "viewer drag smoke test passed"
