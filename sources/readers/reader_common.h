// SPDX-License-Identifier: BSD-3-Clause
// Checks every header-driven reader applies to the VolumeInfo it built: sane dims, and the
// command line's --dims/--type (must agree with the header) and --spacing (overrides it).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

#include "base/checked_math.h"
#include "base/limits.h"
#include "sources/volume_source.h"

namespace voxlink::sources {

// kCorrupt for a zero axis, kTooLarge for an axis beyond limits::kMaxAxis or a volume beyond
// limits::kMaxVoxels (base/limits.h); `field` names the header field or option.
Status checkDims(const std::array<uint64_t, 3>& dims, const std::string& file,
                 std::string_view field);

// checkDims on a VolumeInfo a reader built; every opened volume passes it (openVolume), so
// voxelCount() * scalarSize() cannot overflow anywhere downstream.
Status checkVolumeShape(const VolumeInfo& info, std::string_view field);

// Applies OpenOptions to a header's VolumeInfo: kInvalidArgument when --dims or --type
// disagree with the header; --spacing replaces the header spacing (with a note).
Status applyOpenOptions(VolumeInfo& info, const OpenOptions& options);

// Spacing must be finite and positive; `field` names where it came from.
Status checkSpacing(const std::array<double, 3>& spacing, const std::string& file,
                    std::string_view field);

// The origin must be finite; `field` names where it came from.
Status checkOrigin(const std::array<double, 3>& origin, const std::string& file,
                   std::string_view field);

// True when the first bytes of `path` are `magic` (false for unreadable files and directories).
bool fileStartsWith(const std::string& path, std::string_view magic);

}  // namespace voxlink::sources
