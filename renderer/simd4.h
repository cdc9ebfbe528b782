#pragma once
// Four-lane vectors for code that runs on four rays or four hits at once (watertight_lanes.h, the Embree
// packet fill, point-light shading). GCC/Clang vector extensions: AVX2 registers in the x86-64-v3 build, SSE2
// pairs in a portable one. Every operation is the IEEE operation of the scalar code, lane by lane, each rounded
// on its own (the build forbids contraction, CMakeLists.txt): the lanes' results are the scalar code's bit for bit.

#include <cstdint>
#include <cstring>

#if defined(__x86_64__) || defined(_M_X64)
#include <immintrin.h>
#endif

namespace rayview {

using Double4 = double __attribute__((vector_size(32)));
using Mask4 = long long __attribute__((vector_size(32)));  // a Double4 comparison: -1 (true) or 0 per lane
using Float4 = float __attribute__((vector_size(16)));
using Int4 = std::int32_t __attribute__((vector_size(16)));  // a Float4 comparison

inline Double4 load4(const double* p) {
  Double4 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

inline void store4(double* p, Double4 v) { std::memcpy(p, &v, sizeof v); }

inline Double4 splat4(double x) { return Double4{x, x, x, x}; }
inline Float4 splat4(float x) { return Float4{x, x, x, x}; }
inline Mask4 splatMask4(long long x) { return Mask4{x, x, x, x}; }

// Correctly rounded square roots, as std::sqrt gives each lane.
inline Double4 sqrt4(Double4 x) {
#if defined(__AVX__)
  return reinterpret_cast<Double4>(_mm256_sqrt_pd(reinterpret_cast<__m256d>(x)));
#elif defined(__SSE2__)
  const __m128d low = _mm_sqrt_pd(_mm_set_pd(x[1], x[0])), high = _mm_sqrt_pd(_mm_set_pd(x[3], x[2]));
  return Double4{low[0], low[1], high[0], high[1]};
#else
  return Double4{__builtin_sqrt(x[0]), __builtin_sqrt(x[1]), __builtin_sqrt(x[2]), __builtin_sqrt(x[3])};
#endif
}

inline Float4 sqrt4(Float4 x) {
#if defined(__SSE__)
  return reinterpret_cast<Float4>(_mm_sqrt_ps(reinterpret_cast<__m128>(x)));
#else
  return Float4{__builtin_sqrtf(x[0]), __builtin_sqrtf(x[1]), __builtin_sqrtf(x[2]), __builtin_sqrtf(x[3])};
#endif
}

// |x| lane by lane, as std::fabs: the sign bit cleared.
inline Double4 abs4(Double4 x) {
  Mask4 bits;
  std::memcpy(&bits, &x, sizeof bits);
  bits &= splatMask4(0x7fffffffffffffffLL);
  std::memcpy(&x, &bits, sizeof x);
  return x;
}

// std::max(a, b) lane by lane: (a < b) ? b : a, NaNs and signed zeros included.
inline Double4 max4(Double4 a, Double4 b) { return a < b ? b : a; }
inline Float4 max4(Float4 a, Float4 b) { return a < b ? b : a; }

}  // namespace rayview
