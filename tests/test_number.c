/* test_number.c - the text formats' number parser (src/io/number.h) gives
 * exactly strtod's and strtof's results in the C locale, bit for bit, on
 * edge cases (ties, subnormals, the ends of the ranges, long mantissas)
 * and on a few hundred thousand random decimal strings of every shape. */
#include "io/number.h"
#include "sr_test.h"

#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static bool same_double(double a, double b)
{
    return memcmp(&a, &b, sizeof a) == 0 || (isnan(a) && isnan(b));
}

static bool same_float(float a, float b)
{
    return memcmp(&a, &b, sizeof a) == 0 || (isnan(a) && isnan(b));
}

static int mismatches;

/* s parsed both ways agrees with strtod and strtof; decimal strings and
 * the words are accepted whole. */
static void check_one(const char *s)
{
    const char *e = s + strlen(s);
    double d = -12345, want_d = strtod(s, NULL);
    float f = -12345, want_f = strtof(s, NULL);
    sr_num_status sd = sr__parse_double(s, e, &d);
    sr_num_status sf = sr__parse_float(s, e, &f);
    bool ok = sd != SR_NUM_MALFORMED && sf != SR_NUM_MALFORMED && same_double(d, want_d) &&
              same_float(f, want_f);
    if (!ok && mismatches++ < 20) {
        sr_test_fail(__FILE__, __LINE__, "'%.80s': double %a (%d) strtod %a, float %a (%d) strtof %a",
                     s, d, (int)sd, want_d, (double)f, (int)sf, (double)want_f);
    }
}

/* The end of a string literal, for the (begin, end) parsers. */
#define LIT_END(lit) (&(lit)[sizeof(lit) - 1])

SR_TEST(edge_cases_match_strtod_and_strtof)
{
    static const char *cases[] = {
        "0", "-0", "+0", "0.0", "-0.0e-0", ".5", "5.", "+.5e+1", "1", "-1", "0.1", "0.2",
        "0.3", "1e23", "8.98846567431158e307", "1.7976931348623157e308",
        "1.7976931348623158e308",   /* rounds down to DBL_MAX */
        "1.797693134862315807e308", /* just below the overflow midpoint */
        "1.7976931348623159e308",   /* overflows */
        "2.2250738585072011e-308", "2.2250738585072012e-308", "2.2250738585072014e-308",
        "4.9406564584124654e-324", "2.4703282292062327e-324", /* half the smallest: 0 */
        "2.4703282292062328e-324", /* just above: the smallest */
        "1e-320", "1e-400", "1e400", "-1e400", "1e-45", "1.4e-45", "7.1e-46", "7e-46",
        "1e-50", "3.4028235e38", "3.40282356e38", "3.4028236e38", "-3.4028234e38",
        "1.17549435e-38", "1.1754942e-38", "16777217", "16777219", "9007199254740993",
        "9007199254740992.5", "9007199254740993.0000000000000000000000001",
        "1.000000059604644775390625", "1.00000005960464477539062499",
        "1.000000059604644775390626", "1.00000000000000011102230246251565404236316680908203125",
        "1.00000000000000011102230246251565404236316680908203124",
        "1.00000000000000011102230246251565404236316680908203126",
        "123456789012345678901234567890", "2.7182818284590452353602874713527",
        "00000000000000000000000012.5", "0.000000000000000000000000000000000000000000001",
        "1e0000000000000000000000001", "1e-99999999999999999999", "1e99999999999999999999",
        "0e999999", "0.0000e-99999", "inf", "-inf", "INF", "Infinity", "-infinity", "nan",
        "-NaN", "nan(123abc_)", "nan()", "4.35e-9", "9.999999e-5", "1.5e-1", "33554431",
        "33554433.0", "7.038531e-26", "1.401298464324817e-45", "7.006492321624085e-46",
        "7.006492321624086e-46", "2e-323", "5e-324", "3e-324",
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        check_one(cases[i]);
    }
}

/* The exact halfway point between two neighbouring doubles, then one
 * digit more or less: the cases that need every digit. */
SR_TEST(midpoints_with_hundreds_of_digits_round_to_even)
{
    sr_rng rng = { 0x6d1d9017ULL };
    char buf[1200];
    for (int i = 0; i < 3000; i++) {
        int exp = sr_rng_int(&rng, -1074, 1023);
        double a = ldexp(sr_rng_unit(&rng) + 1, exp);
        if (i % 5 == 0) {
            a = ldexp((double)sr_rng_int(&rng, 1, 1 << 20), -1074); /* subnormal */
        }
        if (!isfinite(a)) {
            continue;
        }
        double b = nextafter(a, INFINITY);
        if (!isfinite(b)) {
            continue;
        }
        /* (a + b) / 2 in long double is exact (64-bit mantissa) where the
         * platform has it; otherwise this is merely another hard case. */
        long double mid = ((long double)a + (long double)b) / 2;
        snprintf(buf, sizeof buf, "%.800Le", mid);
        check_one(buf);
        /* One unit in the last printed place up and down. */
        char *e = strchr(buf, 'e');
        for (int dir = 0; dir < 2 && e; dir++) {
            char tmp[1200];
            snprintf(tmp, sizeof tmp, "%s", buf);
            char *p = tmp + (e - buf) - 1;
            if (dir == 0) {
                while (*p == '9') {
                    *p-- = '0';
                }
                if (*p != '.') {
                    (*p)++;
                }
            } else {
                while (*p == '0') {
                    *p-- = '9';
                }
                if (*p != '.') {
                    (*p)--;
                }
            }
            check_one(tmp);
        }
        /* The same value with 1000 digits (past the 800 kept). */
        snprintf(buf, sizeof buf, "%.1000Lf", mid * 0x1p-60L);
        check_one(buf);
    }
}

SR_TEST(random_decimals_match_strtod_and_strtof)
{
    sr_rng rng = { 0xdec1a1ULL };
    char s[400];
    for (int i = 0; i < 300000; i++) {
        double x = (sr_rng_unit(&rng) * 2 - 1) * pow(10.0, sr_rng_int(&rng, -30, 30));
        switch (i % 8) {
        case 0:
            snprintf(s, sizeof s, "%.*f", sr_rng_int(&rng, 0, 12), x);
            break;
        case 1:
            snprintf(s, sizeof s, "%.*g", sr_rng_int(&rng, 1, 9), x);
            break;
        case 2:
            snprintf(s, sizeof s, "%.17g", x);
            break;
        case 3: /* exponents across both ranges, subnormals included */
            snprintf(s, sizeof s, "%.*e", sr_rng_int(&rng, 0, 25),
                     sr_rng_range(&rng, -9.99, 9.99) * pow(10.0, sr_rng_int(&rng, -330, 310)));
            break;
        case 4: /* long mantissas */
            snprintf(s, sizeof s, "%.*e", sr_rng_int(&rng, 17, 120), x);
            break;
        case 5: { /* random digit strings with a random exponent */
            int n = sr_rng_int(&rng, 1, 60), point = sr_rng_int(&rng, 0, n), at = 0;
            if (sr_rng_int(&rng, 0, 1)) {
                s[at++] = '-';
            }
            for (int k = 0; k < n; k++) {
                s[at++] = (char)('0' + sr_rng_int(&rng, 0, 9));
                if (k == point) {
                    s[at++] = '.';
                }
            }
            snprintf(s + at, sizeof s - (size_t)at, "e%d", sr_rng_int(&rng, -360, 340));
            break;
        }
        case 6: /* floats printed shortest, then nudged in the last digit */
            snprintf(s, sizeof s, "%.9g", (double)(float)x);
            s[strlen(s) - 1 - (strchr(s, 'e') ? strlen(strchr(s, 'e')) : 0)] =
                (char)('0' + sr_rng_int(&rng, 0, 9));
            break;
        default: /* integers */
            snprintf(s, sizeof s, "%d", sr_rng_int(&rng, -1000000000, 1000000000));
            break;
        }
        check_one(s);
    }
    CHECK_EQ(mismatches, 0);
}

SR_TEST(malformed_numbers_are_refused_and_out_is_kept)
{
    static const char *bad[] = {
        "", "-", "+", ".", "e5", ".e5", "1e", "1e+", "1e-", "1.2.3", "1,5", "abc", "0x10",
        "--1", "1ee2", "1e2.5", "1f", " 1", "1 ", "info", "nanx", "nan(", "nan(a b)", "in",
        "infinit", "+-1",
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        double d = 42;
        float f = 42;
        const char *s = bad[i];
        CHECK_EQ(sr__parse_double(s, s + strlen(s), &d), SR_NUM_MALFORMED);
        CHECK_EQ(sr__parse_float(s, s + strlen(s), &f), SR_NUM_MALFORMED);
        CHECK(d == 42 && f == 42);
    }
}

SR_TEST(statuses_tell_words_from_overflow)
{
    double d;
    float f;
    CHECK_EQ(sr__parse_float("1e39", LIT_END("1e39"), &f), SR_NUM_OVERFLOW);
    CHECK(isinf(f) && f > 0);
    CHECK_EQ(sr__parse_double("1e39", LIT_END("1e39"), &d), SR_NUM_OK);
    CHECK_EQ(sr__parse_double("-1e999", LIT_END("-1e999"), &d), SR_NUM_OVERFLOW);
    CHECK(isinf(d) && d < 0);
    CHECK_EQ(sr__parse_double("-inf", LIT_END("-inf"), &d), SR_NUM_NOT_FINITE);
    CHECK(isinf(d) && d < 0);
    CHECK_EQ(sr__parse_float("NaN", LIT_END("NaN"), &f), SR_NUM_NOT_FINITE);
    CHECK(isnan(f));
    /* The largest float and the midpoint above it. */
    CHECK_EQ(sr__parse_float("3.4028235677973366e38", LIT_END("3.4028235677973366e38"), &f),
             SR_NUM_OK);
    CHECK(f == FLT_MAX);
    CHECK_EQ(sr__parse_float("3.4028235677973366164e38", LIT_END("3.4028235677973366164e38"), &f),
             SR_NUM_OVERFLOW);
    const char *tie = "340282356779733661637539395458142568448"; /* to even: infinity */
    CHECK_EQ(sr__parse_float(tie, tie + strlen(tie), &f), SR_NUM_OVERFLOW);
}

SR_TEST(scan_finds_the_number_in_front)
{
    static const struct { const char *s; size_t n; } cases[] = {
        { "10px", 2 }, { "1.5.5", 3 }, { "-.5e3,", 5 }, { "1e", 1 }, { "1e+", 1 },
        { "2E-3x", 4 }, { ".", 0 }, { "-", 0 }, { "abc", 0 }, { "7.", 2 }, { "+3e+07 ", 6 },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        const char *s = cases[i].s;
        CHECK_EQ(sr__scan_decimal(s, s + strlen(s)), cases[i].n);
    }
}

/* The one-pass prefix parser: the length sr__scan_decimal finds, and the
 * value and status sr__parse_double gives that prefix; nothing written
 * when there is no number. */
static void check_prefix(const char *s)
{
    const char *e = s + strlen(s);
    size_t want_n = sr__scan_decimal(s, e);
    double got = -12345, want = -12345;
    sr_num_status st = SR_NUM_MALFORMED, want_st = SR_NUM_MALFORMED;
    size_t n = sr__parse_double_prefix(s, e, &got, &st);
    if (want_n > 0) {
        want_st = sr__parse_double(s, s + want_n, &want);
    }
    bool ok = n == want_n && st == want_st && same_double(got, want);
    if (!ok && mismatches++ < 20) {
        sr_test_fail(__FILE__, __LINE__, "'%.80s': prefix %zu (%d) %a, want %zu (%d) %a", s, n,
                     (int)st, got, want_n, (int)want_st, want);
    }
}

SR_TEST(prefix_parse_is_scan_then_parse)
{
    static const char *cases[] = {
        "10px", "1.5.5", "-.5e3,", "1e", "1e+", "1e-x", "2E-3x", ".", "-", "abc", "7.", "+3e+07 ",
        "0", "-0", "00012.500e", "1e400q", "-1e-400,", "123456789012345678901234567890 1",
        "0.1 0.2", "inf", "nan", "", "9007199254740993,", "1e22e", "5e-324", ".e1", "+.",
    };
    mismatches = 0;
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        check_prefix(cases[i]);
    }
    sr_rng rng = { 0x9f1a5ULL };
    char s[200];
    static const char *const tails[] = { "", " ", ",", "px", "e", "e+", ".5", "%", "-1" };
    for (int i = 0; i < 100000; i++) {
        double x = (sr_rng_unit(&rng) * 2 - 1) * pow(10.0, sr_rng_int(&rng, -30, 30));
        const char *tail = tails[sr_rng_int(&rng, 0, 8)];
        if (i % 2) {
            snprintf(s, sizeof s, "%.*f%s", sr_rng_int(&rng, 0, 12), x, tail);
        } else {
            snprintf(s, sizeof s, "%.*e%s", sr_rng_int(&rng, 0, 25), x, tail);
        }
        check_prefix(s);
    }
    CHECK_EQ(mismatches, 0);
}
