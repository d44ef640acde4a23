#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Fails, naming the files, when a tracked C++ file differs from what clang-format 14 makes of it
# (.clang-format: Google, 100 columns). Fix with: clang-format-14 -i FILE...
set -euo pipefail
cd "$(dirname "$0")/.."
format=$(command -v clang-format-14 || command -v clang-format || true)
if [ -z "$format" ]; then
  echo "check-format: clang-format-14 is not installed (scripts/install-deps.sh installs it)" >&2
  exit 1
fi
bad=()
while IFS= read -r -d '' file; do
  "$format" --dry-run -Werror "$file" >/dev/null 2>&1 || bad+=("$file")
done < <(git ls-files -z '*.h' '*.cpp')
if [ "${#bad[@]}" -gt 0 ]; then
  echo "check-format: ${#bad[@]} file(s) not formatted with $format: ${bad[*]}" >&2
  exit 1
fi
echo "check-format: every C++ file is formatted"
