// SPDX-License-Identifier: BSD-3-Clause
// libvoxlink_imageio_oiio.so: every call to OpenImageIO in VoxLink is in this file.
#include <OpenImageIO/imageio.h>

#include <string>

#include "imageio/imageio_plugin_api.h"

namespace voxlink::plugins {

using imageio::ImageSpec;

namespace {

using OIIO::TypeDesc;

TypeDesc toOiio(ScalarType type) {
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

ImageSpec fromOiio(const OIIO::ImageSpec& s) {
  ImageSpec spec;
  spec.width = s.width;
  spec.height = s.height;
  spec.depth = s.depth;
  spec.channels = s.nchannels;
  spec.formatName = s.format.c_str();
  switch (s.format.basetype) {
    case TypeDesc::UINT8:
      spec.type = ScalarType::kU8;
      break;
    case TypeDesc::INT8:
      spec.type = ScalarType::kI8;
      break;
    case TypeDesc::UINT16:
      spec.type = ScalarType::kU16;
      break;
    case TypeDesc::INT16:
      spec.type = ScalarType::kI16;
      break;
    case TypeDesc::UINT32:
      spec.type = ScalarType::kU32;
      break;
    case TypeDesc::INT32:
      spec.type = ScalarType::kI32;
      break;
    case TypeDesc::HALF:
      spec.type = ScalarType::kF32;
      spec.halfFloat = true;
      break;
    case TypeDesc::FLOAT:
      spec.type = ScalarType::kF32;
      break;
    case TypeDesc::DOUBLE:
      spec.type = ScalarType::kF64;
      break;
    default:
      spec.supportedType = false;
      break;
  }
  return spec;
}

// OpenImageIO's error text can span lines (libpng's warnings, then the error); our messages are
// one line, so the lines are joined with "; ".
std::string oneLine(const std::string& text) {
  std::string out;
  size_t start = 0;
  while (start <= text.size()) {
    size_t end = text.find_first_of("\r\n", start);
    if (end == std::string::npos) end = text.size();
    if (end > start) out += (out.empty() ? "" : "; ") + text.substr(start, end - start);
    start = end + 1;
  }
  return out;
}

Result<std::unique_ptr<OIIO::ImageInput>> openInput(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in)
    return makeError(ErrorCode::kCorrupt, path, ": OpenImageIO cannot open it (",
                     oneLine(OIIO::geterror()), ")");
  return std::unique_ptr<OIIO::ImageInput>(std::move(in));
}

Result<ImageSpec> oiioProbe(const std::string& path, int subimage) {
  VOXLINK_ASSIGN_OR_RETURN(auto in, openInput(path));
  if (!in->seek_subimage(subimage, 0))
    return makeError(ErrorCode::kInvalidArgument, path, ": no page ", subimage);
  return fromOiio(in->spec());
}

Result<int> oiioSubimageCount(const std::string& path) {
  VOXLINK_ASSIGN_OR_RETURN(auto in, openInput(path));
  int count = 0;
  while (in->seek_subimage(count, 0)) ++count;
  return count;
}

Status oiioRead(const std::string& path, int subimage, int channels, ScalarType as, void* dst) {
  VOXLINK_ASSIGN_OR_RETURN(auto in, openInput(path));
  if (!in->read_image(subimage, 0, 0, channels, toOiio(as), dst))
    return makeError(ErrorCode::kCorrupt, path, subimage ? cat(": page ", subimage) : std::string(),
                     ": cannot read pixels (", oneLine(in->geterror()), ")");
  return Status::ok();
}

Status oiioWrite(const std::string& path, int width, int height, int channels, ScalarType from,
                 const void* pixels, bool halfFloat, const char* colorSpace) {
  auto out = OIIO::ImageOutput::create(path);
  if (!out)
    return makeError(ErrorCode::kUnsupported, path, ": OpenImageIO cannot write this file type (",
                     oneLine(OIIO::geterror()), ")");
  OIIO::ImageSpec spec(width, height, channels, halfFloat ? TypeDesc::HALF : TypeDesc::UINT8);
  if (colorSpace) spec.attribute("oiio:ColorSpace", colorSpace);
  if (!out->open(path, spec))
    return makeError(ErrorCode::kIo, path, ": cannot open for writing: ", oneLine(out->geterror()));
  if (!out->write_image(toOiio(from), pixels))
    return makeError(ErrorCode::kIo, path, ": write failed: ", oneLine(out->geterror()));
  if (!out->close())
    return makeError(ErrorCode::kIo, path, ": close failed: ", oneLine(out->geterror()));
  return Status::ok();
}

}  // namespace
}  // namespace voxlink::plugins

const voxlink::imageio::ImageIoPluginApi* voxlink_imageio_plugin() {
  namespace plugin = voxlink::plugins;
  static const voxlink::imageio::ImageIoPluginApi api{
      &plugin::oiioProbe, &plugin::oiioSubimageCount, &plugin::oiioRead, &plugin::oiioWrite};
  return &api;
}
