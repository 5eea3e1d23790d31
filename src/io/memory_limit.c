/* memory_limit.c - how much memory a program's images may take, checked
 * before they are allocated (sr_query_memory_limit, sr_check_memory): the
 * softrast tool and the Python package both ask here.  Linux overcommits,
 * so an image larger than the machine holds is rarely refused when it is
 * allocated; the OOM killer ends the process later, without a word, as its
 * pages are touched.  Reads the environment and the process limits only:
 * any thread. */
#include "softrast_io.h"

#include "io/io_util.h"
#include "io/number.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>

/* "1073741824", "512M", "8G", "1.5T": binary multiples, as ulimit and
 * cgroups count them; "8Gi", "8GiB" and "8GB" too.  False for anything
 * else, and for 0 and sizes beyond 64 bits. */
static bool parse_bytes(const char *s, uint64_t *out)
{
    const char *end = s + strlen(s);
    double v;
    sr_num_status status;
    size_t n = sr__parse_double_prefix(s, end, &v, &status);
    if (n == 0 || status != SR_NUM_OK || !(v > 0)) {
        return false;
    }
    const char *p = s + n;
    if (*p) {
        static const char units[] = "KMGT";
        const char *u = strchr(units, toupper((unsigned char)*p));
        if (!u) {
            return false;
        }
        for (const char *k = units; k <= u; k++) {
            v *= 1024;
        }
        p += 1 + (p[1] == 'i');
        p += *p == 'B';
    }
    if (*p || v >= 18e18) {
        return false;
    }
    *out = (uint64_t)v;
    return true;
}

sr_result sr_query_memory_limit(sr_memory_limit_info *out, sr_io_error *err)
{
    if (!out) {
        return sr__io_message(err, SR_INVALID_ARG, "sr_query_memory_limit: out is NULL");
    }
    const char *env = getenv("SR_MEMORY_LIMIT");
    if (env) {
        uint64_t bytes;
        if (!parse_bytes(env, &bytes)) {
            return sr__io_message(err, SR_INVALID_ARG,
                                  "SR_MEMORY_LIMIT: expected a size in bytes such as 512M or 8G "
                                  "(got '%.200s')", env);
        }
        *out = (sr_memory_limit_info){ .bytes = bytes, .from_environment = true };
        snprintf(out->source, sizeof out->source, "SR_MEMORY_LIMIT=%.100s", env);
        return SR_OK;
    }
    long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    sr_memory_limit_info info = {
        .bytes = pages > 0 && page > 0 ? (uint64_t)pages * (uint64_t)page : UINT64_MAX,
    };
    const char *what = "the physical memory";
    static const struct {
        int resource;
        const char *what;
    } limits[] = { { RLIMIT_AS, "the address space limit (ulimit -v)" },
                   { RLIMIT_DATA, "the data size limit (ulimit -d)" } };
    for (size_t i = 0; i < sizeof limits / sizeof limits[0]; i++) {
        struct rlimit rl;
        if (getrlimit(limits[i].resource, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY &&
            (uint64_t)rl.rlim_cur < info.bytes) {
            info.bytes = (uint64_t)rl.rlim_cur;
            what = limits[i].what;
        }
    }
    snprintf(info.source, sizeof info.source, "%s", what);
    *out = info;
    return SR_OK;
}

void sr__format_bytes(uint64_t n, char *buf, size_t size)
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

sr_result sr_check_memory(const sr_memory_check_desc *desc, sr_io_error *err)
{
    const char *bad = !desc                             ? "desc is NULL"
                      : !desc->what || !desc->what[0]   ? "sr_memory_check_desc.what must be set"
                      : !desc->lower || !desc->lower[0] ? "sr_memory_check_desc.lower must be set"
                                                        : NULL;
    if (bad) {
        return sr__io_message(err, SR_INVALID_ARG, "sr_check_memory: %s", bad);
    }
    sr_memory_limit_info limit;
    sr_result r = sr_query_memory_limit(&limit, err);
    if (r != SR_OK || desc->bytes <= limit.bytes) {
        return r;
    }
    const char *kind = desc->memory && desc->memory[0] ? desc->memory : "memory";
    char need[32], has[32], allows[256];
    sr__format_bytes(desc->bytes, need, sizeof need);
    sr__format_bytes(limit.bytes, has, sizeof has);
    if (limit.from_environment) {
        snprintf(allows, sizeof allows, "more than %s allows", limit.source);
    } else {
        snprintf(allows, sizeof allows,
                 "more than the %s of %s (SR_MEMORY_LIMIT sets another limit)", has,
                 limit.source);
    }
    return sr__io_message(err, SR_TOO_LARGE, "%s needs about %s of %s, %s: %s", desc->what, need,
                          kind, allows, desc->lower);
}
