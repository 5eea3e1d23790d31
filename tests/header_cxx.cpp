// Compiles the public headers as C++ (STYLE.md: headers usable from C++).
#include "softrast.h"
#include "softrast_io.h"

// Descriptor structs stay aggregates that zero-initialize from {}.
extern const sr_draw_desc sr_header_cxx_desc;
const sr_draw_desc sr_header_cxx_desc = {};
