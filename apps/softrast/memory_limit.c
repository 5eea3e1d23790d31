/* memory_limit.c - how much memory the frames of one command may take,
 * checked before they are allocated: a frame larger than the machine can
 * hold is refused in one line instead of being allocated and then touched
 * until the kernel's OOM killer ends the process without a word.  The
 * limit and the message are the library's (sr_check_memory), as the
 * Python package's are. */
#include "cli.h"

#include "softrast_io.h"

#include <stdlib.h>

int cli_check_memory(const char *what, uint64_t need, const char *lower)
{
    sr_io_error err = { { 0 } };
    sr_result r = sr_check_memory(&(sr_memory_check_desc){ .what = what, .bytes = need,
                                                           .memory = "frame memory",
                                                           .lower = lower },
                                  &err);
    if (r == SR_OK) {
        return -1;
    }
    cli_error("%s", err.message);
    return EXIT_USAGE;
}
