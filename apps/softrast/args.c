/* args.c - option value parsers for the CLI.  Every failure prints one
 * line that names the option and the offending text. */
#include "cli.h"

#include <ctype.h>
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

/* Where messages go instead of stderr while a batch holds them
 * (cli_capture): one place a thread, as a batch reads the next model on
 * one thread while it draws the last on another. */
static _Thread_local char *capture_buf;
static _Thread_local size_t capture_size;

void cli_capture(char *buf, size_t size)
{
    capture_buf = size ? buf : NULL;
    capture_size = size;
    if (capture_buf) {
        capture_buf[0] = '\0';
    }
}

void cli_one_line(char *text)
{
    for (unsigned char *c = (unsigned char *)text; *c; c++) {
        if (*c < 0x20 || *c == 0x7f) {
            *c = '?';
        }
    }
}

static void report(const char *prefix, const char *fmt, va_list ap)
{
    if (!capture_buf) {
        char line[8192];
        vsnprintf(line, sizeof line, fmt, ap);
        cli_one_line(line);
        fprintf(stderr, "%s%s\n", prefix, line);
        return;
    }
    /* Held messages are joined with "; " into one line. */
    size_t n = strlen(capture_buf);
    if (n > 0 && n + 2 < capture_size) {
        memcpy(capture_buf + n, "; ", 3);
        n += 2;
    }
    if (n + 1 < capture_size) {
        vsnprintf(capture_buf + n, capture_size - n, fmt, ap);
        cli_one_line(capture_buf + n);
    }
}

const char *cli_why(sr_result r)
{
    return sr_last_error()[0] ? sr_last_error() : sr_result_text(r);
}

void cli_error(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    report("softrast: ", fmt, ap);
    va_end(ap);
}

void cli_message(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    report("", fmt, ap);
    va_end(ap);
}

cli_arg_kind cli_arg(const char *arg, bool *ended)
{
    if (*ended || arg[0] != '-' || arg[1] == '\0') {
        return CLI_ARG_OPERAND;
    }
    if (strcmp(arg, "--") == 0) {
        *ended = true;
        return CLI_ARG_END;
    }
    return CLI_ARG_OPTION;
}

void cli_split_option(const char *arg, cli_opt *o)
{
    const char *eq = strncmp(arg, "--", 2) == 0 ? strchr(arg, '=') : NULL;
    size_t n = eq ? (size_t)(eq - arg) : strlen(arg);
    /* A name too long for any option stays whole: it is unknown anyway. */
    if (n >= sizeof o->name) {
        n = sizeof o->name - 1;
        eq = NULL;
    }
    memcpy(o->name, arg, n);
    o->name[n] = '\0';
    o->value = eq ? eq + 1 : NULL;
}

const char *cli_option_value(const cli_opt *o, int argc, char **argv, int *i)
{
    if (o->value) {
        return o->value;
    }
    if (*i + 1 >= argc) {
        cli_error("%s: missing value", o->name);
        return NULL;
    }
    return argv[++*i];
}

bool cli_option_flag(const cli_opt *o)
{
    if (o->value) {
        cli_error("%s: takes no value", o->name);
        return false;
    }
    return true;
}

int cli_help_option(const cli_opt *o, void (*help)(FILE *))
{
    if (strcmp(o->name, "-h") != 0 && strcmp(o->name, "--help") != 0) {
        return -1;
    }
    if (!cli_option_flag(o)) {
        return EXIT_USAGE;
    }
    help(stdout);
    return EXIT_OK;
}

bool parse_int(const char *opt, const char *s, int lo, int hi, int *out)
{
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (errno || end == s || *end || v < lo || v > hi) {
        cli_error("%s: expected a whole number from %d to %d (got '%s')", opt, lo, hi, s);
        return false;
    }
    *out = (int)v;
    return true;
}

bool parse_float(const char *opt, const char *s, float lo, float hi, float *out)
{
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    /* Compared as the float it is stored as: a limit written as a float
     * literal (0.001f) rounds away from its decimal, so the double parsed
     * from that same decimal may fall just outside it. */
    bool ok = !errno && end != s && !*end && isfinite(v) && fabs(v) <= FLT_MAX;
    float f = ok ? (float)v : 0.0f;
    if (!ok || f < lo || f > hi) {
        cli_error("%s: expected a number from %g to %g (got '%s')", opt, (double)lo, (double)hi, s);
        return false;
    }
    *out = f;
    return true;
}

/* A side of WxH: digits only (no sign or space), from 1 to max; *s moves
 * past them.  strtol, unlike sscanf's %d, says when
 * a number overflows. */
static bool size_side(const char **s, int max, int *out)
{
    if (!isdigit((unsigned char)**s)) {
        return false;
    }
    char *end;
    errno = 0;
    long v = strtol(*s, &end, 10);
    *s = end;
    if (errno || v < 1 || v > max) {
        return false;
    }
    *out = (int)v;
    return true;
}

bool parse_size(const char *opt, const char *s, int *w, int *h)
{
    return parse_size_max(opt, s, SR_MAX_FRAMEBUFFER_SIZE, w, h);
}

bool parse_size_max(const char *opt, const char *s, int max, int *w, int *h)
{
    int a, b;
    const char *p = s;
    bool ok = size_side(&p, max, &a) && (*p == 'x' || *p == 'X');
    if (ok) {
        p++;
        ok = size_side(&p, max, &b) && *p == 0;
    }
    if (!ok) {
        cli_error("%s: expected WxH with each from 1 to %d (got '%s')", opt, max, s);
        return false;
    }
    *w = a;
    *h = b;
    return true;
}

bool parse_vec3(const char *opt, const char *s, sr_vec3 *out)
{
    float v[3];
    const char *p = s;
    for (int i = 0; i < 3; i++) {
        char *end;
        errno = 0;
        double d = strtod(p, &end);
        if (errno || end == p || !isfinite(d) || (i < 2 && *end != ',') || (i == 2 && *end)) {
            cli_error("%s: expected three numbers X,Y,Z (got '%s')", opt, s);
            return false;
        }
        v[i] = (float)d;
        p = end + 1;
    }
    *out = (sr_vec3){ v[0], v[1], v[2] };
    return true;
}

static const struct { const char *name; unsigned rgb; } color_names[] = {
    { "black", 0x000000 }, { "white", 0xffffff }, { "red", 0xff0000 }, { "green", 0x008000 },
    { "lime", 0x00ff00 }, { "blue", 0x0000ff }, { "yellow", 0xffff00 }, { "cyan", 0x00ffff },
    { "magenta", 0xff00ff }, { "gray", 0x808080 }, { "grey", 0x808080 }, { "silver", 0xc0c0c0 },
    { "maroon", 0x800000 }, { "olive", 0x808000 }, { "navy", 0x000080 }, { "teal", 0x008080 },
    { "purple", 0x800080 }, { "orange", 0xffa500 }, { "brown", 0xa52a2a }, { "pink", 0xffc0cb },
    { "gold", 0xffd700 }, { "skyblue", 0x87ceeb }, { "steelblue", 0x4682b4 },
    { "slategray", 0x708090 }, { "darkgray", 0xa9a9a9 }, { "lightgray", 0xd3d3d3 },
    { "ivory", 0xfffff0 }, { "coral", 0xff7f50 }, { "crimson", 0xdc143c },
};

/* Names (CSS/SVG keywords), #rgb, #rrggbb, three numbers r,g,b in [0, 1],
 * or one number: a gray level in [0, 1]. */
bool parse_color(const char *opt, const char *s, sr_vec3 *out)
{
    for (size_t i = 0; i < sizeof color_names / sizeof color_names[0]; i++) {
        if (strcasecmp(s, color_names[i].name) == 0) {
            unsigned c = color_names[i].rgb;
            *out = (sr_vec3){ ((c >> 16) & 255) / 255.0f, ((c >> 8) & 255) / 255.0f,
                              (c & 255) / 255.0f };
            return true;
        }
    }
    size_t n = strlen(s);
    if (s[0] == '#' && (n == 4 || n == 7)) {
        bool hex = true;
        for (size_t i = 1; i < n; i++) {
            hex &= isxdigit((unsigned char)s[i]) != 0;
        }
        if (hex) {
            unsigned v = (unsigned)strtoul(s + 1, NULL, 16);
            if (n == 4) {
                unsigned r = (v >> 8) & 15, g = (v >> 4) & 15, b = v & 15;
                v = (r * 17) << 16 | (g * 17) << 8 | (b * 17);
            }
            *out = (sr_vec3){ ((v >> 16) & 255) / 255.0f, ((v >> 8) & 255) / 255.0f,
                              (v & 255) / 255.0f };
            return true;
        }
    }
    sr_vec3 v;
    char *end;
    double gray = strtod(s, &end);
    if (end != s && *end == 0 && gray >= 0.0 && gray <= 1.0) {
        *out = (sr_vec3){ (float)gray, (float)gray, (float)gray };
        return true;
    }
    /* R,G,B: three numbers and nothing after them. */
    float *c[3] = { &v.x, &v.y, &v.z };
    const char *p = s;
    bool ok = true;
    for (int i = 0; i < 3 && ok; i++) {
        errno = 0;
        double d = strtod(p, &end);
        ok = !errno && end != p && isfinite(d) && d >= 0.0 && d <= FLT_MAX &&
             *end == (i < 2 ? ',' : 0);
        *c[i] = (float)d;
        p = end + 1;
    }
    if (ok) {
        *out = v;
        return true;
    }
    cli_error("%s: expected a color name, #rgb, #rrggbb, R,G,B or a gray level 0..1 (got '%s')",
              opt, s);
    return false;
}

bool parse_choice(const char *opt, const char *s, const char *const *names, int *out)
{
    for (int i = 0; names[i]; i++) {
        if (strcmp(s, names[i]) == 0) {
            *out = i;
            return true;
        }
    }
    char list[256] = "";
    for (int i = 0; names[i]; i++) {
        strncat(list, i ? "|" : "", sizeof list - strlen(list) - 1);
        strncat(list, names[i], sizeof list - strlen(list) - 1);
    }
    cli_error("%s: expected one of %s (got '%s')", opt, list, s);
    return false;
}

bool parse_kv_list(const char *opt, const char *s, kv_fn fn, void *user)
{
    char buf[512];
    if (strlen(s) >= sizeof buf) {
        cli_error("%s: value too long", opt);
        return false;
    }
    strcpy(buf, s);
    char *p = buf;
    while (*p) {
        char *eq = strchr(p, '=');
        if (!eq) {
            cli_error("%s: expected key=value pairs (got '%s')", opt, s);
            return false;
        }
        *eq = 0;
        char *value = eq + 1;
        /* The value runs to the comma before the next "key=". */
        char *next = value + strlen(value);
        for (char *c = value; *c; c++) {
            if (*c == ',') {
                char *k = c + 1;
                while (isalpha((unsigned char)*k)) {
                    k++;
                }
                if (*k == '=' && k > c + 1) {
                    *c = 0;
                    next = c + 1;
                    break;
                }
            }
        }
        bool at_end = next == value + strlen(value);
        if (!fn(user, opt, p, value)) {
            return false;
        }
        if (at_end) {
            break;
        }
        p = next;
    }
    return true;
}
