/* fuzz_draw.c - libFuzzer target for sr_draw: the input bytes are decoded
 * into a framebuffer, a pipeline state (viewport, depth range and function,
 * cull, polygon modes, offset, line width, point size, rasterizer, shading,
 * lights) and one draw (primitive, indices, positions with w) whose
 * coordinates come from a table of hostile floats (+-FLT_MAX, +-Inf, NaN,
 * denormals, -0, w = 0, w < 0, guard-band and near-plane crossings) or
 * straight from the bytes.  Then (bytes appended later, so older corpus
 * inputs keep their meaning): multisampling, a stencil buffer and stencil
 * state (invalid values included), alpha to coverage, and a program whose
 * fragment shader discards by a pattern and writes hostile depths.
 * Missing bytes read as zero.
 *
 * Checked on every input:
 *   - the result is SR_OK or an error with a message, and a failed call
 *     changed nothing;
 *   - no pixel (color, depth or stencil) outside viewport ∩ framebuffer
 *     changed;
 *   - 1 and 2 threads give the same result, color bytes and depth values;
 *   - ASan/UBSan: no out-of-bounds access or undefined behaviour;
 *   - libFuzzer's -timeout: the work per input stays bounded.
 * scripts/fuzz.sh fuzz_draw SECONDS. */
#include "softrast.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define FUZZ_CHECK(cond)                                                     \
    do {                                                                     \
        if (!(cond)) {                                                       \
            fprintf(stderr, "%s:%d: fuzz invariant failed: %s\n", __FILE__, \
                    __LINE__, #cond);                                        \
            abort();                                                         \
        }                                                                    \
    } while (0)

enum { MAX_FB = 80, MAX_VERTS = 48, MAX_INDICES = 64 };

typedef struct reader {
    const uint8_t *p;
    size_t n, at;
} reader;

static uint8_t u8(reader *r) { return r->at < r->n ? r->p[r->at++] : 0; }
static uint16_t u16(reader *r) { uint16_t a = u8(r); return (uint16_t)(a | (u8(r) << 8)); }
static uint32_t u32(reader *r) { uint32_t a = u16(r); return a | ((uint32_t)u16(r) << 16); }

static float raw_float(reader *r)
{
    uint32_t b = u32(r);
    float f;
    memcpy(&f, &b, sizeof f);
    return f;
}

/* One byte picks the kind of value: hostile constants, small exact values
 * on the 1/256 grid, values near the guard band, or a raw float. */
static float hostile_float(reader *r)
{
    static const float table[] = {
        0.0f, -0.0f, 1.0f, -1.0f, 0.5f, -0.5f, 2.0f, -2.0f,
        FLT_MAX, -FLT_MAX, INFINITY, -INFINITY, NAN, FLT_MIN, -FLT_MIN, 1e-45f,
        -1e-45f, FLT_EPSILON, 1e-30f, 1e30f, -1e30f, 16777216.0f, 1e6f, -1e6f,
        1000.0f, -1000.0f, 3.0f, -3.0f, 0.999999f, 1.000001f, 1e-7f, -1e-7f,
    };
    uint8_t k = u8(r);
    if (k < 64) {
        return table[k % (sizeof table / sizeof table[0])];
    }
    if (k < 160) { /* small exact values in [-4, 4) */
        return (float)((int16_t)u16(r)) / 8192.0f;
    }
    if (k < 192) { /* around the guard band (+-16384 px for an 8..80 px viewport) */
        return (float)((int16_t)u16(r)) * 0.25f;
    }
    return raw_float(r);
}

static const sr_depth_format depth_formats[] = {
    SR_DEPTH_NONE, SR_DEPTH_D16, SR_DEPTH_D24, SR_DEPTH_D32, SR_DEPTH_D32F,
};

/* The program's uniforms: which quad lanes to discard, and a depth to
 * write (any float, NaN and infinities included). */
typedef struct fuzz_uniforms {
    unsigned discard;
    float z;
    bool write_z;
} fuzz_uniforms;

static void fuzz_vs(const void *u, const sr_vertex_input *in, float clip[4], float *vary)
{
    (void)u;
    memcpy(clip, in->position, 4 * sizeof(float));
    memcpy(vary, in->color, 4 * sizeof(float));
    vary[4] = (float)in->index;
}

static void fuzz_fs(const void *uniforms, sr_fragment_quad *q)
{
    const fuzz_uniforms *u = uniforms;
    for (int i = 0; i < 4; i++) {
        for (int c = 0; c < 4; c++) {
            q->color[c][i] = q->varyings[c][i];
        }
        if (u->write_z) {
            q->z[i] = u->z;
        }
    }
    q->discard = u->discard & 15u;
}

typedef struct decoded {
    int fb_w, fb_h;
    sr_depth_format depth_format;
    int samples;
    bool stencil;
    sr_program prog;
    fuzz_uniforms uniforms;
    sr_state st;
    sr_draw_desc d;
    sr_mat4 proj, view;
    float pos[MAX_VERTS * 4];
    float nrm[MAX_VERTS * 3];
    float col[MAX_VERTS * 4];
    uint32_t idx32[MAX_INDICES];
    uint16_t idx16[MAX_INDICES];
    uint8_t idx8[MAX_INDICES];
} decoded;

static void decode(reader *r, decoded *o)
{
    memset(o, 0, sizeof *o);
    o->fb_w = 1 + u8(r) % MAX_FB;
    o->fb_h = 1 + u8(r) % MAX_FB;
    o->depth_format = depth_formats[u8(r) % 5];

    sr_state *st = &o->st;
    uint8_t vpk = u8(r);
    if (vpk & 1) {
        st->viewport.x = (int8_t)u8(r) * 2;
        st->viewport.y = (int8_t)u8(r) * 2;
        st->viewport.width = 1 + u8(r) % 200;
        st->viewport.height = 1 + u8(r) % 200;
        if (vpk & 2) { /* a viewport reaching the guard band */
            st->viewport.x = SR_MAX_FRAMEBUFFER_SIZE * 2 - st->viewport.width - (vpk >> 3);
            st->viewport.y = -16384 + (vpk >> 3);
        }
        if (vpk & 4) { /* anything at all (INT_MAX, INT_MIN, negative sizes) */
            st->viewport.x = (int)u32(r);
            st->viewport.y = (int)u32(r);
            st->viewport.width = (int)u32(r);
            st->viewport.height = (int)u32(r);
        }
    }
    static const float depths[] = { 0.0f, 1.0f, 0.5f, 0.25f, 0.75f, 1e-7f, 0.999999f, 2.0f };
    st->depth_range = SR_DEPTH_RANGE_SET;
    st->depth_near = depths[u8(r) % 8];
    st->depth_far = depths[u8(r) % 8];
    uint8_t f = u8(r);
    st->depth_zero_to_one = f & 1;
    st->depth_test = (f >> 1) & 1 ? SR_OFF : SR_SWITCH_DEFAULT;
    st->depth_write = (f >> 2) & 1 ? SR_OFF : SR_ON;
    st->two_sided = (f >> 3) & 1;
    st->offset.fill = (f >> 4) & 1;
    st->offset.line = (f >> 5) & 1;
    st->offset.point = (f >> 6) & 1;
    st->material.vertex_color = (f >> 7) & 1 ? SR_OFF : SR_SWITCH_DEFAULT;
    st->cull = (sr_cull_mode)(u8(r) % 5);
    st->front_face = (sr_front_face)(u8(r) % 3);
    st->rasterizer = (sr_rasterizer)(u8(r) % 4);
    st->polygon_mode_front = (sr_polygon_mode)(u8(r) % 4);
    st->polygon_mode_back = (sr_polygon_mode)(u8(r) % 4);
    st->line_width = (float)(u8(r) % 66);        /* 65 is invalid */
    uint8_t ps = u8(r);
    st->point_size = ps < 200 ? ps * 0.25f : (ps < 250 ? 1024.0f : 1025.0f);
    st->depth_func = (sr_depth_func)(u8(r) % 9);
    uint8_t ok = u8(r);
    st->offset.factor = ok & 1 ? hostile_float(r) : (float)((int8_t)u8(r));
    st->offset.units = ok & 2 ? hostile_float(r) : (float)((int8_t)u8(r));
    st->offset.clamp = ok & 4 ? hostile_float(r) : 0.0f;
    st->shading = (sr_shading)(u8(r) % 7);
    st->interpolation = (sr_interpolation)(u8(r) % 3);
    st->provoking = (sr_provoking_vertex)(u8(r) % 3);
    st->ambient = (sr_vec3){ 0.2f, 0.2f, 0.2f };
    st->material.specular = (sr_vec3){ 0.5f, 0.5f, 0.5f };
    st->material.shininess = (float)(u8(r) % 40);
    uint8_t lk = u8(r);
    if (lk & 1) {
        st->lights[0] = (sr_light){ .type = SR_LIGHT_DIRECTIONAL, .vector = { 0.3f, -1, -0.5f } };
    }
    if (lk & 2) {
        st->lights[1] = (sr_light){ .type = SR_LIGHT_POINT,
                                    .vector = { hostile_float(r), 1, 2 } };
    }

    sr_draw_desc *d = &o->d;
    d->primitive = (sr_primitive)(u8(r) % 8);
    uint8_t pk = u8(r);
    int proj = pk % 4;
    if (proj == 1) {
        o->proj = sr_perspective(1.0f, 1.0f, 0.1f + (pk >> 2) * 0.05f, 10.0f, st->depth_zero_to_one);
        o->view = sr_mat4_translate(0, 0, -2);
        d->projection = &o->proj;
        d->view = &o->view;
    } else if (proj == 2) {
        o->proj = sr_ortho(-2, 2, -2, 2, -2, 2, st->depth_zero_to_one);
        d->projection = &o->proj;
    } else if (proj == 3) { /* a matrix straight from the input */
        for (int i = 0; i < 16; i++) {
            o->proj.m[i] = hostile_float(r);
        }
        d->projection = &o->proj;
    }
    int psize = (pk >> 2) & 1 ? 4 : 3;
    d->position_size = psize;
    int nv = u8(r) % (MAX_VERTS + 1);
    for (int i = 0; i < nv; i++) {
        for (int c = 0; c < psize; c++) {
            o->pos[i * psize + c] = hostile_float(r);
        }
        float nx = (float)((int8_t)u8(r)), ny = (float)((int8_t)u8(r));
        o->nrm[i * 3 + 0] = nx;
        o->nrm[i * 3 + 1] = ny;
        o->nrm[i * 3 + 2] = 1.0f;
        uint8_t c = u8(r);
        o->col[i * 4 + 0] = (c & 3) / 3.0f;
        o->col[i * 4 + 1] = ((c >> 2) & 3) / 3.0f;
        o->col[i * 4 + 2] = ((c >> 4) & 3) / 3.0f;
        o->col[i * 4 + 3] = 1.0f;
    }
    d->vertex_count = (size_t)nv;
    d->positions = o->pos;
    d->normals = o->nrm;
    d->colors = (pk >> 3) & 1 ? o->col : NULL;
    uint8_t ik = u8(r);
    d->index_type = (sr_index_type)(ik % 4);
    if (d->index_type != SR_INDEX_NONE) {
        int ni = u8(r) % (MAX_INDICES + 1);
        for (int i = 0; i < ni; i++) {
            /* Mostly in range; a few out of range or huge. */
            uint8_t b = u8(r);
            uint32_t v = b < 240 || nv == 0 ? (uint32_t)(b % (nv ? nv : 1)) : u32(r);
            o->idx32[i] = v;
        }
        /* The narrow copies over the whole arrays (zero past ni): a loop of
         * ni iterations storing bytes vectorizes with an epilogue that
         * GCC's s390x cross compiler takes for a write past idx8's end. */
        for (int i = 0; i < MAX_INDICES; i++) {
            o->idx16[i] = (uint16_t)o->idx32[i];
            o->idx8[i] = (uint8_t)o->idx32[i];
        }
        d->index_count = (size_t)ni;
        d->indices = d->index_type == SR_INDEX_U8 ? (const void *)o->idx8
                     : d->index_type == SR_INDEX_U16 ? (const void *)o->idx16
                                                     : (const void *)o->idx32;
    }

    /* Multisampling, stencil, alpha to coverage, a program. */
    static const int sample_counts[] = { 0, 2, 4, 8, 16 };
    uint8_t mk = u8(r);
    o->samples = sample_counts[(mk & 7) % 5];   /* bits 0-2; the flags above */
    o->stencil = (mk >> 3) & 1;
    st->alpha_to_coverage = (mk >> 4) & 1;
    st->material.opacity = (mk >> 5) & 1 ? (u8(r) % 101) / 100.0f : 0.0f;
    if ((mk >> 6) & 1) {
        st->stencil.enabled = true;
        st->stencil.separate = (mk >> 7) & 1;
        sr_stencil_face *faces[2] = { &st->stencil.front, &st->stencil.back };
        for (int i = 0; i < 2; i++) {
            sr_stencil_face *sf = faces[i];
            sf->func = (sr_depth_func)(u8(r) % 10);       /* 9 is invalid */
            sf->ref = u8(r);
            sf->masked = u8(r) & 1;
            sf->read_mask = u8(r);
            sf->write_mask = u8(r);
            sf->fail = (sr_stencil_op)(u8(r) % 9);         /* 8 is invalid */
            sf->depth_fail = (sr_stencil_op)(u8(r) % 9);
            sf->pass = (sr_stencil_op)(u8(r) % 9);
        }
    }
    uint8_t gk = u8(r);
    if (gk & 1) {
        o->prog = (sr_program){ .vertex = fuzz_vs, .fragment = fuzz_fs, .uniforms = &o->uniforms,
                                .varying_count = (gk >> 1) & 1 ? 5 : 17,  /* 17 is invalid */
                                .may_discard = (gk >> 2) & 1, .writes_depth = (gk >> 3) & 1,
                                .independent_lanes = (gk >> 6) & 1 };
        o->prog.modes[4] = (sr_varying_mode)((gk >> 4) % 4);           /* 3 is invalid */
        o->uniforms.discard = o->prog.may_discard ? u8(r) : 0;
        o->uniforms.write_z = o->prog.writes_depth;
        o->uniforms.z = hostile_float(r);
        st->program = &o->prog;
        /* The vertex shader reads four position floats. */
        d->position_size = 4;
    }
}

typedef struct run {
    sr_result r;
    uint8_t color[MAX_FB * MAX_FB * 4];
    float depth[MAX_FB * MAX_FB];
    uint8_t stencil[MAX_FB * MAX_FB];
    sr_draw_info info;
} run;

static sr_context *contexts[2];

static void run_once(int which, const decoded *o, run *out, run *before)
{
    sr_context *ctx = contexts[which];
    sr_framebuffer *fb = NULL;
    sr_result r = sr_make_framebuffer(ctx, &(sr_framebuffer_desc){
        .width = o->fb_w, .height = o->fb_h, .depth_format = o->depth_format,
        .samples = o->samples, .stencil = o->stencil }, &fb);
    FUZZ_CHECK(r == SR_OK);
    /* A recognisable background that no draw produces by accident. */
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0.2f, 0.4f, 0.6f, 0.8f }, .depth_action = SR_ACTION_CLEAR,
                                        .depth = 0.625f, .stencil_action = SR_ACTION_CLEAR,
                                        .stencil = 0x5a });
    size_t npx = (size_t)o->fb_w * o->fb_h;
    bool has_depth = o->depth_format != SR_DEPTH_NONE;
    if (before) {
        memcpy(before->color, sr_framebuffer_pixels(fb), npx * 4);
        memset(before->depth, 0, sizeof before->depth);
        if (has_depth) {
            sr_read_depth(ctx, fb, 0, 0, o->fb_w, o->fb_h, before->depth, (size_t)o->fb_w);
        }
        memset(before->stencil, 0, sizeof before->stencil);
        if (o->stencil) {
            sr_read_stencil(ctx, fb, 0, 0, o->fb_w, o->fb_h, before->stencil, (size_t)o->fb_w);
        }
    }
    out->r = sr_draw(ctx, fb, &o->st, &o->d);
    out->info = sr_last_draw_info(ctx);
    if (out->r != SR_OK) {
        FUZZ_CHECK(out->r > SR_OK && out->r < SR_RESULT_COUNT);
        FUZZ_CHECK(sr_context_error(ctx)[0] != '\0');
    }
    memcpy(out->color, sr_framebuffer_pixels(fb), npx * 4);
    memset(out->depth, 0, sizeof out->depth);
    if (has_depth) {
        FUZZ_CHECK(sr_read_depth(ctx, fb, 0, 0, o->fb_w, o->fb_h, out->depth,
                                 (size_t)o->fb_w) == SR_OK);
    }
    memset(out->stencil, 0, sizeof out->stencil);
    if (o->stencil) {
        FUZZ_CHECK(sr_read_stencil(ctx, fb, 0, 0, o->fb_w, o->fb_h, out->stencil,
                                   (size_t)o->fb_w) == SR_OK);
    }
    sr_destroy_framebuffer(ctx, fb);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (!contexts[0]) {
        FUZZ_CHECK(sr_make_context(&(sr_context_desc){ .threads = 1 }, &contexts[0]) == SR_OK);
        FUZZ_CHECK(sr_make_context(&(sr_context_desc){ .threads = 2 }, &contexts[1]) == SR_OK);
    }
    static decoded o;
    static run before, a, b;
    reader rd = { data, size, 0 };
    decode(&rd, &o);

    run_once(0, &o, &a, &before);
    run_once(1, &o, &b, NULL);
    size_t npx = (size_t)o.fb_w * o.fb_h;

    /* Same result and same bytes for 1 and 2 threads. */
    FUZZ_CHECK(a.r == b.r);
    FUZZ_CHECK(memcmp(a.color, b.color, npx * 4) == 0);
    FUZZ_CHECK(memcmp(a.depth, b.depth, npx * sizeof(float)) == 0);
    FUZZ_CHECK(memcmp(a.stencil, b.stencil, npx) == 0);
    FUZZ_CHECK(a.info.fragments == b.info.fragments);
    FUZZ_CHECK(a.info.triangles_in == b.info.triangles_in);

    /* Nothing outside viewport ∩ framebuffer changes; nothing at all when
     * the call failed. */
    sr_viewport vp = o.st.viewport;
    if (vp.width == 0) {
        vp = (sr_viewport){ 0, 0, o.fb_w, o.fb_h };
    }
    for (int y = 0; y < o.fb_h; y++) {
        for (int x = 0; x < o.fb_w; x++) {
            bool inside = a.r == SR_OK && x >= vp.x && x < vp.x + vp.width && y >= vp.y &&
                          y < vp.y + vp.height;
            if (inside) {
                continue;
            }
            size_t i = (size_t)y * o.fb_w + x;
            FUZZ_CHECK(memcmp(a.color + i * 4, before.color + i * 4, 4) == 0);
            FUZZ_CHECK(memcmp(&a.depth[i], &before.depth[i], sizeof(float)) == 0);
            FUZZ_CHECK(a.stencil[i] == before.stencil[i]);
        }
    }
    /* Written depth stays inside the depth range (quantized). */
    if (a.r == SR_OK && o.depth_format != SR_DEPTH_NONE) {
        for (size_t i = 0; i < npx; i++) {
            FUZZ_CHECK(a.depth[i] >= 0.0f && a.depth[i] <= 1.0f);
        }
    }
    return 0;
}
