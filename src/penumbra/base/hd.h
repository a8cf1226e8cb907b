#pragma once
// PENUMBRA_HD marks code that runs per ray, per sample or per texel. It expands
// to __host__ __device__ under nvcc and to nothing otherwise, so the CPU backend
// and a later CUDA backend compile the same kernel source. Code marked with it
// must not throw, allocate, call virtual functions or do I/O.
#if defined(__CUDACC__)
#define PENUMBRA_HD __host__ __device__
#else
#define PENUMBRA_HD
#endif

// Forces inlining of small per-sample helpers whose call overhead would
// dominate (the sample cursor of the marching loop).
#if defined(__CUDACC__)
#define PENUMBRA_FORCE_INLINE __forceinline__
#elif defined(__GNUC__) || defined(__clang__)
#define PENUMBRA_FORCE_INLINE __attribute__((always_inline)) inline
#else
#define PENUMBRA_FORCE_INLINE inline
#endif

// The same for a lambda, written after its parameter list:
//   [&](float x) PENUMBRA_FORCE_INLINE_LAMBDA { ... }
#if defined(__CUDACC__) || !(defined(__GNUC__) || defined(__clang__))
#define PENUMBRA_FORCE_INLINE_LAMBDA
#else
#define PENUMBRA_FORCE_INLINE_LAMBDA __attribute__((always_inline))
#endif

// Keeps a rarely taken path of a hot loop out of line on the CPU, so that
// the loop's registers are not spent on (and shuffled for) the state only
// that path touches; inlined as usual on the device.
#if defined(__CUDA_ARCH__) || !(defined(__GNUC__) || defined(__clang__))
#define PENUMBRA_COLD_PATH
#else
#define PENUMBRA_COLD_PATH __attribute__((noinline))
#endif

// Keeps a whole secondary march (a shadow ray's transmittance) out of line in
// the SIMD units, with everything it calls inlined into it. Its call costs
// nothing next to its samples, and the packet units' tile bodies are
// `flatten`: inlined, every call site of such a march (area light, point
// light, cache miss) became a copy of it with every voxel type's sampler,
// which made one unit take 72 s to compile (docs/PERFORMANCE.md). Elsewhere
// (scalar units, the sanitizer build, CUDA) the compiler decides as before;
// nothing measured there called for a change.
#if defined(PENUMBRA_SIMD_TARGET) && !defined(__CUDA_ARCH__) && (defined(__GNUC__) || defined(__clang__))
#define PENUMBRA_OUTLINED_MARCH __attribute__((noinline, flatten))
#else
#define PENUMBRA_OUTLINED_MARCH
#endif
