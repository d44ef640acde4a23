#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The measurements that need a real GPU (docs/gpu-measurements.md), as one prepared script for a lent
# machine with only the NVIDIA driver (../shared/tools/gpu-bundle.sh packs the CLI for it).
#   here, after the build:  bash bench/gpu_session.sh prepare     (fills .gpu/: CLI, data, this script)
#   on the GPU machine:     bash .gpu/gpu_session.sh run [SECTION...] (carry [".gpu"]; log in $OUT/log.md)
# Sections (default: all, in this order): foot256 table1 animate foot1024 krige.
#   foot256   the foot CT 256^3 (bench/tf/foot-bone.tf.json), 1000x1000: voxlink vs the dense 3D-texture
#             caster, voxel and trilinear, without and with --shadows, voxlink with row words in
#             place of row groups, the shadow rays' bench (per-sample, per-voxel, still; and shadowed
#             frames with and without the marking frame compared byte for byte) (issue 29)
#   table1    the paper's Table 1 scenes (dragon plain and ray-traced, house and glass bunny ray-traced) at
#             256 [8], 512 [8], 1024 [16], 1000x1000 (issue 29 item 2). On NVIDIA the first use of the
#             ray-traced mode compiles its shaders for 35-210 s (then the driver's cache holds them).
#   animate   the paper's Table 2 in process: the animated dragon re-voxelized + rendered (issue 28 item 4)
#   foot1024  the foot upsampled 4x to 1024^3 there (bench/upsample_volume.cpp), converted, voxlink vs dense
#   krige     local kriging, 2e5 samples onto 216^3 nodes, 32 neighbours, 16 / 8 / 2 threads (issue 27)
set -u
mode=${1:-}
shift || true
if [[ $mode == prepare ]]; then
  set -e
  here=$(cd "$(dirname "$0")/.." && pwd); cd "$here"
  data=${VOXLINK_DATA:-../shared/data}
  samples=/tmp/voxlink-gpu-session/samples200000.csv
  [[ -e $samples ]] || /usr/bin/python3 bench/krige_scale.py build/cli/voxlink --dims 20 \
    --dir /tmp/voxlink-gpu-session >/dev/null
  bash ../shared/tools/gpu-bundle.sh "$data/ct/openscivis_lossy/foot_256x256x256_uint8_lossy.nrrd" \
    bench/tf/foot-bone.tf.json "$data/mesh/stanford_dragon_decimated.ply" \
    "$data/mesh/c3dtm_stanford-bunny.obj" "$samples"
  cp build/bench/voxlink_bench_upsample .gpu/upsample
  cp build/bench/voxlink_bench_shadow_rays .gpu/shadow_rays
  cp bench/gpu_session.sh .gpu/
  git rev-parse --short HEAD >.gpu/commit
  echo "gpu_session: .gpu/ ready ($(du -sh .gpu | cut -f1))"
  exit 0
fi
[[ $mode == run ]] || { echo "usage: $0 prepare | run [foot256 table1 animate foot1024 krige]" >&2; exit 2; }
sections=${*:-foot256 table1 animate foot1024 krige}
exec > >(tee -a "${OUT:-/tmp}/log.md") 2>&1
V="bash .gpu/run.sh"
D=.gpu/data
T=/tmp/w
mkdir -p $T
t() { local s; s=$(date +%s%N); "$@"; echo "[exit $? in $((($(date +%s%N) - s) / 1000000)) ms: $*]"; }
echo "# device run $(date -u +%FT%TZ), commit $(cat .gpu/commit), $(nproc) cores"
(nvidia-smi -L || /usr/local/nvidia/bin/nvidia-smi -L) 2>&1 | head -2
# What .gpu/run.sh sets for the CLI, for the bench tools run beside it (their libraries: the bundle's).
NV=$(ls -d /usr/local/nvidia/lib64 /usr/local/nvidia/lib 2>/dev/null | tr '\n' ':')
EGL_VENDOR=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
# The sample scenes name their meshes as ../../../shared/data/mesh/...: put them there.
M="$(dirname "$PWD")/shared/data/mesh"
mkdir -p "$M" && cp $D/*.ply $D/*.obj "$M"/
foot=$D/foot_256x256x256_uint8_lossy.nrrd
tf=$D/foot-bone.tf.json
for section in $sections; do
  echo "## $section"
  case $section in
    foot256)
      t $V convert $foot --tf $tf -o $T/foot.vxl -q
      t $V bench-render $T/foot.vxl --tf $tf --sizes 1000x1000 --no-reference --source $foot
      # Row words in place of the GPU's row groups (docs/gpu-measurements.md): speed against memory.
      t env VOXLINK_ROW_GROUPS=0 $V bench-render $T/foot.vxl --tf $tf --sizes 1000x1000 --no-reference --no-dense
      t $V bench-render $T/foot.vxl --tf $tf --sizes 1000x1000 --no-reference --shadows --source $foot
      # Shadowed frames against plain ones in one process (docs/shadows.md): per-sample rays, per-voxel
      # rays with their fill, and the still frame that reuses the cache; PSNRs against float64 references.
      # Its "marks" line: in every view, the same image with and without the marking frame (a
      # program compiled apart from the frame's: does this GPU's compiler trace both alike?).
      for sampling in voxel trilinear; do
        t env LD_LIBRARY_PATH=/tmp/bundle/lib:$NV __EGL_VENDOR_LIBRARY_FILENAMES=$EGL_VENDOR \
          .gpu/shadow_rays foot $T/foot.vxl $tf $sampling 1000x1000 12
      done ;;
    table1)
      for grid in "256 8" "512 8" "1024 16"; do
        set -- $grid
        t $V scene build samples/scenes/dragon.scene.json -o $T/dragon$1.vxl --resolution $1 --brick $2 -q
        t $V bench-render $T/dragon$1.vxl --sizes 1000x1000 --no-reference --no-dense --samplings voxel
        t $V bench-render $T/dragon$1.vxl --sizes 1000x1000 --no-reference --no-dense --samplings voxel --effects all
        for s in house bunny-glass; do
          t $V scene build samples/scenes/$s.scene.json -o $T/$s$1.vxl --resolution $1 --brick $2 -q
          t $V bench-render $T/$s$1.vxl --sizes 1000x1000 --no-reference --no-dense --samplings voxel --effects all
        done
      done ;;
    animate)
      t $V bench-render --animate samples/scenes/dragon-animated.scene.json --resolutions 256 512 1024 \
        --bricks 4 8 16 --sizes 512x512 1000x1000 --frames 30 ;;
    foot1024)
      t env LD_LIBRARY_PATH=/tmp/bundle/lib .gpu/upsample $foot 4 $T/foot1024.raw
      t $V convert $T/foot1024.raw --dims 1024 1024 1024 --type u8 --tf $tf -o $T/foot1024.vxl -q
      t $V bench-render $T/foot1024.vxl --tf $tf --sizes 1000x1000 --no-reference --frames-per-turn 12 \
        --source $T/foot1024.raw --source-dims 1024,1024,1024 --source-type u8
      t $V bench-render $T/foot1024.vxl --tf $tf --sizes 1000x1000 --no-reference --frames-per-turn 12 \
        --shadows --no-dense
      # Voxel sampling marks before the fill at this size (docs/shadows.md): the fill of every visible voxel.
      t env VOXLINK_SHADOW_MARK=0 $V bench-render $T/foot1024.vxl --tf $tf --sizes 1000x1000 --no-reference \
        --frames-per-turn 12 --shadows --no-dense --samplings voxel ;;
    krige)
      for threads in 16 8 2; do
        t $V krige $D/samples200000.csv --x x --y y --z z --value v --variogram exp:psill=1,range=16 -k 32 \
          --dims 216,216,216 --origin 0,0,0 --spacing 0.5906976744186047,0.5906976744186047,0.5906976744186047 \
          -o $T/k.npy --threads $threads
      done ;;
    *) echo "unknown section $section" ;;
  esac
done
echo "# done $(date -u +%FT%TZ)"
