/* json_pointer.c - io stage: the JSON pointers a reader names the
 * elements it walks by ("/accessors/12/bufferView"), for its messages.
 * Any thread. */
#include "io/io_util.h"

#include <assert.h>
#include <stdarg.h>
#include <stdbool.h>
#include <string.h>

/* A pointer is made for every element read but printed only in a
 * message, so it has to cost little: snprintf parses its format and
 * handles every case of every conversion, several times these appends. */
void sr__json_pointer(char *out, size_t cap, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    size_t at = 0;
    for (const char *f = fmt; *f; f++) {
        char digits[24];
        const char *piece = digits;
        size_t n = 0;
        if (f[0] != '%') {
            piece = f;
            n = strcspn(f, "%");
            f += n - 1;
        } else if (f[1] == 's') {
            piece = va_arg(ap, const char *);
            n = strlen(piece);
            f += 1;
        } else {
            unsigned long long v;
            bool negative = false;
            if (f[1] == 'd') {
                int i = va_arg(ap, int);
                negative = i < 0;
                v = negative ? 0ULL - (unsigned long long)i : (unsigned long long)i;
                f += 1;
            } else if (f[1] == 'l' && f[2] == 'd') {
                long i = va_arg(ap, long);
                negative = i < 0;
                v = negative ? 0ULL - (unsigned long long)i : (unsigned long long)i;
                f += 2;
            } else {
                assert(f[1] == 'z' && f[2] == 'u');
                v = va_arg(ap, size_t);
                f += 2;
            }
            size_t k = sizeof digits;
            do {
                digits[--k] = (char)('0' + v % 10);
                v /= 10;
            } while (v);
            if (negative) {
                digits[--k] = '-';
            }
            piece = digits + k;
            n = sizeof digits - k;
        }
        size_t room = at < cap ? cap - at - 1 : 0;
        memcpy(out + at, piece, n < room ? n : room);
        at += n < room ? n : room;
    }
    va_end(ap);
    if (cap > 0) {
        out[at] = 0;
    }
}
