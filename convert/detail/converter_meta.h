// SPDX-License-Identifier: BSD-3-Clause
// The META section of a converted file: where the volume came from, how it was classified,
// and the errors its value type and gradient codec introduced (JSON, docs/format.md).
#pragma once

#include <string>

#include "convert/converter.h"
#include "convert/detail/value_mapping.h"

namespace voxlink::convert {

using sources::VolumeInfo;

std::string metaJson(const VolumeInfo& info, const ConvertOptions& options,
                     const ValueMapping& mapping, const ConvertSummary& summary);

}  // namespace voxlink::convert
