// SPDX-License-Identifier: BSD-3-Clause
// GL reports a failed allocation (a texture or buffer too large for the driver) only through
// glGetError. Renderers check right after allocating, so that a frame is not dispatched into
// nothing for a minute and then reported as a bare error code.
#pragma once

#include <string>

#include "base/error.h"

namespace voxlink::render::gl {

// Drops errors left by earlier calls, so that the next check sees only what follows.
void discardPendingGlErrors();

// OK, or kTooLarge: "render: GL cannot allocate WHAT (DETAILGL error 0x505, out of memory);
// render a smaller image".
Status checkGlAllocation(const std::string& what, const std::string& detail = "");

}  // namespace voxlink::render::gl
