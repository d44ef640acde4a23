// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "base/error.h"
#include "format/voxlink_file.h"

// Opening a .vxl that may be packed: what every reader of files calls. format/ reads plain
// files only; a packed file (pack/packed_file.h) is unpacked here, into memory, at most
// limits::kMaxUnpackedBytes.
namespace voxlink::pack {

// format::VoxLinkFile::open(), or the unpacked file.
Result<format::VoxLinkFile> openFile(const std::string& path);
// format::VoxLinkFile::read() (a private copy, for long-lived handles), or the unpacked file.
Result<format::VoxLinkFile> readFile(const std::string& path);
// format::VoxLinkFile::fromBytes(), or the unpacked file; `name` is used in error messages.
Result<format::VoxLinkFile> fileFromBytes(std::vector<uint8_t> bytes, const std::string& name);

// openFile() then format::validateFile(): what every command that reads a .vxl (render, view,
// info, bench-render) uses, so a file `voxlink validate` rejects is refused with the same
// message and never reaches a renderer that trusts its invariants.
Result<format::VoxLinkFile> openValidatedFile(const std::string& path);
// readFile() then format::validateFile(): the same for long-lived handles (a private copy).
Result<format::VoxLinkFile> readValidatedFile(const std::string& path);

}  // namespace voxlink::pack
