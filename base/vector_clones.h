// SPDX-License-Identifier: BSD-3-Clause
// VOXLINK_VECTOR_CLONES before a function with a vectorizable loop: on x86-64 the compiler also
// builds it for AVX2 and AVX-512 (x86-64-v4: with only AVX-512F, GCC kept 256-bit vectors) and
// picks the widest the CPU runs when the program starts; elsewhere it is the one plain build. Only
// for code whose result must not depend on the clone: the same IEEE operations lane by lane, in
// files built with -ffp-contract=off (no FMA).
#pragma once

// GCC only. Clang 14 breaks a function declared first without the attribute (as every one here
// is, in its header): it emits the AVX-512F body alone under the plain name, no dispatch, and the
// program dies of SIGILL on a CPU without AVX-512 (the fuzz build on an AMD EPYC, 2026-11-27);
// without that declaration it names the dispatcher apart from the callers' symbol. Clang builds
// (fuzzing, sanitizers) take the one plain build.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define VOXLINK_VECTOR_CLONES __attribute__((target_clones("arch=x86-64-v4", "avx2", "default")))
#else
#define VOXLINK_VECTOR_CLONES
#endif
