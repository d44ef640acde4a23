// SPDX-License-Identifier: BSD-3-Clause
// Options that `voxlink render`, `bench-render` and `view` share: the flags of
// render/render_options.h (image size, camera, transfer function, sampling and shading), and
// --source for the dense peer.
#pragma once

#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include "format/voxlink_file.h"
#include "render/render_options.h"
#include "sources/volume_source.h"
#include "tf/transfer_function.h"

namespace voxlink::cli {

// The render options as command-line flags.
struct RenderOptions : render::RenderOptions {
  // Registers the options on `cmd`; `withSize` is false for commands with their own size flag.
  void add(CLI::App* cmd, bool withSize = true);
};

// --source PATH [--source-dims X,Y,Z --source-type T]: the dense volume for the reference and the
// dense peer, when META's record is not wanted (or a raw file needs its dims and type).
struct SourceOptions {
  std::string path;
  std::string dims;
  std::string type;

  void add(CLI::App* cmd);
  Result<sources::OpenOptions> openOptions() const;
};

}  // namespace voxlink::cli
