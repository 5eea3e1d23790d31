/* batch_log.c - what a batch tells about each input: a JSON Lines record
 * per input for pipelines (--log), and a progress line for people, drawn
 * only on a terminal so that logs and pipes carry nothing but errors. */
#include "batch.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

typedef struct text {
    char *s;
    size_t len, cap;
    bool failed;
} text;

static void put(text *t, const char *s, size_t n)
{
    if (t->failed) {
        return;
    }
    if (t->len + n + 1 > t->cap) {
        size_t cap = t->cap ? t->cap : 256;
        while (t->len + n + 1 > cap) {
            cap *= 2;
        }
        char *grown = realloc(t->s, cap);
        if (!grown) {
            t->failed = true;
            return;
        }
        t->s = grown;
        t->cap = cap;
    }
    memcpy(t->s + t->len, s, n);
    t->len += n;
    t->s[t->len] = '\0';
}

static void putf(text *t, const char *fmt, double v)
{
    char buf[64];
    int n = snprintf(buf, sizeof buf, fmt, v);
    put(t, buf, (size_t)n);
}

/* The length of the UTF-8 sequence at s, or 0 when it is not one. */
static size_t utf8_length(const unsigned char *s)
{
    size_t n = s[0] >= 0xf0 && s[0] <= 0xf4 ? 4 : s[0] >= 0xe0 ? 3 : s[0] >= 0xc2 ? 2 : 0;
    if (s[0] >= 0xf8) {
        n = 0;
    }
    for (size_t i = 1; i < n; i++) {
        if ((s[i] & 0xc0) != 0x80) {
            return 0;
        }
    }
    return n;
}

/* A JSON string, or null.  File names are bytes, JSON is Unicode: a byte
 * that is not part of valid UTF-8 becomes U+FFFD. */
static void put_string(text *t, const char *s)
{
    if (!s) {
        put(t, "null", 4);
        return;
    }
    put(t, "\"", 1);
    for (const unsigned char *p = (const unsigned char *)s; *p;) {
        char esc[8];
        if (*p == '"' || *p == '\\') {
            esc[0] = '\\';
            esc[1] = (char)*p;
            put(t, esc, 2);
            p++;
        } else if (*p < 0x20) {
            snprintf(esc, sizeof esc, "\\u%04x", *p);
            put(t, esc, 6);
            p++;
        } else if (*p < 0x80) {
            put(t, (const char *)p, 1);
            p++;
        } else {
            size_t n = utf8_length(p);
            put(t, n ? (const char *)p : "\xef\xbf\xbd", n ? n : 3);
            p += n ? n : 1;
        }
    }
    put(t, "\"", 1);
}

bool batch_log_write(int fd, const batch_record *r)
{
    text t = { 0 };
    put(&t, "{\"input\":", 9);
    put_string(&t, r->input);
    put(&t, ",\"output\":", 10);
    put_string(&t, r->output);
    putf(&t, ",\"index\":%.0f", (double)r->index);
    put(&t, ",\"status\":", 10);
    put_string(&t, r->status);
    put(&t, ",\"error\":", 9);
    put_string(&t, r->error);
    putf(&t, ",\"triangles\":%.0f", (double)r->triangles);
    putf(&t, ",\"load_ms\":%.3f", r->load_ms);
    putf(&t, ",\"render_ms\":%.3f", r->render_ms);
    putf(&t, ",\"encode_ms\":%.3f", r->encode_ms);
    putf(&t, ",\"ms\":%.3f", r->load_ms + r->render_ms + r->encode_ms);
    put(&t, "}\n", 2);
    bool ok = !t.failed;
    /* One write to a file opened O_APPEND: shards sharing a log never
     * interleave within a record. */
    for (size_t done = 0; ok && done < t.len;) {
        ssize_t w = write(fd, t.s + done, t.len - done);
        if (w < 0 && errno == EINTR) {
            continue;
        }
        ok = w > 0;
        done += ok ? (size_t)w : 0;
    }
    free(t.s);
    return ok;
}

void batch_progress_start(batch_progress *p, size_t total, double now_ms)
{
    *p = (batch_progress){ .tty = isatty(STDERR_FILENO) == 1, .total = total,
                           .start_ms = now_ms };
}

void batch_progress_show(batch_progress *p, double now_ms, bool final)
{
    if (!p->tty || (!final && p->shown && now_ms - p->drawn_ms < 100.0)) {
        return;
    }
    double secs = (now_ms - p->start_ms) / 1000.0;
    double rate = secs > 0.0 ? (double)p->done / secs : 0.0;
    double eta = rate > 0.0 ? (double)(p->total - p->done) / rate : 0.0;
    fprintf(stderr, "\r\033[K%zu/%zu  %.1f/s  ETA %d:%02d", p->done, p->total, rate,
            (int)(eta / 60.0), (int)eta % 60);
    if (p->skipped) {
        fprintf(stderr, "  %zu skipped", p->skipped);
    }
    if (p->failed) {
        fprintf(stderr, "  %zu failed", p->failed);
    }
    fputs(final ? "\n" : "", stderr);
    fflush(stderr);
    p->shown = !final;
    p->drawn_ms = now_ms;
}

void batch_progress_clear(batch_progress *p)
{
    if (p->tty && p->shown) {
        fputs("\r\033[K", stderr);
        p->shown = false;
    }
}
