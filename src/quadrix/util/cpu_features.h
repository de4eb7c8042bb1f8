// The AVX2 and baseline versions of the vectorised loops, and the choice between them.
//
// A loop that the compiler vectorises is built twice from one body: the body is an always-inline
// function, and two thin functions call it, one compiled for AVX2 (QUADRIX_AVX2) and one for the
// x86-64 baseline; the caller takes the first when gCpuHasAvx2. The results are the same bits
// either way (IEEE arithmetic in the same order, no FMA contraction: the project builds with
// -ffp-contract=off).
//
// gCpuHasAvx2 comes from glibc's record of the processor's CPUID and of what the OS saves
// (sys/platform/x86.h CPU_FEATURE_ACTIVE, glibc 2.33), which the dynamic loader made at start-up:
// no CPUID instruction runs. GCC's target_clones, used before, chose at load time through
// libgcc's __cpu_indicator_init, which surveys every CPUID leaf; each CPUID traps to the
// hypervisor on a virtual machine, and the survey cost 0.1 ms of every quadrix process (2 % of a
// 64 × 64 render: docs/performance.md "Small pictures").
#pragma once

namespace quadrix {

// Whether this processor runs AVX2 code and the OS saves its registers. Set before main (a
// loop called during static initialisation, before it is set, takes the baseline version: the
// same bits).
extern const bool gCpuHasAvx2;

}  // namespace quadrix

#if defined(__x86_64__) || defined(__i386__)
#define QUADRIX_AVX2 __attribute__((target("avx2")))
#else
#define QUADRIX_AVX2
#endif
