/* make_parents.c - the directories above an output file, made before it is
 * written (mkdir -p of its dirname): a batch's --output-dir and --name, and
 * explain's -o DIR or PATTERN, may name directories that do not exist yet. */
#include "cli.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

bool cli_make_parents(const char *path, sr_io_error *err)
{
    char dir[4096];
    snprintf(dir, sizeof dir, "%s", path);
    for (char *p = dir + 1; *p; p++) {
        if (*p != '/') {
            continue;
        }
        *p = '\0';
        if (mkdir(dir, 0777) != 0 && errno != EEXIST) {
            snprintf(err->message, sizeof err->message, "cannot make the directory '%.400s': %s",
                     dir, strerror(errno));
            return false;
        }
        *p = '/';
    }
    return true;
}
