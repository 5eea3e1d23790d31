/*
 * context_cache.c - the context, framebuffer and per-vertex scratch that
 * render() draws with, kept from one call for the next.  Making them is
 * most of a small view's time: the pool's threads start, and the
 * framebuffer's and the scratch's pages are mapped and populated afresh;
 * a batch of views pays for that once.  Taken and given back with the
 * GIL held, so one call at a time draws with the kept set; a call that
 * finds it taken (another Python thread is rendering) makes its own.
 */
#include "module.h"

#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* What sr_make_context reads besides its desc (softrast.h): a kept
 * context is reused only while they say the same. */
static const char *const env_names[] = { "SR_THREADS", "SR_SIMD" };
enum { ENV_COUNT = sizeof env_names / sizeof env_names[0], ENV_MAX = 32 };

static struct {
    sr_py_render_set set;
    bool kept, taken;
    pid_t pid;
    char env[ENV_COUNT][ENV_MAX + 2];   /* "" unset; values longer than ENV_MAX never match */
} cache;

static void env_snapshot(char out[ENV_COUNT][ENV_MAX + 2])
{
    /* Compared whole (memcmp): the bytes after each value too. */
    memset(out, 0, ENV_COUNT * (ENV_MAX + 2));
    for (int i = 0; i < ENV_COUNT; i++) {
        const char *v = getenv(env_names[i]);
        out[i][0] = '\0';
        if (v) {
            size_t n = strlen(v);
            /* "=" marks set, so that an empty value differs from unset;
             * too long a value is marked so that it never matches. */
            out[i][0] = n > ENV_MAX ? '!' : '=';
            memcpy(out[i] + 1, v, n > ENV_MAX ? 0 : n);
            out[i][n > ENV_MAX ? 1 : n + 1] = '\0';
        }
    }
}

void sr_py_release_render_set(sr_py_render_set *s)
{
    if (s->ctx) {
        sr_destroy_framebuffer(s->ctx, s->fb);
        sr_destroy_context(s->ctx);
    }
    free(s->vertices);
    free(s->visibility);
    memset(s, 0, sizeof *s);
}

void sr_py_take_render_set(int threads, sr_py_render_set *out)
{
    memset(out, 0, sizeof *out);
    if (cache.kept && cache.pid != getpid()) {
        /* A forked child: the parent's pool threads are not here to be
         * joined, so its context is left as it is, never destroyed. */
        memset(&cache, 0, sizeof cache);
    }
    if (!cache.kept || cache.taken) {
        return;
    }
    char env[ENV_COUNT][ENV_MAX + 2];
    env_snapshot(env);
    if (cache.set.threads != threads || memcmp(env, cache.env, sizeof env) != 0) {
        sr_py_release_render_set(&cache.set);
        cache.kept = false;
        return;
    }
    *out = cache.set;
    out->cached = true;
    cache.taken = true;
}

void sr_py_give_back_render_set(sr_py_render_set *s, bool keep)
{
    if (s->cached) {
        cache.taken = false;
        cache.kept = keep;
    }
    if (keep && (s->cached || !cache.kept)) {
        cache.set = *s;
        cache.set.cached = false;
        if (!s->cached) {
            cache.kept = true;
            cache.pid = getpid();
            env_snapshot(cache.env);
        }
    } else {
        sr_py_release_render_set(s);
    }
    memset(s, 0, sizeof *s);
}
