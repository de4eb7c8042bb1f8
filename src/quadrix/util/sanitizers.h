// QUADRIX_ASAN is 1 when the code is compiled with AddressSanitizer, by gcc (which defines
// __SANITIZE_ADDRESS__) or by clang (which answers __has_feature(address_sanitizer)), else 0.
// Tests that cannot run under it (ulimit -v, very large frames, deep stacks) ask this.
#pragma once

#if defined(__SANITIZE_ADDRESS__)
#define QUADRIX_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define QUADRIX_ASAN 1
#endif
#endif
#ifndef QUADRIX_ASAN
#define QUADRIX_ASAN 0
#endif
