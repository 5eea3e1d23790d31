/* number.c - the text formats' decimal numbers (src/io, number.h):
 * locale-independent and correctly rounded to double or float.
 *
 * Most numbers in model files have few digits and a small exponent; those
 * take Clinger's fast path (an exact integer times or divided by an exact
 * power of ten rounds once).  The others get an estimate from their first
 * 19 digits, then exact big-integer comparisons against the midpoints
 * between neighbouring values move it to the correctly rounded one (ties
 * to even), as Clinger's "algorithm R" does.  Correct rounding needs at
 * most 768 significant digits for a double (the longest midpoint between
 * two doubles has 767); digits beyond MAX_DIGITS only say whether anything
 * non-zero follows, which one extra digit 1 stands for exactly. */
#include "io/number.h"

#include <assert.h>
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#define MAX_DIGITS 800

/* ---- the grammar ------------------------------------------------------------ */

static bool is_digit(char c)
{
    return c >= '0' && c <= '9';
}

static char lower(char c)
{
    return c >= 'A' && c <= 'Z' ? (char)(c - 'A' + 'a') : c;
}

/* [s, e) starts with the word w, any case. */
static bool has_word(const char *s, const char *e, const char *w)
{
    size_t n = strlen(w);
    if ((size_t)(e - s) < n) {
        return false;
    }
    for (size_t i = 0; i < n; i++) {
        if (lower(s[i]) != w[i]) {
            return false;
        }
    }
    return true;
}

size_t sr__scan_decimal(const char *s, const char *e)
{
    const char *p = s;
    if (p < e && (*p == '+' || *p == '-')) {
        p++;
    }
    bool digits = false;
    while (p < e && is_digit(*p)) {
        p++;
        digits = true;
    }
    if (p < e && *p == '.') {
        p++;
        while (p < e && is_digit(*p)) {
            p++;
            digits = true;
        }
    }
    if (!digits) {
        return 0;
    }
    if (p < e && (*p == 'e' || *p == 'E')) {
        const char *x = p + 1;
        if (x < e && (*x == '+' || *x == '-')) {
            x++;
        }
        if (x < e && is_digit(*x)) {
            while (x < e && is_digit(*x)) {
                x++;
            }
            p = x;
        }
    }
    return (size_t)(p - s);
}

/* The value D * 10^exp10, D the integer spelled by digits[0..n) (no
 * leading or trailing zeros; n == 0 for zero). */
typedef struct decimal {
    bool neg;
    int n;
    long exp10;
    uint8_t digits[MAX_DIGITS + 1];
} decimal;

/* Read [s, e) into *d; false when it is not the digits form. */
static bool read_decimal(const char *s, const char *e, decimal *d)
{
    size_t n = sr__scan_decimal(s, e);
    if (n == 0 || n != (size_t)(e - s)) {
        return false;
    }
    d->neg = *s == '-';
    if (*s == '+' || *s == '-') {
        s++;
    }
    d->n = 0;
    d->exp10 = 0;
    bool sticky = false, point = false;
    for (; s < e && *s != 'e' && *s != 'E'; s++) {
        if (*s == '.') {
            point = true;
            continue;
        }
        int v = *s - '0';
        if (d->n == 0 && v == 0) {
            d->exp10 -= point;          /* a leading zero only places the point */
            continue;
        }
        if (d->n < MAX_DIGITS) {
            d->digits[d->n++] = (uint8_t)v;
            d->exp10 -= point;
        } else {
            sticky |= v != 0;
            d->exp10 += !point;         /* dropped, but its place still counts */
        }
    }
    if (s < e) {                        /* the exponent: saturated, since */
        s++;                            /* anything this big over- or underflows */
        bool eneg = *s == '-';
        if (*s == '+' || *s == '-') {
            s++;
        }
        long x = 0;
        for (; s < e; s++) {
            if (x < 100000000) {
                x = x * 10 + (*s - '0');
            }
        }
        d->exp10 += eneg ? -x : x;
    }
    if (sticky) {
        d->digits[d->n++] = 1;
        d->exp10--;
    }
    while (d->n > 0 && d->digits[d->n - 1] == 0) {
        d->n--;
        d->exp10++;
    }
    return true;
}

/* ---- big integers: just what the comparisons need ---------------------------- */

/* The largest operand: 2 D with 801 digits (2662 bits) shifted by up to
 * 1077 bits, or a 56-bit midpoint times 10^1125 (3738 bits) shifted by up
 * to 970 bits; 160 limbs leave room. */
#define BIG_LIMBS 160

typedef struct big {
    int n;                     /* limbs in use; no leading zero limb */
    uint32_t limb[BIG_LIMBS];  /* least significant first */
} big;

static void big_set(big *b, uint64_t v)
{
    b->n = 0;
    while (v) {
        b->limb[b->n++] = (uint32_t)v;
        v >>= 32;
    }
}

static void big_mul_small(big *b, uint32_t k)
{
    uint64_t carry = 0;
    for (int i = 0; i < b->n; i++) {
        uint64_t t = (uint64_t)b->limb[i] * k + carry;
        b->limb[i] = (uint32_t)t;
        carry = t >> 32;
    }
    if (carry) {
        assert(b->n < BIG_LIMBS);
        b->limb[b->n++] = (uint32_t)carry;
    }
}

static void big_add_small(big *b, uint32_t k)
{
    uint64_t carry = k;
    for (int i = 0; i < b->n && carry; i++) {
        uint64_t t = (uint64_t)b->limb[i] + carry;
        b->limb[i] = (uint32_t)t;
        carry = t >> 32;
    }
    if (carry) {
        assert(b->n < BIG_LIMBS);
        b->limb[b->n++] = (uint32_t)carry;
    }
}

static void big_mul_pow10(big *b, long k)
{
    for (; k >= 9; k -= 9) {
        big_mul_small(b, 1000000000u);
    }
    static const uint32_t small[9] = { 1, 10, 100, 1000, 10000, 100000, 1000000, 10000000,
                                       100000000 };
    big_mul_small(b, small[k]);
}

static void big_shl(big *b, long bits)
{
    if (b->n == 0 || bits == 0) {
        return;
    }
    int words = (int)(bits / 32), r = (int)(bits % 32);
    assert(b->n + words + 1 <= BIG_LIMBS);
    b->limb[b->n + words] = 0;
    for (int i = b->n - 1; i >= 0; i--) {
        uint32_t v = b->limb[i];
        b->limb[i + words + 1] |= r ? v >> (32 - r) : 0;
        b->limb[i + words] = r ? v << r : v;
    }
    for (int i = 0; i < words; i++) {
        b->limb[i] = 0;
    }
    b->n += words + 1;
    while (b->n > 0 && b->limb[b->n - 1] == 0) {
        b->n--;
    }
}

/* r = a * b (r distinct from both). */
static void big_mul(big *r, const big *a, const big *b)
{
    assert(a->n + b->n <= BIG_LIMBS);
    memset(r->limb, 0, sizeof r->limb[0] * (size_t)(a->n + b->n));
    for (int i = 0; i < a->n; i++) {
        uint64_t carry = 0;
        for (int j = 0; j < b->n; j++) {
            uint64_t t = (uint64_t)a->limb[i] * b->limb[j] + r->limb[i + j] + carry;
            r->limb[i + j] = (uint32_t)t;
            carry = t >> 32;
        }
        r->limb[i + b->n] = (uint32_t)carry;
    }
    r->n = a->n + b->n;
    while (r->n > 0 && r->limb[r->n - 1] == 0) {
        r->n--;
    }
}

static int big_cmp(const big *a, const big *b)
{
    if (a->n != b->n) {
        return a->n < b->n ? -1 : 1;
    }
    for (int i = a->n - 1; i >= 0; i--) {
        if (a->limb[i] != b->limb[i]) {
            return a->limb[i] < b->limb[i] ? -1 : 1;
        }
    }
    return 0;
}

/* ---- correct rounding ---------------------------------------------------------- */

/* A binary format: values m 2^k with m < 2^bits, k >= kmin, and
 * m >= 2^(bits-1) unless k == kmin (the subnormals). */
typedef struct format {
    int bits;
    int kmin, kmax;            /* exponent of the last mantissa bit */
} format;

static const format DOUBLE = { 53, -1074, 971 };
static const format FLOAT = { 24, -149, 104 };

/* x = D 10^exp10 made comparable with midpoints S 2^f, both as integers:
 * x scaled = D 10^max(exp10, 0), the midpoint's factor 10^max(-exp10, 0). */
typedef struct exact {
    big x;
    big pow10;
} exact;

static void exact_init(exact *q, const decimal *d)
{
    big_set(&q->x, 0);
    for (int i = 0; i < d->n; i++) {
        big_mul_small(&q->x, 10);
        big_add_small(&q->x, d->digits[i]);
    }
    big_set(&q->pow10, 1);
    if (d->exp10 >= 0) {
        big_mul_pow10(&q->x, d->exp10);
    } else {
        big_mul_pow10(&q->pow10, -d->exp10);
    }
}

/* The sign of x - s 2^f. */
static int exact_cmp(const exact *q, uint64_t s, long f)
{
    big lhs = q->x, mid, rhs;
    big_set(&mid, s);
    big_mul(&rhs, &mid, &q->pow10);
    if (f >= 0) {
        big_shl(&rhs, f);
    } else {
        big_shl(&lhs, -f);
    }
    return big_cmp(&lhs, &rhs);
}

/* The value of d (positive, n > 0) rounded to fmt, ties to even, starting
 * from the estimate `est`; false when it rounds to infinity. */
static bool round_exact(const decimal *d, const format *fmt, double est, uint64_t *m_out,
                        int *k_out)
{
    const uint64_t top = (uint64_t)1 << fmt->bits, half = top >> 1;
    uint64_t m;
    int k;
    if (!(est < INFINITY)) {
        m = top - 1;
        k = fmt->kmax;
    } else if (est <= 0) {
        m = 0;
        k = fmt->kmin;
    } else {
        int x;
        frexp(est, &x);                 /* est = f 2^x, f in [0.5, 1) */
        k = x - fmt->bits;
        if (k < fmt->kmin) {
            k = fmt->kmin;
        }
        if (k > fmt->kmax) {
            k = fmt->kmax;
        }
        double mm = ldexp(est, -k);
        m = mm >= (double)top ? top - 1 : (uint64_t)mm;
        if (m < half && k > fmt->kmin) {
            m = half;
        }
    }
    exact q;
    exact_init(&q, d);
    for (;;) {
        /* Up while x is above the midpoint to the next value. */
        int c = exact_cmp(&q, 2 * m + 1, (long)k - 1);
        if (c > 0 || (c == 0 && (m & 1))) {
            if (++m == top) {
                m = half;
                if (++k > fmt->kmax) {
                    return false;
                }
            }
            continue;
        }
        if (m == 0) {
            break;
        }
        /* Down while x is below the midpoint to the previous value, which
         * is half as far below a power of two (but for the subnormals). */
        bool pow2 = m == half && k > fmt->kmin;
        c = pow2 ? exact_cmp(&q, 4 * m - 1, (long)k - 2) : exact_cmp(&q, 2 * m - 1, (long)k - 1);
        if (c < 0 || (c == 0 && (m & 1))) {
            if (pow2) {
                m = top - 1;
                k--;
            } else {
                m--;
            }
            continue;
        }
        break;
    }
    *m_out = m;
    *k_out = k;
    return true;
}

/* Powers of ten that doubles (5^22 < 2^53) and floats (5^10 < 2^24) hold
 * exactly. */
static const double pow10_exact[23] = {
    1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
    1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
};
static const float pow10_exact_f[11] = {
    1e0f, 1e1f, 1e2f, 1e3f, 1e4f, 1e5f, 1e6f, 1e7f, 1e8f, 1e9f, 1e10f,
};

/* D from its first 19 digits and the rest's count. */
static uint64_t leading_digits(const decimal *d, int *used)
{
    uint64_t m = 0;
    int n = d->n < 19 ? d->n : 19;
    for (int i = 0; i < n; i++) {
        m = m * 10 + d->digits[i];
    }
    *used = n;
    return m;
}

/* Within a few units in the last place of a double: the start for
 * round_exact. */
static double estimate(uint64_t m, long exp10)
{
    double v = (double)m;
    if (exp10 >= 0) {
        for (; exp10 > 22 && v < INFINITY; exp10 -= 22) {
            v *= 1e22;
        }
        return v * pow10_exact[exp10 > 22 ? 22 : exp10];
    }
    for (exp10 = -exp10; exp10 > 22 && v > 0; exp10 -= 22) {
        v /= 1e22;
    }
    return v / pow10_exact[exp10 > 22 ? 22 : exp10];
}

/* The words: inf, infinity, nan, nan(letters digits _), any case. */
static bool read_word(const char *s, const char *e, double *out)
{
    double sign = 1;
    if (s < e && (*s == '+' || *s == '-')) {
        sign = *s == '-' ? -1 : 1;
        s++;
    }
    if (has_word(s, e, "infinity") && e - s == 8) {
        *out = sign * INFINITY;
        return true;
    }
    if (has_word(s, e, "inf") && e - s == 3) {
        *out = sign * INFINITY;
        return true;
    }
    if (!has_word(s, e, "nan")) {
        return false;
    }
    s += 3;
    if (s < e) {
        if (*s != '(' || e[-1] != ')') {
            return false;
        }
        for (s++; s < e - 1; s++) {
            char c = lower(*s);
            if (!is_digit(c) && !(c >= 'a' && c <= 'z') && c != '_') {
                return false;
            }
        }
    }
    *out = copysign(NAN, sign);
    return true;
}

/* One pass over the decimal number at the start of [s, e) (the one
 * sr__scan_decimal finds) for the common case: the sign, the first 19
 * significant digits in *m, their count in *nd (more than 19: *m holds
 * only the first) and the exponent of m's last digit.  Returns the
 * number's length, 0 when there is none. */
static size_t quick_decimal(const char *s, const char *e, bool *neg, uint64_t *m, int *nd,
                            long *exp10)
{
    const char *start = s;
    *neg = s < e && *s == '-';
    if (s < e && (*s == '+' || *s == '-')) {
        s++;
    }
    uint64_t v = 0;
    int n = 0;
    long x = 0;
    bool digits = false;
    while (s < e && *s == '0') {
        s++;
        digits = true;
    }
    for (; s < e && is_digit(*s); s++, n++) {
        if (n < 19) {
            v = v * 10 + (uint64_t)(*s - '0');
        } else {
            x++;                /* dropped, but its place still counts */
        }
        digits = true;
    }
    if (s < e && *s == '.') {
        s++;
        if (n == 0) {
            for (; s < e && *s == '0'; s++) {
                x--;
                digits = true;
            }
        }
        for (; s < e && is_digit(*s); s++, n++) {
            if (n < 19) {
                v = v * 10 + (uint64_t)(*s - '0');
                x--;
            }
            digits = true;
        }
    }
    if (!digits) {
        return 0;
    }
    if (s < e && (*s == 'e' || *s == 'E')) {
        const char *t = s + 1;
        bool eneg = t < e && *t == '-';
        if (t < e && (*t == '+' || *t == '-')) {
            t++;
        }
        if (t < e && is_digit(*t)) { /* else the number ends before the e */
            long k = 0;
            for (; t < e && is_digit(*t); t++) {
                if (k < 100000000) {
                    k = k * 10 + (*t - '0');
                }
            }
            x += eneg ? -k : k;
            s = t;
        }
    }
    *m = v;
    *nd = n;
    *exp10 = x;
    return (size_t)(s - start);
}

/* The rare numbers: more than 19 digits, exponents beyond the exact powers
 * of ten, float midpoints; apart so that the common path's frame stays
 * small. */
__attribute__((noinline)) static sr_num_status parse_exact(const char *s, const char *e,
                                                            const format *fmt, double sign,
                                                            double *out)
{
    decimal d;
    if (!read_decimal(s, e, &d)) {
        return SR_NUM_MALFORMED; /* never: the same grammar as quick_decimal's */
    }
    /* D < 10^n: at most 10^(n + exp10), and anything below half the
     * smallest subnormal (2^-1075 > 10^-324, 2^-150 > 10^-46) is zero. */
    long mag = d.n + d.exp10;
    if (d.n == 0 || mag < (fmt == &FLOAT ? -46 : -324)) {
        *out = sign * 0.0;
        return SR_NUM_OK;
    }
    if (mag > (fmt == &FLOAT ? 40 : 310)) {
        *out = sign * INFINITY;
        return SR_NUM_OVERFLOW;
    }
    int used;
    uint64_t lead = leading_digits(&d, &used);
    uint64_t rm;
    int rk;
    if (!round_exact(&d, fmt, estimate(lead, d.exp10 + (d.n - used)), &rm, &rk)) {
        *out = sign * INFINITY;
        return SR_NUM_OVERFLOW;
    }
    *out = sign * ldexp((double)rm, rk);
    return SR_NUM_OK;
}

/* The number [s, e), which quick_decimal read as neg, m, nd, exp10,
 * rounded to fmt, as a double (exact for a float too, as every float is
 * a double). */
static sr_num_status convert(const char *s, const char *e, const format *fmt, bool neg,
                             uint64_t m, int nd, long exp10, double *out)
{
    double sign = neg ? -1 : 1;
    if (m == 0 && nd <= 19) {
        *out = sign * 0.0;
        return SR_NUM_OK;
    }
#if FLT_EVAL_METHOD == 0
    /* Clinger's fast path: both factors exact, so one rounding. */
    if (nd <= 19 && m < ((uint64_t)1 << 53) && exp10 >= -22 && exp10 <= 22) {
        double v = exp10 >= 0 ? (double)m * pow10_exact[exp10] : (double)m / pow10_exact[-exp10];
        if (fmt == &DOUBLE) {
            *out = sign * v;
            return SR_NUM_OK;
        }
        if (m < ((uint64_t)1 << 24) && exp10 >= -10 && exp10 <= 10) {
            float f = exp10 >= 0 ? (float)m * pow10_exact_f[exp10]
                                 : (float)m / pow10_exact_f[-exp10];
            *out = sign * (double)f;
            return SR_NUM_OK;
        }
        /* The double v is x correctly rounded; rounding it again to float
         * is right unless v is exactly a midpoint between two floats (its
         * 29 bits below a float's mantissa are 1000...).  v is normal here
         * (at least 1e-22), and so is the float. */
        uint64_t bits;
        memcpy(&bits, &v, sizeof bits);
        if ((bits & ((1u << 29) - 1)) != (1u << 28)) {
            *out = sign * (double)(float)v;
            return SR_NUM_OK;
        }
    }
#endif
    return parse_exact(s, e, fmt, sign, out);
}

/* Both types: the whole of [s, e). */
static sr_num_status parse(const char *s, const char *e, const format *fmt, double *out)
{
    bool neg;
    uint64_t m;
    int nd;
    long exp10;
    size_t n = quick_decimal(s, e, &neg, &m, &nd, &exp10);
    if (n == 0 || n != (size_t)(e - s)) {
        return read_word(s, e, out) ? SR_NUM_NOT_FINITE : SR_NUM_MALFORMED;
    }
    return convert(s, e, fmt, neg, m, nd, exp10, out);
}

sr_num_status sr__parse_double(const char *s, const char *e, double *out)
{
    double v = 0;
    sr_num_status st = parse(s, e, &DOUBLE, &v);
    if (st != SR_NUM_MALFORMED) {
        *out = v;
    }
    return st;
}

size_t sr__parse_double_prefix(const char *s, const char *e, double *out, sr_num_status *status)
{
    bool neg;
    uint64_t m;
    int nd;
    long exp10;
    size_t n = quick_decimal(s, e, &neg, &m, &nd, &exp10);
    if (n > 0) {
        *status = convert(s, s + n, &DOUBLE, neg, m, nd, exp10, out);
    }
    return n;
}

sr_num_status sr__parse_float(const char *s, const char *e, float *out)
{
    double v = 0;
    sr_num_status st = parse(s, e, &FLOAT, &v);
    if (st != SR_NUM_MALFORMED) {
        *out = (float)v;        /* exact: v is a float's value, or inf, or nan */
    }
    return st;
}
