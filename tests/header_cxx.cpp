// Compiles the public headers as C++ (STYLE.md: headers usable from C++).
#include "softrast.h"
#include "softrast_io.h"
static sr_draw_desc desc_is_aggregate = {};
