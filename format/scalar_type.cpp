// SPDX-License-Identifier: BSD-3-Clause
#include "format/scalar_type.h"

#include <cstring>

#include "format/half.h"

namespace voxlink {

size_t scalarSize(ScalarType type) {
  return dispatchScalar(type, [](auto v) { return sizeof(v); });
}

bool isFloat(ScalarType type) { return type == ScalarType::kF32 || type == ScalarType::kF64; }

bool isSigned(ScalarType type) {
  return type == ScalarType::kI8 || type == ScalarType::kI16 || type == ScalarType::kI32 ||
         isFloat(type);
}

std::string_view scalarName(ScalarType type) {
  switch (type) {
    case ScalarType::kU8:
      return "u8";
    case ScalarType::kI8:
      return "i8";
    case ScalarType::kU16:
      return "u16";
    case ScalarType::kI16:
      return "i16";
    case ScalarType::kU32:
      return "u32";
    case ScalarType::kI32:
      return "i32";
    case ScalarType::kF32:
      return "f32";
    case ScalarType::kF64:
      return "f64";
  }
  return "?";
}

std::optional<ScalarType> parseScalarName(std::string_view name) {
  for (uint8_t raw = 1; raw <= 8; ++raw) {
    auto type = static_cast<ScalarType>(raw);
    if (scalarName(type) == name) return type;
  }
  return std::nullopt;
}

bool isValidScalarType(uint8_t raw) { return raw >= 1 && raw <= 8; }

size_t storedSize(StoredType type) {
  switch (type) {
    case StoredType::kU8:
      return 1;
    case StoredType::kU16:
      return 2;
    case StoredType::kF16:
      return 2;
    case StoredType::kF32:
      return 4;
  }
  return 0;
}

std::string_view storedName(StoredType type) {
  switch (type) {
    case StoredType::kU8:
      return "u8";
    case StoredType::kU16:
      return "u16";
    case StoredType::kF16:
      return "f16";
    case StoredType::kF32:
      return "f32";
  }
  return "?";
}

std::optional<StoredType> parseStoredName(std::string_view name) {
  for (uint8_t raw = 1; raw <= 4; ++raw) {
    auto type = static_cast<StoredType>(raw);
    if (storedName(type) == name) return type;
  }
  return std::nullopt;
}

bool isValidStoredType(uint8_t raw) { return raw >= 1 && raw <= 4; }

double storedBitsValue(StoredType type, uint32_t bits) {
  switch (type) {
    case StoredType::kU8:
      return bits & 0xFF;
    case StoredType::kU16:
      return bits & 0xFFFF;
    case StoredType::kF16:
      return format::halfToFloat(static_cast<uint16_t>(bits));
    case StoredType::kF32: {
      float f;
      std::memcpy(&f, &bits, 4);
      return f;
    }
  }
  return 0;
}

}  // namespace voxlink
