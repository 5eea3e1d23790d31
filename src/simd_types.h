/* simd_types.h - the vector types of every vector path (GCC/Clang vector
 * extensions: lane-wise operators, the same source for each instruction
 * set) and the target attribute of the AVX-512 level.  Used by the
 * vertex stage, setup, the rasterizers' kernels and the fragment stage's
 * lighting lanes, on any thread.  Internal to the library. */
#ifndef SR_SIMD_TYPES_H
#define SR_SIMD_TYPES_H

#include <stdint.h>

typedef double v4d __attribute__((vector_size(32)));   /* exact edge values, depth */
typedef int64_t v4l __attribute__((vector_size(32)));  /* masks of v4d lanes */
typedef float v4f __attribute__((vector_size(16)));
typedef float v8f __attribute__((vector_size(32)));    /* AVX2 lanes of float sums */
typedef int32_t v4i __attribute__((vector_size(16)));  /* masks of v4f lanes, packed pixels */
typedef float v16f __attribute__((vector_size(64)));
typedef int32_t v16i __attribute__((vector_size(64)));

/* What the AVX-512 level needs of the CPU (sr__simd_cpu_level checks each of
 * them): the target of every function built for that level. */
#define SR_TARGET_AVX512 __attribute__((target("avx2,avx512f,avx512dq,avx512bw,avx512vl,popcnt")))

#endif
