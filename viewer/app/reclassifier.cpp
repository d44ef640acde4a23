// SPDX-License-Identifier: BSD-3-Clause
#include "viewer/app/detail/reclassifier.h"

#include <filesystem>

#include "convert/classification.h"
#include "convert/converter.h"
#include "render/recorded_source.h"

namespace voxlink::viewer {

using render::RecordedSource;
using render::recordedSource;

Reclassifier::~Reclassifier() {
  cancel();
  join();
}

void Reclassifier::join() {
  if (thread_.joinable()) thread_.join();
}

std::string Reclassifier::outputPathFor(const std::string& path) {
  namespace fs = std::filesystem;
  const fs::path p(path);
  std::string stem = p.stem().string();
  const std::string suffix = ".reclassified";
  if (stem.size() < suffix.size() ||
      stem.compare(stem.size() - suffix.size(), suffix.size(), suffix) != 0)
    stem += suffix;
  return (p.parent_path() / (stem + ".vxl")).string();
}

std::string Reclassifier::stage() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return stage_;
}

std::optional<Result<std::string>> Reclassifier::takeResult() {
  if (running_.load()) return std::nullopt;
  join();
  std::lock_guard<std::mutex> lock(mutex_);
  auto r = std::move(result_);
  result_.reset();
  return r;
}

Status Reclassifier::start(const format::VoxLinkFile& file, const tf::TransferFunction& tf,
                           const std::string& outputPath) {
  if (running_.load())
    return makeError(ErrorCode::kInvalidArgument, "re-classification is already running");
  join();
  VOXLINK_ASSIGN_OR_RETURN(RecordedSource source, recordedSource(file));
  convert::ConvertOptions options;
  options.brickSize = file.brickSize();
  options.axis = file.predominantAxis();
  options.classification = convert::tfClassification(tf);
  options.sourceOptions = source.options;
  cancel_.store(false);
  progress_.store(0.0);
  running_.store(true);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stage_ = "opening " + source.path;
    result_.reset();
  }
  thread_ = std::thread([this, source, options, outputPath]() mutable {
    options.cancel = &cancel_;
    options.progress = [this](double fraction, const char* stage) {
      progress_.store(fraction);
      std::lock_guard<std::mutex> lock(mutex_);
      stage_ = stage;
    };
    Result<std::string> result = [&]() -> Result<std::string> {
      VOXLINK_ASSIGN_OR_RETURN(auto volume, sources::openVolume(source.path, source.options));
      VOXLINK_RETURN_IF_ERROR(convert::convertVolume(*volume, options, outputPath).status());
      return outputPath;
    }();
    {
      std::lock_guard<std::mutex> lock(mutex_);
      result_ = std::move(result);
    }
    running_.store(false);
  });
  return Status::ok();
}

}  // namespace voxlink::viewer
