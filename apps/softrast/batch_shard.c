/* batch_shard.c - which share of a batch's inputs this process renders,
 * so that a cluster's scheduler can run N copies of one command over one
 * list: --shard I/N, or the index (and count) a Kubernetes Indexed Job or
 * a Slurm job array puts in each task's environment.  An input belongs
 * to shard hash(path) mod N: every input lands on exactly one shard,
 * always the same one, whatever the order of the list or its other
 * entries (a list that grows moves no finished input to another shard). */
#include "batch.h"
#include "cli.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

/* More tasks than any array a scheduler runs (Slurm's MaxArraySize is
 * at most 4000001). */
#define SHARD_MAX_COUNT 100000000L

/* A whole decimal number in [lo, hi] from `s`, all of it; false after one
 * line naming `what` (an option or an environment variable). */
static bool parse_whole(const char *what, const char *s, long lo, long hi, long *out)
{
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (errno || end == s || *end || s[0] == ' ' || s[0] == '+' || v < lo || v > hi) {
        cli_error("%s: expected a whole number from %ld to %ld (got '%s')", what, lo, hi, s);
        return false;
    }
    *out = v;
    return true;
}

/* An environment variable's number, or `dflt` when it is not set. */
static bool env_whole(const char *name, long dflt, long lo, long hi, long *out)
{
    const char *s = getenv(name);
    if (!s) {
        *out = dflt;
        return true;
    }
    return parse_whole(name, s, lo, hi, out);
}

static int from_option(const char *shard, batch_shard *out)
{
    const char *slash = strchr(shard, '/');
    char index[32];
    long i, n;
    if (!slash || (size_t)(slash - shard) >= sizeof index) {
        cli_error("--shard: expected I/N, shard I (from 0) of N (got '%s')", shard);
        return EXIT_USAGE;
    }
    memcpy(index, shard, (size_t)(slash - shard));
    index[slash - shard] = '\0';
    if (!parse_whole("--shard (the count N of I/N)", slash + 1, 1, SHARD_MAX_COUNT, &n) ||
        !parse_whole("--shard (the index I of I/N)", index, 0, n - 1, &i)) {
        return EXIT_USAGE;
    }
    *out = (batch_shard){ (int)i, (int)n, "--shard" };
    return -1;
}

/* A Slurm array's task: its ID less the array's first ID, over its step
 * (--array=1-8 numbers tasks 1..8, --array=0-30:10 numbers 0,10,20,30). */
static int from_slurm(const char *count, batch_shard *out)
{
    long id, min, step, n;
    if (!env_whole("SLURM_ARRAY_TASK_ID", 0, 0, SHARD_MAX_COUNT * 1000, &id) ||
        !env_whole("SLURM_ARRAY_TASK_MIN", 0, 0, id, &min) ||
        !env_whole("SLURM_ARRAY_TASK_STEP", 1, 1, SHARD_MAX_COUNT, &step)) {
        return EXIT_USAGE;
    }
    if (count) {
        if (!parse_whole("--shard-count", count, 1, SHARD_MAX_COUNT, &n)) {
            return EXIT_USAGE;
        }
    } else if (!getenv("SLURM_ARRAY_TASK_COUNT")) {
        cli_error("SLURM_ARRAY_TASK_ID is set but not SLURM_ARRAY_TASK_COUNT (give --shard-count N)");
        return EXIT_USAGE;
    } else if (!env_whole("SLURM_ARRAY_TASK_COUNT", 1, 1, SHARD_MAX_COUNT, &n)) {
        return EXIT_USAGE;
    }
    long i = (id - min) / step;
    if ((id - min) % step != 0 || i >= n) {
        cli_error("SLURM_ARRAY_TASK_ID %ld is not one of the %ld tasks from %ld in steps of %ld",
                  id, n, min, step);
        return EXIT_USAGE;
    }
    *out = (batch_shard){ (int)i, (int)n, "SLURM_ARRAY_TASK_ID" };
    return -1;
}

int batch_shard_resolve(const char *shard, const char *count, batch_shard *out)
{
    *out = (batch_shard){ 0, 1, NULL };
    if (shard) {
        if (count) {
            cli_error("--shard-count: give either --shard I/N or --shard-count N");
            return EXIT_USAGE;
        }
        return from_option(shard, out);
    }
    const char *job_index = getenv("JOB_COMPLETION_INDEX");
    if (job_index) {
        long i, n;
        if (!count) {
            cli_error("JOB_COMPLETION_INDEX is set (a Kubernetes Indexed Job): give the job's "
                      "completions as --shard-count N");
            return EXIT_USAGE;
        }
        if (!parse_whole("--shard-count", count, 1, SHARD_MAX_COUNT, &n) ||
            !parse_whole("JOB_COMPLETION_INDEX", job_index, 0, n - 1, &i)) {
            return EXIT_USAGE;
        }
        *out = (batch_shard){ (int)i, (int)n, "JOB_COMPLETION_INDEX" };
        return -1;
    }
    if (getenv("SLURM_ARRAY_TASK_ID")) {
        return from_slurm(count, out);
    }
    if (count) {
        cli_error("--shard-count: neither JOB_COMPLETION_INDEX nor SLURM_ARRAY_TASK_ID is set "
                  "(use --shard I/N)");
        return EXIT_USAGE;
    }
    return -1;
}

/* FNV-1a, 64 bits, then MurmurHash3's finalizer so that the low bits a
 * small N keeps depend on every byte: fixed by their definitions, so
 * every machine of a cluster agrees on the shards. */
static uint64_t path_hash(const char *s)
{
    uint64_t h = 14695981039346656037ull;
    for (; *s; s++) {
        h = (h ^ (unsigned char)*s) * 1099511628211ull;
    }
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdull;
    h ^= h >> 33;
    h *= 0xc4ceb9fe1a85ec53ull;
    return h ^ (h >> 33);
}

bool batch_in_shard(const char *input, const batch_shard *s)
{
    return s->count <= 1 || path_hash(input) % (uint64_t)s->count == (uint64_t)s->index;
}
