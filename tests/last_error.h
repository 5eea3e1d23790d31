/* last_error.h - the check test_last_error and test_last_error_io make of
 * each failing call: its result, and the thread's message naming what is
 * wrong (sr_last_error). */
#ifndef SR_TEST_LAST_ERROR_H
#define SR_TEST_LAST_ERROR_H

#include "sr_test.h"
#include "softrast.h"

/* `call` fails with `code`, and this thread's message then holds `needle`
 * (the message cleared first, so that an old one cannot pass). */
#define CHECK_FAILS(call, code, needle)                                      \
    do {                                                                     \
        sr_set_last_error(NULL);                                             \
        CHECK_EQ((call), (code));                                            \
        CHECK_STR_CONTAINS(sr_last_error(), (needle));                       \
    } while (0)

#endif
