#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# scripts/check-layers.sh passes on a copy of the sources, and fails naming the file, the line and
# the arrow when one upward or sideways include is planted in it (also one into a subfolder room,
# render/gl), when a file includes another room's detail/ header (a room's own passes), and when a
# file runs over 500 lines or a folder is missing from cmake/layers.txt.
#   bash tests/layers/check_layers_test.sh SOURCE_DIR
set -euo pipefail
src=$(cd "$1" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
copy="$tmp/tree"
mkdir "$copy"
if git -C "$src" rev-parse --is-inside-work-tree > /dev/null 2>&1; then
  (cd "$src" && git ls-files -z --cached --others --exclude-standard -- '*.h' '*.cpp' cmake/layers.txt scripts/check-layers.sh |
    xargs -0 cp --parents -t "$copy")
else
  (cd "$src" && find . -path './build*' -prune -o \( -name '*.h' -o -name '*.cpp' \) -print0 |
    xargs -0 cp --parents -t "$copy" && cp --parents cmake/layers.txt scripts/check-layers.sh "$copy")
fi
check() { bash "$copy/scripts/check-layers.sh" "$copy" 2> "$tmp/err"; }
failures=0
expect_fail() {  # what, the message expected on stderr
  if check; then
    echo "FAIL: $1: check-layers passed" >&2
    failures=$((failures + 1))
  elif ! grep -qF -- "$2" "$tmp/err"; then
    echo "FAIL: $1: expected \"$2\" in:" >&2
    cat "$tmp/err" >&2
    failures=$((failures + 1))
  else
    echo "ok: $1: $(grep -F -- "$2" "$tmp/err")"
  fi
}
plant() {  # file, line to insert as line 2
  cp "$copy/$1" "$tmp/saved"
  sed -i "2i $2" "$copy/$1"
}
restore() { cp "$tmp/saved" "$copy/$1"; }

if ! check; then
  echo "FAIL: the unchanged copy does not pass:" >&2
  cat "$tmp/err" >&2
  exit 1
fi
echo "ok: the unchanged copy passes"

plant base/error.h '#include "cli/render_options.h"'
expect_fail "upward include" 'base/error.h:2: forbidden arrow base -> cli'
restore base/error.h

plant pack/packed_file.cpp '#include "tf/transfer_function.h"'
expect_fail "sibling include" 'pack/packed_file.cpp:2: forbidden arrow pack -> tf'
restore pack/packed_file.cpp

plant render/camera.cpp '#include "render/gl/gl_context.h"'
expect_fail "include of a subfolder room above" 'render/camera.cpp:2: forbidden arrow render -> render/gl'
restore render/camera.cpp

plant scene/scene_assembly.cpp '#include "convert/detail/slab_window.h"'
expect_fail "another room's detail header" 'scene/scene_assembly.cpp:2: scene/ includes a detail/ header of convert/'
restore scene/scene_assembly.cpp

plant convert/converter.cpp '#include "convert/detail/slab_window.h"'
if check; then
  echo "ok: a room's own detail header passes"
else
  echo "FAIL: a room's own detail header: check-layers failed:" >&2
  cat "$tmp/err" >&2
  failures=$((failures + 1))
fi
restore convert/converter.cpp

seq 501 | sed 's|^|// line |' > "$copy/format/long_file.cpp"
expect_fail "a file over 500 lines" 'format/long_file.cpp: 501 lines'
rm "$copy/format/long_file.cpp"

mkdir "$copy/newroom"
echo '#include "base/error.h"' > "$copy/newroom/thing.cpp"
expect_fail "a folder the table lacks" 'newroom/thing.cpp: folder newroom/ is not in cmake/layers.txt'
exit $((failures > 0))
