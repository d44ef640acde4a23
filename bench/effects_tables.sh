#!/usr/bin/env bash
# The paper's Tables 1 and 2 on this machine (llvmpipe): for the dragon, the house with glass
# windows and the glass-bunny scene at 256 [8], 512 [8] and 1024 [16]: voxels, non-empty bricks,
# file MB and frames per second (the paper's rotation protocol, `voxlink bench-render`) plain
# (dragon) and ray traced (`--effects all`); then Table 2: voxelizing every frame with the GL
# voxelizer plus a plain frame, bricks 4/8/16, as frames per second 1 / (voxelize + render).
# Usage: bash bench/effects_tables.sh BUILD_DIR OUT_DIR [FRAMES_PER_TURN] [SIZE...]
# (default 2 frames per turn, sizes 512x512 1000x1000). Prints markdown tables.
set -euo pipefail
build=${1:?build dir}
out=${2:?output dir}
turn=${3:-2}
shift $(( $# < 3 ? $# : 3 ))
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(512x512 1000x1000)
here=$(cd "$(dirname "$0")/.." && pwd)
voxlink="$build/cli/voxlink"
mkdir -p "$out"
scenes=(dragon house bunny-glass)
configs=("256 8" "512 8" "1024 16")

fps() {  # FILE SIZE [render options...] -> frames per second of the voxlink row
  local file=$1 size=$2
  shift 2
  "$voxlink" bench-render "$file" --sizes "$size" --frames-per-turn "$turn" --no-reference "$@" \
    2>/dev/null | awk -F'|' '$2 ~ /voxlink/ {gsub(/ /, "", $9); print $9}'
}

echo "## Table 1 (llvmpipe, $(nproc) cores; ${turn} frames per turn, two turns)"
echo
header="| scene | mode | resolution [brick] | voxels (10^3) | non-empty bricks % | MB |"
rule="|---|---|---|---:|---:|---:|"
for s in "${sizes[@]}"; do header+=" FPS $s |"; rule+="---:|"; done
echo "$header"
echo "$rule"
for scene in "${scenes[@]}"; do
  for config in "${configs[@]}"; do
    read -r res brick <<<"$config"
    file="$out/${scene}_${res}_${brick}.vxl"
    "$voxlink" scene build "$here/samples/scenes/$scene.scene.json" -o "$file" \
      --resolution "$res" --brick "$brick" >/dev/null 2>&1
    read -r voxels bricks bytes < <("$voxlink" info "$file" --json --no-vdb | python3 -c \
      'import json,sys; d=json.load(sys.stdin); print(d["voxels"], d["bricks_nonempty_fraction"], d["bytes_total"])')
    modes=("ray traced|--effects all")
    [ "$scene" = dragon ] && modes=("plain|--effects none" "${modes[@]}")
    for mode in "${modes[@]}"; do
      name=${mode%%|*}
      read -r -a opts <<<"${mode#*|}"
      row="| $scene | $name | $res [$brick] | $(awk -v v="$voxels" 'BEGIN{printf "%.1f", v/1e3}') |"
      row+=" $(awk -v f="$bricks" 'BEGIN{printf "%.1f", 100*f}') | $(awk -v b="$bytes" 'BEGIN{printf "%.1f", b/1e6}') |"
      for s in "${sizes[@]}"; do row+=" $(fps "$file" "$s" "${opts[@]}") |"; done
      echo "$row"
    done
  done
done

echo
echo "## Table 2: GL voxelization every frame + a plain frame at ${sizes[0]} (FPS = 1 / (voxelize + render))"
echo
echo "| scene | resolution | brick 4 | brick 8 | brick 16 |"
echo "|---|---|---:|---:|---:|"
for scene in "${scenes[@]}"; do
  for res in 256 512 1024; do
    row="| $scene | $res |"
    for brick in 4 8 16; do
      file="$out/${scene}_gl_${res}_${brick}.vxl"
      voxelize=$("$voxlink" scene build "$here/samples/scenes/$scene.scene.json" -o "$file" \
        --resolution "$res" --brick "$brick" --voxelizer gl 2>/dev/null |
        sed -n 's/.*voxelize \([0-9.]*\) s.*/\1/p' | tail -1)
      render=$(fps "$file" "${sizes[0]}")
      row+=" $(awk -v v="$voxelize" -v r="$render" 'BEGIN{printf "%.2f", 1/(v + 1/r)}') |"
      rm -f "$file"
    done
    echo "$row"
  done
done
