// SPDX-License-Identifier: BSD-3-Clause
// VOXLINK_VECTOR_CLONES before a function with a vectorizable loop: on x86-64 the compiler also
// builds it for AVX2 and AVX-512 (x86-64-v4: with only AVX-512F, GCC kept 256-bit vectors) and
// picks the widest the CPU runs when the program starts; elsewhere it is the one plain build. Only
// for code whose result must not depend on the clone: the same IEEE operations lane by lane, in
// files built with -ffp-contract=off (no FMA).
#pragma once

#if defined(__x86_64__) && defined(__clang__)
// (clang 14 cannot dispatch to an "arch=x86-64-v4" clone: it gets AVX-512F by name)
#define VOXLINK_VECTOR_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#elif defined(__x86_64__) && defined(__GNUC__)
#define VOXLINK_VECTOR_CLONES __attribute__((target_clones("arch=x86-64-v4", "avx2", "default")))
#else
#define VOXLINK_VECTOR_CLONES
#endif
