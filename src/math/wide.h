/* wide.h - exact 128-bit signed integers for the 2D toolkit's line and
 * ellipse set-up, whose products of two 64-bit coordinates need them.
 * GCC and Clang have __int128 on 64-bit targets; 32-bit ones (armhf, the
 * embedded profile's cross target) get two 64-bit words in two's
 * complement and the same values.  Any thread.  Internal to the library. */
#ifndef SR_WIDE_H
#define SR_WIDE_H

#include <stdbool.h>
#include <stdint.h>

#ifdef __SIZEOF_INT128__
__extension__ typedef __int128 sr_i128;

static inline sr_i128 sr__wide(int64_t a) { return a; }
static inline sr_i128 sr__wide_mul(int64_t a, int64_t b) { return (sr_i128)a * b; }
/* The low 128 bits of a * b. */
static inline sr_i128 sr__wide_mul64(sr_i128 a, int64_t b) { return a * b; }
static inline sr_i128 sr__wide_add(sr_i128 a, sr_i128 b) { return a + b; }
static inline sr_i128 sr__wide_sub(sr_i128 a, sr_i128 b) { return a - b; }
static inline bool sr__wide_negative(sr_i128 a) { return a < 0; }
static inline int64_t sr__wide_low(sr_i128 a) { return (int64_t)a; }
/* floor(a / b) and ceil(a / b) for b > 0. */
static inline sr_i128 sr__wide_floor_div(sr_i128 a, int64_t b)
{
    sr_i128 q = a / b;
    return (a % b != 0 && a < 0) ? q - 1 : q;
}
static inline sr_i128 sr__wide_ceil_div(sr_i128 a, int64_t b)
{
    sr_i128 q = a / b;
    return (a % b != 0 && a > 0) ? q + 1 : q;
}
#else
typedef struct sr_i128 { uint64_t lo, hi; } sr_i128;

static inline sr_i128 sr__wide(int64_t a)
{
    return (sr_i128){ (uint64_t)a, a < 0 ? ~(uint64_t)0 : 0 };
}
static inline sr_i128 sr__wide_add(sr_i128 a, sr_i128 b)
{
    uint64_t lo = a.lo + b.lo;
    return (sr_i128){ lo, a.hi + b.hi + (lo < a.lo) };
}
static inline sr_i128 sr__wide_sub(sr_i128 a, sr_i128 b)
{
    return (sr_i128){ a.lo - b.lo, a.hi - b.hi - (a.lo < b.lo) };
}
static inline bool sr__wide_negative(sr_i128 a) { return (a.hi >> 63) != 0; }
static inline int64_t sr__wide_low(sr_i128 a) { return (int64_t)a.lo; }
static inline sr_i128 sr__wide_abs(sr_i128 a)
{
    return sr__wide_negative(a) ? sr__wide_sub((sr_i128){ 0, 0 }, a) : a;
}
/* The full product of two unsigned 64-bit values, from 32-bit halves. */
static inline sr_i128 sr__wide_umul(uint64_t a, uint64_t b)
{
    uint64_t a0 = a & 0xffffffffu, a1 = a >> 32, b0 = b & 0xffffffffu, b1 = b >> 32;
    uint64_t p00 = a0 * b0, p01 = a0 * b1, p10 = a1 * b0, p11 = a1 * b1;
    uint64_t mid = (p00 >> 32) + (p01 & 0xffffffffu) + (p10 & 0xffffffffu);
    return (sr_i128){ (p00 & 0xffffffffu) | (mid << 32),
                      p11 + (p01 >> 32) + (p10 >> 32) + (mid >> 32) };
}
static inline sr_i128 sr__wide_mul64(sr_i128 a, int64_t b)
{
    sr_i128 m = sr__wide_abs(a);
    uint64_t ub = b < 0 ? 0 - (uint64_t)b : (uint64_t)b;
    sr_i128 r = sr__wide_umul(m.lo, ub);
    r.hi += m.hi * ub;
    return sr__wide_negative(a) != (b < 0) ? sr__wide_sub((sr_i128){ 0, 0 }, r) : r;
}
static inline sr_i128 sr__wide_mul(int64_t a, int64_t b)
{
    return sr__wide_mul64(sr__wide(a), b);
}
/* |a| / b and its remainder for 0 < b < 2^63, a bit at a time. */
static inline sr_i128 sr__wide_udiv(sr_i128 a, uint64_t b, uint64_t *rem)
{
    sr_i128 q = { 0, 0 };
    uint64_t r = 0;
    for (int i = 127; i >= 0; i--) {
        uint64_t bit = i >= 64 ? (a.hi >> (i - 64)) & 1u : (a.lo >> i) & 1u;
        r = r << 1 | bit;
        if (r >= b) {
            r -= b;
            if (i >= 64) {
                q.hi |= (uint64_t)1 << (i - 64);
            } else {
                q.lo |= (uint64_t)1 << i;
            }
        }
    }
    *rem = r;
    return q;
}
static inline sr_i128 sr__wide_floor_div(sr_i128 a, int64_t b)
{
    uint64_t r;
    sr_i128 q = sr__wide_udiv(sr__wide_abs(a), (uint64_t)b, &r);
    if (!sr__wide_negative(a)) {
        return q;
    }
    return sr__wide_sub((sr_i128){ 0, 0 }, sr__wide_add(q, sr__wide(r != 0)));
}
static inline sr_i128 sr__wide_ceil_div(sr_i128 a, int64_t b)
{
    uint64_t r;
    sr_i128 q = sr__wide_udiv(sr__wide_abs(a), (uint64_t)b, &r);
    if (sr__wide_negative(a)) {
        return sr__wide_sub((sr_i128){ 0, 0 }, q);
    }
    return sr__wide_add(q, sr__wide(r != 0));
}
#endif

static inline sr_i128 sr__wide_neg(sr_i128 a) { return sr__wide_sub(sr__wide(0), a); }

#endif
