/* error.c - failure messages: the context's (sr_context_error) and the
 * calling thread's (sr_last_error), which every failing call sets,
 * softrast_io's included (through sr_set_last_error).  Any thread; a
 * context's message is written by the one thread using the context. */
#include "error.h"
#include "context.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

/* One message a thread, as errno is one number a thread.  The embedded
 * profile runs on one thread, and a bare-metal target may have no runtime
 * for thread-local storage (ARM's __aeabi_read_tp), so there it is one
 * static buffer. */
#ifdef SR_EMBEDDED
#define SR__THREAD_LOCAL
#else
#define SR__THREAD_LOCAL _Thread_local
#endif

/* As long as softrast_io's messages (sr_io_error.message). */
static SR__THREAD_LOCAL char last_error[512];

/* Copy as much of src as fits in dst[size], always terminated. */
static void copy_message(char *dst, size_t size, const char *src)
{
    size_t n = strlen(src);
    if (n >= size) {
        n = size - 1;
    }
    memmove(dst, src, n);
    dst[n] = 0;
}

sr_result sr__fail(sr_context *ctx, sr_result code, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(last_error, sizeof last_error, fmt, ap);
    va_end(ap);
    if (ctx) {
        copy_message(ctx->error, sizeof ctx->error, last_error);
    }
    return code;
}

void sr__ok(sr_context *ctx)
{
    ctx->error[0] = 0;
}

const char *sr_context_error(const sr_context *ctx)
{
    return ctx ? ctx->error : "sr_context is NULL";
}

const char *sr_last_error(void)
{
    return last_error;
}

void sr_set_last_error(const char *message)
{
    copy_message(last_error, sizeof last_error, message ? message : "");
}
