// Function multi-versioning of the vectorised loops: each gets an AVX2 and a baseline version,
// chosen at load time (the results are the same bits either way: IEEE arithmetic in the same
// order, no FMA contraction). gcc clones function templates too; clang (14, the sanitizer and
// fuzz build of scripts/test.sh) does not support target_clones on templates, so there the
// templates keep only their baseline version.
#pragma once

#define QUADRIX_TARGET_CLONES __attribute__((target_clones("avx2", "default")))
#if defined(__clang__)
#define QUADRIX_TARGET_CLONES_TEMPLATE
#else
#define QUADRIX_TARGET_CLONES_TEMPLATE QUADRIX_TARGET_CLONES
#endif
