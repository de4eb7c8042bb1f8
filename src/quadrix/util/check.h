// Internal invariants (STYLE.md, errors tier 3): checks that print the values involved and abort.
// A failed check is a bug in Quadrix, never the user's input: user errors go to Diagnostics.
//
//   QUADRIX_CHECK(cond, "what", values...)   e.g. QUADRIX_CHECK(i < n, "index {} of {}", i, n)
//   QUADRIX_CHECK_EQ(a, b) / _NE / _LT / _LE  print both operands
//   QUADRIX_DCHECK...(...)                     the same, compiled out in release (NDEBUG) builds
#pragma once

#include <fmt/format.h>

#include <cstdio>
#include <cstdlib>

namespace quadrix::detail {

[[noreturn]] inline void CheckFailed(const char* file, int line, const char* condition,
                                     const std::string& detail) {
    std::fprintf(stderr, "%s:%d: internal error: check failed: %s%s%s\n", file, line, condition,
                 detail.empty() ? "" : ": ", detail.c_str());
    std::fflush(stderr);
    std::abort();
}

}  // namespace quadrix::detail

#define QUADRIX_CHECK(cond, ...)                                                          \
    do {                                                                                  \
        if (!(cond)) [[unlikely]]                                                         \
            ::quadrix::detail::CheckFailed(__FILE__, __LINE__, #cond,                     \
                                           ::fmt::format("" __VA_OPT__(, ) __VA_ARGS__)); \
    } while (0)

#define QUADRIX_CHECK_OP(a, op, b)                                          \
    do {                                                                    \
        const auto& quadrixCheckA_ = (a);                                   \
        const auto& quadrixCheckB_ = (b);                                   \
        if (!(quadrixCheckA_ op quadrixCheckB_)) [[unlikely]]               \
            ::quadrix::detail::CheckFailed(                                 \
                __FILE__, __LINE__, #a " " #op " " #b,                      \
                ::fmt::format("{} vs {}", quadrixCheckA_, quadrixCheckB_)); \
    } while (0)

#define QUADRIX_CHECK_EQ(a, b) QUADRIX_CHECK_OP(a, ==, b)
#define QUADRIX_CHECK_NE(a, b) QUADRIX_CHECK_OP(a, !=, b)
#define QUADRIX_CHECK_LT(a, b) QUADRIX_CHECK_OP(a, <, b)
#define QUADRIX_CHECK_LE(a, b) QUADRIX_CHECK_OP(a, <=, b)

#ifdef NDEBUG
#define QUADRIX_DCHECK(cond, ...) \
    do {                          \
    } while (0)
#define QUADRIX_DCHECK_OP(a, op, b) \
    do {                            \
    } while (0)
#else
#define QUADRIX_DCHECK(cond, ...) QUADRIX_CHECK(cond __VA_OPT__(, ) __VA_ARGS__)
#define QUADRIX_DCHECK_OP(a, op, b) QUADRIX_CHECK_OP(a, op, b)
#endif
#define QUADRIX_DCHECK_EQ(a, b) QUADRIX_DCHECK_OP(a, ==, b)
#define QUADRIX_DCHECK_LT(a, b) QUADRIX_DCHECK_OP(a, <, b)
