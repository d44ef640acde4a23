// SPDX-License-Identifier: BSD-3-Clause
// Full check of a VoxLink file: every checksum and every structural invariant of docs/format.md.
// Returns the first problem found, naming file, section and field; it never aborts.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "base/error.h"
#include "base/progress.h"
#include "format/voxlink_file.h"

namespace voxlink::format {

struct ValidationReport {
  uint64_t bytesChecked = 0;
  uint64_t voxelsChecked = 0;
  uint64_t bricksChecked = 0;
};

// `progress` (may be empty) hears the fraction done after each stage and every sixteenth of the
// brick grid, weighted by the bytes each stage reads.
Result<ValidationReport> validateFile(const VoxLinkFile& file,
                                      const ProgressCallback& progress = {});

// The brick level, the bricks' rows and masks, and a scene's masks, materials and sphere
// references (no checksums, values or gradients): what code that walks the structure must know
// first, e.g. unpacking a packed file's gradients (which walks VMSK slots in a scene).
Status validateStructure(const VoxLinkFile& file);

// The CRC-32C of every section, in table order. A file of 8 MiB or more is checksummed on
// `threads` threads (0: every core; GRAD alone is about half of it); a smaller one on the calling
// thread, where starting threads would cost more than it saves.
std::vector<uint32_t> sectionChecksums(const VoxLinkFile& file, unsigned threads = 0);

}  // namespace voxlink::format
