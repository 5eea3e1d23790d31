/* svg_filter.c - the SVG reader's filter effects (SVG 1.1 / Filter Effects
 * 1): runs a <filter>'s primitives on the layer an element was drawn into
 * (svg.c draws it, then composites what this leaves in the layer).
 *
 * Work is done at the output's device resolution over the filter region
 * (its bounding box in pixels, cut to the image), in premultiplied float
 * RGBA, each result in the colour space its primitive's
 * color-interpolation-filters asks for (linearRGB by default) and
 * converted when another primitive reads it in the other space.  Lengths
 * scale with the transform along each axis; offsets map through it
 * exactly.  Caller's thread; no state outside the job. */
#include "io/svg.h"
#include "math/affine2.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* Primitives of one filter, at most: beyond that the filter is refused. */
#define MAX_PRIMITIVES 1024

/* One result: premultiplied RGBA over the region, zero outside `sub`. */
typedef struct fimg {
    float *p;
    bool srgb;                   /* its values are sRGB (else linearRGB) */
    int sub[4];                  /* x0 y0 x1 y1 in region pixels */
} fimg;

typedef struct fctx {
    const svg_filter_job *job;
    int rx, ry, rw, rh;          /* the filter region in the layer's pixels */
    size_t n;                    /* rw * rh */
    double region[4];            /* the region in user space: x y w h */
    bool obb;                    /* primitiveUnits="objectBoundingBox" */
    double bw, bh;               /* the bounding box's size (user units) */
    double sx, sy;               /* pixels per user unit along x and y */
    fimg source, source_alpha, empty, fill, stroke;
    /* images freed and not yet made again: reused, as a new one would
     * fault in and clear its pages (never more than the peak is held) */
    float *spare[8];
    int n_spare;
    bool failed;
} fctx;

/* Input names that are not results: SourceGraphic, SourceAlpha, the
 * transparent black of the unsupported ones. */
enum { IN_SOURCE = -1, IN_SOURCE_ALPHA = -2, IN_EMPTY = -3, IN_FILL = -5, IN_STROKE = -6 };

static const char *fattr(const svg_node *n, const char *name)
{
    for (int i = 0; n->atts[i]; i += 2) {
        if (strcmp(n->atts[i], name) == 0) {
            return n->atts[i + 1];
        }
    }
    return NULL;
}

static bool is(const svg_node *n, const char *name)
{
    return strcmp(n->name, name) == 0;
}

static void fail(fctx *fc, const svg_node *at, sr_result r, const char *msg)
{
    if (!fc->failed) {
        fc->job->fail(fc->job->host, at, r, msg);
    }
    fc->failed = true;
}

/* Up to max numbers separated by blanks or commas; the count, or -1 when
 * the list is malformed or longer. */
static int numbers(const char *s, double *out, int max)
{
    int n = 0;
    s = svg_skip_ws(s);
    while (*s) {
        double v;
        if (n == max || !svg_parse_number(&s, &v) || !isfinite(v)) {
            return -1;
        }
        out[n++] = v;
        s = svg_skip_ws_comma(s);
    }
    return n;
}

/* A number attribute, `def` when absent; a malformed one is warned. */
static double number_attr(fctx *fc, const svg_node *n, const char *name, double def)
{
    const char *v = fattr(n, name);
    double x;
    if (!v) {
        return def;
    }
    if (numbers(v, &x, 1) != 1) {
        fc->job->warn(fc->job->host, n, name, v);
        return def;
    }
    return x;
}

/* One or two numbers ("x [y]"), each `def` when absent; false when
 * malformed (warned). */
static bool pair_attr(fctx *fc, const svg_node *n, const char *name, double def, double out[2])
{
    const char *v = fattr(n, name);
    out[0] = out[1] = def;
    if (!v) {
        return true;
    }
    int k = numbers(v, out, 2);
    if (k < 1) {
        fc->job->warn(fc->job->host, n, name, v);
        out[0] = out[1] = def;
        return false;
    }
    if (k == 1) {
        out[1] = out[0];
    }
    return true;
}

/* ---- regions ------------------------------------------------------------------ */

/* A user-space rectangle (x y w h) in the layer's pixels, rounded out:
 * the bounding box of its corners under the transform. */
static void rect_to_px(const fctx *fc, const double r[4], double px[4])
{
    const double *m = fc->job->m;
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    for (int i = 0; i < 4; i++) {
        double x = r[0] + (i & 1 ? r[2] : 0), y = r[1] + (i & 2 ? r[3] : 0);
        double X = m[0] * x + m[2] * y + m[4], Y = m[1] * x + m[3] * y + m[5];
        x0 = fmin(x0, X);
        y0 = fmin(y0, Y);
        x1 = fmax(x1, X);
        y1 = fmax(y1, Y);
    }
    /* a hair of tolerance: a region on whole pixels stays on them */
    px[0] = floor(x0 + 1e-6);
    px[1] = floor(y0 + 1e-6);
    px[2] = ceil(x1 - 1e-6);
    px[3] = ceil(y1 - 1e-6);
}

/* x, y, width, height of a <filter> or a primitive into r (x y w h):
 * fractions of the bounding box when bbox_units, else user lengths with
 * percentages of the viewport; an attribute absent keeps r's value. */
static void region_attrs(fctx *fc, const svg_node *n, bool bbox_units, double r[4], bool *given)
{
    static const char *const names[4] = { "x", "y", "width", "height" };
    const double *b = fc->job->bbox;
    *given = false;
    for (int i = 0; i < 4; i++) {
        const char *v = fattr(n, names[i]);
        double x;
        bool pct;
        if (!v) {
            continue;
        }
        if (!svg_parse_length(v, 16, &x, &pct)) {
            fc->job->warn(fc->job->host, n, names[i], v);
            continue;
        }
        *given = true;
        if (bbox_units) {
            x = pct ? x / 100 : x;
            r[i] = i < 2 ? b[i] + x * (b[i + 2] - b[i]) : x * (b[i] - b[i - 2]);
        } else {
            r[i] = pct ? x / 100 * (i % 2 ? fc->job->vp_h : fc->job->vp_w) : x;
        }
    }
}

/* The filter region from the <filter>'s attributes (fc->region) and in
 * the layer's pixels, rounded out but not cut to the layer (px: x0 y0 x1
 * y1); false when it is empty (nothing is drawn). */
static bool region_px(fctx *fc, double px[4])
{
    const svg_node *f = fc->job->filter;
    const char *units = fattr(f, "filterUnits");
    bool obb = !units || strcmp(units, "userSpaceOnUse") != 0;
    const double *b = fc->job->bbox;
    bool have_box = b[2] > b[0] && b[3] > b[1];
    if (obb && !have_box) {
        return false; /* no box to be a fraction of */
    }
    double r[4];
    if (obb) {
        double w = b[2] - b[0], h = b[3] - b[1];
        r[0] = b[0] - 0.1 * w;
        r[1] = b[1] - 0.1 * h;
        r[2] = 1.2 * w;
        r[3] = 1.2 * h;
    } else {
        r[0] = -0.1 * fc->job->vp_w;
        r[1] = -0.1 * fc->job->vp_h;
        r[2] = 1.2 * fc->job->vp_w;
        r[3] = 1.2 * fc->job->vp_h;
    }
    bool given;
    region_attrs(fc, f, obb, r, &given);
    if (!(r[2] > 0 && r[3] > 0)) {
        return false;
    }
    memcpy(fc->region, r, sizeof r);
    rect_to_px(fc, r, px);
    const char *pu = fattr(f, "primitiveUnits");
    fc->obb = pu && strcmp(pu, "objectBoundingBox") == 0;
    fc->bw = b[2] - b[0];
    fc->bh = b[3] - b[1];
    const double *m = fc->job->m;
    fc->sx = hypot(m[0], m[1]);
    fc->sy = hypot(m[2], m[3]);
    return true;
}

/* The filter region, cut to the layer; false when nothing of it is left. */
static bool filter_region(fctx *fc)
{
    double px[4];
    if (!region_px(fc, px)) {
        return false;
    }
    px[0] = fmax(px[0], 0);
    px[1] = fmax(px[1], 0);
    px[2] = fmin(px[2], fc->job->width);
    px[3] = fmin(px[3], fc->job->height);
    if (!(px[2] > px[0] && px[3] > px[1])) {
        return false;
    }
    fc->rx = (int)px[0];
    fc->ry = (int)px[1];
    fc->rw = (int)(px[2] - px[0]);
    fc->rh = (int)(px[3] - px[1]);
    fc->n = (size_t)fc->rw * (size_t)fc->rh;
    return true;
}

/* A primitive's subregion in region pixels, from its attributes over
 * `def` (the union of its inputs' or the whole region). */
static void subregion(fctx *fc, const svg_node *n, const int def[4], int out[4])
{
    double r[4];
    memcpy(r, fc->region, sizeof r);
    bool given;
    region_attrs(fc, n, fc->obb, r, &given);
    memcpy(out, def, 4 * sizeof *out);
    if (!given) {
        return;
    }
    double px[4];
    rect_to_px(fc, r, px);
    /* cut to the region before the cast: a subregion far beyond it is
     * empty, not a value outside int */
    out[0] = (int)fmin(fmax(px[0] - fc->rx, 0), fc->rw);
    out[1] = (int)fmin(fmax(px[1] - fc->ry, 0), fc->rh);
    out[2] = (int)fmin(fmax(px[2] - fc->rx, 0), fc->rw);
    out[3] = (int)fmin(fmax(px[3] - fc->ry, 0), fc->rh);
    if (out[2] < out[0]) {
        out[2] = out[0];
    }
    if (out[3] < out[1]) {
        out[3] = out[1];
    }
}

/* ---- colour spaces ----------------------------------------------------------- */

static float to_linear(float c)
{
    return c <= 0.04045f ? c / 12.92f : powf((c + 0.055f) / 1.055f, 2.4f);
}

static float to_srgb(float c)
{
    return c <= 0.0031308f ? c * 12.92f : 1.055f * powf(c, 1 / 2.4f) - 0.055f;
}

/* fminf(fmaxf(v, 0), 1) inline (NaN gives 0 as well): the library
 * calls are not inlined where NaN must be honoured. */
static inline float clamp01(float v)
{
    return v > 0 ? (v < 1 ? v : 1) : 0;
}

/* A pixel's premultiplied colour into the other space, alpha kept. */
static inline void convert_pixel(float *p, bool srgb)
{
    if (p[3] <= 0) {
        return;
    }
    for (int c = 0; c < 3; c++) {
        float v = clamp01(p[c] / p[3]);
        p[c] = (srgb ? to_srgb(v) : to_linear(v)) * p[3];
    }
}

/* The image's values converted to sRGB or linearRGB, alpha kept. */
static void convert(fctx *fc, fimg *im, bool srgb)
{
    if (im->srgb == srgb || !im->p) {
        im->srgb = srgb;
        return;
    }
    /* zero outside its subregion: nothing to convert there */
    for (int y = im->sub[1]; y < im->sub[3]; y++) {
        float *row = im->p + (size_t)y * fc->rw * 4;
        for (int x = im->sub[0]; x < im->sub[2]; x++) {
            convert_pixel(row + (size_t)x * 4, srgb);
        }
    }
    im->srgb = srgb;
}

/* ---- images ------------------------------------------------------------------ */

/* A transparent image of the region. */
static float *new_pixels(fctx *fc, const svg_node *at)
{
    if (fc->n_spare > 0) {
        float *p = fc->spare[--fc->n_spare];
        memset(p, 0, fc->n * 4 * sizeof *p);
        return p;
    }
    float *p = calloc(fc->n, 4 * sizeof *p);
    if (!p) {
        fail(fc, at, SR_OUT_OF_MEMORY, "out of memory");
    }
    return p;
}

static void release(fctx *fc, float *p)
{
    if (p && fc->n_spare < (int)(sizeof fc->spare / sizeof fc->spare[0])) {
        fc->spare[fc->n_spare++] = p;
    } else {
        free(p);
    }
}

/* The region's part of an RGBA8 straight-alpha layer, premultiplied
 * (its alpha alone, the colour left black, when alpha_only). */
static void from_layer(const fctx *fc, const uint8_t *px, float *out, bool alpha_only)
{
    for (int y = 0; y < fc->rh; y++) {
        const uint8_t *s = px + ((size_t)(y + fc->ry) * fc->job->width + fc->rx) * 4;
        float *d = out + (size_t)y * fc->rw * 4;
        for (int x = 0; x < fc->rw; x++, s += 4, d += 4) {
            float al = s[3] / 255.0f;
            for (int c = 0; c < 3 && !alpha_only; c++) {
                d[c] = s[c] / 255.0f * al;
            }
            d[3] = al;
        }
    }
}

static void premultiplied(sr_rgba c, bool srgb, float out[4]);
static void flood(fctx *fc, const int sub[4], float *out, const float color[4]);

/* A standard input, made when first read: SourceGraphic and SourceAlpha
 * from the layer's pixels in the region, FillPaint and StrokePaint the
 * element's flat colors over it, or transparent black; NULL after a
 * failure. */
static fimg *standard(fctx *fc, int k)
{
    fimg *im = k == IN_SOURCE ? &fc->source
             : k == IN_SOURCE_ALPHA ? &fc->source_alpha
             : k == IN_FILL ? &fc->fill
             : k == IN_STROKE ? &fc->stroke : &fc->empty;
    if (im->p) {
        return im;
    }
    im->p = new_pixels(fc, fc->job->filter);
    if (!im->p) {
        return NULL;
    }
    int whole[4] = { 0, 0, fc->rw, fc->rh };
    memcpy(im->sub, whole, sizeof whole);
    im->srgb = true;
    float paint[4];
    if (k == IN_SOURCE || k == IN_SOURCE_ALPHA) {
        from_layer(fc, fc->job->source, im->p, k == IN_SOURCE_ALPHA);
    } else if (k == IN_FILL || k == IN_STROKE) {
        premultiplied(k == IN_FILL ? fc->job->fill : fc->job->stroke, true, paint);
        flood(fc, whole, im->p, paint);
    }
    return im;
}

/* Zero outside the subregion. */
static void cut_to(fctx *fc, fimg *im)
{
    for (int y = 0; y < fc->rh; y++) {
        float *row = im->p + (size_t)y * fc->rw * 4;
        if (y < im->sub[1] || y >= im->sub[3]) {
            memset(row, 0, (size_t)fc->rw * 4 * sizeof *row);
            continue;
        }
        memset(row, 0, (size_t)im->sub[0] * 4 * sizeof *row);
        memset(row + (size_t)im->sub[2] * 4, 0, (size_t)(fc->rw - im->sub[2]) * 4 * sizeof *row);
    }
}

/* ---- the primitives ----------------------------------------------------------- */

/* Each pixel of the subregion `sub` (x0 y0 x1 y1), i the index of its
 * first float: a primitive that works pixel by pixel leaves the rest of
 * its result as new_pixels made it, transparent, which is what cut_to
 * would make of it. */
#define EACH_PIXEL(fc, sub, i)                                                               \
    for (int y_ = (sub)[1]; y_ < (sub)[3]; y_++)                                             \
        for (size_t i = ((size_t)y_ * (size_t)(fc)->rw + (size_t)(sub)[0]) * 4,              \
                    end_ = ((size_t)y_ * (size_t)(fc)->rw + (size_t)(sub)[2]) * 4;           \
             i < end_; i += 4)

typedef struct prim {
    const svg_node *node;
    int in[2];                   /* inputs (IN_* or an earlier primitive), -4: none */
    const char *result;
} prim;

/* A deviation of the primitive's units in the region's pixels.  Huge
 * geometry (drawn since fills cut it to a guard band) can scale it past
 * double's range: any deviation far beyond the largest region spreads it
 * to nothing alike, so it is held at 1e15 px (and 0 x inf counts as 0). */
static double blur_sigma_px(const fctx *fc, double sd, bool y)
{
    double s = fmax(sd, 0) * (y ? fc->sy : fc->sx) * (fc->obb ? (y ? fc->bh : fc->bw) : 1);
    return s < 1e15 ? s : s >= 1e15 ? 1e15 : 0;
}

/* The pixel operations a blur of deviation s pixels costs each pixel along
 * one axis, as sr_blur_image documents it: the exact kernel's taps, 3
 * deviations each side, below 2 pixels; from 2 up, three running sums. */
static double blur_axis_work(double s)
{
    return !(s > 0) ? 0 : s < 2 ? 2 * ceil(3 * s) + 1 : 3;
}

static void blur(fctx *fc, const svg_node *n, const float *in, float *out, double sd_x,
                 double sd_y)
{
    memcpy(out, in, fc->n * 4 * sizeof *out);
    if (!(sd_x > 0 || sd_y > 0)) {
        return;
    }
    const char *e = fattr(n, "edgeMode");
    sr_blur_edge edge = SR_BLUR_EDGE_NONE;
    if (e && strcmp(e, "duplicate") == 0) {
        edge = SR_BLUR_EDGE_DUPLICATE;
    } else if (e && strcmp(e, "wrap") == 0) {
        edge = SR_BLUR_EDGE_WRAP;
    } else if (e && strcmp(e, "none") != 0) {
        fc->job->warn(fc->job->host, n, "edgeMode", e);
    }
    sr_blur_desc d = { .sigma_x = blur_sigma_px(fc, sd_x, false),
                       .sigma_y = blur_sigma_px(fc, sd_y, true), .edge = edge };
    sr_result r = sr_blur_image(fc->job->ctx, out, fc->rw, fc->rh, 4, &d);
    if (r != SR_OK) {
        fail(fc, n, r, sr_context_error(fc->job->ctx));
    }
}

/* The input shifted by (dx, dy) user units: through the transform, and
 * between pixels bilinearly (a whole-pixel shift copies exactly). */
static void offset(fctx *fc, const int sub[4], const float *in, float *out, double dx, double dy)
{
    const double *m = fc->job->m;
    if (fc->obb) {
        dx *= fc->bw;
        dy *= fc->bh;
    }
    double ox = m[0] * dx + m[2] * dy, oy = m[1] * dx + m[3] * dy;
    ox = fmax(fmin(ox, 1e7), -1e7);
    oy = fmax(fmin(oy, 1e7), -1e7);
    long ix = (long)floor(ox), iy = (long)floor(oy);
    float fx = (float)(ox - ix), fy = (float)(oy - iy);
    float w[4] = { (1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy };
    for (int y = sub[1]; y < sub[3]; y++) {
        /* taps in order, each over the columns whose source lies inside */
        for (int t = 0; t < 4; t++) {
            long sy = y - iy - (t >> 1), shift = ix + (t & 1);
            if (w[t] == 0 || sy < 0 || sy >= fc->rh) {
                continue;
            }
            long x0 = sub[0] > shift ? sub[0] : shift;
            long x1 = sub[2] < fc->rw + shift ? sub[2] : fc->rw + shift;
            float *d = out + ((size_t)y * fc->rw) * 4;
            const float *s = in + ((size_t)sy * fc->rw) * 4;
            for (long x = x0; x < x1; x++) {
                for (int c = 0; c < 4; c++) {
                    d[x * 4 + c] += w[t] * s[(x - shift) * 4 + c];
                }
            }
        }
    }
}

/* A straight sRGB colour as premultiplied values in the space asked. */
static void premultiplied(sr_rgba c, bool srgb, float out[4])
{
    float v[3] = { c.r, c.g, c.b };
    for (int i = 0; i < 3; i++) {
        out[i] = (srgb ? v[i] : to_linear(v[i])) * c.a;
    }
    out[3] = c.a;
}

static void flood(fctx *fc, const int sub[4], float *out, const float color[4])
{
    EACH_PIXEL(fc, sub, i) {
        memcpy(out + i, color, 4 * sizeof *color);
    }
}

static void over(fctx *fc, const int sub[4], const float *a, float *out)
{
    EACH_PIXEL(fc, sub, i) {
        float k = 1 - a[i + 3];
        for (int c = 0; c < 4; c++) {
            out[i + c] = a[i + c] + out[i + c] * k;
        }
    }
}

typedef enum { OP_OVER, OP_IN, OP_OUT, OP_ATOP, OP_XOR, OP_ARITHMETIC, OP_LIGHTER } comp_op;

static void composite(fctx *fc, const svg_node *n, const int sub[4], const float *a,
                      const float *b, float *out)
{
    static const char *const names[] = { "over", "in", "out", "atop", "xor", "arithmetic",
                                         "lighter" };
    const char *v = fattr(n, "operator");
    comp_op op = OP_OVER;
    if (v) {
        int i = 0;
        while (i < 7 && strcmp(v, names[i]) != 0) {
            i++;
        }
        if (i == 7) {
            fc->job->warn(fc->job->host, n, "operator", v);
        } else {
            op = (comp_op)i;
        }
    }
    float k[4];
    for (int i = 0; i < 4; i++) {
        static const char *const kn[4] = { "k1", "k2", "k3", "k4" };
        k[i] = (float)number_attr(fc, n, kn[i], 0);
    }
    EACH_PIXEL(fc, sub, i) {
        float aa = a[i + 3], ba = b[i + 3];
        for (int c = 0; c < 4; c++) {
            float A = a[i + c], B = b[i + c], r;
            switch (op) {
            case OP_IN: r = A * ba; break;
            case OP_OUT: r = A * (1 - ba); break;
            case OP_ATOP: r = A * ba + B * (1 - aa); break;
            case OP_XOR: r = A * (1 - ba) + B * (1 - aa); break;
            case OP_ARITHMETIC: r = k[0] * A * B + k[1] * A + k[2] * B + k[3]; break;
            case OP_LIGHTER: r = A + B; break;
            default: r = A + B * (1 - aa); break;
            }
            out[i + c] = clamp01(r);
        }
        /* premultiplied: no channel above alpha */
        for (int c = 0; c < 3; c++) {
            out[i + c] = out[i + c] < out[i + 3] ? out[i + c] : out[i + 3];
        }
    }
}

static void blend(fctx *fc, const svg_node *n, const int sub[4], const float *a, const float *b,
                  float *out)
{
    const char *v = fattr(n, "mode");
    int mode = v ? svg_blend_mode(v) : SVG_BLEND_NORMAL;
    if (mode < 0) {
        fc->job->warn(fc->job->host, n, "mode", v);
        mode = SVG_BLEND_NORMAL;
    }
    EACH_PIXEL(fc, sub, i) {
        float aa = a[i + 3], ba = b[i + 3], cs[3], cb[3], mix[3];
        for (int c = 0; c < 3; c++) {
            cs[c] = aa > 0 ? a[i + c] / aa : 0;
            cb[c] = ba > 0 ? b[i + c] / ba : 0;
        }
        svg_blend_mix((svg_blend_kind)mode, cb, cs, mix);
        for (int c = 0; c < 3; c++) {
            out[i + c] = (1 - ba) * a[i + c] + (1 - aa) * b[i + c] + aa * ba * mix[c];
        }
        out[i + 3] = aa + ba - aa * ba;
    }
}

/* Straight colour per pixel through f, premultiplied again after. */
static void per_pixel(fctx *fc, const int sub[4], const float *in, float *out,
                      void (*f)(const void *data, float c[4]), const void *data)
{
    EACH_PIXEL(fc, sub, i) {
        float c[4], a = in[i + 3];
        for (int k = 0; k < 3; k++) {
            c[k] = a > 0 ? in[i + k] / a : 0;
        }
        c[3] = a;
        f(data, c);
        a = clamp01(c[3]);
        for (int k = 0; k < 3; k++) {
            out[i + k] = clamp01(c[k]) * a;
        }
        out[i + 3] = a;
    }
}

static void apply_matrix(const void *data, float c[4])
{
    const double *m = data;
    float r[4];
    for (int i = 0; i < 4; i++) {
        const double *row = m + i * 5;
        r[i] = (float)(row[0] * c[0] + row[1] * c[1] + row[2] * c[2] + row[3] * c[3] + row[4]);
    }
    memcpy(c, r, sizeof r);
}

static void color_matrix(fctx *fc, const svg_node *n, const int sub[4], const float *in,
                         float *out)
{
    double m[20] = { 1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0 };
    const char *type = fattr(n, "type"), *values = fattr(n, "values");
    if (!type || strcmp(type, "matrix") == 0) {
        double v[20];
        if (values && numbers(values, v, 20) == 20) {
            memcpy(m, v, sizeof m);
        } else if (values) {
            fc->job->warn(fc->job->host, n, "values", values);
        }
    } else if (strcmp(type, "saturate") == 0 || strcmp(type, "hueRotate") == 0) {
        bool sat = type[0] == 's';
        double s = sat ? 1 : 0;
        if (values && numbers(values, &s, 1) != 1) {
            fc->job->warn(fc->job->host, n, "values", values);
            s = sat ? 1 : 0;
        }
        double a[9];
        if (sat) {
            double t[9] = { 0.213 + 0.787 * s, 0.715 - 0.715 * s, 0.072 - 0.072 * s,
                            0.213 - 0.213 * s, 0.715 + 0.285 * s, 0.072 - 0.072 * s,
                            0.213 - 0.213 * s, 0.715 - 0.715 * s, 0.072 + 0.928 * s };
            memcpy(a, t, sizeof a);
        } else {
            double co = cos(s * M_PI / 180), si = sin(s * M_PI / 180);
            double t[9] = { 0.213 + co * 0.787 - si * 0.213, 0.715 - co * 0.715 - si * 0.715,
                            0.072 - co * 0.072 + si * 0.928, 0.213 - co * 0.213 + si * 0.143,
                            0.715 + co * 0.285 + si * 0.140, 0.072 - co * 0.072 - si * 0.283,
                            0.213 - co * 0.213 - si * 0.787, 0.715 - co * 0.715 + si * 0.715,
                            0.072 + co * 0.928 + si * 0.072 };
            memcpy(a, t, sizeof a);
        }
        for (int r = 0; r < 3; r++) {
            for (int c = 0; c < 3; c++) {
                m[r * 5 + c] = a[r * 3 + c];
            }
        }
    } else if (strcmp(type, "luminanceToAlpha") == 0) {
        double t[20] = { 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0.2125, 0.7154, 0.0721, 0, 0 };
        memcpy(m, t, sizeof m);
    } else {
        fc->job->warn(fc->job->host, n, "type", type);
    }
    per_pixel(fc, sub, in, out, apply_matrix, m);
}

/* feComponentTransfer: one transfer function per channel. */
typedef struct transfer {
    int type;                    /* 0 identity, 1 table, 2 discrete, 3 linear, 4 gamma */
    double table[256];
    int n;
    double slope, intercept, amplitude, exponent, offset;
} transfer;

static float transfer_one(const transfer *t, float c)
{
    int n = t->n;
    switch (t->type) {
    case 1: {
        if (n == 1) {
            return (float)t->table[0];
        }
        double x = c * (n - 1);
        int k = (int)fmin(floor(x), n - 2);
        return (float)(t->table[k] + (x - k) * (t->table[k + 1] - t->table[k]));
    }
    case 2: {
        int k = (int)fmin(floor(c * n), n - 1);
        return (float)t->table[k];
    }
    case 3: return (float)(t->slope * c + t->intercept);
    case 4: return (float)(t->amplitude * pow(c, t->exponent) + t->offset);
    default: return c;
    }
}

static void apply_transfer(const void *data, float c[4])
{
    const transfer *t = data;
    for (int i = 0; i < 4; i++) {
        c[i] = transfer_one(&t[i], clamp01(c[i]));
    }
}

static void component_transfer(fctx *fc, const svg_node *n, const int sub[4], const float *in,
                               float *out)
{
    transfer t[4] = { { 0 } };
    static const char *const funcs[4] = { "feFuncR", "feFuncG", "feFuncB", "feFuncA" };
    static const char *const types[5] = { "identity", "table", "discrete", "linear", "gamma" };
    for (const svg_node *c = n->first; c; c = c->next) {
        int ch = 0;
        while (ch < 4 && !is(c, funcs[ch])) {
            ch++;
        }
        if (ch == 4) {
            continue;
        }
        transfer *f = &t[ch];
        *f = (transfer){ .slope = number_attr(fc, c, "slope", 1),
                         .intercept = number_attr(fc, c, "intercept", 0),
                         .amplitude = number_attr(fc, c, "amplitude", 1),
                         .exponent = number_attr(fc, c, "exponent", 1),
                         .offset = number_attr(fc, c, "offset", 0) };
        const char *type = fattr(c, "type");
        for (int k = 0; type && k < 5; k++) {
            if (strcmp(type, types[k]) == 0) {
                f->type = k;
            }
        }
        if (f->type == 1 || f->type == 2) {
            const char *tv = fattr(c, "tableValues");
            f->n = tv ? numbers(tv, f->table, 256) : 0;
            if (f->n <= 0) { /* an empty or malformed table: identity */
                if (f->n < 0) {
                    fc->job->warn(fc->job->host, c, "tableValues", tv);
                }
                f->type = 0;
            }
        }
    }
    per_pixel(fc, sub, in, out, apply_transfer, t);
}

/* fmaxf and fminf inline: NaN loses to a number, as in the library calls,
 * which are not inlined where NaN must be honoured. */
static inline float max_f(float a, float b)
{
    return a > b || b != b ? a : b;
}

static inline float min_f(float a, float b)
{
    return a < b || b != b ? a : b;
}

/* The min (or max) over windows of w = 2k + 1 elements of a line of n + 2k
 * elements, `vec` floats each (a pixel's channels, or a strip of columns):
 * out[j] = op(line[j .. j + 2k]), j < n, by van Herk and Gil-Werman's
 * blocks, so that the cost does not grow with k: within each block of w
 * elements, `pre` holds the op from the block's start and `line` (in
 * place) to its end, and any window is one block's end joined to the
 * next one's start. */
static void window_op(float *line, float *pre, size_t n, size_t k, int vec, bool dilate,
                      float *out, size_t out_step)
{
    size_t len = n + 2 * k, w = 2 * k + 1;
    for (size_t i = 0, at = 0; i < len; i++, at = at + 1 == w ? 0 : at + 1) {
        float *p = pre + i * (size_t)vec;
        const float *s = line + i * (size_t)vec;
        if (at == 0) { /* a block starts */
            memcpy(p, s, (size_t)vec * sizeof *p);
            continue;
        }
        for (int c = 0; c < vec; c++) {
            p[c] = dilate ? max_f(p[c - vec], s[c]) : min_f(p[c - vec], s[c]);
        }
    }
    for (size_t i = len - 1; i-- > 0;) {
        if ((i + 1) % w == 0) {
            continue; /* the next element starts a block */
        }
        float *s = line + i * (size_t)vec;
        for (int c = 0; c < vec; c++) {
            s[c] = dilate ? max_f(s[c], s[c + vec]) : min_f(s[c], s[c + vec]);
        }
    }
    for (size_t j = 0; j < n; j++) {
        const float *a = line + j * (size_t)vec, *b = pre + (j + 2 * k) * (size_t)vec;
        float *d = out + j * out_step;
        /* joined to the empty window's value (0 for max, 1 for min), as
         * the direct loop starts from it */
        for (int c = 0; c < vec; c++) {
            d[c] = dilate ? max_f(max_f(a[c], b[c]), 0.0f) : min_f(min_f(a[c], b[c]), 1.0f);
        }
    }
}

/* Columns a strip of the column pass holds: its lines are a few cache
 * lines wide. */
#define MORPH_STRIP 8

/* feMorphology's radius in pixels along x and y, cut to the region (a
 * window wider than the region sees all of it); false when it is
 * disabled. */
static bool morph_radius(fctx *fc, const svg_node *n, size_t k[2])
{
    double r[2];
    pair_attr(fc, n, "radius", 0, r);
    if (!(r[0] > 0 && r[1] > 0)) {
        return false;
    }
    k[0] = (size_t)lround(fmin(r[0] * fc->sx * (fc->obb ? fc->bw : 1), fc->rw));
    k[1] = (size_t)lround(fmin(r[1] * fc->sy * (fc->obb ? fc->bh : 1), fc->rh));
    return true;
}

/* Erode (min) or dilate (max) each premultiplied channel over a
 * (2 kx + 1) x (2 ky + 1) window, beyond the region transparent black:
 * rows, then columns in strips. */
static void morphology(fctx *fc, const svg_node *n, const float *in, float *out)
{
    const char *op = fattr(n, "operator");
    bool dilate = op && strcmp(op, "dilate") == 0;
    size_t k[2];
    memcpy(out, in, fc->n * 4 * sizeof *out);
    if (!morph_radius(fc, n, k)) {
        return; /* Filter Effects 1: disabled, the input passes */
    }
    size_t kx = k[0], ky = k[1], rw = (size_t)fc->rw, rh = (size_t)fc->rh;
    size_t row = (rw + 2 * kx) * 4, strip = (rh + 2 * ky) * 4 * MORPH_STRIP;
    size_t most = row > strip ? row : strip;
    float *tmp = new_pixels(fc, n), *line = calloc(most, sizeof *line),
          *pre = malloc(most * sizeof *pre);
    if (!tmp || !line || !pre) {
        if (tmp) {
            fail(fc, n, SR_OUT_OF_MEMORY, "out of memory");
        }
        release(fc, tmp);
        free(line);
        free(pre);
        return;
    }
    /* the padding stays 0: transparent black beyond the region */
    for (size_t y = 0; y < rh; y++) {
        memcpy(line + kx * 4, in + y * rw * 4, rw * 4 * sizeof *line);
        window_op(line, pre, rw, kx, 4, dilate, tmp + y * rw * 4, 4);
        memset(line, 0, row * sizeof *line);
    }
    for (size_t x0 = 0; x0 < rw; x0 += MORPH_STRIP) {
        size_t sw = rw - x0 < MORPH_STRIP ? rw - x0 : MORPH_STRIP;
        int vec = (int)sw * 4;
        memset(line, 0, (rh + 2 * ky) * (size_t)vec * sizeof *line);
        for (size_t y = 0; y < rh; y++) {
            memcpy(line + (ky + y) * (size_t)vec, tmp + (y * rw + x0) * 4,
                   (size_t)vec * sizeof *line);
        }
        window_op(line, pre, rh, ky, vec, dilate, out + x0 * 4, rw * 4);
    }
    release(fc, tmp);
    free(line);
    free(pre);
}

/* The input's subregion repeated over the whole region. */
static void tile(fctx *fc, const fimg *in, float *out)
{
    int tx = in->sub[0], ty = in->sub[1], tw = in->sub[2] - tx, th = in->sub[3] - ty;
    if (tw <= 0 || th <= 0) {
        return;
    }
    for (int y = 0; y < fc->rh; y++) {
        int sy = ty + (((y - ty) % th) + th) % th;
        for (int x = 0; x < fc->rw; x++) {
            int sx = tx + (((x - tx) % tw) + tw) % tw;
            memcpy(out + ((size_t)y * fc->rw + x) * 4, in->p + ((size_t)sy * fc->rw + sx) * 4,
                   4 * sizeof *out);
        }
    }
}

/* Kernels of feConvolveMatrix, at most this many values a side. */
#define MAX_KERNEL_ORDER 64

/* feConvolveMatrix's order (columns, rows); false when it is in error. */
static bool kernel_order(fctx *fc, const svg_node *n, int *ox, int *oy)
{
    double ord[2];
    pair_attr(fc, n, "order", 3, ord);
    if (!(ord[0] >= 1 && ord[0] <= MAX_KERNEL_ORDER && ord[1] >= 1 &&
          ord[1] <= MAX_KERNEL_ORDER) || ord[0] != floor(ord[0]) || ord[1] != floor(ord[1])) {
        return false;
    }
    *ox = (int)ord[0];
    *oy = (int)ord[1];
    return true;
}

/* feConvolveMatrix on device pixels (the kernel turned half a turn, as
 * SVG defines it), edges by edgeMode (duplicate by default); false when
 * its attributes are in error (the result stays transparent black). */
static bool convolve(fctx *fc, const svg_node *n, const float *in, float *out)
{
    int ox, oy;
    if (!kernel_order(fc, n, &ox, &oy)) {
        return false;
    }
    double *k = malloc(sizeof *k * (size_t)(ox * oy));
    const char *kv = fattr(n, "kernelMatrix");
    if (!k || !kv || numbers(kv, k, ox * oy) != ox * oy) {
        free(k);
        return false;
    }
    double sum = 0;
    for (int i = 0; i < ox * oy; i++) {
        sum += k[i];
    }
    double divisor = number_attr(fc, n, "divisor", sum == 0 ? 1 : sum);
    double bias = number_attr(fc, n, "bias", 0);
    double txd = number_attr(fc, n, "targetX", ox / 2), tyd = number_attr(fc, n, "targetY", oy / 2);
    int tx = txd >= 0 && txd < ox ? (int)txd : -1, ty = tyd >= 0 && tyd < oy ? (int)tyd : -1;
    const char *e = fattr(n, "edgeMode"), *pa = fattr(n, "preserveAlpha");
    int edge = !e || strcmp(e, "duplicate") == 0 ? 1 : strcmp(e, "wrap") == 0 ? 2 : 0;
    bool keep_alpha = pa && strcmp(pa, "true") == 0;
    if (divisor == 0 || tx < 0 || tx >= ox || ty < 0 || ty >= oy) {
        free(k);
        return false;
    }
    for (int y = 0; y < fc->rh; y++) {
        for (int x = 0; x < fc->rw; x++) {
            double acc[4] = { 0, 0, 0, 0 };
            for (int i = 0; i < oy; i++) {
                for (int j = 0; j < ox; j++) {
                    int sx = x - tx + j, sy = y - ty + i;
                    if (sx < 0 || sy < 0 || sx >= fc->rw || sy >= fc->rh) {
                        if (edge == 0) {
                            continue;
                        }
                        sx = edge == 1 ? (sx < 0 ? 0 : sx >= fc->rw ? fc->rw - 1 : sx)
                                       : ((sx % fc->rw) + fc->rw) % fc->rw;
                        sy = edge == 1 ? (sy < 0 ? 0 : sy >= fc->rh ? fc->rh - 1 : sy)
                                       : ((sy % fc->rh) + fc->rh) % fc->rh;
                    }
                    const float *p = in + ((size_t)sy * fc->rw + (size_t)sx) * 4;
                    double w = k[(oy - i - 1) * ox + (ox - j - 1)];
                    float a = p[3];
                    for (int c = 0; c < 4; c++) {
                        /* preserveAlpha: the straight colour is convolved */
                        acc[c] += w * (keep_alpha && c < 3 ? (a > 0 ? p[c] / a : 0) : p[c]);
                    }
                }
            }
            float *d = out + ((size_t)y * fc->rw + x) * 4;
            const float *src = in + ((size_t)y * fc->rw + x) * 4;
            float a = keep_alpha ? src[3] : (float)fmin(fmax(acc[3] / divisor + bias, 0), 1);
            for (int c = 0; c < 3; c++) {
                float v = (float)(acc[c] / divisor + bias * (keep_alpha ? 1 : a));
                d[c] = keep_alpha ? fminf(fmaxf(v, 0), 1) * a : fminf(fmaxf(v, 0), a);
            }
            d[3] = a;
        }
    }
    free(k);
    return true;
}

/* feDisplacementMap: each pixel taken from where the map's channels
 * (straight values) point, scale user units for a full channel. */
static void displace(fctx *fc, const svg_node *n, const float *in, const float *map, float *out)
{
    double scale = number_attr(fc, n, "scale", 0);
    static const char *const sel[2] = { "xChannelSelector", "yChannelSelector" };
    int ch[2];
    for (int a = 0; a < 2; a++) {
        const char *v = fattr(n, sel[a]);
        ch[a] = !v || strcmp(v, "A") == 0 ? 3 : strcmp(v, "R") == 0 ? 0 : strcmp(v, "G") == 0 ? 1
              : strcmp(v, "B") == 0 ? 2 : 3;
    }
    double kx = scale * fc->sx * (fc->obb ? fc->bw : 1), ky = scale * fc->sy * (fc->obb ? fc->bh : 1);
    for (int y = 0; y < fc->rh; y++) {
        for (int x = 0; x < fc->rw; x++) {
            const float *m = map + ((size_t)y * fc->rw + x) * 4;
            float a = m[3];
            double vx = ch[0] == 3 ? a : a > 0 ? m[ch[0]] / a : 0;
            double vy = ch[1] == 3 ? a : a > 0 ? m[ch[1]] / a : 0;
            double sx = floor(x + kx * (vx - 0.5) + 0.5), sy = floor(y + ky * (vy - 0.5) + 0.5);
            if (!(sx >= 0 && sy >= 0 && sx < fc->rw && sy < fc->rh)) { /* NaN too */
                continue;
            }
            memcpy(out + ((size_t)y * fc->rw + x) * 4,
                   in + ((size_t)sy * fc->rw + (size_t)sx) * 4, 4 * sizeof *out);
        }
    }
}

/* ---- lighting ---------------------------------------------------------------- */

typedef struct light {
    int kind;                    /* 0 distant, 1 point, 2 spot, -1 none */
    double dir[3];               /* distant: towards the light */
    double pos[3], at[3];        /* point and spot, in device pixels (z scaled alike) */
    double spot_exp, cos_cone;   /* spot: specularExponent, cos(limitingConeAngle) or -2 */
} light;

/* The light source child of a lighting primitive, in device pixels. */
static light light_of(fctx *fc, const svg_node *n)
{
    light l = { .kind = -1 };
    const double *m = fc->job->m;
    double zk = sqrt(fc->sx * fc->sy);
    for (const svg_node *c = n->first; c; c = c->next) {
        if (is(c, "feDistantLight")) {
            double az = number_attr(fc, c, "azimuth", 0) * M_PI / 180;
            double el = number_attr(fc, c, "elevation", 0) * M_PI / 180;
            l = (light){ .kind = 0, .dir = { cos(az) * cos(el), sin(az) * cos(el), sin(el) } };
            /* the direction turns and mirrors with the transform */
            double dx = m[0] * l.dir[0] + m[2] * l.dir[1], dy = m[1] * l.dir[0] + m[3] * l.dir[1];
            double len = hypot(dx, dy), flat = hypot(l.dir[0], l.dir[1]);
            if (len > 0) {
                l.dir[0] = dx / len * flat;
                l.dir[1] = dy / len * flat;
            }
            return l;
        }
        if (is(c, "fePointLight") || is(c, "feSpotLight")) {
            bool spot = is(c, "feSpotLight");
            double p[3] = { number_attr(fc, c, "x", 0), number_attr(fc, c, "y", 0),
                            number_attr(fc, c, "z", 0) };
            double q[3] = { number_attr(fc, c, "pointsAtX", 0), number_attr(fc, c, "pointsAtY", 0),
                            number_attr(fc, c, "pointsAtZ", 0) };
            if (fc->obb) {
                const double *b = fc->job->bbox;
                double diag = sqrt((fc->bw * fc->bw + fc->bh * fc->bh) / 2);
                p[0] = b[0] + p[0] * fc->bw;
                p[1] = b[1] + p[1] * fc->bh;
                p[2] *= diag;
                q[0] = b[0] + q[0] * fc->bw;
                q[1] = b[1] + q[1] * fc->bh;
                q[2] *= diag;
            }
            l.kind = spot ? 2 : 1;
            l.pos[0] = m[0] * p[0] + m[2] * p[1] + m[4];
            l.pos[1] = m[1] * p[0] + m[3] * p[1] + m[5];
            l.pos[2] = p[2] * zk;
            l.at[0] = m[0] * q[0] + m[2] * q[1] + m[4];
            l.at[1] = m[1] * q[0] + m[3] * q[1] + m[5];
            l.at[2] = q[2] * zk;
            l.spot_exp = number_attr(fc, c, "specularExponent", 1);
            const char *cone = fattr(c, "limitingConeAngle");
            l.cos_cone = cone ? cos(fabs(number_attr(fc, c, "limitingConeAngle", 90)) * M_PI / 180)
                              : -2;
            return l;
        }
    }
    return l;
}

/* The input's alpha at (x, y), the edges repeated. */
static double alpha_at(const fctx *fc, const float *in, int x, int y)
{
    x = x < 0 ? 0 : x >= fc->rw ? fc->rw - 1 : x;
    y = y < 0 ? 0 : y >= fc->rh ? fc->rh - 1 : y;
    return in[((size_t)y * fc->rw + x) * 4 + 3];
}

/* The surface normal's x and y (z is 1) from the alpha by SVG's Sobel
 * kernels, which shrink at the image's edges: 2 / (span * weights). */
static void normal(const fctx *fc, const float *in, int x, int y, double ss, double nrm[2])
{
    int xl = x > 0 ? x - 1 : x, xr = x < fc->rw - 1 ? x + 1 : x;
    int yt = y > 0 ? y - 1 : y, yb = y < fc->rh - 1 ? y + 1 : y;
    double gx = 0, gy = 0, wx = 0, wy = 0;
    for (int d = -1; d <= 1; d++) {
        double w = d == 0 ? 2 : 1;
        if (y + d >= 0 && y + d < fc->rh) {
            gx += w * (alpha_at(fc, in, xr, y + d) - alpha_at(fc, in, xl, y + d));
            wx += w;
        }
        if (x + d >= 0 && x + d < fc->rw) {
            gy += w * (alpha_at(fc, in, x + d, yb) - alpha_at(fc, in, x + d, yt));
            wy += w;
        }
    }
    nrm[0] = xr > xl ? -ss * 2 / ((xr - xl) * wx) * gx : 0;
    nrm[1] = yb > yt ? -ss * 2 / ((yb - yt) * wy) * gy : 0;
}

/* feDiffuseLighting and feSpecularLighting: the input's alpha as a
 * height field lit by its light source, in lighting-color. */
static void lighting(fctx *fc, const svg_node *n, const svg_fe_style *st, const float *in,
                     float *out)
{
    bool specular = is(n, "feSpecularLighting");
    double ss = number_attr(fc, n, "surfaceScale", 1);
    double kd = number_attr(fc, n, specular ? "specularConstant" : "diffuseConstant", 1);
    double se = specular ? number_attr(fc, n, "specularExponent", 1) : 1;
    light l = light_of(fc, n);
    if (l.kind < 0 || kd < 0 || (specular && (se < 1 || se > 128))) {
        fc->job->warn(fc->job->host, n, "lighting in error (transparent black)", n->name);
        return;
    }
    /* lighting-color is taken as it is, whatever the space: both
     * references do (and W3C's filters-light-* with them) */
    float lc[4];
    premultiplied(st->lighting, true, lc);
    double s_dir[3] = { l.at[0] - l.pos[0], l.at[1] - l.pos[1], l.at[2] - l.pos[2] };
    double s_len = sqrt(s_dir[0] * s_dir[0] + s_dir[1] * s_dir[1] + s_dir[2] * s_dir[2]);
    for (int y = 0; y < fc->rh; y++) {
        for (int x = 0; x < fc->rw; x++) {
            double nv[3], L[3];
            normal(fc, in, x, y, ss, nv);
            nv[2] = 1;
            double nl = sqrt(nv[0] * nv[0] + nv[1] * nv[1] + 1);
            /* heights are surfaceScale times alpha in pixels, unscaled, as
             * the normals are (both references agree) */
            double z = ss * alpha_at(fc, in, x, y), k = 1;
            if (l.kind == 0) {
                memcpy(L, l.dir, sizeof L);
            } else {
                L[0] = l.pos[0] - (x + fc->rx);
                L[1] = l.pos[1] - (y + fc->ry);
                L[2] = l.pos[2] - z;
                double len = sqrt(L[0] * L[0] + L[1] * L[1] + L[2] * L[2]);
                for (int i = 0; i < 3 && len > 0; i++) {
                    L[i] /= len;
                }
                if (l.kind == 2) {
                    double c = s_len > 0 ? -(L[0] * s_dir[0] + L[1] * s_dir[1] + L[2] * s_dir[2]) / s_len
                                         : 0;
                    k = c <= 0 || c < l.cos_cone ? 0 : pow(c, l.spot_exp);
                }
            }
            double f;
            if (specular) {
                double h[3] = { L[0], L[1], L[2] + 1 };
                double hl = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
                double nh = hl > 0 ? (nv[0] * h[0] + nv[1] * h[1] + h[2]) / (nl * hl) : 0;
                f = kd * pow(fmax(nh, 0), se);
            } else {
                f = kd * fmax((nv[0] * L[0] + nv[1] * L[1] + L[2]) / nl, 0);
            }
            float *d = out + ((size_t)y * fc->rw + x) * 4;
            float mx = 0;
            for (int c = 0; c < 3; c++) {
                d[c] = (float)fmin(f * k * lc[c], 1);
                mx = fmaxf(mx, d[c]);
            }
            /* diffuse light is opaque; specular light is as opaque as it is bright */
            d[3] = specular ? mx : 1;
        }
    }
}

/* ---- feTurbulence: Perlin noise as SVG 1.1 specifies it ---------------------- */

#define TURB_B 0x100            /* lattice size */
#define TURB_BM 0xff
#define TURB_N 0x1000           /* offset that keeps lattice coordinates positive */
/* Octaves beyond this add less than a 2^-24 part: more are not computed. */
#define TURB_MAX_OCTAVES 24

typedef struct turbulence_state {
    int lattice[TURB_B + TURB_B + 2];
    double gradient[4][TURB_B + TURB_B + 2][2];
} turbulence_state;

/* 64 bits: each octave doubles them, from up to 2^24, for 24 octaves */
typedef struct stitch {
    int64_t width, height, wrap_x, wrap_y;
} stitch;

/* The specification's Park-Miller generator (a = 16807, m = 2^31 - 1). */
static long turb_random(long seed)
{
    long r = 16807 * (seed % 127773) - 2836 * (seed / 127773);
    return r <= 0 ? r + 2147483647 : r;
}

static void turbulence_init(turbulence_state *t, long seed)
{
    if (seed <= 0) {
        seed = -(seed % (2147483647 - 1)) + 1;
    }
    if (seed > 2147483647 - 1) {
        seed = 2147483647 - 1;
    }
    int i = 0;
    for (int k = 0; k < 4; k++) {
        for (i = 0; i < TURB_B; i++) {
            t->lattice[i] = i;
            for (int j = 0; j < 2; j++) {
                seed = turb_random(seed);
                t->gradient[k][i][j] = (double)((seed % (TURB_B + TURB_B)) - TURB_B) / TURB_B;
            }
            double *g = t->gradient[k][i], len = sqrt(g[0] * g[0] + g[1] * g[1]);
            if (len > 0) {
                g[0] /= len;
                g[1] /= len;
            }
        }
    }
    while (--i) {
        int k = t->lattice[i];
        seed = turb_random(seed);
        int j = (int)(seed % TURB_B);
        t->lattice[i] = t->lattice[j];
        t->lattice[j] = k;
    }
    for (i = 0; i < TURB_B + 2; i++) {
        t->lattice[TURB_B + i] = t->lattice[i];
        for (int k = 0; k < 4; k++) {
            t->gradient[k][TURB_B + i][0] = t->gradient[k][i][0];
            t->gradient[k][TURB_B + i][1] = t->gradient[k][i][1];
        }
    }
}

static double s_curve(double t)
{
    return t * t * (3 - 2 * t);
}

static double noise2(const turbulence_state *t, int channel, double x, double y, const stitch *st)
{
    double tx = x + TURB_N, ty = y + TURB_N;
    /* far coordinates fold onto the lattice's period (256 cells) before
     * they pass int's range; NaN and infinity (a frequency at double's
     * end) are 0 */
    tx = fabs(tx) < (1 << 30) ? tx : !isfinite(tx) ? 0 : fmod(tx, 1 << 24);
    ty = fabs(ty) < (1 << 30) ? ty : !isfinite(ty) ? 0 : fmod(ty, 1 << 24);
    int64_t bx0 = (int)tx, by0 = (int)ty, bx1 = bx0 + 1, by1 = by0 + 1;
    double rx0 = tx - (int)tx, ry0 = ty - (int)ty, rx1 = rx0 - 1, ry1 = ry0 - 1;
    if (st) {
        bx0 -= bx0 >= st->wrap_x ? st->width : 0;
        bx1 -= bx1 >= st->wrap_x ? st->width : 0;
        by0 -= by0 >= st->wrap_y ? st->height : 0;
        by1 -= by1 >= st->wrap_y ? st->height : 0;
    }
    int x0 = (int)(bx0 & TURB_BM), x1 = (int)(bx1 & TURB_BM);
    int y0 = (int)(by0 & TURB_BM), y1 = (int)(by1 & TURB_BM);
    int i = t->lattice[x0], j = t->lattice[x1];
    const double *q00 = t->gradient[channel][t->lattice[i + y0]];
    const double *q10 = t->gradient[channel][t->lattice[j + y0]];
    const double *q01 = t->gradient[channel][t->lattice[i + y1]];
    const double *q11 = t->gradient[channel][t->lattice[j + y1]];
    double sx = s_curve(rx0), sy = s_curve(ry0);
    double u = rx0 * q00[0] + ry0 * q00[1], v = rx1 * q10[0] + ry0 * q10[1];
    double a = u + sx * (v - u);
    u = rx0 * q01[0] + ry1 * q01[1];
    v = rx1 * q11[0] + ry1 * q11[1];
    double b = u + sx * (v - u);
    return a + sy * (b - a);
}

/* The frequency nearest `f` that fits a whole number of cycles in `len`. */
static double stitch_frequency(double f, double len)
{
    double lo = floor(len * f) / len, hi = ceil(len * f) / len;
    return lo > 0 && f / lo < hi / f ? lo : hi;
}

/* numOctaves as computed: none below 1, at most TURB_MAX_OCTAVES. */
static int turb_octaves(double oct)
{
    return oct < 0 ? 0 : oct > TURB_MAX_OCTAVES ? TURB_MAX_OCTAVES : (int)oct;
}

/* The noise is in the primitive's colour space, as its result is. */
static void turbulence(fctx *fc, const svg_node *n, const int out_sub[4], float *out)
{
    double freq[2];
    pair_attr(fc, n, "baseFrequency", 0, freq);
    double oct = number_attr(fc, n, "numOctaves", 1), seed = number_attr(fc, n, "seed", 0);
    const char *type = fattr(n, "type"), *st_attr = fattr(n, "stitchTiles");
    bool fractal = type && strcmp(type, "fractalNoise") == 0;
    if (!(freq[0] >= 0 && freq[1] >= 0)) {
        return; /* a negative frequency is an error: transparent black */
    }
    int octaves = turb_octaves(oct);
    turbulence_state *t = malloc(sizeof *t);
    if (!t) {
        fail(fc, n, SR_OUT_OF_MEMORY, "out of memory");
        return;
    }
    /* the seed is truncated, as W3C's filters-turb-02-f expects (1.5 as 1,
     * -0.8 as 0) and both references do */
    turbulence_init(t, (long)fmax(fmin(trunc(seed), 2e9), -2e9));
    /* the tile is the primitive subregion in pixels, as both references
     * take it (mixed with a frequency in user units) */
    double tile[4] = { fc->job->origin[0] + fc->rx + out_sub[0],
                       fc->job->origin[1] + fc->ry + out_sub[1], out_sub[2] - out_sub[0],
                       out_sub[3] - out_sub[1] };
    stitch base = { 0 };
    bool stitching = st_attr && strcmp(st_attr, "stitch") == 0;
    if (stitching) {
        for (int a = 0; a < 2; a++) {
            if (freq[a] != 0) {
                freq[a] = stitch_frequency(freq[a], tile[2 + a]);
            }
        }
        /* lattice cells stay far inside int, whatever the frequency */
        double cw = fmin(tile[2] * freq[0] + 0.5, 1 << 20), ch = fmin(tile[3] * freq[1] + 0.5, 1 << 20);
        base.width = (int64_t)cw;
        base.wrap_x = (int64_t)fmax(fmin(tile[0] * freq[0] + TURB_N + (double)base.width,
                                         1 << 24), -(1 << 24));
        base.height = (int64_t)ch;
        base.wrap_y = (int64_t)fmax(fmin(tile[1] * freq[1] + TURB_N + (double)base.height,
                                         1 << 24), -(1 << 24));
    }
    /* pixels -> user space, noise at each pixel's corner (as resvg samples it) */
    const double *m = fc->job->m;
    double inv[6];
    if (!sr__affine2_invert(m, 0, inv)) {
        free(t);
        return;
    }
    double ia = inv[0], ib = inv[1], ic = inv[2], id = inv[3];
    for (int y = 0; y < fc->rh; y++) {
        for (int x = 0; x < fc->rw; x++) {
            double px = x + fc->rx - m[4], py = y + fc->ry - m[5];
            double ux = ia * px + ic * py, uy = ib * px + id * py;
            float c[4];
            for (int ch = 0; ch < 4; ch++) {
                stitch s = base;
                double sum = 0, vx = ux * freq[0], vy = uy * freq[1], ratio = 1;
                for (int o = 0; o < octaves; o++) {
                    double v = noise2(t, ch, vx, vy, stitching ? &s : NULL);
                    sum += (fractal ? v : fabs(v)) / ratio;
                    vx *= 2;
                    vy *= 2;
                    ratio *= 2;
                    s.width *= 2;
                    s.wrap_x = 2 * s.wrap_x - TURB_N;
                    s.height *= 2;
                    s.wrap_y = 2 * s.wrap_y - TURB_N;
                }
                c[ch] = fminf(fmaxf((float)(fractal ? (sum + 1) / 2 : sum), 0), 1);
            }
            float *d = out + ((size_t)y * fc->rw + x) * 4;
            for (int ch = 0; ch < 3; ch++) {
                d[ch] = c[ch] * c[3];
            }
            d[3] = c[3];
        }
    }
    free(t);
}

/* feImage: an element of the document ("#id") or a picture (a file next
 * to the document or a data: URI) fitted into the subregion, drawn by the
 * reader. */
static void image(fctx *fc, const svg_node *n, fimg *out)
{
    const char *href = fattr(n, "href");
    if (!href) {
        href = fattr(n, "xlink:href");
    }
    if (!href) {
        return;
    }
    double r[4];
    memcpy(r, fc->region, sizeof r);
    bool given;
    region_attrs(fc, n, fc->obb, r, &given);
    size_t bytes = (size_t)fc->job->width * (size_t)fc->job->height * 4;
    uint8_t *px = calloc(bytes, 1);
    if (!px) {
        fail(fc, n, SR_OUT_OF_MEMORY, "out of memory");
        return;
    }
    if (fc->job->draw(fc->job->host, n, href, r, px)) {
        from_layer(fc, px, out->p, false);
        out->srgb = true;
    } else {
        fc->failed = true;
    }
    free(px);
}

/* ---- the graph ------------------------------------------------------------------- */

static const char *const primitives[] = {
    "feGaussianBlur", "feOffset", "feFlood", "feMerge", "feComposite", "feBlend",
    "feColorMatrix", "feDropShadow", "feComponentTransfer", "feMorphology", "feTile", "feImage",
    "feTurbulence", "feConvolveMatrix", "feDisplacementMap", "feDiffuseLighting",
    "feSpecularLighting", NULL,
};

static bool is_primitive(const svg_node *n)
{
    for (int i = 0; primitives[i]; i++) {
        if (is(n, primitives[i])) {
            return true;
        }
    }
    return false;
}

/* An input named by `name` as primitive i sees it: the latest earlier
 * result of that name, a standard input, or (absent, or naming no result,
 * as Filter Effects 1 and resvg take it) the previous result. */
static int resolve(fctx *fc, const prim *p, int i, const svg_node *at, const char *name)
{
    if (name) {
        if (strcmp(name, "SourceGraphic") == 0) {
            return IN_SOURCE;
        }
        if (strcmp(name, "SourceAlpha") == 0) {
            return IN_SOURCE_ALPHA;
        }
        if (strcmp(name, "FillPaint") == 0 || strcmp(name, "StrokePaint") == 0) {
            return name[0] == 'F' ? IN_FILL : IN_STROKE; /* as both references: a flat color */
        }
        if (strcmp(name, "BackgroundImage") == 0 || strcmp(name, "BackgroundAlpha") == 0) {
            fc->job->warn(fc->job->host, at, "filter input (transparent black)", name);
            return IN_EMPTY;
        }
        for (int j = i - 1; j >= 0; j--) {
            if (p[j].result && strcmp(p[j].result, name) == 0) {
                return j;
            }
        }
        fc->job->warn(fc->job->host, at, "filter input (the previous result)", name);
    }
    return i > 0 ? i - 1 : IN_SOURCE;
}

/* An input's image; NULL after a failure. */
static fimg *image_of(fctx *fc, fimg *res, int k)
{
    return k >= 0 ? &res[k] : standard(fc, k);
}

/* The default subregion: the union of the inputs' when all are results,
 * else the whole region. */
static void default_sub(fctx *fc, fimg *res, const int *ins, int n_ins, int out[4])
{
    int u[4] = { fc->rw, fc->rh, 0, 0 };
    for (int i = 0; i < n_ins; i++) {
        if (ins[i] < 0) {
            u[0] = u[1] = 0;
            u[2] = fc->rw;
            u[3] = fc->rh;
            break;
        }
        const int *s = res[ins[i]].sub;
        u[0] = s[0] < u[0] ? s[0] : u[0];
        u[1] = s[1] < u[1] ? s[1] : u[1];
        u[2] = s[2] > u[2] ? s[2] : u[2];
        u[3] = s[3] > u[3] ? s[3] : u[3];
    }
    if (n_ins == 0 || u[2] < u[0]) {
        u[0] = u[1] = 0;
        u[2] = fc->rw;
        u[3] = fc->rh;
    }
    memcpy(out, u, sizeof u);
}

/* Whether the primitive reads its `in` (those that fill their subregion
 * do not; a merge reads its nodes'). */
static bool reads_in(const svg_node *n)
{
    return !is(n, "feFlood") && !is(n, "feImage") && !is(n, "feTurbulence") && !is(n, "feMerge");
}

/* The images of the region primitive p reads, as run() counts them: a
 * merge its nodes; those that fill their subregion none of `in`. */
static double prim_reads(const prim *p)
{
    double reads = (p->in[1] != -4) + (reads_in(p->node) && !is(p->node, "feTile"));
    for (const svg_node *m = p->node->first; m && is(p->node, "feMerge"); m = m->next) {
        reads += is(m, "feMergeNode");
    }
    return reads;
}

/* What primitive n counts of the work budget per pixel of the region:
 * a pass for each image it reads (`reads`) and one for its result, and
 * the work whose cost grows with its attributes: a convolution's kernel,
 * a blur's taps along each axis, the octaves of noise in each channel, a
 * morphology's two passes (its window's cost does not grow with the
 * radius).  svg_apply_filter() counts it for every primitive before
 * any runs, and svg_filter_extent() adds it up, so that the larger layer
 * is chosen on what the filter will count. */
static double prim_work(fctx *fc, const svg_node *n, double reads)
{
    double w = reads + 1;
    int ox, oy;
    if (is(n, "feConvolveMatrix") && kernel_order(fc, n, &ox, &oy)) {
        w += (double)ox * oy;
    } else if (is(n, "feGaussianBlur") || is(n, "feDropShadow")) {
        double v[2];
        pair_attr(fc, n, "stdDeviation", is(n, "feDropShadow") ? 2 : 0, v);
        w += blur_axis_work(blur_sigma_px(fc, v[0], false)) +
             blur_axis_work(blur_sigma_px(fc, v[1], true));
    } else if (is(n, "feTurbulence")) {
        w += 4.0 * (turb_octaves(number_attr(fc, n, "numOctaves", 1)) + 1);
    } else if (is(n, "feMorphology")) {
        w += 2;
    }
    return w;
}

/* Run primitive i into res[i]. */
static void run(fctx *fc, prim *p, fimg *res, int i)
{
    const svg_node *n = p[i].node;
    svg_fe_style st = fc->job->style(fc->job->host, n);
    fimg *out = &res[i];
    out->srgb = st.srgb;
    int ins[64], n_ins = 0; /* a merge's first 64 make its default subregion */
    if (is(n, "feMerge")) {
        for (const svg_node *c = n->first; c; c = c->next) {
            if (is(c, "feMergeNode") && n_ins < 64) {
                ins[n_ins++] = resolve(fc, p, i, c, fattr(c, "in"));
            }
        }
    } else if (!is(n, "feFlood") && !is(n, "feImage") && !is(n, "feTurbulence") &&
               !is(n, "feTile")) { /* a tile fills the region, as both references draw it */
        ins[n_ins++] = p[i].in[0];
        if (p[i].in[1] != -4) {
            ins[n_ins++] = p[i].in[1];
        }
    }
    int def[4];
    default_sub(fc, res, ins, n_ins, def);
    subregion(fc, n, def, out->sub);
    out->p = new_pixels(fc, n);
    if (!out->p) {
        return;
    }
    fimg *a = n_ins > 0 ? image_of(fc, res, ins[0]) : NULL;
    fimg *b = n_ins > 1 ? image_of(fc, res, ins[1]) : NULL;
    if (fc->failed) {
        return;
    }
    if (!is(n, "feMerge")) {
        /* a displacement moves its image's pixels in whatever space they
         * are: color-interpolation-filters applies to its map alone */
        if (a && is(n, "feDisplacementMap")) {
            out->srgb = a->srgb;
        } else if (a) {
            convert(fc, a, st.srgb);
        }
        if (b) {
            convert(fc, b, st.srgb);
        }
    }
    double v[2];
    if (is(n, "feGaussianBlur")) {
        pair_attr(fc, n, "stdDeviation", 0, v);
        blur(fc, n, a->p, out->p, v[0], v[1]);
    } else if (is(n, "feOffset")) {
        offset(fc, out->sub, a->p, out->p, number_attr(fc, n, "dx", 0),
               number_attr(fc, n, "dy", 0));
    } else if (is(n, "feFlood")) {
        float c[4];
        premultiplied(st.flood, st.srgb, c);
        flood(fc, out->sub, out->p, c);
    } else if (is(n, "feMerge")) {
        for (const svg_node *c = n->first; c; c = c->next) {
            if (is(c, "feMergeNode")) {
                fimg *m = image_of(fc, res, resolve(fc, p, i, c, fattr(c, "in")));
                if (!m) {
                    return;
                }
                convert(fc, m, st.srgb);
                over(fc, out->sub, m->p, out->p);
            }
        }
    } else if (is(n, "feComposite")) {
        composite(fc, n, out->sub, a->p, b->p, out->p);
    } else if (is(n, "feBlend")) {
        blend(fc, n, out->sub, a->p, b->p, out->p);
    } else if (is(n, "feColorMatrix")) {
        color_matrix(fc, n, out->sub, a->p, out->p);
    } else if (is(n, "feComponentTransfer")) {
        component_transfer(fc, n, out->sub, a->p, out->p);
    } else if (is(n, "feMorphology")) {
        morphology(fc, n, a->p, out->p);
    } else if (is(n, "feTile")) {
        fimg *t = image_of(fc, res, p[i].in[0]);
        if (!t) {
            return;
        }
        convert(fc, t, st.srgb);
        tile(fc, t, out->p);
    } else if (is(n, "feDropShadow")) {
        /* flood-color in the input's alpha, blurred, offset, under the input */
        float c[4], *t = new_pixels(fc, n), *u = new_pixels(fc, n);
        premultiplied(st.flood, st.srgb, c);
        if (t && u) {
            for (size_t k = 0; k < fc->n; k++) {
                for (int ch = 0; ch < 4; ch++) {
                    t[k * 4 + ch] = c[ch] * a->p[k * 4 + 3];
                }
            }
            pair_attr(fc, n, "stdDeviation", 2, v);
            blur(fc, n, t, u, v[0], v[1]);
            offset(fc, out->sub, u, out->p, number_attr(fc, n, "dx", 2),
                   number_attr(fc, n, "dy", 2));
            over(fc, out->sub, a->p, out->p);
        }
        release(fc, t);
        release(fc, u);
    } else if (is(n, "feImage")) {
        image(fc, n, out);
    } else if (is(n, "feConvolveMatrix")) {
        if (!convolve(fc, n, a->p, out->p)) {
            memset(out->p, 0, fc->n * 4 * sizeof *out->p);
            fc->job->warn(fc->job->host, n, "feConvolveMatrix in error (transparent black)",
                          fattr(n, "kernelMatrix") ? fattr(n, "kernelMatrix") : "");
        }
    } else if (is(n, "feDisplacementMap")) {
        displace(fc, n, a->p, b->p, out->p);
    } else if (is(n, "feDiffuseLighting") || is(n, "feSpecularLighting")) {
        lighting(fc, n, &st, a->p, out->p);
    } else if (is(n, "feTurbulence")) {
        turbulence(fc, n, out->sub, out->p);
    } else {
        fc->job->warn(fc->job->host, n, "filter primitive (transparent black)", n->name);
    }
    cut_to(fc, out);
}

/* The final result into the layer: sRGB, straight alpha, zero outside
 * the region. */
static void write_back(fctx *fc, fimg *im)
{
    const svg_filter_job *job = fc->job;
    size_t stride = (size_t)job->width * 4;
    for (int y = 0; y < job->height; y++) {
        uint8_t *row = job->pixels + (size_t)y * stride;
        int Y = y - fc->ry;
        if (Y < 0 || Y >= fc->rh) {
            memset(row, 0, stride);
            continue;
        }
        memset(row, 0, (size_t)fc->rx * 4);
        memset(row + (size_t)(fc->rx + fc->rw) * 4, 0, stride - (size_t)(fc->rx + fc->rw) * 4);
        for (int X = 0; X < fc->rw; X++) {
            uint8_t *d = row + (size_t)(X + fc->rx) * 4;
            float s[4];
            memcpy(s, im->p + ((size_t)Y * fc->rw + X) * 4, sizeof s);
            if (!im->srgb) {
                convert_pixel(s, true);
            }
            float a = clamp01(s[3]);
            for (int c = 0; c < 3; c++) {
                float v = a > 0 ? clamp01(s[c] / a) : 0;
                d[c] = (uint8_t)(v * 255 + 0.5f);
            }
            d[3] = (uint8_t)(a * 255 + 0.5f);
        }
    }
}

/* The primitives of the filter, unknown ones warned. */
static int count_primitives(const svg_filter_job *job)
{
    int count = 0;
    for (const svg_node *c = job->filter->first; c; c = c->next) {
        if (is_primitive(c)) {
            count++;
        } else if (!c->foreign && strncmp(c->name, "fe", 2) == 0) {
            /* an unknown primitive is left out, as both references do */
            job->warn(job->host, c, "filter primitive", c->name);
        }
    }
    return count;
}

/* The primitives in order, their inputs resolved, and each result's last
 * reader (0: none). */
typedef struct graph {
    prim *p;
    int *last_use;
    int count;
} graph;

static void free_graph(graph *g)
{
    free(g->p);
    free(g->last_use);
}

/* The graph of `count` primitives; false after a failure. */
static bool make_graph(fctx *fc, int count, graph *g)
{
    *g = (graph){ .p = calloc((size_t)count, sizeof *g->p),
                  .last_use = calloc((size_t)count, sizeof *g->last_use), .count = count };
    if (!g->p || !g->last_use) {
        fail(fc, fc->job->filter, SR_OUT_OF_MEMORY, "out of memory");
        free_graph(g);
        return false;
    }
    prim *p = g->p;
    int i = 0;
    for (const svg_node *c = fc->job->filter->first; c; c = c->next) {
        if (!is_primitive(c)) {
            continue;
        }
        p[i] = (prim){ .node = c, .in = { -4, -4 }, .result = fattr(c, "result") };
        p[i].in[0] = resolve(fc, p, i, c, fattr(c, "in"));
        if (is(c, "feComposite") || is(c, "feBlend") || is(c, "feDisplacementMap")) {
            p[i].in[1] = resolve(fc, p, i, c, fattr(c, "in2"));
        }
        for (int k = 0; k < 2; k++) {
            if (p[i].in[k] >= 0) {
                g->last_use[p[i].in[k]] = i;
            }
        }
        for (const svg_node *m = c->first; m && is(c, "feMerge"); m = m->next) {
            int j = is(m, "feMergeNode") ? resolve(fc, p, i, m, fattr(m, "in")) : -1;
            if (j >= 0) {
                g->last_use[j] = i;
            }
        }
        i++;
    }
    return true;
}

/* Whether result j is still held while primitive i runs: until its last
 * reader has run; one no later primitive reads is freed at once, the
 * last one is kept for the layer. */
static bool held(const graph *g, int j, int i)
{
    return j == i || j == g->count - 1 || g->last_use[j] >= i;
}

/* Images of the region a primitive allocates besides its result. */
static int scratch_images(const svg_node *n)
{
    return is(n, "feDropShadow") ? 2 : is(n, "feMorphology") ? 1 : 0;
}

uint64_t svg_filter_peak(const svg_filter_job *job, int *images)
{
    fctx fc = { .job = job };
    graph g;
    *images = 0;
    int count = count_primitives(job);
    if (count == 0 || count > MAX_PRIMITIVES || !filter_region(&fc) ||
        !make_graph(&fc, count, &g)) {
        return 0;
    }
    /* the standard inputs are made when first read and kept to the end */
    bool standard_read[7] = { false };
    int most = 0;
    bool picture = false;
    for (int i = 0; i < count; i++) {
        const prim *p = &g.p[i];
        for (int k = 0; k < 2; k++) {
            int in = p->in[k];
            if (in < 0 && in != -4 && (k == 1 || reads_in(p->node))) {
                standard_read[-in] = true;
            }
        }
        for (const svg_node *m = p->node->first; m && is(p->node, "feMerge"); m = m->next) {
            int in = is(m, "feMergeNode") ? resolve(&fc, g.p, i, m, fattr(m, "in")) : 0;
            if (in < 0) {
                standard_read[-in] = true;
            }
        }
        picture = picture || is(p->node, "feImage");
        int live = scratch_images(p->node);
        for (int j = 0; j <= i; j++) {
            live += held(&g, j, i);
        }
        most = live > most ? live : most;
    }
    for (int k = 1; k < 7; k++) {
        most += standard_read[k];
    }
    free_graph(&g);
    *images = most;
    /* an feImage's picture comes as an RGBA8 copy of the layer */
    return (uint64_t)most * fc.n * 4 * sizeof(float) +
           (picture ? (uint64_t)job->width * (uint64_t)job->height * 4 : 0);
}

/* How far (pixels) from each of its pixels primitive n reads: r[0] and
 * r[1] towards -x and -y, r[2] and r[3] towards +x and +y (an offset
 * reads on one side only). */
static void own_reach(fctx *fc, const svg_node *n, double r[4])
{
    double kx = fc->sx * (fc->obb ? fc->bw : 1), ky = fc->sy * (fc->obb ? fc->bh : 1), v[2];
    bool shadow = is(n, "feDropShadow");
    const char *e = fattr(n, "edgeMode");
    bool wrap = e && strcmp(e, "wrap") == 0;
    double both[2] = { 0, 0 };
    r[0] = r[1] = r[2] = r[3] = 0;
    if (is(n, "feGaussianBlur") || shadow) {
        pair_attr(fc, n, "stdDeviation", shadow ? 2 : 0, v);
        /* the sampled kernel's 3 deviations, or the three boxes' 2.9 */
        both[0] += 3 * fabs(v[0]) * kx + 3;
        both[1] += 3 * fabs(v[1]) * ky + 3;
    }
    if (is(n, "feOffset") || shadow) {
        /* a shift by d reads d behind, and a pixel either side between pixels */
        const double *m = fc->job->m;
        double dx = number_attr(fc, n, "dx", shadow ? 2 : 0) * (fc->obb ? fc->bw : 1);
        double dy = number_attr(fc, n, "dy", shadow ? 2 : 0) * (fc->obb ? fc->bh : 1);
        double d[2] = { m[0] * dx + m[2] * dy, m[1] * dx + m[3] * dy };
        for (int a = 0; a < 2; a++) {
            r[a] = fmax(d[a], 0) + 1;
            r[a + 2] = fmax(-d[a], 0) + 1;
        }
    } else if (is(n, "feMorphology")) {
        pair_attr(fc, n, "radius", 0, v);
        both[0] = fabs(v[0]) * kx + 1;
        both[1] = fabs(v[1]) * ky + 1;
    } else if (is(n, "feConvolveMatrix")) {
        pair_attr(fc, n, "order", 3, v);
        both[0] = fabs(v[0]) + 1;
        both[1] = fabs(v[1]) + 1;
    } else if (is(n, "feDisplacementMap")) {
        double scale = fabs(number_attr(fc, n, "scale", 0));
        both[0] = scale * kx / 2 + 1;
        both[1] = scale * ky / 2 + 1;
    } else if (is(n, "feDiffuseLighting") || is(n, "feSpecularLighting")) {
        both[0] = both[1] = 2; /* the normals' kernels */
    }
    for (int a = 0; a < 4; a++) {
        r[a] += both[a % 2];
    }
    if (is(n, "feTile") || (wrap && !is(n, "feMorphology"))) {
        r[0] = r[1] = r[2] = r[3] = INFINITY; /* anything in the region can come in */
    }
}

/* Primitive i's input k (a merge's nodes after `in` and `in2`) into
 * reach[i] when it holds the source: the farthest reach on each side. */
static void take_reach(double (*reach)[4], bool *from_source, int i, int in)
{
    bool source = in == IN_SOURCE || in == IN_SOURCE_ALPHA;
    if (in >= 0 && from_source[in]) {
        for (int a = 0; a < 4; a++) {
            reach[i][a] = fmax(reach[i][a], reach[in][a]);
        }
        source = true;
    }
    from_source[i] = from_source[i] || source;
}

bool svg_filter_extent(const svg_filter_job *job, int out[4], double *passes)
{
    fctx fc = { .job = job };
    double px[4];
    graph g;
    int count = count_primitives(job);
    if (count == 0 || count > MAX_PRIMITIVES || !region_px(&fc, px) ||
        !make_graph(&fc, count, &g)) {
        return false;
    }
    /* how far each result reads the source, and whether it reads it at
     * all: a flood, noise or picture brings in nothing from beyond */
    double(*reach)[4] = calloc((size_t)count, sizeof *reach);
    bool *from_source = calloc((size_t)count, sizeof *from_source);
    if (!reach || !from_source) {
        free(reach);
        free(from_source);
        free_graph(&g);
        return false;
    }
    *passes = 0;
    for (int i = 0; i < count; i++) {
        const prim *p = &g.p[i];
        *passes += prim_work(&fc, p->node, prim_reads(p));
        for (int k = 0; k < 2; k++) {
            if (p->in[k] != -4 && (k == 1 || reads_in(p->node))) {
                take_reach(reach, from_source, i, p->in[k]);
            }
        }
        for (const svg_node *m = p->node->first; m && is(p->node, "feMerge"); m = m->next) {
            if (is(m, "feMergeNode")) {
                take_reach(reach, from_source, i, resolve(&fc, g.p, i, m, fattr(m, "in")));
            }
        }
        double own[4];
        own_reach(&fc, p->node, own);
        for (int a = 0; a < 4; a++) {
            reach[i][a] += own[a];
        }
    }
    /* NaN and infinity alike: at most the layer's size */
    double r[4] = { 0, 0, 0, 0 };
    for (int a = 0; a < 4 && from_source[count - 1]; a++) {
        r[a] = fmin(reach[count - 1][a], a % 2 ? job->height : job->width);
    }
    free(reach);
    free(from_source);
    free_graph(&g);
    px[0] = fmax(px[0], -r[0]);
    px[1] = fmax(px[1], -r[1]);
    px[2] = fmin(px[2], job->width + r[2]);
    px[3] = fmin(px[3], job->height + r[3]);
    if (!(px[2] > px[0] && px[3] > px[1])) {
        return false;
    }
    for (int k = 0; k < 4; k++) {
        out[k] = (int)px[k];
    }
    return true;
}

void svg_apply_filter(const svg_filter_job *job)
{
    fctx fc = { .job = job };
    size_t all = (size_t)job->width * (size_t)job->height * 4;
    int count = count_primitives(job);
    if (count > MAX_PRIMITIVES) {
        char msg[96];
        snprintf(msg, sizeof msg, "filter: %d primitives, more than %d", count, MAX_PRIMITIVES);
        job->fail(job->host, job->filter, SR_TOO_LARGE, msg);
        return;
    }
    /* No primitive, or an empty region: the element is not drawn. */
    if (count == 0 || !filter_region(&fc)) {
        memset(job->pixels, 0, all);
        return;
    }
    graph g;
    fimg *res = calloc((size_t)count, sizeof *res);
    if (!res) {
        fail(&fc, job->filter, SR_OUT_OF_MEMORY, "out of memory");
        return;
    }
    if (!make_graph(&fc, count, &g)) {
        free(res);
        return;
    }
    /* The whole chain's work is counted before any of it runs: a chain
     * past the budget is refused at the primitive that passes it, without
     * first doing the work of all those before it. */
    for (int i = 0; i < count && !fc.failed; i++) {
        double work = (double)fc.n * prim_work(&fc, g.p[i].node, prim_reads(&g.p[i]));
        fc.failed = !job->budget(job->host, g.p[i].node, work);
    }
    for (int i = 0; i < count && !fc.failed; i++) {
        run(&fc, g.p, res, i);
        for (int j = 0; j <= i; j++) {
            if (res[j].p && !held(&g, j, i + 1)) {
                release(&fc, res[j].p);
                res[j].p = NULL;
            }
        }
    }
    if (!fc.failed) {
        write_back(&fc, &res[count - 1]);
    } else {
        memset(job->pixels, 0, all); /* reported: not used */
    }
    for (int i = 0; i < count; i++) {
        free(res[i].p);
    }
    free(fc.source.p);
    free(fc.source_alpha.p);
    free(fc.empty.p);
    free(fc.fill.p);
    free(fc.stroke.p);
    for (int k = 0; k < fc.n_spare; k++) {
        free(fc.spare[k]);
    }
    free(res);
    free_graph(&g);
}
