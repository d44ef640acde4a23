#include "convert/readers/image_stack_reader.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <filesystem>

#include "convert/readers/file_list.h"
#include "convert/readers/reader_common.h"
#include "convert/readers/reader_registry.h"

namespace voxlink::convert {
namespace {

namespace fs = std::filesystem;
using OIIO::ImageInput;
using OIIO::TypeDesc;

Result<ScalarType> scalarFromOiio(TypeDesc format, const std::string& file, bool& halfFloat) {
  halfFloat = false;
  switch (format.basetype) {
    case TypeDesc::UINT8:
      return ScalarType::kU8;
    case TypeDesc::INT8:
      return ScalarType::kI8;
    case TypeDesc::UINT16:
      return ScalarType::kU16;
    case TypeDesc::INT16:
      return ScalarType::kI16;
    case TypeDesc::UINT32:
      return ScalarType::kU32;
    case TypeDesc::INT32:
      return ScalarType::kI32;
    case TypeDesc::HALF:
      halfFloat = true;
      return ScalarType::kF32;
    case TypeDesc::FLOAT:
      return ScalarType::kF32;
    case TypeDesc::DOUBLE:
      return ScalarType::kF64;
    default:
      return makeError(ErrorCode::kUnsupported, file, ": pixel format ", format.c_str(),
                       " (8/16/32-bit integers and floats are supported)");
  }
}

TypeDesc oiioType(ScalarType type) {
  switch (type) {
    case ScalarType::kU8:
      return TypeDesc::UINT8;
    case ScalarType::kI8:
      return TypeDesc::INT8;
    case ScalarType::kU16:
      return TypeDesc::UINT16;
    case ScalarType::kI16:
      return TypeDesc::INT16;
    case ScalarType::kU32:
      return TypeDesc::UINT32;
    case ScalarType::kI32:
      return TypeDesc::INT32;
    case ScalarType::kF32:
      return TypeDesc::FLOAT;
    case ScalarType::kF64:
      break;
  }
  return TypeDesc::DOUBLE;
}

Result<std::unique_ptr<ImageInput>> openImage(const std::string& file) {
  auto in = ImageInput::open(file);
  if (!in)
    return makeError(ErrorCode::kCorrupt, file, ": OpenImageIO cannot open it (", OIIO::geterror(),
                     ")");
  return std::unique_ptr<ImageInput>(std::move(in));
}

// What every slice must share; the first slice sets it.
struct SliceShape {
  int width = 0, height = 0, channels = 0;
  TypeDesc format;
  std::string from;  // the file (and page) that set it
};

Status checkSlice(const OIIO::ImageSpec& spec, const std::string& where, SliceShape& shape) {
  if (spec.depth > 1)
    return makeError(ErrorCode::kUnsupported, where, ": image depth ", spec.depth,
                     " (only 2-D slices)");
  if (shape.from.empty()) {
    shape = {spec.width, spec.height, spec.nchannels, spec.format, where};
    return Status::ok();
  }
  if (spec.width != shape.width || spec.height != shape.height)
    return makeError(ErrorCode::kSizeMismatch, where, ": image size ", spec.width, "x", spec.height,
                     " differs from ", shape.width, "x", shape.height, " of ", shape.from);
  if (spec.format != shape.format || spec.nchannels != shape.channels)
    return makeError(ErrorCode::kSizeMismatch, where, ": pixel format ", spec.format.c_str(), " x ",
                     spec.nchannels, " channels differs from ", shape.format.c_str(), " x ",
                     shape.channels, " of ", shape.from);
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
    if (uint64_t{z0} + count > info_.dims[2])
      return makeError(ErrorCode::kInvalidArgument, info_.path, ": slices [", z0, ", ",
                       uint64_t{z0} + count, ") beyond z size ", info_.dims[2]);
    auto* out = static_cast<uint8_t*>(dst);
    for (uint32_t z = z0; z < z0 + count; ++z) {
      const std::string& file = multiPage_ ? files_[0] : files_[z];
      if (!multiPage_ || !input_) {
        VOXLINK_ASSIGN_OR_RETURN(input_, openImage(file));
      }
      const int subimage = multiPage_ ? static_cast<int>(z) : 0;
      if (!input_->read_image(subimage, 0, 0, 1, oiioType(info_.type),
                              out + uint64_t{z - z0} * info_.sliceBytes()))
        return makeError(ErrorCode::kCorrupt, file, multiPage_ ? cat(": page ", z) : std::string(),
                         ": cannot read pixels (", input_->geterror(), ")");
      if (!multiPage_) input_.reset();
    }
    return Status::ok();
  }

 private:
  std::vector<std::string> files_;
  bool multiPage_;
  std::unique_ptr<ImageInput> input_;
};

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
      VOXLINK_ASSIGN_OR_RETURN(auto in, openImage(file));
      VOXLINK_RETURN_IF_ERROR(checkSlice(in->spec(), file, shape));
    }
    slices = files.size();
  } else {
    files.push_back(path);
    VOXLINK_ASSIGN_OR_RETURN(auto in, openImage(path));
    for (int page = 0; in->seek_subimage(page, 0); ++page) {
      VOXLINK_RETURN_IF_ERROR(checkSlice(in->spec(), cat(path, ": page ", page), shape));
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
  bool halfFloat = false;
  VOXLINK_ASSIGN_OR_RETURN(info.type, scalarFromOiio(shape.format, shape.from, halfFloat));
  VOXLINK_RETURN_IF_ERROR(
      checkDims({uint64_t(shape.width), uint64_t(shape.height), slices}, path, "image size"));
  info.dims = {static_cast<uint32_t>(shape.width), static_cast<uint32_t>(shape.height),
               static_cast<uint32_t>(slices)};
  info.notes.push_back(folder ? cat(slices, " slice images ordered by the numbers in their names, ",
                                    fs::path(files.front()).filename().string(), " first")
                              : cat(slices, " pages of one file"));
  if (shape.channels > 1)
    info.notes.push_back(cat("images have ", shape.channels, " channels; channel 0 is read"));
  if (halfFloat) info.notes.push_back("half-float pixels are served as f32");
  info.notes.push_back("image files carry no voxel spacing: 1 1 1 unless --spacing is given");
  VOXLINK_RETURN_IF_ERROR(applyOpenOptions(info, options));
  return std::unique_ptr<VolumeSource>(
      new ImageStackSource(std::move(info), std::move(files), !folder));
}

}  // namespace voxlink::convert
