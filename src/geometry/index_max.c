/* index_max.c - the largest index of an indexed draw's range, for the
 * check that every index names a vertex (vertex stage jobs, each over its
 * share of the indices); and the smallest with it, for a draw whose
 * indices are fewer than its vertices (draw.c: the vertex stage then
 * shades only the range between them; application thread).
 *
 * A single running maximum is a chain of dependent compares: GCC makes it
 * one SSE2 vector whose unsigned max is three instructions, and the
 * bunny's 208,353 indices took 116 us (in the L2 cache), 2% of the
 * two-thread frame's samples.  Sixteen independent maxima give the
 * compiler four vectors to keep in flight (31 us), and AVX2's unsigned
 * max on four 8-lane vectors reads them as fast as the cache delivers
 * them (6 us).  Either way the result is the same number. */
#include "pipeline.h"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define SR_HAVE_AVX2_INDEX_MAX 1
#endif

#define SR_INDEX_ACCUMULATORS 16

/* The portable loop: SR_INDEX_ACCUMULATORS running maxima. */
#define PORTABLE_MAX(type)                                                      \
    do {                                                                        \
        const type *ix = indices;                                               \
        type m[SR_INDEX_ACCUMULATORS] = { 0 };                                  \
        size_t i = begin;                                                       \
        for (; i + SR_INDEX_ACCUMULATORS <= end; i += SR_INDEX_ACCUMULATORS) {  \
            for (int k = 0; k < SR_INDEX_ACCUMULATORS; k++) {                   \
                m[k] = ix[i + k] > m[k] ? ix[i + k] : m[k];                     \
            }                                                                   \
        }                                                                       \
        type r = 0;                                                             \
        for (int k = 0; k < SR_INDEX_ACCUMULATORS; k++) {                       \
            r = m[k] > r ? m[k] : r;                                            \
        }                                                                       \
        for (; i < end; i++) {                                                  \
            r = ix[i] > r ? ix[i] : r;                                          \
        }                                                                       \
        return r;                                                               \
    } while (0)

static uint32_t max_u8(const void *indices, size_t begin, size_t end) { PORTABLE_MAX(uint8_t); }
static uint32_t max_u16(const void *indices, size_t begin, size_t end) { PORTABLE_MAX(uint16_t); }
static uint32_t max_u32(const void *indices, size_t begin, size_t end) { PORTABLE_MAX(uint32_t); }

#ifdef SR_HAVE_AVX2_INDEX_MAX
/* Four 32-byte vectors a step, each with its own running maximum (`max`
 * is _mm256_max_epu8/16/32); `rest` (the portable loop) takes the tail. */
#define AVX2_MAX(type, max, rest)                                                     \
    do {                                                                              \
        const type *ix = indices;                                                     \
        const size_t lanes = 32 / sizeof(type);                                       \
        __m256i m[4] = { _mm256_setzero_si256(), _mm256_setzero_si256(),              \
                         _mm256_setzero_si256(), _mm256_setzero_si256() };            \
        size_t i = begin;                                                             \
        for (; i + 4 * lanes <= end; i += 4 * lanes) {                                \
            for (int k = 0; k < 4; k++) {                                             \
                m[k] = max(m[k], _mm256_loadu_si256((const __m256i *)&ix[i + k * lanes])); \
            }                                                                         \
        }                                                                             \
        type lane[32 / sizeof(type)];                                                 \
        _mm256_storeu_si256((__m256i *)lane, max(max(m[0], m[1]), max(m[2], m[3])));   \
        uint32_t r = rest(indices, i, end);                                           \
        for (size_t k = 0; k < lanes; k++) {                                          \
            r = lane[k] > r ? lane[k] : r;                                            \
        }                                                                             \
        return r;                                                                     \
    } while (0)

#define SR_AVX2 __attribute__((target("avx2")))
SR_AVX2 static uint32_t max_u8_avx2(const void *indices, size_t begin, size_t end)
{
    AVX2_MAX(uint8_t, _mm256_max_epu8, max_u8);
}
SR_AVX2 static uint32_t max_u16_avx2(const void *indices, size_t begin, size_t end)
{
    AVX2_MAX(uint16_t, _mm256_max_epu16, max_u16);
}
SR_AVX2 static uint32_t max_u32_avx2(const void *indices, size_t begin, size_t end)
{
    AVX2_MAX(uint32_t, _mm256_max_epu32, max_u32);
}
#undef SR_AVX2
#endif

uint32_t sr__index_max(sr_index_type type, const void *indices, size_t begin, size_t end,
                       bool avx2)
{
#ifdef SR_HAVE_AVX2_INDEX_MAX
    if (avx2) {
        switch (type) {
        case SR_INDEX_U8:  return max_u8_avx2(indices, begin, end);
        case SR_INDEX_U16: return max_u16_avx2(indices, begin, end);
        case SR_INDEX_U32: return max_u32_avx2(indices, begin, end);
        default:           return 0;
        }
    }
#else
    (void)avx2;
#endif
    switch (type) {
    case SR_INDEX_U8:  return max_u8(indices, begin, end);
    case SR_INDEX_U16: return max_u16(indices, begin, end);
    case SR_INDEX_U32: return max_u32(indices, begin, end);
    default:           return 0;
    }
}

/* The smallest and largest together, SR_INDEX_ACCUMULATORS of each (the
 * compiler's vectors, as above); only for draws with fewer indices than
 * vertices, so the portable loop is enough. */
#define PORTABLE_RANGE(type)                                                    \
    do {                                                                        \
        const type *ix = indices;                                               \
        type lo[SR_INDEX_ACCUMULATORS], hi[SR_INDEX_ACCUMULATORS];              \
        for (int k = 0; k < SR_INDEX_ACCUMULATORS; k++) {                       \
            lo[k] = (type)-1;                                                   \
            hi[k] = 0;                                                          \
        }                                                                       \
        size_t i = 0;                                                           \
        for (; i + SR_INDEX_ACCUMULATORS <= count; i += SR_INDEX_ACCUMULATORS) { \
            for (int k = 0; k < SR_INDEX_ACCUMULATORS; k++) {                   \
                lo[k] = ix[i + k] < lo[k] ? ix[i + k] : lo[k];                  \
                hi[k] = ix[i + k] > hi[k] ? ix[i + k] : hi[k];                  \
            }                                                                   \
        }                                                                       \
        type l = (type)-1, h = 0;                                               \
        for (int k = 0; k < SR_INDEX_ACCUMULATORS; k++) {                       \
            l = lo[k] < l ? lo[k] : l;                                          \
            h = hi[k] > h ? hi[k] : h;                                          \
        }                                                                       \
        for (; i < count; i++) {                                                \
            l = ix[i] < l ? ix[i] : l;                                          \
            h = ix[i] > h ? ix[i] : h;                                          \
        }                                                                       \
        *min = l;                                                               \
        *max = h;                                                               \
    } while (0)

static void range_u8(const void *indices, size_t count, uint32_t *min, uint32_t *max)
{
    PORTABLE_RANGE(uint8_t);
}
static void range_u16(const void *indices, size_t count, uint32_t *min, uint32_t *max)
{
    PORTABLE_RANGE(uint16_t);
}
static void range_u32(const void *indices, size_t count, uint32_t *min, uint32_t *max)
{
    PORTABLE_RANGE(uint32_t);
}

void sr__index_range(sr_index_type type, const void *indices, size_t count, uint32_t *min,
                     uint32_t *max)
{
    *min = *max = 0;
    if (count == 0) {
        return;
    }
    switch (type) {
    case SR_INDEX_U8:  range_u8(indices, count, min, max); break;
    case SR_INDEX_U16: range_u16(indices, count, min, max); break;
    case SR_INDEX_U32: range_u32(indices, count, min, max); break;
    default:           break;
    }
}
