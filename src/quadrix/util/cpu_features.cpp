#include "quadrix/util/cpu_features.h"

#if defined(__x86_64__) || defined(__i386__)
#if defined(__has_include)
#if __has_include(<sys/platform/x86.h>)
// The header is C: its inline functions return _Bool, which g++ takes as an extension and
// clang++ does not.
#define _Bool bool
#include <sys/platform/x86.h>
#undef _Bool
#define QUADRIX_HAVE_GLIBC_X86_FEATURES 1
#endif
#endif
#endif

namespace quadrix {

namespace {

bool DetectAvx2() {
#if defined(QUADRIX_HAVE_GLIBC_X86_FEATURES)
    return CPU_FEATURE_ACTIVE(AVX2);
#elif defined(__x86_64__) || defined(__i386__)
    __builtin_cpu_init();  // libgcc's survey of CPUID (a C library without glibc's record)
    return __builtin_cpu_supports("avx2");
#else
    return false;
#endif
}

}  // namespace

extern const bool gCpuHasAvx2 = DetectAvx2();

}  // namespace quadrix
