/* memory_limit.c - how much memory the frames of one command may take,
 * checked before they are allocated: a frame larger than the machine can
 * hold is refused in one line instead of being allocated and then
 * touched until the kernel's OOM killer ends the process without a word
 * (Linux overcommits: the allocation itself rarely fails).  The limit is
 * SR_MEMORY_LIMIT when set, else the physical memory, or less under a
 * ulimit. */
#include "cli.h"

#include <ctype.h>
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>

/* "1073741824", "512M", "8G", "1.5T": binary multiples, as ulimit and
 * cgroups count them.  False for anything else. */
static bool parse_bytes(const char *s, uint64_t *out)
{
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || errno || !(v > 0)) {
        return false;
    }
    if (*end) {
        static const char units[] = "KMGT";
        const char *u = strchr(units, toupper((unsigned char)*end));
        if (!u) {
            return false;
        }
        for (const char *k = units; k <= u; k++) {
            v *= 1024;
        }
        end += 1 + (end[1] == 'i');        /* "8G", "8Gi", "8GiB", "8GB" */
        end += *end == 'B';
    }
    if (*end) {
        return false;
    }
    if (v >= 18e18) {
        return false;
    }
    *out = (uint64_t)v;
    return true;
}

int cli_memory_limit(uint64_t *bytes, const char **what)
{
    const char *env = getenv("SR_MEMORY_LIMIT");
    if (env) {
        if (!parse_bytes(env, bytes)) {
            cli_error("SR_MEMORY_LIMIT: expected a size in bytes such as 512M or 8G (got '%s')",
                      env);
            return EXIT_USAGE;
        }
        *what = "SR_MEMORY_LIMIT";
        return -1;
    }
    long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    *bytes = pages > 0 && page > 0 ? (uint64_t)pages * (uint64_t)page : UINT64_MAX;
    *what = "the physical memory";
    static const struct {
        int resource;
        const char *what;
    } limits[] = { { RLIMIT_AS, "the address space limit (ulimit -v)" },
                   { RLIMIT_DATA, "the data size limit (ulimit -d)" } };
    for (size_t i = 0; i < sizeof limits / sizeof limits[0]; i++) {
        struct rlimit rl;
        if (getrlimit(limits[i].resource, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY &&
            (uint64_t)rl.rlim_cur < *bytes) {
            *bytes = (uint64_t)rl.rlim_cur;
            *what = limits[i].what;
        }
    }
    return -1;
}

/* Bytes as people read them: "8.5 GiB", "640 MiB". */
static void format_bytes(uint64_t n, char *buf, size_t size)
{
    double v = (double)n;
    const char *unit = "bytes";
    static const char *const units[] = { "KiB", "MiB", "GiB", "TiB" };
    for (int i = 0; i < 4 && v >= 1024; i++) {
        v /= 1024;
        unit = units[i];
    }
    snprintf(buf, size, v < 10 && unit[0] != 'b' ? "%.1f %s" : "%.0f %s", v, unit);
}

int cli_check_memory(const char *what, uint64_t need, const char *lower)
{
    uint64_t limit;
    const char *source;
    int status = cli_memory_limit(&limit, &source);
    if (status >= 0 || need <= limit) {
        return status;
    }
    char a[32], b[32];
    format_bytes(need, a, sizeof a);
    format_bytes(limit, b, sizeof b);
    if (strcmp(source, "SR_MEMORY_LIMIT") == 0) {
        cli_error("%s needs about %s of frame memory, more than SR_MEMORY_LIMIT=%s allows: %s",
                  what, a, getenv("SR_MEMORY_LIMIT"), lower);
    } else {
        cli_error("%s needs about %s of frame memory, more than the %s of %s: %s "
                  "(SR_MEMORY_LIMIT sets another limit)", what, a, b, source, lower);
    }
    return EXIT_USAGE;
}
