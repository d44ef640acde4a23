// SPDX-License-Identifier: BSD-3-Clause
// Invariants and preconditions. A failed check is a bug in VoxLink, never bad input (bad input
// gets a Status): the process stops with the file, line, expression and, for the comparisons,
// both operand values, instead of running on into undefined behaviour.
//   VOXLINK_CHECK(cond) / VOXLINK_CHECK(cond, "what")   every build
//   VOXLINK_CHECK_EQ/NE/LT/LE/GT/GE(a, b)                every build; prints a and b
//   VOXLINK_DCHECK(cond), VOXLINK_DCHECK_EQ/...(a, b)    debug builds only: in NDEBUG (Release)
//       they still compile, so they cannot rot, but evaluate nothing. For hot per-voxel paths.
#pragma once

#include <concepts>
#include <ostream>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>

namespace voxlink {
inline namespace base {

[[noreturn, gnu::cold]] void checkFailed(const char* file, int line, const char* macro,
                                         const char* expression, const std::string& detail);

namespace check_detail {

// An operand as the failure message shows it: numbers as numbers (char-sized ones too),
// enums by value, anything else that streams, or a placeholder.
template <class T>
std::string describe(const T& value) {
  if constexpr (std::is_same_v<T, bool>) {
    return value ? "true" : "false";
  } else if constexpr (std::is_enum_v<T>) {
    return describe(static_cast<std::underlying_type_t<T>>(value));
  } else if constexpr (std::is_integral_v<T> && sizeof(T) == 1) {
    return std::to_string(static_cast<int>(value));
  } else if constexpr (requires(std::ostream & out) { out << value; }) {
    std::ostringstream out;
    out.precision(17);
    out << value;
    return out.str();
  } else {
    return "(not printable)";
  }
}

// Integers compare by value whatever their signedness (std::cmp_*: -1 < 0u holds), so a check
// cannot pass or fail through a conversion; everything else uses its own operators.
template <class T>
constexpr bool isComparedByValue =  // the types std::cmp_* takes: no bool, no character types
    std::is_integral_v<T> && !std::is_same_v<T, bool> && !std::is_same_v<T, char> &&
    !std::is_same_v<T, wchar_t> && !std::is_same_v<T, char8_t> && !std::is_same_v<T, char16_t> &&
    !std::is_same_v<T, char32_t>;
template <class A, class B>
constexpr bool bothIntegers = isComparedByValue<A>&& isComparedByValue<B>;

#define VOXLINK_CHECK_DETAIL_COMPARE(name, op, integers) \
  template <class A, class B>                            \
  constexpr bool name(const A& a, const B& b) {          \
    if constexpr (bothIntegers<A, B>)                    \
      return integers(a, b);                             \
    else                                                 \
      return a op b;                                     \
  }
VOXLINK_CHECK_DETAIL_COMPARE(eq, ==, std::cmp_equal)
VOXLINK_CHECK_DETAIL_COMPARE(ne, !=, std::cmp_not_equal)
VOXLINK_CHECK_DETAIL_COMPARE(lt, <, std::cmp_less)
VOXLINK_CHECK_DETAIL_COMPARE(le, <=, std::cmp_less_equal)
VOXLINK_CHECK_DETAIL_COMPARE(gt, >, std::cmp_greater)
VOXLINK_CHECK_DETAIL_COMPARE(ge, >=, std::cmp_greater_equal)
#undef VOXLINK_CHECK_DETAIL_COMPARE

template <class A, class B>
[[noreturn, gnu::cold, gnu::noinline]] void comparisonFailed(const char* file, int line,
                                                             const char* macro, const char* aText,
                                                             const char* bText, const A& a,
                                                             const B& b) {
  checkFailed(file, line, macro, (std::string(aText) + ", " + bText).c_str(),
              std::string(aText) + " = " + describe(a) + ", " + bText + " = " + describe(b));
}

}  // namespace check_detail
}  // namespace base
}  // namespace voxlink

// VOXLINK_CHECK(condition) or VOXLINK_CHECK(condition, "what went wrong").
#define VOXLINK_CHECK(condition, ...)                                         \
  do {                                                                        \
    if (!(condition)) [[unlikely]]                                            \
      ::voxlink::checkFailed(__FILE__, __LINE__, "VOXLINK_CHECK", #condition, \
                             std::string(__VA_OPT__(__VA_ARGS__)));           \
  } while (0)

#define VOXLINK_CHECK_COMPARE_DETAIL(macro, compare, a, b)                                        \
  do {                                                                                            \
    const auto& voxlinkCheckA = (a);                                                              \
    const auto& voxlinkCheckB = (b);                                                              \
    if (!::voxlink::check_detail::compare(voxlinkCheckA, voxlinkCheckB)) [[unlikely]]             \
      ::voxlink::check_detail::comparisonFailed(__FILE__, __LINE__, macro, #a, #b, voxlinkCheckA, \
                                                voxlinkCheckB);                                   \
  } while (0)

#define VOXLINK_CHECK_EQ(a, b) VOXLINK_CHECK_COMPARE_DETAIL("VOXLINK_CHECK_EQ", eq, a, b)
#define VOXLINK_CHECK_NE(a, b) VOXLINK_CHECK_COMPARE_DETAIL("VOXLINK_CHECK_NE", ne, a, b)
#define VOXLINK_CHECK_LT(a, b) VOXLINK_CHECK_COMPARE_DETAIL("VOXLINK_CHECK_LT", lt, a, b)
#define VOXLINK_CHECK_LE(a, b) VOXLINK_CHECK_COMPARE_DETAIL("VOXLINK_CHECK_LE", le, a, b)
#define VOXLINK_CHECK_GT(a, b) VOXLINK_CHECK_COMPARE_DETAIL("VOXLINK_CHECK_GT", gt, a, b)
#define VOXLINK_CHECK_GE(a, b) VOXLINK_CHECK_COMPARE_DETAIL("VOXLINK_CHECK_GE", ge, a, b)

#ifdef NDEBUG
// Type-checked inside a branch the compiler drops: nothing is evaluated.
#define VOXLINK_DCHECK_DETAIL(check) \
  do {                               \
    if constexpr (false) check;      \
  } while (0)
#else
#define VOXLINK_DCHECK_DETAIL(check) check
#endif

#define VOXLINK_DCHECK(...) VOXLINK_DCHECK_DETAIL(VOXLINK_CHECK(__VA_ARGS__))
#define VOXLINK_DCHECK_EQ(a, b) VOXLINK_DCHECK_DETAIL(VOXLINK_CHECK_EQ(a, b))
#define VOXLINK_DCHECK_NE(a, b) VOXLINK_DCHECK_DETAIL(VOXLINK_CHECK_NE(a, b))
#define VOXLINK_DCHECK_LT(a, b) VOXLINK_DCHECK_DETAIL(VOXLINK_CHECK_LT(a, b))
#define VOXLINK_DCHECK_LE(a, b) VOXLINK_DCHECK_DETAIL(VOXLINK_CHECK_LE(a, b))
#define VOXLINK_DCHECK_GT(a, b) VOXLINK_DCHECK_DETAIL(VOXLINK_CHECK_GT(a, b))
#define VOXLINK_DCHECK_GE(a, b) VOXLINK_DCHECK_DETAIL(VOXLINK_CHECK_GE(a, b))
