#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Times the README's main job (scripts/run-sample.sh) as a new user meets it: a fresh clone of
# this checkout's HEAD, no compiler cache (CCACHE_DISABLE=1). Prints the seconds. Run as root.
#   bash scripts/time-first-run.sh            # packages already installed on this machine
#   bash scripts/time-first-run.sh --fresh    # also apt: a new Debian 12 (debootstrap minbase,
#                                             # not timed) in a temporary chroot
# The job's own output goes to $TMPDIR/time-first-run.log.
set -euo pipefail
cd "$(dirname "$0")/.."
fresh=0
case "${1:-}" in
  --fresh) fresh=1 ;;
  "") ;;
  *)
    echo "usage: $0 [--fresh]" >&2
    exit 2
    ;;
esac
work=$(mktemp -d)
log=${TMPDIR:-/tmp}/time-first-run.log
mounted=()
cleanup() {
  for ((i = ${#mounted[@]} - 1; i >= 0; i--)); do umount "${mounted[i]}"; done
  rm -rf "$work"
}
trap cleanup EXIT

if [ "$fresh" = 0 ]; then
  git clone --quiet . "$work/voxlink"
  cd "$work/voxlink"
  start=$(date +%s.%N)
  CCACHE_DISABLE=1 bash scripts/run-sample.sh > "$log" 2>&1
else
  command -v debootstrap > /dev/null || apt-get install -y --no-install-recommends debootstrap
  root=$work/root
  debootstrap --variant=minbase bookworm "$root" http://deb.debian.org/debian > "$log" 2>&1
  # The same package sources as this machine (bookworm, -updates, -security).
  if [ -d /etc/apt/sources.list.d ]; then cp -r /etc/apt/sources.list.d/. "$root/etc/apt/sources.list.d/"; fi
  if [ -f /etc/apt/sources.list ]; then cp /etc/apt/sources.list "$root/etc/apt/"; fi
  mount -t proc proc "$root/proc" && mounted+=("$root/proc")
  mount --bind /dev "$root/dev" && mounted+=("$root/dev")
  git clone --quiet . "$root/root/voxlink"
  start=$(date +%s.%N)
  chroot "$root" env CCACHE_DISABLE=1 bash /root/voxlink/scripts/run-sample.sh >> "$log" 2>&1
fi
end=$(date +%s.%N)
echo "main job: $(awk "BEGIN { printf \"%.0f\", $end - $start }") s ($([ "$fresh" = 1 ] && echo "fresh Debian 12, apt included" || echo "packages installed"), cold compiler cache, $(nproc) cores; log $log)"
