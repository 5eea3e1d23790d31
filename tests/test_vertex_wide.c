/* test_vertex_wide.c - sr__vertex_stage16, the Gouraud vertex stage
 * sixteen vertices at a time, against sr__vertex_shade, the scalar
 * vertex it restates, and the scalar classification (outcode, divide by
 * w, viewport, snap): the same bits of every clip position, outcode,
 * window position, color and texture coordinate, for random states
 * (directional and point lights, a local viewer or not, two-sided
 * or not, specular or not; vertex colors or the material's; depth range
 * [-1, 1] or [0, 1]) and random draws (three- and four-component
 * positions, interleaved strides, normals and colors present or not,
 * vertex counts that leave a part group), with the scalar code's edge
 * cases among the vertices: zero-length normals, NaN coordinates, an eye
 * transform whose w is 0 or not 1. */
#include "sr_test.h"
#include "pipeline.h"
#include "raster/triangle_simd.h"

#include <math.h>
#include <string.h>

/* Same bits, or both NaN (a NaN's payload is not part of the contract). */
static bool same(float a, float b)
{
    return memcmp(&a, &b, sizeof a) == 0 || (isnan(a) && isnan(b));
}

static float frand(sr_rng *rng, double lo, double hi)
{
    return (float)sr_rng_range(rng, lo, hi);
}

/* vertex.c's classify, restated: the outcode, and for a vertex inside
 * every plane its snapped window position. */
static void classify_ref(const sr_draw_state *ds, const float clip[4], sr_vertex_post *v)
{
    memset(v, 0, sizeof *v);
    if (!(isfinite(clip[0]) && isfinite(clip[1]) && isfinite(clip[2]) && isfinite(clip[3]))) {
        v->outcode = SR_OUTCODE_NONFINITE;
        return;
    }
    sr_clip_planes k;
    sr__clip_planes(ds, &k);
    v->outcode = sr__clip_outcode_with(&k, clip);
    if (v->outcode == 0) {
        sr__project(ds, clip, &v->x_q8, &v->y_q8, &v->z, &v->inv_w);
    }
}

static void random_matrix(sr_rng *rng, sr_mat4 *m, bool projective)
{
    for (int k = 0; k < 16; k++) {
        m->m[k] = frand(rng, -2, 2);
    }
    if (!projective) {
        m->m[3] = m->m[7] = m->m[11] = 0.0f;
        m->m[15] = 1.0f;
    }
}

static void random_state(sr_rng *rng, int s, sr_draw_state *ds)
{
    static const int shininess[] = { 0, 1, 2, 7, 8, 32, 129 };
    memset(ds, 0, sizeof *ds);
    ds->shading = SR_SHADING_GOURAUD;
    ds->zero_to_one = s / 5 % 2;
    ds->vp_px = sr_rng_range(rng, 20, 1000);
    ds->vp_py = sr_rng_range(rng, 20, 1000);
    ds->vp_ox = ds->vp_px + sr_rng_range(rng, -5, 5);
    ds->vp_oy = ds->vp_py + sr_rng_range(rng, -5, 5);
    ds->vp_zs = sr_rng_range(rng, 0.1, 0.5);
    ds->vp_zb = sr_rng_range(rng, 0.1, 0.5);
    for (int k = 0; k < 3; k++) {
        ds->ambient[k] = frand(rng, 0, 0.4);
        ds->specular[k] = s % 3 == 0 ? 0.0f : frand(rng, 0, 1);
    }
    for (int k = 0; k < 4; k++) {
        ds->diffuse[k] = frand(rng, 0, 1.2);
    }
    ds->local_viewer = s % 2;
    ds->two_sided = s / 2 % 2;
    ds->use_vertex_color = s / 4 % 2;
    ds->shininess_int = shininess[s % 7];
    ds->shininess = (float)ds->shininess_int;
    ds->light_count = 1 + s % SR_MAX_LIGHTS;
    for (int i = 0; i < ds->light_count; i++) {
        sr_light_eye *lt = &ds->lights[i];
        lt->point = (s / 3 + i) % 2;
        for (int k = 0; k < 3; k++) {
            lt->vec[k] = frand(rng, -2, 2);
            lt->color[k] = frand(rng, 0, 1.5);
        }
        if (!lt->point) {
            float len = sqrtf(lt->vec[0] * lt->vec[0] + lt->vec[1] * lt->vec[1] +
                              lt->vec[2] * lt->vec[2]);
            for (int k = 0; k < 3; k++) {
                lt->vec[k] /= len;
            }
        }
    }
    /* Texture coordinates after the color in some states. */
    ds->nvary = 8;
    ds->uv_index = s % 5 == 0 ? 5 : -1;
    ds->light_lanes = true;
    ds->vertex_lanes16 = true;
}

SR_TEST(sixteen_lanes_give_the_scalar_vertex_bits)
{
    if (sr__simd_cpu_level() != SR_SIMD_AVX512) {
        SKIP("this CPU has no AVX-512: the sixteen-lane stage is not used");
    }
    enum { MAXV = 64, MAXSTRIDE = 9 };
    sr_rng rng = { 0x16f0 };
    float pos[MAXV * MAXSTRIDE], nrm[MAXV * MAXSTRIDE], col[MAXV * MAXSTRIDE], uv[MAXV * 2];
    sr_vertex_post post[MAXV];
    float vary[MAXV * 8];
    long compared = 0, nan_values = 0, groups_part = 0, inside = 0, nonfinite = 0;
    for (int s = 0; s < 600 && !sr_test_failed_now(); s++) {
        sr_draw_state ds;
        random_state(&rng, s, &ds);
        sr_mat4 mvp, mv, nm;
        random_matrix(&rng, &mvp, true);
        random_matrix(&rng, &mv, s % 4 == 1);
        random_matrix(&rng, &nm, false);
        if (s % 8 == 3) {
            mv.m[3] = mv.m[7] = mv.m[11] = mv.m[15] = 0.0f; /* eye w = 0: not divided */
        }
        int psize = 3 + s % 2, csize = 3 + s / 2 % 2;
        /* Packed arrays, or each attribute in a record of MAXSTRIDE floats. */
        bool interleaved = s % 3 == 2;
        size_t pstride = interleaved ? MAXSTRIDE * sizeof(float) : 0;
        size_t pstep = interleaved ? MAXSTRIDE : (size_t)psize;
        size_t nstep = interleaved ? MAXSTRIDE : 3, cstep = interleaved ? MAXSTRIDE : (size_t)csize;
        for (int i = 0; i < MAXV * MAXSTRIDE; i++) {
            pos[i] = frand(&rng, -3, 3);
            nrm[i] = frand(&rng, -1, 1);
            col[i] = frand(&rng, -0.2, 1.2);
        }
        for (int i = 0; i < MAXV * 2; i++) {
            uv[i] = frand(&rng, -1, 2);
        }
        for (int v = 0; v < MAXV; v++) {
            switch (sr_rng_int(&rng, 0, 11)) {
            case 0: /* zero-length normal */
                nrm[v * nstep] = nrm[v * nstep + 1] = nrm[v * nstep + 2] = 0.0f;
                break;
            case 1: /* NaN position: NaN clip and eye coordinates */
                pos[v * pstep + 1] = NAN;
                break;
            case 2: /* NaN normal */
                nrm[v * nstep + 2] = NAN;
                break;
            case 3: /* at the object origin (w 1 in object space) */
                pos[v * pstep] = pos[v * pstep + 1] = pos[v * pstep + 2] = 0.0f;
                break;
            default:
                break;
            }
        }
        sr_draw_desc d = { .positions = pos, .position_size = psize, .position_stride = pstride,
                           .normals = s % 6 == 5 ? NULL : nrm,
                           .normal_stride = interleaved ? MAXSTRIDE * sizeof(float) : 0,
                           .colors = s % 7 == 6 ? NULL : col, .color_size = csize,
                           .color_stride = interleaved ? MAXSTRIDE * sizeof(float) : 0,
                           .texcoords = uv };
        size_t first = (size_t)sr_rng_int(&rng, 0, 8);
        size_t count = (size_t)sr_rng_int(&rng, 1, MAXV - 8);
        groups_part += count % 16 != 0;
        memset(post, 0, sizeof post);
        memset(vary, 0, sizeof vary);
        REQUIRE(sr__vertex_stage16(&ds, &d, &mvp, &mv, &nm, first, count, post, vary));
        for (size_t i = 0; i < count; i++) {
            size_t v = first + i;
            float obj[4] = { pos[v * pstep], pos[v * pstep + 1], pos[v * pstep + 2],
                             psize == 4 ? pos[v * pstep + 3] : 1.0f };
            float rgba[4] = { col[v * cstep], col[v * cstep + 1], col[v * cstep + 2],
                              csize == 4 ? col[v * cstep + 3] : 1.0f };
            float clip[4], want[8] = { 0 };
            sr__vertex_shade(&ds, obj, d.normals ? &nrm[v * nstep] : NULL,
                             d.colors ? rgba : NULL, &uv[v * 2], NULL, &mvp, &mv, &nm, clip,
                             want);
            sr_vertex_post want_post;
            classify_ref(&ds, clip, &want_post);
            if (post[i].outcode != want_post.outcode) {
                sr_test_fail(__FILE__, __LINE__, "state %d vertex %zu: outcode %#x, scalar %#x", s,
                             i, post[i].outcode, want_post.outcode);
            } else if (want_post.outcode == 0 &&
                       (post[i].x_q8 != want_post.x_q8 || post[i].y_q8 != want_post.y_q8 ||
                        memcmp(&post[i].z, &want_post.z, sizeof(double)) != 0 ||
                        !same(post[i].inv_w, want_post.inv_w))) {
                sr_test_fail(__FILE__, __LINE__, "state %d vertex %zu: window (%d, %d, %a, %a), "
                             "scalar (%d, %d, %a, %a)", s, i, post[i].x_q8, post[i].y_q8,
                             post[i].z, (double)post[i].inv_w, want_post.x_q8, want_post.y_q8,
                             want_post.z, (double)want_post.inv_w);
            }
            inside += want_post.outcode == 0;
            nonfinite += want_post.outcode == SR_OUTCODE_NONFINITE;
            for (int k = 0; k < 4; k++) {
                if (!same(post[i].pos[k], clip[k])) {
                    sr_test_fail(__FILE__, __LINE__, "state %d vertex %zu clip %d: %a, scalar %a",
                                 s, i, k, (double)post[i].pos[k], (double)clip[k]);
                }
                const float *got = &vary[i * 8 + SR_VARY_COLOR];
                if (!same(got[k], want[SR_VARY_COLOR + k])) {
                    sr_test_fail(__FILE__, __LINE__, "state %d vertex %zu color %d: %a, scalar %a",
                                 s, i, k, (double)got[k], (double)want[SR_VARY_COLOR + k]);
                }
                nan_values += isnan(want[SR_VARY_COLOR + k]);
                compared += 2;
            }
            if (ds.uv_index >= 0) {
                CHECK(same(vary[i * 8 + 5], uv[v * 2]) && same(vary[i * 8 + 6], uv[v * 2 + 1]));
            }
        }
    }
    CHECK(compared > 100000);
    CHECK(nan_values > 0);  /* the NaN cases were reached */
    CHECK(groups_part > 0); /* and part groups */
    CHECK(inside > 1000);   /* window positions compared */
    CHECK(nonfinite > 0);
}

/* Strides too long for the gathers' 32-bit offsets, and states it does
 * not cover: the stage declines and writes nothing (vertex.c then takes
 * its own stages). */
SR_TEST(sixteen_lanes_decline_strides_beyond_their_offsets)
{
    if (sr__simd_cpu_level() != SR_SIMD_AVX512) {
        SKIP("this CPU has no AVX-512: the sixteen-lane stage is not used");
    }
    sr_draw_state ds;
    sr_rng rng = { 7 };
    random_state(&rng, 1, &ds);
    sr_mat4 m;
    random_matrix(&rng, &m, false);
    float pos[3] = { 1, 2, 3 };
    sr_vertex_post post[1];
    float vary[8] = { 0 };
    memset(post, 0x5a, sizeof post);
    sr_draw_desc d = { .positions = pos, .position_stride = (size_t)1 << 28 };
    CHECK(!sr__vertex_stage16(&ds, &d, &m, &m, &m, 0, 1, post, vary));
    d.position_stride = 0;
    d.texcoords = pos;
    d.texcoord_stride = (size_t)1 << 28;
    CHECK(!sr__vertex_stage16(&ds, &d, &m, &m, &m, 0, 1, post, vary));
    d.texcoord_stride = 0;
    ds.shading = SR_SHADING_PHONG;
    CHECK(!sr__vertex_stage16(&ds, &d, &m, &m, &m, 0, 1, post, vary));
    ds.shading = SR_SHADING_UNLIT;
    CHECK(!sr__vertex_stage16(&ds, &d, &m, &m, &m, 0, 1, post, vary));
    ds.shading = SR_SHADING_GOURAUD;
    ds.shininess_int = -1; /* powf shininess: the scalar stage */
    CHECK(!sr__vertex_stage16(&ds, &d, &m, &m, &m, 0, 1, post, vary));
    unsigned char untouched[sizeof post];
    memset(untouched, 0x5a, sizeof untouched);
    CHECK(memcmp(post, untouched, sizeof post) == 0);
    ds.shininess_int = 8;
    CHECK(sr__vertex_stage16(&ds, &d, &m, &m, &m, 0, 1, post, vary));
}

/* sr__classify16, the classification alone in lanes (what the UNLIT and
 * other stages use after their own transforms), against the scalar
 * classification: random clip positions inside, outside and across the
 * planes, w near 0 and negative, NaN and infinite coordinates, both
 * depth conventions, counts that leave a part group. */
SR_TEST(sixteen_lane_classification_gives_the_scalar_outcodes_and_positions)
{
    if (sr__simd_cpu_level() != SR_SIMD_AVX512) {
        SKIP("this CPU has no AVX-512: the sixteen-lane classification is "
             "not used");
    }
    sr_rng rng = { 0xc1a55e5ull };
    int inside = 0, outside = 0, nonfinite = 0, part = 0;
    for (int s = 0; s < 300; s++) {
        sr_draw_state ds;
        random_state(&rng, s, &ds);
        size_t count = (size_t)sr_rng_int(&rng, 1, 70);
        part += count % 16 != 0;
        sr_vertex_post post[70], want[70];
        memset(post, 0, sizeof post);
        for (size_t i = 0; i < count; i++) {
            float *c = post[i].pos;
            float w = sr_rng_int(&rng, 0, 9) == 0 ? frand(&rng, -1e-6, 1e-6) : frand(&rng, -0.5, 3);
            for (int k = 0; k < 3; k++) {
                c[k] = frand(&rng, -1.3, 1.3) * (w < 0 ? -w : w);
            }
            c[3] = w;
            int odd = sr_rng_int(&rng, 0, 40);
            if (odd == 0) {
                c[sr_rng_int(&rng, 0, 3)] = NAN;
            } else if (odd == 1) {
                c[sr_rng_int(&rng, 0, 3)] = sr_rng_int(&rng, 0, 1) ? INFINITY : -INFINITY;
            } else if (odd == 2) {
                c[0] = frand(&rng, -1e9, 1e9);   /* far past the guard band */
            }
            classify_ref(&ds, c, &want[i]);
        }
        REQUIRE(sr__classify16(&ds, post, count));
        for (size_t i = 0; i < count; i++) {
            inside += want[i].outcode == 0;
            outside += want[i].outcode != 0 && want[i].outcode != SR_OUTCODE_NONFINITE;
            nonfinite += want[i].outcode == SR_OUTCODE_NONFINITE;
            if (post[i].outcode != want[i].outcode) {
                sr_test_fail(__FILE__, __LINE__, "state %d vertex %zu: outcode %#x, scalar %#x", s,
                             i, post[i].outcode, want[i].outcode);
            } else if (want[i].outcode == 0 &&
                       (post[i].x_q8 != want[i].x_q8 || post[i].y_q8 != want[i].y_q8 ||
                        memcmp(&post[i].z, &want[i].z, sizeof(double)) != 0 ||
                        !same(post[i].inv_w, want[i].inv_w))) {
                sr_test_fail(__FILE__, __LINE__, "state %d vertex %zu: window (%d, %d, %a, %a), "
                             "scalar (%d, %d, %a, %a)", s, i, post[i].x_q8, post[i].y_q8,
                             post[i].z, (double)post[i].inv_w, want[i].x_q8, want[i].y_q8,
                             want[i].z, (double)want[i].inv_w);
            }
        }
    }
    CHECK(inside > 2000);
    CHECK(outside > 500);
    CHECK(nonfinite > 50);
    CHECK(part > 200);
}
