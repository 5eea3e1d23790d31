/* svg_path_data.c - SVG path data (the d attribute) into a path (src/io):
 * every command, absolute and relative, implicit repeats, the smooth
 * curves' reflected control points and arcs, stopped at the first error
 * as SVG's error handling asks.  The SVG reader builds its paths through
 * sr_io_parse_path_data, and so do programs (the Python package's
 * Path.from_svg).  Works without expat; any thread, one path per call. */
#include "io/svg.h"
#include "io/io_util.h"
#include "io/number.h"

#include <ctype.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>

/* ---- numbers and separators, shared with svg.c -------------------------- */

const char *svg_skip_ws(const char *s)
{
    while (isspace((unsigned char)*s)) {
        s++;
    }
    return s;
}

const char *svg_skip_ws_comma(const char *s)
{
    s = svg_skip_ws(s);
    if (*s == ',') {
        s = svg_skip_ws(s + 1);
    }
    return s;
}

/* An SVG number (sign, digits, fraction, exponent), no leading blanks. */
bool svg_parse_number(const char **s, double *out)
{
    const char *e = *s + strnlen(*s, 64);
    sr_num_status st = SR_NUM_MALFORMED;
    size_t n = sr__parse_double_prefix(*s, e, out, &st);
    if (n == 0 || n == 64 || st != SR_NUM_OK) {
        return false;
    }
    *s += n;
    return true;
}

/* ---- path commands --------------------------------------------------- */

typedef struct path_build {
    sr_path *path;
    double cx, cy;        /* current point */
    double sx, sy;        /* subpath start */
    double ctrl_x, ctrl_y;/* last control point (for S and T) */
    char last;            /* last command, upper case */
    bool started;
} path_build;

/* One path command with its numbers; the library's result. */
static sr_result path_command(path_build *b, char cmd, const double *a)
{
    bool rel = islower((unsigned char)cmd) != 0;
    char up = (char)toupper((unsigned char)cmd);
    double ox = rel ? b->cx : 0, oy = rel ? b->cy : 0;
    sr_result r = SR_OK;
    switch (up) {
    case 'M':
        b->cx = b->sx = a[0] + ox;
        b->cy = b->sy = a[1] + oy;
        r = sr_path_move_to(b->path, b->cx, b->cy);
        b->started = true;
        break;
    case 'L':
        b->cx = a[0] + ox;
        b->cy = a[1] + oy;
        r = sr_path_line_to(b->path, b->cx, b->cy);
        break;
    case 'H':
        b->cx = a[0] + ox;
        r = sr_path_line_to(b->path, b->cx, b->cy);
        break;
    case 'V':
        b->cy = a[0] + oy;
        r = sr_path_line_to(b->path, b->cx, b->cy);
        break;
    case 'C':
    case 'S': {
        double x1, y1, x2, y2, x, y;
        if (up == 'C') {
            x1 = a[0] + ox, y1 = a[1] + oy, x2 = a[2] + ox, y2 = a[3] + oy;
            x = a[4] + ox, y = a[5] + oy;
        } else { /* first control point: the reflection of the previous one */
            bool prev = b->last == 'C' || b->last == 'S';
            x1 = prev ? 2 * b->cx - b->ctrl_x : b->cx;
            y1 = prev ? 2 * b->cy - b->ctrl_y : b->cy;
            x2 = a[0] + ox, y2 = a[1] + oy, x = a[2] + ox, y = a[3] + oy;
        }
        r = sr_path_cubic_to(b->path, x1, y1, x2, y2, x, y);
        b->ctrl_x = x2;
        b->ctrl_y = y2;
        b->cx = x;
        b->cy = y;
        break;
    }
    case 'Q':
    case 'T': {
        double x1, y1, x, y;
        if (up == 'Q') {
            x1 = a[0] + ox, y1 = a[1] + oy, x = a[2] + ox, y = a[3] + oy;
        } else {
            bool prev = b->last == 'Q' || b->last == 'T';
            x1 = prev ? 2 * b->cx - b->ctrl_x : b->cx;
            y1 = prev ? 2 * b->cy - b->ctrl_y : b->cy;
            x = a[0] + ox, y = a[1] + oy;
        }
        r = sr_path_quad_to(b->path, x1, y1, x, y);
        b->ctrl_x = x1;
        b->ctrl_y = y1;
        b->cx = x;
        b->cy = y;
        break;
    }
    case 'A':
        r = sr_path_arc_to(b->path, a[0], a[1], a[2], a[3] != 0, a[4] != 0, a[5] + ox,
                           a[6] + oy);
        b->cx = a[5] + ox;
        b->cy = a[6] + oy;
        break;
    case 'Z':
        r = sr_path_close(b->path);
        b->cx = b->sx;
        b->cy = b->sy;
        break;
    }
    b->last = up;
    return r;
}

static int args_for(char up)
{
    switch (up) {
    case 'M': case 'L': case 'T': return 2;
    case 'H': case 'V': return 1;
    case 'C': return 6;
    case 'S': case 'Q': return 4;
    case 'A': return 7;
    default: return 0;
    }
}

/* err (when given) and sr_last_error get "path data: DETAIL at offset N". */
static void fail_at(sr_io_error *err, long offset, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

static void fail_at(sr_io_error *err, long offset, const char *fmt, ...)
{
    char detail[128];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(detail, sizeof detail, fmt, ap);
    va_end(ap);
    sr__io_message(err, SR_BAD_FORMAT, "path data: %s at offset %ld", detail, offset);
}

sr_result sr_io_parse_path_data(const char *d, sr_path *path, const sr_io_path_data_desc *desc,
                                long *error_offset, sr_io_error *err)
{
    if (error_offset) {
        *error_offset = -1;
    }
    if (err) {
        err->message[0] = 0;
    }
    if (!d || !path) {
        return sr__io_message(err, SR_INVALID_ARG, "sr_io_parse_path_data: %s is NULL",
                              d ? "path" : "d");
    }
    sr_io_path_data_desc none = { 0 };
    desc = desc ? desc : &none;
    path_build b = { .path = path };
    const char *s = svg_skip_ws(d), *at = s;
    char cmd = 0;
    sr_result r = SR_OK;
    while (*s && r == SR_OK) {
        at = s;
        char up = (char)toupper((unsigned char)*s);
        double a[7];
        if (isalpha((unsigned char)*s)) {
            cmd = *s++;
            if (!args_for(up) && up != 'Z') {
                r = SR_BAD_FORMAT;
                fail_at(err, (long)(at - d), "unknown command '%c'", cmd);
                break;
            }
            if (!b.started && up != 'M') {
                r = SR_BAD_FORMAT;
                fail_at(err, (long)(at - d), "no moveto first");
                break;
            }
            if (up == 'Z') {
                r = path_command(&b, cmd, NULL);
                s = svg_skip_ws_comma(s);
                if (r == SR_OK && desc->command) {
                    r = desc->command(desc->user, cmd, (long)(s - d));
                }
                continue;
            }
        } else if (!cmd || toupper((unsigned char)cmd) == 'Z') {
            r = SR_BAD_FORMAT;
            fail_at(err, (long)(s - d), "expected a command");
            break;
        }
        /* One set of arguments (commands repeat implicitly); a set cut
         * short by an error draws nothing. */
        up = (char)toupper((unsigned char)cmd);
        int n = args_for(up);
        for (int i = 0; i < n && r == SR_OK; i++) {
            s = svg_skip_ws(s);
            if (up == 'A' && (i == 3 || i == 4)) { /* flags: a single 0 or 1 */
                if (*s != '0' && *s != '1') {
                    r = SR_BAD_FORMAT;
                    fail_at(err, (long)(s - d), "arc flag not 0 or 1");
                    break;
                }
                a[i] = *s++ - '0';
            } else if (!svg_parse_number(&s, &a[i])) {
                r = SR_BAD_FORMAT;
                fail_at(err, (long)(s - d), "expected a number");
                break;
            }
            s = svg_skip_ws_comma(s);
        }
        if (r != SR_OK) {
            at = s;
            break;
        }
        r = path_command(&b, cmd, a);
        if (r == SR_OK && desc->command) {
            r = desc->command(desc->user, cmd, (long)(s - d));
        }
        /* After a moveto, further pairs are linetos. */
        if (up == 'M') {
            cmd = cmd == 'M' ? 'L' : 'l';
        }
    }
    if (r != SR_OK && error_offset) {
        *error_offset = (long)(at - d);
    }
    if (r != SR_OK && r != SR_BAD_FORMAT && err && !err->message[0]) {
        /* The path's refusal is already sr_last_error, with its reason. */
        snprintf(err->message, sizeof err->message, "path data: %s at offset %ld",
                 sr_result_text(r), (long)(at - d));
    }
    return r;
}

bool svg_parse_length(const char *s, double em, double *out, bool *percent)
{
    s = svg_skip_ws(s);
    if (!svg_parse_number(&s, out)) {
        return false;
    }
    const struct { const char *unit; double px; } units[] = {
        { "px", 1 }, { "pt", 96.0 / 72 }, { "pc", 16 }, { "in", 96 }, { "cm", 96 / 2.54 },
        { "mm", 96 / 25.4 }, { "em", em }, { "ex", em / 2 },
    };
    if (percent) {
        *percent = false;
    }
    s = svg_skip_ws(s);
    if (*s == 0) {
        return true;
    }
    if (*s == '%' && percent) {
        *percent = true;
        return *svg_skip_ws(s + 1) == 0;
    }
    for (size_t i = 0; i < sizeof units / sizeof units[0]; i++) {
        size_t n = strlen(units[i].unit);
        if (strncasecmp(s, units[i].unit, n) == 0 && *svg_skip_ws(s + n) == 0) {
            *out *= units[i].px;
            return true;
        }
    }
    return false;
}
