// SPDX-License-Identifier: BSD-3-Clause
#include "render/gl/dense_renderer.h"

#include <cmath>
#include <cstring>

#include "base/parallel_for.h"
#include "format/gradient_codec.h"
#include "format/half.h"

namespace voxlink::render::gl {

namespace {

constexpr GLint kValuesUnit = 2;
constexpr GLint kGradientsUnit = 3;

uint32_t storedBitsOf(double value, const VolumeGeometry& m) {
  const double stored = (value - m.valueOffset) / m.valueScale;
  switch (m.valueType) {
    case StoredType::kU8:
      return uint32_t(std::clamp(std::lround(stored), 0L, 255L));
    case StoredType::kU16:
      return uint32_t(std::clamp(std::lround(stored), 0L, 65535L));
    case StoredType::kF16:
      return format::floatToHalf(float(stored));
    case StoredType::kF32:
      break;
  }
  const float f = float(stored);
  uint32_t bits;
  std::memcpy(&bits, &f, 4);
  return bits;
}

template <class T>
GlTexture upload3d(GLenum internalFormat, GLenum format, GLenum type, const std::vector<T>& data,
                   const std::array<uint32_t, 3>& dims) {
  GlTexture t = createTexture(GL_TEXTURE_3D);
  glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);  // integer textures: no filtering
  glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureStorage3D(t.id(), 1, internalFormat, GLsizei(dims[0]), GLsizei(dims[1]),
                     GLsizei(dims[2]));
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage3D(t.id(), 0, 0, 0, 0, GLsizei(dims[0]), GLsizei(dims[1]), GLsizei(dims[2]),
                      format, type, data.data());
  return t;
}

}  // namespace

Result<std::unique_ptr<DenseRenderer>> DenseRenderer::create(const DenseVolume& volume,
                                                             const VolumeGeometry& mapping) {
  GLint maxSide = 0;
  glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &maxSide);
  for (uint32_t d : volume.dims)
    if (d == 0 || d > uint32_t(maxSide))
      return makeError(ErrorCode::kTooLarge, "dense renderer: dims ", volume.dims[0], "x",
                       volume.dims[1], "x", volume.dims[2], " exceed the 3D texture limit ",
                       maxSide);
  VolumeGeometry g = mapping;
  g.dims = volume.dims;
  g.spacing = volume.spacing;
  g.origin = volume.origin;
  // Every value of the source, not only those a VoxLink file kept: the whole TF table.
  g.firstValueBits = 0;
  g.valueBitsCount = 0;
  std::unique_ptr<DenseRenderer> r(new DenseRenderer(g));
  const size_t n = volume.values.size();
  std::vector<uint16_t> codes(n);
  base::parallelFor(volume.dims[2], 0, [&](uint64_t z64) {
    const auto z = static_cast<uint32_t>(z64);
    for (uint32_t y = 0; y < volume.dims[1]; ++y)
      for (uint32_t x = 0; x < volume.dims[0]; ++x) {
        const glm::dvec3 gr = volume.gradient(x, y, z);
        codes[volume.index(x, y, z)] = format::encodeGradient(gr.x, gr.y, gr.z);
      }
  });
  r->gradients_ = upload3d(GL_R16UI, GL_RED_INTEGER, GL_UNSIGNED_SHORT, codes, volume.dims);
  const size_t valueBytes = storedSize(g.valueType);
  if (valueBytes == 1) {
    std::vector<uint8_t> v(n);
    for (size_t i = 0; i < n; ++i) v[i] = uint8_t(storedBitsOf(volume.values[i], g));
    r->values_ = upload3d(GL_R8UI, GL_RED_INTEGER, GL_UNSIGNED_BYTE, v, volume.dims);
  } else if (valueBytes == 2) {
    std::vector<uint16_t> v(n);
    for (size_t i = 0; i < n; ++i) v[i] = uint16_t(storedBitsOf(volume.values[i], g));
    r->values_ = upload3d(GL_R16UI, GL_RED_INTEGER, GL_UNSIGNED_SHORT, v, volume.dims);
  } else {
    std::vector<uint32_t> v(n);
    for (size_t i = 0; i < n; ++i) v[i] = storedBitsOf(volume.values[i], g);
    r->values_ = upload3d(GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, v, volume.dims);
  }
  r->bytes_ = n * (valueBytes + 2);
  if (const GLenum e = glGetError(); e != GL_NO_ERROR)
    return makeError(ErrorCode::kTooLarge, "dense renderer: the GL refused the 3D textures (0x",
                     std::hex, e, ")");
  return r;
}

void DenseRenderer::bindData(const ComputeProgram& program) const {
  glBindTextureUnit(kValuesUnit, values_.id());
  glBindTextureUnit(kGradientsUnit, gradients_.id());
  glUniform1i(program.uniform("uDenseValues"), kValuesUnit);
  glUniform1i(program.uniform("uDenseGradients"), kGradientsUnit);
}

}  // namespace voxlink::render::gl
