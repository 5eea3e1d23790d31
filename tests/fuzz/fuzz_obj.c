/* fuzz_obj.c - libFuzzer target: sr_parse_obj on arbitrary bytes (see
 * fuzz_mesh.h for what is checked).  scripts/fuzz.sh fuzz_obj SECONDS. */
#include "fuzz_mesh.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    sr_mesh m;
    sr_io_error err;
    memset(&m, 0, sizeof m);
    memset(&err, 0, sizeof err);
    sr_result r = sr_parse_obj(fuzz_context(), "fuzz.obj", (const char *)data, size, &m, &err);
    fuzz_check_mesh(r, &m, &err);
    return 0;
}
