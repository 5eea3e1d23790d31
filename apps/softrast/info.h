/* info.h - `softrast info`'s parts (info.c, info_metadata.c). */
#ifndef SR_CLI_INFO_H
#define SR_CLI_INFO_H

#include "softrast_io.h"

/* A JSON string on stdout: quotes, backslashes and control bytes escaped. */
void info_json_string(const char *s);
/* What the file says about itself (sr_scene.metadata): lines of text, or
 * the "metadata" member of the JSON object. */
void info_print_metadata_text(const sr_scene *sc);
void info_print_metadata_json(const sr_scene *sc);

#endif
