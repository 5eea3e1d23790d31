/* explain_transform.c - `softrast explain transform`: one triangle's
 * vertices through the viewing pipeline S P E M_O, stage by stage: object
 * coordinates, the modelling transformation M_O into the world, the camera
 * frame u, v, w built from eye, target and up and the camera matrix E into
 * eye coordinates, the projection P (perspective or orthographic) into clip
 * space, the perspective divide into NDC and the viewport matrix S onto the
 * pixel extents of the grid, snapped as the rasterizer gets them.  Every
 * matrix is the library's (sr_mat4_*, sr_camera_frame, sr_perspective,
 * sr_ortho, sr_fit_fovy, sr_viewport_matrix) and the window position is
 * computed as the pipeline's vertex stage does (docs/raster-rules.md 1.4),
 * so the last frame's pixels are what sr_draw draws with these matrices. */
#include "explain.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define PI 3.14159265358979323846

static const sr_rgba AXIS = { 0.45f, 0.47f, 0.52f, 1 };
static const sr_rgba CAMERA = { 0.85f, 0.45f, 0.10f, 1 };

/* The stages' matrices and each vertex at each stage. */
typedef struct stages {
    sr_mat4 model, view, proj, mv, mvp, viewport;
    sr_camera_basis basis;
    double aspect, fovy;         /* the projection's, as given to it */
    double half_w, half_h;       /* orthographic: the view volume's half extents */
    sr_vec4 obj[3], world[3], eye[3], clip[3];
    double ndc[3][3];
    int64_t x_q8[3], y_q8[3];    /* the window position, snapped */
} stages;

static sr_vec3 vec3(const double v[3])
{
    return sr_vec3_make((float)v[0], (float)v[1], (float)v[2]);
}

/* The pipeline's snap (round to nearest even, as sr_draw's). */
static int64_t snap(double v)
{
    return (int64_t)nearbyint(v * 256.0);
}

/* All the stages of prim's triangle for a viewport of the whole grid;
 * false when the camera frame cannot be built (eye on the target, up
 * along the gaze). */
static bool compute(const ex_primitive *prim, int grid_w, int grid_h, stages *s)
{
    const ex_view *v = &prim->view;
    memset(s, 0, sizeof *s);
    sr_mat4 r = sr_mat4_rotate((float)(v->rotate * PI / 180), sr_vec3_make(0, 1, 0));
    sr_mat4 t = sr_mat4_translate((float)v->translate[0], (float)v->translate[1],
                                  (float)v->translate[2]);
    s->model = sr_mat4_mul(&t, &r);
    sr_vec3 eye = vec3(v->eye), target = vec3(v->target);
    if (!sr_camera_frame(eye, sr_vec3_sub(target, eye), vec3(v->up), &s->basis)) {
        return false;
    }
    s->view = sr_camera_matrix(&s->basis);
    double fov = v->fov * PI / 180, aspect = (double)grid_w / grid_h;
    if (v->orthographic) {
        /* as tall at the target as the perspective view volume */
        double base = sr_vec3_length(sr_vec3_sub(target, eye)) * tan(fov / 2);
        s->half_w = v->stretch || grid_w < grid_h ? base : base * aspect;
        s->half_h = v->stretch || grid_w >= grid_h ? base : base / aspect;
        s->proj = sr_ortho((float)-s->half_w, (float)s->half_w, (float)-s->half_h,
                           (float)s->half_h, (float)v->near_far[0], (float)v->near_far[1], false);
    } else {
        s->fovy = v->stretch ? fov : sr_fit_fovy((float)fov, grid_w, grid_h);
        s->aspect = v->stretch ? 1 : aspect;
        s->proj = sr_perspective((float)s->fovy, (float)s->aspect, (float)v->near_far[0],
                                 (float)v->near_far[1], false);
    }
    /* sr_draw's products, in its order: (P (E M_O)) times the vertex */
    s->mv = sr_mat4_mul(&s->view, &s->model);
    s->mvp = sr_mat4_mul(&s->proj, &s->mv);
    s->viewport = sr_viewport_matrix(0, 0, (float)grid_w, (float)grid_h, 0, 1, false);
    for (int i = 0; i < 3; i++) {
        s->obj[i] = (sr_vec4){ (float)prim->pts[i].x, (float)prim->pts[i].y, (float)prim->z[i],
                               1 };
        s->world[i] = sr_mat4_mul_vec4(&s->model, s->obj[i]);
        s->eye[i] = sr_mat4_mul_vec4(&s->mv, s->obj[i]);
        s->clip[i] = sr_mat4_mul_vec4(&s->mvp, s->obj[i]);
        /* the divide and S as the vertex stage computes them: in double,
         * x_S = S03 + S00 x/w, y_S = S13 + S11 y/w (S11 < 0: y down) */
        double iw = 1.0 / s->clip[i].w;
        const float *m = s->viewport.m;
        s->ndc[i][0] = s->clip[i].x * iw;
        s->ndc[i][1] = s->clip[i].y * iw;
        s->ndc[i][2] = s->clip[i].z * iw;
        s->x_q8[i] = snap((double)m[12] + (double)m[0] * s->ndc[i][0]);
        s->y_q8[i] = snap((double)m[13] + (double)m[5] * s->ndc[i][1]);
    }
    return true;
}

bool ex_transform_check(const ex_primitive *prim, int grid_w, int grid_h, char *why,
                        size_t size)
{
    stages s;
    if (!compute(prim, grid_w, grid_h, &s)) {
        snprintf(why, size, "--eye, --target, --up: no camera frame (the eye is on the target, "
                            "or up is along the gaze)");
        return false;
    }
    for (int i = 0; i < 3; i++) {
        const sr_vec4 *c = &s.clip[i];
        if (!(c->w > 0) || !(fabs(c->z) <= c->w)) {
            snprintf(why, size, "V%d is outside the near or far plane (clip z = %.3g, w = %.3g): "
                     "move --eye, or see 'softrast explain clip4d'", i, c->z, c->w);
            return false;
        }
        if (!(fabs(s.ndc[i][0]) <= 16 && fabs(s.ndc[i][1]) <= 16)) {
            snprintf(why, size, "V%d is far outside the viewport (NDC %.3g, %.3g): move "
                     "--eye or --target", i, s.ndc[i][0], s.ndc[i][1]);
            return false;
        }
    }
    return true;
}

/* A number in a caption: three significant digits, no "-0". */
static const char *num(char *buf, size_t size, double v)
{
    if (fabs(v) < 5e-4) {
        v = 0;
    }
    snprintf(buf, size, "%.3g", v);
    return buf;
}

/* A matrix row by row, "[a b c d; ...]". */
static void fmt_matrix(char *buf, size_t size, const sr_mat4 *m)
{
    int len = snprintf(buf, size, "[");
    for (int r = 0; r < 4; r++) {
        for (int col = 0; col < 4; col++) {
            char n[32];
            len += snprintf(buf + len, size - (size_t)len, "%s%s",
                            num(n, sizeof n, m->m[col * 4 + r]),
                            col < 3 ? " " : r < 3 ? "; " : "]");
        }
    }
}

/* "V0 = (x, y, z), V1 = ..." with `dims` coordinates of each point. */
static void fmt_points(char *buf, size_t size, const double p[3][4], int dims)
{
    int len = 0;
    for (int i = 0; i < 3; i++) {
        len += snprintf(buf + len, size - (size_t)len, "%sV%d = (", i ? ", " : "", i);
        for (int k = 0; k < dims; k++) {
            char n[32];
            len += snprintf(buf + len, size - (size_t)len, "%s%s", k ? ", " : "",
                            num(n, sizeof n, p[i][k]));
        }
        len += snprintf(buf + len, size - (size_t)len, ")");
    }
}

static void vec4s(const sr_vec4 v[3], double out[3][4])
{
    for (int i = 0; i < 3; i++) {
        out[i][0] = v[i].x;
        out[i][1] = v[i].y;
        out[i][2] = v[i].z;
        out[i][3] = v[i].w;
    }
}

/* A plot of x, y (y up) fitted to the grid with a cell to spare. */
typedef struct plot { double s, ox, oy; } plot;

static sr_point2 at(const plot *p, double x, double y)
{
    return (sr_point2){ p->ox + p->s * x, p->oy - p->s * y };
}

/* The plot that holds the points and the origin, uniform in x and y. */
static plot fit(const ex_canvas *c, const sr_point2 *pts, int n)
{
    double x0 = 0, x1 = 0, y0 = 0, y1 = 0;
    for (int i = 0; i < n; i++) {
        x0 = fmin(x0, pts[i].x);
        x1 = fmax(x1, pts[i].x);
        y0 = fmin(y0, pts[i].y);
        y1 = fmax(y1, pts[i].y);
    }
    double dx = fmax(x1 - x0, 1e-6), dy = fmax(y1 - y0, 1e-6);
    double s = fmin((c->grid_w - 2) / dx, (c->grid_h - 2) / dy);
    return (plot){ s, c->grid_w / 2.0 - s * (x0 + x1) / 2, c->grid_h / 2.0 + s * (y0 + y1) / 2 };
}

/* The axes through the plot's origin, named. */
static void axes(ex_canvas *c, const plot *p, const char *xname, const char *yname)
{
    ex_segment(c, (sr_point2){ 0, p->oy }, (sr_point2){ c->grid_w, p->oy }, AXIS, 1);
    ex_segment(c, (sr_point2){ p->ox, 0 }, (sr_point2){ p->ox, c->grid_h }, AXIS, 1);
    ex_label(c, (sr_point2){ c->grid_w - 1.2, p->oy }, xname, AXIS);
    ex_label(c, (sr_point2){ p->ox, 0.9 }, yname, AXIS);
}

/* A triangle in grid coordinates, its vertices dotted and named V0..V2:
 * a stage's (blue, pink dots) or over the pixels (dark). */
static void named_triangle(ex_canvas *c, const sr_point2 q[3], bool dark)
{
    ex_outline(c, q, 3, true, dark ? EX_EDGE : EX_INK, dark ? 1 : 2.5);
    for (int i = 0; i < 3; i++) {
        char name[8];
        snprintf(name, sizeof name, "V%d", i);
        ex_dot(c, q[i], dark ? 3 : 4, dark ? EX_EDGE : EX_HILITE);
        ex_label(c, q[i], name, EX_TEXT);
    }
}

/* The triangle of x, y (in p) on the plot. */
static void triangle(ex_canvas *c, const plot *pl, const double p[3][4])
{
    sr_point2 q[3];
    for (int i = 0; i < 3; i++) {
        q[i] = at(pl, p[i][0], p[i][1]);
    }
    named_triangle(c, q, false);
}

/* One frame plotting x, y of p (and of the extra points), uniform. */
static plot plot_points(ex_canvas *c, const double p[3][4], const sr_point2 *extra, int n_extra,
                        const char *xname, const char *yname)
{
    sr_point2 pts[8];
    int n = 0;
    for (int i = 0; i < 3; i++) {
        pts[n++] = (sr_point2){ p[i][0], p[i][1] };
    }
    for (int i = 0; i < n_extra && n < 8; i++) {
        pts[n++] = extra[i];
    }
    plot pl = fit(c, pts, n);
    ex_begin(c);
    axes(c, &pl, xname, yname);
    triangle(c, &pl, p);
    return pl;
}

/* The caption of the window frame, from its numbers. */
static void window_caption(char *buf, size_t size, int frame, int grid_w, int grid_h,
                           const sr_mat4 *viewport, const int64_t x_q8[3],
                           const int64_t y_q8[3])
{
    char m[256];
    fmt_matrix(m, sizeof m, viewport);
    int len = snprintf(buf, size,
                       "%d. The viewport matrix S maps NDC -1..1 onto the pixel extents of the "
                       "%dx%d viewport, x_S = %d/2 (x + 1), y_S = %d/2 (1 - y) (y down), z_S = "
                       "(z + 1)/2: S = %s. Window coordinates, snapped to 1/256 pixel: ",
                       frame, grid_w, grid_h, grid_w, grid_h, m);
    for (int i = 0; i < 3 && len < (int)size; i++) {
        len += snprintf(buf + len, size - (size_t)len, "%sV%d = (%.4f, %.4f)", i ? ", " : "", i,
                        x_q8[i] / 256.0, y_q8[i] / 256.0);
    }
    if (len < (int)size) {
        snprintf(buf + len, size - (size_t)len, ".");
    }
}

sr_result explain_transform(ex_canvas *c, const ex_primitive *prim)
{
    const ex_view *v = &prim->view;
    stages s;
    if (!compute(prim, c->grid_w, c->grid_h, &s)) {
        return c->error = SR_INVALID_ARG;   /* explain.c checks first */
    }
    char cap[2000], mat[256], pts[400], n[6][32];
    double p[3][4];

    /* 1. object coordinates and M_O, a unit min(grid)/4 cells from the
     * grid's centre when they fit (the web page's handles are there) */
    vec4s(s.obj, p);
    plot po = { fmin(c->grid_w, c->grid_h) / 4.0, c->grid_w / 2.0, c->grid_h / 2.0 };
    bool fits = true;
    for (int i = 0; i < 3; i++) {
        sr_point2 q = at(&po, p[i][0], p[i][1]);
        fits &= q.x >= 0 && q.x <= c->grid_w && q.y >= 0 && q.y <= c->grid_h;
    }
    if (fits) {
        ex_begin(c);
        axes(c, &po, "x_O", "y_O");
        triangle(c, &po, p);
    } else {
        plot_points(c, p, NULL, 0, "x_O", "y_O");
    }
    fmt_points(pts, sizeof pts, p, 3);
    fmt_matrix(mat, sizeof mat, &s.model);
    char unit[48] = "";
    if (fits) {
        snprintf(unit, sizeof unit, ", a unit %s cells", num(n[0], sizeof n[0], po.s));
    }
    snprintf(cap, sizeof cap,
             "1. Object coordinates: %s (plotted x right, y up%s; z towards you). The modelling "
             "transformation M_O takes them to the world: a rotation by %s degrees about y, then "
             "a translation by (%s, %s, %s), M_O = %s.",
             pts, unit, num(n[0], sizeof n[0], v->rotate), num(n[1], sizeof n[1], v->translate[0]),
             num(n[2], sizeof n[2], v->translate[1]), num(n[3], sizeof n[3], v->translate[2]),
             mat);
    ex_end(c, cap);

    /* 2. world coordinates, with the eye and the target */
    vec4s(s.world, p);
    sr_point2 cam[2] = { { v->eye[0], v->eye[1] }, { v->target[0], v->target[1] } };
    plot pl = plot_points(c, p, cam, 2, "x", "y");
    ex_segment(c, at(&pl, cam[0].x, cam[0].y), at(&pl, cam[1].x, cam[1].y), CAMERA, 1.5);
    ex_dot(c, at(&pl, cam[0].x, cam[0].y), 5, CAMERA);
    ex_dot(c, at(&pl, cam[1].x, cam[1].y), 3, CAMERA);
    ex_label(c, at(&pl, cam[0].x, cam[0].y), "eye", CAMERA);
    ex_label(c, at(&pl, cam[1].x, cam[1].y), "target", CAMERA);
    fmt_points(pts, sizeof pts, p, 3);
    char up[3][32];
    snprintf(cap, sizeof cap,
             "2. World coordinates M_O V: %s. The camera: the eye e = (%s, %s, %s) looks at the "
             "target (%s, %s, %s), gaze g = target - e, view-up t = (%s, %s, %s) (orange: both "
             "seen along z).",
             pts, num(n[0], 32, v->eye[0]), num(n[1], 32, v->eye[1]), num(n[2], 32, v->eye[2]),
             num(n[3], 32, v->target[0]), num(n[4], 32, v->target[1]),
             num(n[5], 32, v->target[2]), num(up[0], 32, v->up[0]), num(up[1], 32, v->up[1]),
             num(up[2], 32, v->up[2]));
    ex_end(c, cap);

    /* 3. the camera frame and eye coordinates */
    vec4s(s.eye, p);
    plot pe = plot_points(c, p, NULL, 0, "x_E", "y_E");
    ex_dot(c, at(&pe, 0, 0), 5, CAMERA);
    ex_label(c, at(&pe, 0, 0), "eye", CAMERA);
    fmt_points(pts, sizeof pts, p, 3);
    fmt_matrix(mat, sizeof mat, &s.view);
    const sr_camera_basis *b = &s.basis;
    char u[3][32], vv[3][32], w[3][32];
    snprintf(cap, sizeof cap,
             "3. The camera frame: w = -g/|g| = (%s, %s, %s), u = t x w / |t x w| = (%s, %s, %s), "
             "v = w x u = (%s, %s, %s). E = M_cam^-1 has rows u, v, w and translation -u.e, "
             "-v.e, -w.e: E = %s. Eye coordinates E M_O V: %s; the eye at the origin looks down "
             "-z.",
             num(w[0], 32, b->w.x), num(w[1], 32, b->w.y), num(w[2], 32, b->w.z),
             num(u[0], 32, b->u.x), num(u[1], 32, b->u.y), num(u[2], 32, b->u.z),
             num(vv[0], 32, b->v.x), num(vv[1], 32, b->v.y), num(vv[2], 32, b->v.z), mat, pts);
    ex_end(c, cap);

    /* 4. the projection into clip space */
    vec4s(s.clip, p);
    plot_points(c, p, NULL, 0, "x_c", "y_c");
    fmt_points(pts, sizeof pts, p, 4);
    fmt_matrix(mat, sizeof mat, &s.proj);
    char what[400];
    if (v->orthographic) {
        snprintf(what, sizeof what,
                 "orthographic, the box x in -%s..%s, y in -%s..%s (%s), near %s, far %s",
                 num(n[0], 32, s.half_w), num(n[1], 32, s.half_w), num(n[2], 32, s.half_h),
                 num(n[3], 32, s.half_h),
                 v->stretch ? "square: NDC is stretched over the viewport"
                            : "its aspect ratio is the viewport's",
                 num(n[4], 32, v->near_far[0]), num(n[5], 32, v->near_far[1]));
    } else if (v->stretch) {
        snprintf(what, sizeof what,
                 "perspective, field of view %s degrees in x and y alike (aspect 1: NDC's square "
                 "is stretched over the viewport), near %s, far %s",
                 num(n[0], 32, v->fov), num(n[1], 32, v->near_far[0]),
                 num(n[2], 32, v->near_far[1]));
    } else {
        snprintf(what, sizeof what,
                 "perspective, field of view %s degrees across the viewport's smaller side, the "
                 "other derived from width/height = %s (vertical %s degrees), near %s, far %s",
                 num(n[0], 32, v->fov), num(n[1], 32, s.aspect),
                 num(n[2], 32, s.fovy * 180 / PI), num(n[3], 32, v->near_far[0]),
                 num(n[4], 32, v->near_far[1]));
    }
    snprintf(cap, sizeof cap,
             "4. The projection P, %s: P = %s. Clip coordinates P E M_O V = (x, y, z, w): %s. "
             "Each w > 0 and -w <= z <= w: nothing to clip.",
             what, mat, pts);
    ex_end(c, cap);

    /* 5. the divide: NDC, plotted uniformly with the canonical square */
    for (int i = 0; i < 3; i++) {
        memcpy(p[i], s.ndc[i], sizeof s.ndc[i]);
        p[i][3] = 1;
    }
    sr_point2 square[4] = { { -1, -1 }, { 1, -1 }, { 1, 1 }, { -1, 1 } };
    pl = plot_points(c, p, square, 4, "x", "y");
    sr_point2 sq[4];
    for (int k = 0; k < 4; k++) {
        sq[k] = at(&pl, square[k].x, square[k].y);
    }
    ex_outline(c, sq, 4, true, EX_EDGE, 1.5);
    fmt_points(pts, sizeof pts, p, 3);
    double area = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) -
                  (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]);
    snprintf(cap, sizeof cap,
             "5. The perspective divide, from 4- to 3-vectors: NDC = (x/w, y/w, z/w): %s. The "
             "canonical view volume is -1..1 in each (the square).%s The vertices run %s in NDC "
             "(y up): the triangle is %s.",
             pts,
             v->orthographic ? " (An orthographic P leaves w = 1: the divide changes nothing.)"
                             : "",
             area > 0 ? "counter-clockwise" : area < 0 ? "clockwise" : "in a line",
             area > 0 ? "front-facing" : area < 0 ? "back-facing (SR_CULL_BACK would drop it)"
                      : "seen edge-on");
    ex_end(c, cap);

    /* 6. the viewport: window coordinates on the pixel grid */
    ex_begin(c);
    ex_primitive win = { .kind = EX_TRIANGLE, .count = 3 };
    for (int i = 0; i < 3; i++) {
        win.pts[i] = (sr_point2){ s.x_q8[i] / 256.0, s.y_q8[i] / 256.0 };
    }
    named_triangle(c, win.pts, false);
    window_caption(cap, sizeof cap, c->frame_count + 1, c->grid_w, c->grid_h,
                   &s.viewport, s.x_q8, s.y_q8);
    ex_end(c, cap);

    /* 7. the pixels (drawn here rather than by ex_tri_coverage, which
     * names the vertices in its own order) */
    ex_tri t;
    ex_tri_setup(&t, &win);
    ex_begin(c);
    int total = 0;
    for (int y = 0; y < c->grid_h; y++) {
        for (int x = 0; x < c->grid_w; x++) {
            if (ex_tri_covers(&t, (int64_t)x * 256 + 128, (int64_t)y * 256 + 128)) {
                ex_cell(c, x, y, EX_INK);
                total++;
            }
        }
    }
    named_triangle(c, win.pts, true);
    snprintf(cap, sizeof cap,
             "%d. The window-space triangle the rasterizer gets, covered by its edge functions "
             "with the top-left rule: %d pixel%s, exactly those sr_draw fills for this triangle "
             "with these M_O, E and P and the grid as its viewport.",
             c->frame_count + 1, total, total == 1 ? "" : "s");
    ex_end(c, cap);
    return c->error;
}
