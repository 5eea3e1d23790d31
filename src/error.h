/* error.h - failure messages: every failing call records one line naming
 * the argument or field and what is wrong with it, on the context it was
 * given (sr_context_error) and on the calling thread (sr_last_error), so
 * that calls without a context have a message too.  Any thread. */
#ifndef SR_ERROR_H
#define SR_ERROR_H

#include "softrast.h"

/* Record a message for the calling thread and, when ctx is not NULL, on
 * ctx; return `code` (for `return sr__fail(...)`).  ctx NULL is how the
 * calls that take no context report. */
sr_result sr__fail(sr_context *ctx, sr_result code, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

#endif
