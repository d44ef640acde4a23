// SPDX-License-Identifier: BSD-3-Clause
// The names of the surface modes (format/layout.h, SurfaceMode) in one place: `scene build
// --surface` takes them, and whatever lists the modes (reports, benchmarks) reads them here.
#pragma once

#include <array>
#include <optional>
#include <string_view>

#include "format/layout.h"

namespace voxlink::format {

inline constexpr std::array<std::string_view, 3> kSurfaceModeNames = {"mean", "planes",
                                                                      "triangles"};

constexpr std::string_view surfaceModeName(SurfaceMode mode) {
  const auto i = static_cast<uint32_t>(mode);
  return i < kSurfaceModeNames.size() ? kSurfaceModeNames[i] : std::string_view("unknown");
}

constexpr std::optional<SurfaceMode> parseSurfaceMode(std::string_view name) {
  for (uint32_t i = 0; i < kSurfaceModeNames.size(); ++i)
    if (kSurfaceModeNames[i] == name) return static_cast<SurfaceMode>(i);
  return std::nullopt;
}

}  // namespace voxlink::format
