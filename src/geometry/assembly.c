/* assembly.c - primitive assembly (geometry stage): the vertices of each
 * triangle, strip, fan, line, loop or point of a draw gathered from the
 * post-transform vertices, with the provoking vertex of docs/raster-rules.md §5.4;
 * trivial reject and homogeneous clipping (clip.c) of what crosses a clip
 * plane; culling by the snapped area; polygon modes; and the hand-off to
 * setup (raster/setup_tri.h), whose records each chunk bins by tile.  Runs
 * on the pool, one job per chunk of a batch (sr__run_front_end). */
#include "geometry/assembly.h"
#include "parallel/bin.h"
#include "scratch.h"
#include "raster/setup_tri.h"

#include <assert.h>
#include <math.h>
#include <string.h>

static bool is_culled(const sr_draw_state *ds, bool front)
{
    switch (ds->cull) {
    case SR_CULL_BACK:           return !front;
    case SR_CULL_FRONT:          return front;
    case SR_CULL_FRONT_AND_BACK: return true;
    default:                     return false;
    }
}

/* On the y-down framebuffer, a triangle that is counter-clockwise on
 * screen has a negative snapped area2 (docs/raster-rules.md §3.3). */
static bool facing_front(const sr_draw_state *ds, int64_t area2)
{
    return ds->front_ccw ? area2 < 0 : area2 > 0;
}

/* The next free record of chunk c, or NULL when out of memory.  The store
 * was sized for the chunk up front, so it nearly always has room. */
static inline void *next_record(const sr_front_end *fe, sr_chunk *c)
{
    size_t at = (size_t)c->tri_count * fe->tri_size;
    if (at + fe->tri_size > c->tri_bytes &&
        !sr__chunk_reserve_tris(&fe->ctx->allocator, c, (size_t)c->tri_count + 1, fe->tri_size)) {
        c->out_of_memory = true;
        return NULL;
    }
    return c->tris + at;
}

/* Record number tri_count of chunk c is complete: note its tiles. */
static inline void keep_record(sr_chunk *c, const sr_prim_head *h)
{
    c->tile_box[c->tri_count++] = sr__tile_box(h);
}

/* Room for any kind of record set up off to the side (sr__record_size). */
typedef union record_buf {
    sr_tri tri;
    sr_line line;
    sr_point point;
} record_buf;

/* A filled triangle; area2 = sr__area2(w0, w1, w2). */
static inline __attribute__((always_inline)) void
emit(const sr_front_end *fe, sr_chunk *c, const sr_window_vertex *w0, const sr_window_vertex *w1,
     const sr_window_vertex *w2, int64_t area2, bool front, const float flat[4])
{
    if (area2 == 0) {
        return; /* setup would find nothing to draw */
    }
    sr_tri *rec = next_record(fe, c);
    if (!rec) {
        return;
    }
    /* Set up in place, or on the stack and then streamed to its place;
     * four varyings (unlit, Gouraud, attribute) is the common case,
     * unrolled. */
    record_buf buf;
    sr_tri *t = c->stream ? &buf.tri : rec;
    const sr_draw_state *ds = fe->ds;
    bool drawn = ds->ninterp == 4
                     ? sr__setup_tri(ds, w0, w1, w2, area2, NAN, front, 4, flat, t)
                     : sr__setup_tri(ds, w0, w1, w2, area2, NAN, front, ds->ninterp, flat, t);
    if (drawn) {
        if (c->stream) {
            sr__stream_record(rec, t, fe->tri_size);
        }
        keep_record(c, &t->h);
        c->info.triangles_drawn++;
    }
}

/* A multisampled line is the rectangle of its width centred on the
 * segment (Vulkan's strict lines, Direct3D's MSAA lines), drawn as two
 * triangles sampled like any other: each corner carries its end's depth,
 * 1/w and varyings. */
static void emit_line_quad(const sr_front_end *fe, sr_chunk *c, const sr_window_vertex *a,
                           const sr_window_vertex *b, double offset, bool front,
                           const float flat[4])
{
    const sr_draw_state *ds = fe->ds;
    double dx = (double)b->x_q8 - a->x_q8, dy = (double)b->y_q8 - a->y_q8;
    double len = sqrt(dx * dx + dy * dy);
    if (len == 0.0) {
        return;
    }
    double half = (ds->smooth_lines ? ds->smooth_width : ds->line_width) * 0.5;
    double nx = -dy / len * half * SR_SUBPIXEL_ONE, ny = dx / len * half * SR_SUBPIXEL_ONE;
    int32_t ox = (int32_t)nearbyint(nx), oy = (int32_t)nearbyint(ny);
    sr_window_vertex q[4] = { *a, *a, *b, *b };
    q[0].x_q8 += ox, q[0].y_q8 += oy;
    q[1].x_q8 -= ox, q[1].y_q8 -= oy;
    q[2].x_q8 -= ox, q[2].y_q8 -= oy;
    q[3].x_q8 += ox, q[3].y_q8 += oy;
    for (int i = 0; i < 2; i++) {
        sr_tri *t = next_record(fe, c);
        if (t && sr__setup_triangle_offset(ds, &q[0], &q[1 + i], &q[2 + i], offset, front,
                                           ds->ninterp, flat, t)) {
            keep_record(c, &t->h);
        }
    }
}

static void emit_line(const sr_front_end *fe, sr_chunk *c, const sr_window_vertex *a,
                      const sr_window_vertex *b, double offset, bool front, const float flat[4])
{
    if (fe->ds->samples > 1) {
        emit_line_quad(fe, c, a, b, offset, front, flat);
        return;
    }
    sr_line *l = next_record(fe, c);
    if (l && sr__setup_line(fe->ds, a, b, offset, front, fe->ds->ninterp, flat, l)) {
        keep_record(c, &l->h);
    }
}

static void emit_point(const sr_front_end *fe, sr_chunk *c, const sr_window_vertex *v,
                       double offset, bool front, const float flat[4])
{
    sr_point *p = next_record(fe, c);
    if (p && sr__setup_point(fe->ds, v, offset, front, fe->ds->ninterp, flat, p)) {
        keep_record(c, &p->h);
    }
}

/* glPolygonMode: a clipped, culled polygon w[0..n-1] drawn as its outline
 * (each edge half-open, so every corner is drawn once) or its corners,
 * with the polygon offset of its plane when enabled for that mode. */
static void polygon_outline(const sr_front_end *fe, sr_chunk *c, const sr_window_vertex *w, int n,
                            sr_polygon_mode mode, bool front, const float flat[4])
{
    double offset = sr__polygon_offset(fe->ds, &w[0], &w[1], &w[2], mode);
    for (int i = 0; i < n; i++) {
        if (mode == SR_POLYGON_LINE) {
            emit_line(fe, c, &w[i], &w[(i + 1) % n], offset, front, flat);
        } else {
            emit_point(fe, c, &w[i], offset, front, flat);
        }
    }
}

static void clip_vertex(const sr_draw_state *ds, const sr_vertex_post *p, const float *vary,
                        sr_clip_vertex *out)
{
    memcpy(out->pos, p->pos, sizeof out->pos);
    memcpy(out->vary, vary, (size_t)ds->nvary * sizeof(float));
}

/* A program's flat varyings take the provoking vertex's values: give each
 * vertex a copy with them in place (clipping then interpolates between
 * equal values, which leaves them exact), or the vertex's own varyings
 * when there are none. */
static const float *flat_varyings(const sr_draw_state *ds, const float *a, const float *pv,
                                  float *buf)
{
    if (!ds->flat_mask || a == pv) {
        return a;
    }
    memcpy(buf, a, (size_t)ds->nvary * sizeof(float));
    for (unsigned m = ds->flat_mask; m; m &= m - 1) {
        int k = __builtin_ctz(m);
        buf[k] = pv[k];
    }
    return buf;
}

/* A triangle with a vertex outside some clip plane (but not all three
 * outside one): clip, then fan the polygon back into triangles.  Facing
 * comes from the whole polygon's snapped area so the fan is culled as
 * one.  Out of line, so the common case above keeps a small frame. */
static __attribute__((noinline)) void clipped_triangle(const sr_front_end *fe, sr_chunk *c,
                                                       const sr_vertex_post *p0,
                                                       const sr_vertex_post *p1,
                                                       const sr_vertex_post *p2, const float *a0,
                                                       const float *a1, const float *a2,
                                                       const float *pva)
{
    const sr_draw_state *ds = fe->ds;
    unsigned c0 = p0->outcode, c1 = p1->outcode, c2 = p2->outcode;
    float flat[4] = { 0, 0, 0, 1 };
    bool need_flat = ds->shading == SR_SHADING_FLAT;
    c->info.triangles_clipped++;
    if (need_flat) {
        sr__flat_color(ds, a0, a1, a2, pva, flat);
    }
    sr_clip_vertex v[3];
    clip_vertex(ds, p0, a0, &v[0]);
    clip_vertex(ds, p1, a1, &v[1]);
    clip_vertex(ds, p2, a2, &v[2]);
    const sr_clip_vertex *in[3] = { &v[0], &v[1], &v[2] };
    sr_clip_vertex poly[SR_CLIP_MAX_VERTS];
    int n = ds->view_volume ? sr__clip_polygon_view(ds, in, poly)
                            : sr__clip_polygon(ds, in, (c0 | c1 | c2), poly);
    if (n < 3) {
        c->info.triangles_culled++;
        return;
    }
    sr_window_vertex w[SR_CLIP_MAX_VERTS];
    for (int i = 0; i < n; i++) {
        /* The one point with w = 0 that passes every plane is the clip-space
         * origin (the band planes force x = y = 0, near/far z = 0), e.g. the
         * midpoint of an edge from v to -v.  A polygon through it has
         * linearly dependent vertices, so no area; the divide would give
         * 0/0 = NaN.  Discard (docs/raster-rules.md §4.3). */
        if (!(poly[i].pos[3] > 0.0f)) {
            c->info.triangles_culled++;
            return;
        }
        sr__window_vertex(ds, &poly[i], &w[i]);
    }
    int64_t area2 = 0;
    for (int i = 1; i + 1 < n; i++) {
        area2 += sr__area2(&w[0], &w[i], &w[i + 1]);
    }
    bool front = facing_front(ds, area2);
    if (area2 == 0 || is_culled(ds, front)) {
        c->info.triangles_culled++;
        return;
    }
    sr_polygon_mode mode = front ? ds->mode_front : ds->mode_back;
    if (mode != SR_POLYGON_FILL) {
        polygon_outline(fe, c, w, n, mode, front, flat);
        return;
    }
    for (int i = 1; i + 1 < n; i++) {
        emit(fe, c, &w[0], &w[i], &w[i + 1], sr__area2(&w[0], &w[i], &w[i + 1]), front, flat);
    }
}

static void triangle(const sr_front_end *fe, sr_chunk *c, const sr_vertex_src *vs, uint32_t i0,
                     uint32_t i1, uint32_t i2, uint32_t pv)
{
    const sr_draw_state *ds = fe->ds;
    size_t b = vs->base;
    const sr_vertex_post *p0 = &vs->post[i0 - b], *p1 = &vs->post[i1 - b], *p2 = &vs->post[i2 - b];
    size_t nv = (size_t)ds->nvary;
    const float *a0 = vs->vary + (i0 - b) * nv, *a1 = vs->vary + (i1 - b) * nv;
    const float *a2 = vs->vary + (i2 - b) * nv;
    float fb0[SR_MAX_VARYINGS], fb1[SR_MAX_VARYINGS], fb2[SR_MAX_VARYINGS];
    const float *pva = vs->vary + (pv - b) * nv;
    if (ds->flat_mask) {
        a0 = flat_varyings(ds, a0, pva, fb0);
        a1 = flat_varyings(ds, a1, pva, fb1);
        a2 = flat_varyings(ds, a2, pva, fb2);
    }
    c->info.triangles_in++;

    unsigned c0 = p0->outcode, c1 = p1->outcode, c2 = p2->outcode;
    if ((c0 | c1 | c2) & SR_OUTCODE_NONFINITE) {
        c->info.triangles_culled++;
        return; /* NaN or infinite positions discard the primitive */
    }
    if (c0 & c1 & c2) {
        c->info.triangles_culled++;
        return; /* all three outside one plane */
    }
    if ((c0 | c1 | c2) != 0) {
        clipped_triangle(fe, c, p0, p1, p2, a0, a1, a2, pva);
        return;
    }

    /* Inside every plane: the window positions are the vertex stage's. */
    sr_window_vertex w[3] = {
        { p0->x_q8, p0->y_q8, p0->z, p0->inv_w, a0 },
        { p1->x_q8, p1->y_q8, p1->z, p1->inv_w, a1 },
        { p2->x_q8, p2->y_q8, p2->z, p2->inv_w, a2 },
    };
    int64_t area2 = sr__area2(&w[0], &w[1], &w[2]);
    bool front = facing_front(ds, area2);
    if (area2 == 0 || is_culled(ds, front)) {
        c->info.triangles_culled++;
        return;
    }
    float flat[4] = { 0, 0, 0, 1 };
    if (ds->shading == SR_SHADING_FLAT) {
        sr__flat_color(ds, a0, a1, a2, pva, flat);
    }
    sr_polygon_mode mode = front ? ds->mode_front : ds->mode_back;
    if (mode == SR_POLYGON_FILL) {
        emit(fe, c, &w[0], &w[1], &w[2], area2, front, flat);
    } else {
        polygon_outline(fe, c, w, 3, mode, front, flat);
    }
}

/* A window vertex straight from the post-transform cache. */
static sr_window_vertex cached_window(const sr_vertex_post *p, const float *vary)
{
    return (sr_window_vertex){ p->x_q8, p->y_q8, p->z, p->inv_w, vary };
}

/* Flat shading of a line or point: the provoking vertex's own color. */
static const float *provoking_color(const sr_draw_state *ds, const float *pv)
{
    return ds->shading == SR_SHADING_FLAT ? &pv[SR_VARY_FLAT_COLOR] : NULL;
}

static void segment(const sr_front_end *fe, sr_chunk *c, const sr_vertex_src *vs, uint32_t i0,
                    uint32_t i1, uint32_t pv)
{
    const sr_draw_state *ds = fe->ds;
    size_t b = vs->base;
    const sr_vertex_post *p0 = &vs->post[i0 - b], *p1 = &vs->post[i1 - b];
    size_t nv = (size_t)ds->nvary;
    const float *a0 = vs->vary + (i0 - b) * nv, *a1 = vs->vary + (i1 - b) * nv;
    const float *pva = vs->vary + (pv - b) * nv;
    const float *flat = provoking_color(ds, pva);
    float fb0[SR_MAX_VARYINGS], fb1[SR_MAX_VARYINGS];
    a0 = flat_varyings(ds, a0, pva, fb0);
    a1 = flat_varyings(ds, a1, pva, fb1);
    unsigned c0 = p0->outcode, c1 = p1->outcode;
    if (((c0 | c1) & SR_OUTCODE_NONFINITE) || (c0 & c1)) {
        return;
    }
    if ((c0 | c1) == 0) {
        sr_window_vertex w0 = cached_window(p0, a0), w1 = cached_window(p1, a1);
        emit_line(fe, c, &w0, &w1, 0.0, true, flat);
        return;
    }
    sr_clip_vertex v0, v1, o0, o1;
    clip_vertex(ds, p0, a0, &v0);
    clip_vertex(ds, p1, a1, &v1);
    if (!sr__clip_segment(ds, &v0, &v1, c0 | c1, &o0, &o1)) {
        return;
    }
    /* As for polygons: an end that rounding left at w <= 0 (the clip-space
     * origin, or t rounded to the outside end) cannot be divided. */
    if (!(o0.pos[3] > 0.0f) || !(o1.pos[3] > 0.0f)) {
        return;
    }
    sr_window_vertex w0, w1;
    sr__window_vertex(ds, &o0, &w0);
    sr__window_vertex(ds, &o1, &w1);
    emit_line(fe, c, &w0, &w1, 0.0, true, flat);
}

/* A point is drawn when its vertex is inside every plane (docs/raster-rules.md §4.4). */
static void point(const sr_front_end *fe, sr_chunk *c, const sr_vertex_src *vs, uint32_t i)
{
    const sr_draw_state *ds = fe->ds;
    const sr_vertex_post *p = &vs->post[i - vs->base];
    if (p->outcode != 0) {
        return;
    }
    const float *a = vs->vary + (i - vs->base) * (size_t)ds->nvary;
    sr_window_vertex w = cached_window(p, a);
    emit_point(fe, c, &w, 0.0, true, provoking_color(ds, a));
}

/* The vertices of primitive p of the draw in the order assembly takes
 * them (a strip's odd triangles swap their first two, to keep winding)
 * and its provoking vertex (docs/raster-rules.md §5.4): 3 of them for a
 * triangle, 2 for a segment, 1 for a point. */
static inline __attribute__((always_inline)) int
prim_vertices(const sr_draw_desc *d, bool last, size_t p, uint32_t v[3], uint32_t *pv)
{
    switch (d->primitive) {
    case SR_PRIM_TRIANGLE_STRIP: {
        uint32_t a = sr__index_at(d, p), b = sr__index_at(d, p + 1), e = sr__index_at(d, p + 2);
        *pv = last ? e : a;
        v[0] = p & 1 ? b : a;
        v[1] = p & 1 ? a : b;
        v[2] = e;
        return 3;
    }
    case SR_PRIM_TRIANGLE_FAN:
        v[0] = sr__index_at(d, 0);
        v[1] = sr__index_at(d, p + 1);
        v[2] = sr__index_at(d, p + 2);
        *pv = last ? v[2] : v[1];
        return 3;
    case SR_PRIM_LINES:
        v[0] = sr__index_at(d, 2 * p);
        v[1] = sr__index_at(d, 2 * p + 1);
        *pv = last ? v[1] : v[0];
        return 2;
    case SR_PRIM_LINE_STRIP:
    case SR_PRIM_LINE_LOOP: {
        /* A loop's last segment closes back to the first vertex. */
        size_t n = d->index_type == SR_INDEX_NONE ? d->vertex_count : d->index_count;
        v[0] = sr__index_at(d, p);
        v[1] = sr__index_at(d, (p + 1) % n);
        *pv = last ? v[1] : v[0];
        return 2;
    }
    case SR_PRIM_POINTS:
        v[0] = *pv = sr__index_at(d, p);
        return 1;
    default:
        v[0] = sr__index_at(d, 3 * p);
        v[1] = sr__index_at(d, 3 * p + 1);
        v[2] = sr__index_at(d, 3 * p + 2);
        *pv = last ? v[2] : v[0];
        return 3;
    }
}

/* The primitive of n vertices v[] with provoking vertex pv, from vs. */
static inline void assemble(const sr_front_end *fe, sr_chunk *c, const sr_vertex_src *vs, int n,
                            const uint32_t v[3], uint32_t pv)
{
    if (n == 3) {
        triangle(fe, c, vs, v[0], v[1], v[2], pv);
    } else if (n == 2) {
        segment(fe, c, vs, v[0], v[1], pv);
    } else {
        point(fe, c, vs, v[0]);
    }
}

/* Primitive p of the draw. */
static void primitive(const sr_front_end *fe, sr_chunk *c, const sr_vertex_src *vs, size_t p)
{
    uint32_t v[3], pv;
    int n = prim_vertices(fe->d, fe->ds->provoking_last, p, v, &pv);
    assemble(fe, c, vs, n, v, pv);
}

/* The vertex stage for vertices [first, first + count) into the window's
 * slots from `slot` on. */
static void window_fill(const sr_front_end *fe, sr_scratch *s, size_t first, size_t count,
                        size_t slot)
{
    sr__vertex_stage(fe->ds, fe->d, fe->mvp, fe->mv, fe->nm, first, count, s->post + slot,
                     s->vary + slot * (size_t)fe->ds->nvary);
}

/* Move the vertex window (s->window_lo .. window_hi) to hold vertices
 * [lo, hi], hi - lo < fe->window: it starts at lo (ends at the last
 * vertex near the end), keeps what it held there and runs the vertex
 * stage for the rest, so that a mesh whose primitives use vertices near
 * their own place in the order transforms each about once. */
static void window_cover(const sr_front_end *fe, sr_chunk *c, sr_scratch *s, size_t lo,
                         size_t hi)
{
    size_t n = fe->window, count = fe->d->vertex_count, nv = (size_t)fe->ds->nvary;
    size_t wlo = count - lo < n ? count - n : lo, whi = wlo + n;
    assert(wlo <= lo && hi < whi);
    (void)hi;
    size_t keep_lo = s->window_lo > wlo ? s->window_lo : wlo;
    size_t keep_hi = s->window_hi < whi ? s->window_hi : whi;
    if (keep_lo < keep_hi) {
        memmove(s->post + (keep_lo - wlo), s->post + (keep_lo - s->window_lo),
                (keep_hi - keep_lo) * sizeof *s->post);
        memmove(s->vary + (keep_lo - wlo) * nv, s->vary + (keep_lo - s->window_lo) * nv,
                (keep_hi - keep_lo) * nv * sizeof *s->vary);
    } else {
        keep_lo = keep_hi = wlo;
    }
    window_fill(fe, s, wlo, keep_lo - wlo, 0);
    window_fill(fe, s, keep_hi, whi - keep_hi, keep_hi - wlo);
    c->info.vertices_shaded += (keep_lo - wlo) + (whi - keep_hi);
    s->window_lo = wlo;
    s->window_hi = whi;
}

/* A primitive whose vertices lie too far apart for the window: the
 * vertex stage for each of them alone. */
static void gathered_primitive(const sr_front_end *fe, sr_chunk *c, int n, const uint32_t v[3],
                               uint32_t pv)
{
    sr_vertex_post post[3];
    float vary[3 * SR_MAX_VARYINGS];
    size_t nv = (size_t)fe->ds->nvary;
    uint32_t slot[3] = { 0, 1, 2 }, pslot = 0;
    for (int k = n - 1; k >= 0; k--) {
        sr__vertex_stage(fe->ds, fe->d, fe->mvp, fe->mv, fe->nm, v[k], 1, &post[k],
                         vary + (size_t)k * nv);
        pslot = v[k] == pv ? slot[k] : pslot;
    }
    c->info.vertices_shaded += (uint64_t)n;
    sr_vertex_src vs = { post, vary, 0 };
    assemble(fe, c, &vs, n, slot, pslot);
}

/* The chunk's primitives through the vertex window (fe->window): the
 * working memory of an indexed draw bounded by the window's size rather
 * than the mesh's. */
static void windowed_primitives(const sr_front_end *fe, sr_chunk *c)
{
    sr_scratch *s = fe->ctx->scratch;
    bool last = fe->ds->provoking_last;
    for (size_t p = c->prim_begin; p < c->prim_end && !c->out_of_memory; p++) {
        uint32_t v[3], pv;
        int n = prim_vertices(fe->d, last, p, v, &pv);
        uint32_t lo = v[0], hi = v[0];
        for (int k = 1; k < n; k++) {
            lo = v[k] < lo ? v[k] : lo;
            hi = v[k] > hi ? v[k] : hi;
        }
        if (hi - lo >= fe->window) {
            gathered_primitive(fe, c, n, v, pv);
            continue;
        }
        if (lo < s->window_lo || hi >= s->window_hi) {
            window_cover(fe, c, s, lo, hi);
        }
        sr_vertex_src vs = { s->post, s->vary, s->window_lo };
        assemble(fe, c, &vs, n, v, pv);
    }
}

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#include <stddef.h>
#include "geometry/assembly_wide.h"
#define SR_HAVE_TRIANGLES16 1
#endif

/* Vertices per block of the fused vertex stage: a multiple of 2 and 3,
 * small enough for the block's positions and varyings to stay in L1. */
#define FUSED_BLOCK_VERTS 192

/* How many triangles ahead an indexed list's vertices are prefetched. */
#define SR_PREFETCH_TRIS 8

/* The chunk's primitives from the whole-draw arrays, which hold the
 * vertices from `base` on. */
static inline __attribute__((always_inline)) void
indexed_primitives(const sr_front_end *fe, sr_chunk *c, size_t base)
{
    const sr_scratch *s = fe->ctx->scratch;
    sr_vertex_src vs = { s->post, s->vary, base };
    const sr_draw_desc *d = fe->d;
    bool list = d->primitive == SR_PRIM_DEFAULT || d->primitive == SR_PRIM_TRIANGLES;
    size_t nv = (size_t)fe->ds->nvary;
    for (size_t p = c->prim_begin; p < c->prim_end && !c->out_of_memory; p++) {
        if (list && p + SR_PREFETCH_TRIS < c->prim_end) {
            /* An indexed mesh's vertices are gathered: ask for those
             * of a triangle a few ahead, so its post-transform
             * vertices (48 bytes, often across two lines) and
             * varyings arrive while this one is set up. */
            for (size_t k = 0; k < 3; k++) {
                size_t i = sr__index_at(d, 3 * (p + SR_PREFETCH_TRIS) + k) - base;
                const char *v = (const char *)&s->post[i];
                __builtin_prefetch(v);
                __builtin_prefetch(v + sizeof(sr_vertex_post) - 1);
                __builtin_prefetch(&s->vary[i * nv]);
            }
        }
        primitive(fe, c, &vs, p);
    }
}

void sr__run_front_end(void *arg, int job, int thread)
{
    (void)thread;
    const sr_front_end *fe = arg;
    sr_chunk *c = &fe->ctx->scratch->chunks[job];
    c->tri_count = 0;
    /* Records go out by streaming stores when more than one thread draws
     * (scratch.h), except in a chunk that was copied in tile order the
     * batch before (parallel/bin.c).  Its records are only read back by
     * that copy, on the thread that wrote them, so plain stores leave
     * them in this core's cache for it (small 64.7 -> 63.0 and 62.8 ->
     * 61.8 ms on two threads).  Whether this batch's chunk is copied too
     * is only known once it is binned; where it is not, the tile jobs
     * read the records from this core's cache instead: the same bytes,
     * only slower. */
    c->stream = fe->shared && !c->in_tile_order;
    /* One triangle per primitive is the common case; size for it once so
     * the store is not regrown (and copied) mid-chunk. */
    if (!sr__chunk_reserve_tris(&fe->ctx->allocator, c, c->prim_end - c->prim_begin + 16, fe->tri_size)) {
        /* No records: the bins must say so rather than keep the last
         * batch's, whose records may no longer be there. */
        c->out_of_memory = true;
        sr__bin_chunk(fe->ctx, fe->ds, c, fe->tri_size, fe->shared);
        return;
    }
    if (fe->fused) {
        /* The vertex stage for this chunk's own vertices, a block at a
         * time into buffers that stay in the L1 cache while the block's
         * primitives are assembled: a draw without indices uses each
         * vertex once, so the whole-draw arrays would only be written
         * out to memory and read back. */
        sr_vertex_post post[FUSED_BLOCK_VERTS];
        float vary[FUSED_BLOCK_VERTS * SR_MAX_VARYINGS];
        size_t k = fe->verts_per_prim, per_block = FUSED_BLOCK_VERTS / k;
        for (size_t p = c->prim_begin; p < c->prim_end && !c->out_of_memory; p += per_block) {
            size_t end = c->prim_end - p < per_block ? c->prim_end : p + per_block;
            sr__vertex_stage(fe->ds, fe->d, fe->mvp, fe->mv, fe->nm, k * p, k * (end - p), post,
                             vary);
            c->info.vertices_shaded += k * (end - p);
            sr_vertex_src vs = { post, vary, k * p };
            if (k == 3) {
                /* primitive()'s triangle list without indices. */
                bool last = fe->ds->provoking_last;
                size_t q = p;
#ifdef SR_HAVE_TRIANGLES16
                for (; fe->ds->triangles16 && q + 16 <= end && !c->out_of_memory; q += 16) {
                    triangles16(fe, c, &vs, (uint32_t)(3 * q));
                }
#endif
                for (; q < end && !c->out_of_memory; q++) {
                    uint32_t a = (uint32_t)(3 * q);
                    triangle(fe, c, &vs, a, a + 1, a + 2, last ? a + 2 : a);
                }
                continue;
            }
            for (size_t q = p; q < end && !c->out_of_memory; q++) {
                primitive(fe, c, &vs, q);
            }
        }
    } else if (fe->window) {
        windowed_primitives(fe, c);
    } else if (fe->vertex_base == 0) {
        /* The whole array, the common case: base 0 folded in. */
        indexed_primitives(fe, c, 0);
    } else {
        indexed_primitives(fe, c, fe->vertex_base);
    }
    if (c->stream) {
        sr__stream_fence();
    }
    if (!sr__bin_chunk(fe->ctx, fe->ds, c, fe->tri_size, fe->shared)) {
        c->out_of_memory = true;
    }
}
