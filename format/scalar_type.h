// SPDX-License-Identifier: BSD-3-Clause
// Element types of dense source volumes and of the values stored in a VoxLink file.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

namespace voxlink {

// Type of a dense source volume's elements. The numbers are written to files: never renumber.
enum class ScalarType : uint8_t {
  kU8 = 1,
  kI8 = 2,
  kU16 = 3,
  kI16 = 4,
  kU32 = 5,
  kI32 = 6,
  kF32 = 7,
  kF64 = 8,
};

size_t scalarSize(ScalarType type);
bool isFloat(ScalarType type);
bool isSigned(ScalarType type);
std::string_view scalarName(ScalarType type);  // "u8", "i16", "f32", ...
std::optional<ScalarType> parseScalarName(std::string_view name);
bool isValidScalarType(uint8_t raw);

// Calls f(T{}) with the C++ type that corresponds to `type`.
template <class F>
decltype(auto) dispatchScalar(ScalarType type, F&& f) {
  switch (type) {
    case ScalarType::kU8:
      return f(uint8_t{});
    case ScalarType::kI8:
      return f(int8_t{});
    case ScalarType::kU16:
      return f(uint16_t{});
    case ScalarType::kI16:
      return f(int16_t{});
    case ScalarType::kU32:
      return f(uint32_t{});
    case ScalarType::kI32:
      return f(int32_t{});
    case ScalarType::kF32:
      return f(float{});
    case ScalarType::kF64:
      break;
  }
  return f(double{});
}

template <class T>
constexpr ScalarType scalarTypeOf();
template <>
constexpr ScalarType scalarTypeOf<uint8_t>() {
  return ScalarType::kU8;
}
template <>
constexpr ScalarType scalarTypeOf<int8_t>() {
  return ScalarType::kI8;
}
template <>
constexpr ScalarType scalarTypeOf<uint16_t>() {
  return ScalarType::kU16;
}
template <>
constexpr ScalarType scalarTypeOf<int16_t>() {
  return ScalarType::kI16;
}
template <>
constexpr ScalarType scalarTypeOf<uint32_t>() {
  return ScalarType::kU32;
}
template <>
constexpr ScalarType scalarTypeOf<int32_t>() {
  return ScalarType::kI32;
}
template <>
constexpr ScalarType scalarTypeOf<float>() {
  return ScalarType::kF32;
}
template <>
constexpr ScalarType scalarTypeOf<double>() {
  return ScalarType::kF64;
}

// How voxel values are held in the file's VALU section. Written to files: never renumber.
enum class StoredType : uint8_t {
  kU8 = 1,   // source = stored * valueScale + valueOffset
  kU16 = 2,  // source = stored * valueScale + valueOffset
  kF16 = 3,  // IEEE half; source = stored * valueScale + valueOffset
  kF32 = 4,  // IEEE single; source = stored * valueScale + valueOffset
};

size_t storedSize(StoredType type);
std::string_view storedName(StoredType type);
std::optional<StoredType> parseStoredName(std::string_view name);
bool isValidStoredType(uint8_t raw);
// A stored value as a double, before valueScale/valueOffset: `bits` holds it in its low bytes
// (u8, u16 and f16 in the low 8/16 bits, f32 as its bit pattern).
double storedBitsValue(StoredType type, uint32_t bits);

}  // namespace voxlink
