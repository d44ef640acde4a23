// SPDX-License-Identifier: BSD-3-Clause
// Turns one fuzz input into the files a path-taking reader opens. Readers with detached data
// (NRRD .nhdr, MetaImage .mhd, Voreen .vvd, numbered file lists) need several files, so an
// input may carry more than one: the bytes up to the first marker line are the main file, and
// each marker line "\n==> NAME <==\n" starts a file called NAME beside it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "base/error.h"
#include "sources/volume_source.h"

namespace voxlink::fuzz {

struct FuzzFile {
  std::string name;
  std::span<const uint8_t> bytes;
};

// Splits `input` at marker lines. Names that are empty, too long, "." or "..", or hold anything
// but letters, digits, '.', '_' and '-' make the marker plain data; at most 64 files.
std::vector<FuzzFile> splitFuzzFiles(std::span<const uint8_t> input, std::string mainName);

// A directory of its own for the files of one run, emptied on each use and removed at exit.
class ScratchDir {
 public:
  ScratchDir();
  ~ScratchDir();
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  // Empties the directory, writes `files` into it and returns the main (first) file's path.
  std::string write(const std::vector<FuzzFile>& files);
  const std::filesystem::path& path() const { return path_; }

 private:
  void clear();
  std::filesystem::path path_;
};

// The scratch directory every entry point in this process shares (fuzzing runs one input at
// a time).
ScratchDir& scratch();

// Reads what an opened volume serves, the way the converter does, within a memory cap: all
// slices when the volume is small, else the first and (random access) the last slice that fit.
// Returns the first error.
Status drainVolume(sources::VolumeSource& source);

}  // namespace voxlink::fuzz
