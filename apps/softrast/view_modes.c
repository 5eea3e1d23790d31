/* view_modes.c - the pipeline modes `softrast view` switches with keys.
 * Every value is the `softrast render` argument that selects it, so the
 * viewer draws through the render options (render_options.c) and the
 * command it prints repeats the view exactly.  A new mode, or a new value
 * of one (an MSAA level, say), is one line of this table. */
#include "view.h"

#include <stdio.h>
#include <string.h>

/* choices[0] is render's default, except for antialiasing: the viewer
 * starts without it, for speed, where render's default is msaa4. */
const view_mode view_modes[] = {
    { 'm', "shading", { { "pbr", "--shading=pbr" }, { "flat", "--shading=flat" },
                        { "gouraud", "--shading=gouraud" }, { "phong", "--shading=phong" },
                        { "normals", "--shading=normals" },
                        { "depth", "--shading=depth" }, { "unlit", "--shading=unlit" } } },
    { 'w', "lines", { { "filled", NULL }, { "wireframe", "--wireframe" },
                      { "hidden-line", "--hidden-line" }, { "edges", "--edges" },
                      { "points", "--points" } } },
    { 'l', "smooth lines", { { "aliased lines", NULL }, { "smooth lines", "--smooth" } } },
    { 'p', "polygon offset", { { "offset 1,1", "--polygon-offset=1,1" },
                               { "offset 0,0", "--polygon-offset=0,0" },
                               { "offset 4,4", "--polygon-offset=4,4" } } },
    { 'c', "culling", { { "cull back", "--cull=back" }, { "cull none", "--cull=none" },
                        { "cull front", "--cull=front" } } },
    { 'v', "front face", { { "ccw", "--front-face=ccw" }, { "cw", "--front-face=cw" } } },
    { 'd', "depth function", { { "depth less", "--depth-func=less" }, { "lequal", "--depth-func=lequal" },
                               { "greater", "--depth-func=greater" },
                               { "gequal", "--depth-func=gequal" },
                               { "equal", "--depth-func=equal" },
                               { "notequal", "--depth-func=notequal" },
                               { "always", "--depth-func=always" },
                               { "never", "--depth-func=never" } } },
    { 'b', "depth format", { { "d24", "--depth-format=d24" }, { "d16", "--depth-format=d16" },
                             { "d32", "--depth-format=d32" }, { "d32f", "--depth-format=d32f" } } },
    { 'a', "antialiasing", { { "aa none", "--aa=none" },
                             { "ssaa2", "--aa=ssaa2" },
                             { "ssaa3", "--aa=ssaa3" },
                             { "ssaa4", "--aa=ssaa4" },
                             { "msaa2", "--aa=msaa2" },
                             { "msaa4", "--aa=msaa4" },
                             { "msaa8", "--aa=msaa8" },
                             { "msaa16", "--aa=msaa16" } } },
    { 'y', "ssaa filter", { { "box filter", "--filter=box" }, { "tent", "--filter=tent" },
                            { "gaussian", "--filter=gaussian" },
                            { "mitchell", "--filter=mitchell" } } },
    { 't', "texture filter", { { "trilinear textures", "--texture-filter=trilinear" },
                               { "bilinear", "--texture-filter=bilinear" },
                               { "nearest", "--texture-filter=nearest" } } },
    { 'u', "texture wrap", { { "wrap repeat", "--wrap=repeat" }, { "clamp", "--wrap=clamp" },
                             { "mirror", "--wrap=mirror" } } },
    { 'i', "interpolation", { { "perspective-correct", "--projection-interp=perspective" },
                              { "affine interpolation", "--projection-interp=affine" } } },
    { 'o', "projection", { { "perspective projection", NULL }, { "orthographic", "--ortho" } } },
    { 'x', "rasterizer", { { "halfspace", "--rasterizer=halfspace" },
                           { "scanline", "--rasterizer=scanline" },
                           { "barycentric", "--rasterizer=barycentric" } } },
    { 'n', "threads", { { "threads auto", NULL }, { "1 thread", "--threads=1" },
                        { "2 threads", "--threads=2" }, { "4 threads", "--threads=4" } } },
};
const int view_mode_count = (int)(sizeof view_modes / sizeof view_modes[0]);

_Static_assert(sizeof view_modes / sizeof view_modes[0] <= 32,
               "view_mode_state.index holds 32 modes");

static int choice_count(const view_mode *m)
{
    int n = 0;
    while (n < VIEW_MAX_CHOICES && m->choices[n].name) {
        n++;
    }
    return n;
}

/* Does argv[i] (with argv[i + 1] for "--opt value") say `want`? */
static bool says(int argc, char *const *argv, int i, const char *want)
{
    if (strcmp(argv[i], want) == 0) {
        return true;
    }
    const char *eq = strchr(want, '=');
    if (!eq || i + 1 >= argc) {
        return false;
    }
    size_t n = (size_t)(eq - want);
    return strlen(argv[i]) == n && memcmp(argv[i], want, n) == 0 &&
           strcmp(argv[i + 1], eq + 1) == 0;
}

/* The option a mode's values set ("--shading"), or NULL for flag values. */
static size_t option_length(const view_mode *m, const char **opt)
{
    for (int c = 0; c < choice_count(m); c++) {
        const char *arg = m->choices[c].arg, *eq = arg ? strchr(arg, '=') : NULL;
        if (eq) {
            *opt = arg;
            return (size_t)(eq - arg);
        }
    }
    *opt = NULL;
    return 0;
}

int view_modes_init(view_mode_state *st, int argc, char *const *argv, const char **base)
{
    memset(st, 0, sizeof *st);
    int n = 0;
    for (int i = 0; i < argc; i++) {
        int used = 0;   /* tokens of argv[i] that select a known choice */
        for (int m = 0; m < view_mode_count && !used; m++) {
            const view_mode *vm = &view_modes[m];
            for (int c = 0; c < choice_count(vm) && !used; c++) {
                const char *arg = vm->choices[c].arg;
                if (arg && says(argc, argv, i, arg)) {
                    st->index[m] = c;   /* the last one wins, as in the parser */
                    used = strcmp(argv[i], arg) == 0 ? 1 : 2;
                }
            }
            const char *opt;
            size_t len = option_length(vm, &opt);
            if (!used && opt && strncmp(argv[i], opt, len) == 0 &&
                (argv[i][len] == 0 || argv[i][len] == '=')) {
                st->index[m] = -1;      /* a value the table does not list: keep it */
            }
        }
        if (used) {
            i += used - 1;   /* the table's argument replaces it */
        } else {
            base[n++] = argv[i];
        }
    }
    return n;
}

int view_mode_for_key(char key)
{
    for (int m = 0; m < view_mode_count; m++) {
        if (view_modes[m].key == key) {
            return m;
        }
    }
    return -1;
}

void view_mode_cycle(view_mode_state *st, int mode, int step)
{
    if (mode < 0 || mode >= view_mode_count) {
        return;
    }
    int n = choice_count(&view_modes[mode]);
    int i = st->index[mode] < 0 ? (step > 0 ? -1 : 0) : st->index[mode];
    st->index[mode] = ((i + step) % n + n) % n;
}

int view_modes_args(const view_mode_state *st, const char **argv, int argc)
{
    for (int m = 0; m < view_mode_count; m++) {
        const char *arg = st->index[m] < 0 ? NULL : view_modes[m].choices[st->index[m]].arg;
        if (arg) {
            argv[argc++] = arg;
        }
    }
    return argc;
}

void view_modes_describe(const view_mode_state *st, char *out, size_t size)
{
    size_t len = 0;
    out[0] = 0;
    for (int m = 0; m < view_mode_count && len + 1 < size; m++) {
        int n = st->index[m] < 0
                    ? snprintf(out + len, size - len, "%s%s as given", m ? ", " : "",
                               view_modes[m].label)
                    : snprintf(out + len, size - len, "%s%s", m ? ", " : "",
                               view_modes[m].choices[st->index[m]].name);
        len += n > 0 ? (size_t)n : 0;
    }
}
