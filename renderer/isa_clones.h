#pragma once
// RAYVIEW_HOT marks the functions that trace and shade: in a build for any x86-64 (-DRAYVIEW_HOST_ISA=OFF) each is
// compiled twice, for x86-64-v3 and for the baseline, and the loader picks the copy the CPU runs (GCC's
// target_clones, an ifunc), so such a build traces at the x86-64-v3 build's speed wherever AVX2 is there. The
// helpers they call are inlined into each copy. Contraction stays forbidden in both (CMakeLists.txt), so both
// copies round every operation as the scalar code does: the same images either way. Where the whole build already
// targets AVX2, or the toolchain has no ifuncs (sanitizers, other compilers, C libraries or CPUs), the mark is empty.

#include <cstddef>  // defines __GLIBC__ where the C library is glibc, whose loader runs ifunc resolvers

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__AVX2__) && \
    !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__) && defined(__GLIBC__)
#define RAYVIEW_HOT __attribute__((target_clones("arch=x86-64-v3", "default"), flatten))
#else
#define RAYVIEW_HOT
#endif
