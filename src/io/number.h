/* number.h - decimal numbers in the text formats (src/io): OBJ, PLY, STL
 * and SVG read them through this one parser.  It ignores the C locale (a
 * host program's setlocale(LC_ALL, "de_DE.UTF-8") would make strtod stop
 * at the '.' of "0.5") and is correctly rounded: for every decimal string
 * it gives exactly what strtod (double) and strtof (float) give in the C
 * locale.  Pure functions of their arguments: any thread. */
#ifndef SR_IO_NUMBER_H
#define SR_IO_NUMBER_H

#include <stdbool.h>
#include <stddef.h>

typedef enum sr_num_status {
    SR_NUM_OK,
    SR_NUM_MALFORMED,      /* not the grammar below */
    SR_NUM_NOT_FINITE,     /* the words inf, infinity, nan, nan(chars): *out is that value */
    SR_NUM_OVERFLOW,       /* digits beyond the type's range (1e39 for a float): *out is +-inf */
} sr_num_status;

/* The whole of [s, e) as [+-] (digits [. [digits]] | . digits)
 * [(e|E) [+-] digits], or one of the words of SR_NUM_NOT_FINITE (any case,
 * optional sign).  No blanks, no hexadecimal.  A value below the smallest
 * subnormal rounds to a signed zero, as strtod's does. */
sr_num_status sr__parse_double(const char *s, const char *e, double *out);
sr_num_status sr__parse_float(const char *s, const char *e, float *out);

/* Length of the decimal number (the digits form above; an exponent only
 * when digits follow it) at the start of [s, e), 0 when there is none:
 * for formats where a number runs into what follows ("10px", "1.5.5"). */
size_t sr__scan_decimal(const char *s, const char *e);

/* sr__scan_decimal and sr__parse_double in one pass: the number's length
 * (0 when there is none: *out and *status are then untouched), its
 * status in *status and, unless malformed, its value in *out. */
size_t sr__parse_double_prefix(const char *s, const char *e, double *out, sr_num_status *status);

#endif /* SR_IO_NUMBER_H */
