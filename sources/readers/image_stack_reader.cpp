// SPDX-License-Identifier: BSD-3-Clause
#include "sources/readers/image_stack_reader.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "base/limits.h"
#include "base/regular_file.h"
#include "imageio/image_io.h"
#include "sources/readers/detail/file_list.h"
#include "sources/readers/detail/reader_registry.h"
#include "sources/readers/reader_common.h"

namespace voxlink::sources {
namespace {

namespace fs = std::filesystem;

// What every slice must share; the first slice sets it.
struct SliceShape {
  imageio::ImageSpec spec;
  std::string from;  // the file (and page) that set it
};

Status checkSlice(const imageio::ImageSpec& spec, const std::string& where, SliceShape& shape) {
  if (spec.depth > 1)
    return makeError(ErrorCode::kUnsupported, where, ": image depth ", spec.depth,
                     " (only 2-D slices)");
  if (!spec.supportedType)
    return makeError(ErrorCode::kUnsupported, where, ": pixel format ", spec.formatName,
                     " (8/16/32-bit integers and floats are supported)");
  if (shape.from.empty()) {
    shape = {spec, where};
    return Status::ok();
  }
  const imageio::ImageSpec& first = shape.spec;
  if (spec.width != first.width || spec.height != first.height)
    return makeError(ErrorCode::kSizeMismatch, where, ": image size ", spec.width, "x", spec.height,
                     " differs from ", first.width, "x", first.height, " of ", shape.from);
  if (spec.formatName != first.formatName || spec.channels != first.channels)
    return makeError(ErrorCode::kSizeMismatch, where, ": pixel format ", spec.formatName, " x ",
                     spec.channels, " channels differs from ", first.formatName, " x ",
                     first.channels, " of ", shape.from);
  return Status::ok();
}

// A PNG's pixels are zlib-compressed, which expands at most limits::kMaxZlibRatio to 1: a file
// too small for the size its header claims is refused before a slab of that size is allocated
// (a 65-byte PNG claiming 60000 x 60000 x 16 bit made the converter allocate 7.2 GB first).
Status checkPngCanHoldItsPixels(const std::string& file, const imageio::ImageSpec& spec) {
  if (lowerExtension(file) != ".png") return Status::ok();
  std::error_code ec;
  const uint64_t fileBytes = fs::file_size(file, ec);
  if (ec) return Status::ok();  // probe() read it; the read reports what went wrong
  const uint64_t pixelBytes = uint64_t(spec.width) * uint64_t(spec.height) *
                              uint64_t(std::max(spec.channels, 1)) * scalarSize(spec.type);
  if (pixelBytes / limits::kMaxZlibRatio > fileBytes)
    return makeError(ErrorCode::kTruncated, file, ": image size ", spec.width, "x", spec.height,
                     " needs ", pixelBytes, " bytes of pixels; a PNG of ", fileBytes,
                     " bytes cannot hold them (zlib expands at most ", limits::kMaxZlibRatio,
                     ":1)");
  return Status::ok();
}

class ImageStackSource final : public VolumeSource {
 public:
  // `files`: one per slice, or the single multi-page file.
  ImageStackSource(VolumeInfo info, std::vector<std::string> files, bool multiPage)
      : files_(std::move(files)), multiPage_(multiPage) {
    info_ = std::move(info);
  }

  bool randomAccess() const override { return true; }

  Status read(uint32_t z0, uint32_t count, void* dst) override {
    VOXLINK_RETURN_IF_ERROR(checkSliceRange(z0, count));
    auto* out = static_cast<uint8_t*>(dst);
    for (uint32_t z = z0; z < z0 + count; ++z) {
      const std::string& file = multiPage_ ? files_[0] : files_[z];
      const int subimage = multiPage_ ? static_cast<int>(z) : 0;
      VOXLINK_RETURN_IF_ERROR(imageio::read(file, subimage, 1, info_.type,
                                            out + uint64_t{z - z0} * info_.sliceBytes()));
    }
    return Status::ok();
  }

 private:
  std::vector<std::string> files_;
  bool multiPage_;
};

// Netpbm headers: OpenImageIO accepts maxval 0 (every pixel would divide by zero) silently.
// "P2"/"P5" (and P3/P6), then width, height and maxval as decimal words; '#' starts a comment.
Status checkNetpbmHeader(const std::string& file) {
  const std::string ext = lowerExtension(file);
  if (ext != ".pgm" && ext != ".pnm" && ext != ".ppm") return Status::ok();
  VOXLINK_ASSIGN_OR_RETURN(std::string head, base::readRegularFilePrefix(file, 1024));
  if (head.size() < 2 || head[0] != 'P' || head[1] < '1' || head[1] > '6') return Status::ok();
  if (head[1] == '1' || head[1] == '4') return Status::ok();  // bitmaps have no maxval
  size_t at = 2;
  uint64_t words[3] = {0, 0, 0};
  for (uint64_t& w : words) {
    for (;;) {
      while (at < head.size() && std::isspace(static_cast<unsigned char>(head[at]))) ++at;
      if (at < head.size() && head[at] == '#') {
        while (at < head.size() && head[at] != '\n') ++at;
        continue;
      }
      break;
    }
    const size_t start = at;
    while (at < head.size() && std::isdigit(static_cast<unsigned char>(head[at])) && w < 1000000)
      w = w * 10 + static_cast<uint64_t>(head[at++] - '0');
    if (at == start) return Status::ok();  // not a header we can read: the image library decides
  }
  if (words[2] == 0 || words[2] > 65535)
    return makeError(ErrorCode::kCorrupt, file, ": Netpbm header field 'maxval': ", words[2],
                     ", expected 1..65535");
  return Status::ok();
}

}  // namespace

bool isSliceImageName(const std::string& path) {
  static const char* kExtensions[] = {".tif", ".tiff", ".png", ".pgm", ".pnm",
                                      ".jpg", ".jpeg", ".bmp", ".exr"};
  const std::string ext = lowerExtension(path);
  return std::any_of(std::begin(kExtensions), std::end(kExtensions),
                     [&](const char* e) { return ext == e; });
}

Result<std::unique_ptr<VolumeSource>> openImageStack(const std::string& path,
                                                     const OpenOptions& options) {
  std::vector<std::string> files;
  SliceShape shape;
  uint64_t slices = 0;
  std::error_code ec;
  const bool folder = fs::is_directory(path, ec);
  if (folder) {
    for (const auto& entry : fs::directory_iterator(path, ec))
      if (entry.is_regular_file(ec) && isSliceImageName(entry.path().string()))
        files.push_back(entry.path().string());
    if (files.empty())
      return makeError(ErrorCode::kCorrupt, path,
                       ": no slice images (.tif, .png, ...) in the folder");
    std::sort(files.begin(), files.end(), [](const std::string& a, const std::string& b) {
      return naturalLess(fs::path(a).filename().string(), fs::path(b).filename().string());
    });
    for (const std::string& file : files) {
      VOXLINK_RETURN_IF_ERROR(checkNetpbmHeader(file));
      VOXLINK_ASSIGN_OR_RETURN(imageio::ImageSpec spec, imageio::probe(file));
      VOXLINK_RETURN_IF_ERROR(checkSlice(spec, file, shape));
      VOXLINK_RETURN_IF_ERROR(checkPngCanHoldItsPixels(file, spec));
    }
    slices = files.size();
  } else {
    files.push_back(path);
    VOXLINK_RETURN_IF_ERROR(checkNetpbmHeader(path));
    VOXLINK_ASSIGN_OR_RETURN(int pages, imageio::subimageCount(path));
    for (int page = 0; page < pages; ++page) {
      VOXLINK_ASSIGN_OR_RETURN(imageio::ImageSpec spec, imageio::probe(path, page));
      VOXLINK_RETURN_IF_ERROR(checkSlice(spec, cat(path, ": page ", page), shape));
      ++slices;
    }
    if (slices < 2)
      return makeError(ErrorCode::kUnsupported, path,
                       ": one page: a 2-D image, not a volume (give a "
                       "multi-page TIFF or a folder of slices)");
  }

  VolumeInfo info;
  info.path = path;
  info.format = "image-stack";
  info.files = files;
  const imageio::ImageSpec& first = shape.spec;
  info.type = first.type;
  const bool halfFloat = first.halfFloat;
  VOXLINK_RETURN_IF_ERROR(
      checkDims({uint64_t(first.width), uint64_t(first.height), slices}, path, "image size"));
  info.dims = {static_cast<uint32_t>(first.width), static_cast<uint32_t>(first.height),
               static_cast<uint32_t>(slices)};
  info.notes.push_back(folder ? cat(slices, " slice images ordered by the numbers in their names, ",
                                    fs::path(files.front()).filename().string(), " first")
                              : cat(slices, " pages of one file"));
  if (first.channels > 1)
    info.notes.push_back(cat("images have ", first.channels, " channels; channel 0 is read"));
  if (halfFloat) info.notes.push_back("half-float pixels are served as f32");
  info.notes.push_back("image files carry no voxel spacing: 1 1 1 unless --spacing is given");
  VOXLINK_RETURN_IF_ERROR(applyOpenOptions(info, options));
  return std::unique_ptr<VolumeSource>(
      new ImageStackSource(std::move(info), std::move(files), !folder));
}

}  // namespace voxlink::sources
