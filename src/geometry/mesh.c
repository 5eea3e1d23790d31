/*
 * mesh.c - geometry stage, before the vertex stage: utilities on sr_mesh.
 * Consumes meshes as the readers and built-in generators produce them;
 * produces bounding boxes and per-vertex normals (smooth or flat).
 * No I/O and no shared state: any thread may call these on its own mesh
 * and context (smooth normals use the context's threads too).  Every
 * array is allocated on the mesh's context.
 */
#define _DEFAULT_SOURCE 1   /* populate.h */
#include "softrast.h"

#include "context.h"
#include "math/dvec3.h"
#include "populate.h"
#include "parallel/pool.h"

#include <math.h>
#include <string.h>

void sr_destroy_mesh(sr_context *ctx, sr_mesh *mesh)
{
    if (!ctx || !mesh) {
        return;
    }
    sr__free(ctx, mesh->positions);
    sr__free(ctx, mesh->normals);
    sr__free(ctx, mesh->colors);
    sr__free(ctx, mesh->texcoords);
    sr__free(ctx, mesh->indices);
    sr__free(ctx, mesh->texture_path);
    sr__free(ctx, mesh->texture_data);
    for (size_t i = 0; mesh->parts && i < mesh->part_count; i++) {
        sr__free(ctx, mesh->parts[i].texture_path);
        sr__free(ctx, mesh->parts[i].material.bump_path);
        sr__free(ctx, mesh->parts[i].texture_data);
    }
    sr__free(ctx, mesh->parts);
    memset(mesh, 0, sizeof *mesh);
}

/* A copy of `bytes` bytes of from on ctx in *to (NULL for none); false
 * when out of memory. */
static bool copy_array(sr_context *ctx, void *to, const void *from, size_t bytes)
{
    void **p = to;
    *p = NULL;
    if (!from || bytes == 0) {
        return true;
    }
    *p = sr__alloc(ctx, bytes);
    if (*p) {
        memcpy(*p, from, bytes);
    }
    return *p != NULL;
}

static size_t string_bytes(const char *s)
{
    return s ? strlen(s) + 1 : 0;
}

static bool copy_part(sr_context *ctx, sr_mesh_part *to, const sr_mesh_part *from)
{
    *to = *from;
    bool ok = copy_array(ctx, &to->texture_path, from->texture_path,
                         string_bytes(from->texture_path));
    ok &= copy_array(ctx, &to->material.bump_path, from->material.bump_path,
                     string_bytes(from->material.bump_path));
    return copy_array(ctx, &to->texture_data, from->texture_data, from->texture_size) && ok;
}

static sr_result validate_mesh(const sr_mesh *mesh);

sr_result sr_make_mesh(sr_context *ctx, const sr_mesh *src, sr_mesh *out)
{
    static const char fn[] = "sr_make_mesh";
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_make_mesh: ctx is NULL");
    }
    if (!out) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: out is NULL", fn);
    }
    /* Zeroing out first would zero src too, and with it the caller's only
     * pointers to its arrays. */
    if (out == src) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: out is src (the copy needs a mesh of its own)",
                        fn);
    }
    memset(out, 0, sizeof *out);
    /* Sizes first: the index check below reads 3 * triangle_count indices. */
    if (src && (src->vertex_count > SIZE_MAX / (4 * sizeof(float)) ||
                src->triangle_count > SIZE_MAX / 12 ||
                src->part_count > SIZE_MAX / sizeof(sr_mesh_part))) {
        return sr__fail(ctx, SR_TOO_LARGE, "%s: the arrays' sizes overflow size_t", fn);
    }
    if (validate_mesh(src) != SR_OK) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "%s: src is NULL, lacks an array it counts, or has an index >= "
                        "vertex_count", fn);
    }
    if (src->part_count > 0 && !src->parts) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: src->part_count %zu with no parts", fn,
                        src->part_count);
    }
    if (src->texture_size > 0 && !src->texture_data) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: src->texture_size %zu with no texture_data", fn,
                        src->texture_size);
    }
    /* The parts are runs in triangle order that cover every triangle
     * (sr_mesh_part): whoever draws by parts indexes with them. */
    size_t next = 0;
    for (size_t i = 0; i < src->part_count; i++) {
        const sr_mesh_part *pt = &src->parts[i];
        if (pt->first_triangle != next || pt->triangle_count > src->triangle_count - next) {
            return sr__fail(ctx, SR_INVALID_ARG,
                            "%s: src->parts[%zu] (first_triangle %zu, triangle_count %zu) does "
                            "not continue the runs at triangle %zu of %zu", fn, i,
                            pt->first_triangle, pt->triangle_count, next, src->triangle_count);
        }
        if (pt->texture_size > 0 && !pt->texture_data) {
            return sr__fail(ctx, SR_INVALID_ARG, "%s: src->parts[%zu].texture_size %zu with no "
                            "texture_data", fn, i, pt->texture_size);
        }
        next += pt->triangle_count;
    }
    if (src->part_count > 0 && next != src->triangle_count) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "%s: src->parts cover triangles 0 .. %zu of %zu (they must cover all)",
                        fn, next, src->triangle_count);
    }
    size_t v = src->vertex_count;
    sr_mesh m = *src;
    bool ok = copy_array(ctx, &m.positions, src->positions, v * 3 * sizeof(float));
    ok &= copy_array(ctx, &m.normals, src->normals, v * 3 * sizeof(float));
    ok &= copy_array(ctx, &m.colors, src->colors, v * 4 * sizeof(float));
    ok &= copy_array(ctx, &m.texcoords, src->texcoords, v * 2 * sizeof(float));
    ok &= copy_array(ctx, &m.indices, src->indices, src->triangle_count * 3 * sizeof(uint32_t));
    ok &= copy_array(ctx, &m.texture_path, src->texture_path, string_bytes(src->texture_path));
    ok &= copy_array(ctx, &m.texture_data, src->texture_data, src->texture_size);
    m.parts = NULL;
    m.part_count = 0;
    if (src->parts && src->part_count > 0) {
        m.parts = sr__calloc(ctx, src->part_count, sizeof *m.parts);
        ok &= m.parts != NULL;
        for (size_t i = 0; m.parts && i < src->part_count; i++) {
            ok &= copy_part(ctx, &m.parts[i], &src->parts[i]);
            m.part_count = i + 1;
        }
    }
    if (!ok) {
        sr_destroy_mesh(ctx, &m);
        return sr__fail(ctx, SR_OUT_OF_MEMORY, "%s: no memory", fn);
    }
    *out = m;
    sr__ok(ctx);
    return SR_OK;
}

bool sr_mesh_bounds(const sr_mesh *mesh, sr_vec3 *min, sr_vec3 *max)
{
    if (!mesh || mesh->vertex_count == 0 || !mesh->positions) {
        return false;
    }
    const float *p = mesh->positions;
    sr_vec3 lo = { p[0], p[1], p[2] };
    sr_vec3 hi = lo;
    for (size_t i = 1; i < mesh->vertex_count; i++) {
        const float *v = p + 3 * i;
        lo.x = fminf(lo.x, v[0]);
        lo.y = fminf(lo.y, v[1]);
        lo.z = fminf(lo.z, v[2]);
        hi.x = fmaxf(hi.x, v[0]);
        hi.y = fmaxf(hi.y, v[1]);
        hi.z = fmaxf(hi.z, v[2]);
    }
    if (min) {
        *min = lo;
    }
    if (max) {
        *max = hi;
    }
    return true;
}

/* The normal given to a vertex (or a degenerate face) that has no surface
 * around it to take a direction from: facing the default camera. */
static const float fallback_normal[3] = { 0.0f, 0.0f, 1.0f };

static void sub3(const float *a, const float *b, double out[3])
{
    out[0] = (double)a[0] - b[0];
    out[1] = (double)a[1] - b[1];
    out[2] = (double)a[2] - b[2];
}

static double length3(const double a[3])
{
    return sqrt(sr__ddot(a, a));
}

/* Angle between two edge vectors leaving the same corner.  atan2 of |a x b|
 * and a.b stays accurate for angles near 0 and pi, where acos of a
 * normalized dot product loses most of its digits. */
static double corner_angle(const double a[3], const double b[3])
{
    double c[3];
    sr__dcross(a, b, c);
    return atan2(length3(c), sr__ddot(a, b));
}

/* Unit normal of triangle (a, b, c), counter-clockwise front.  Returns
 * false for a triangle with no area (or non-finite corners). */
static bool face_normal(const float *a, const float *b, const float *c, double n[3])
{
    double e1[3], e2[3];
    sub3(b, a, e1);
    sub3(c, a, e2);
    sr__dcross(e1, e2, n);
    double len = length3(n);
    if (!(len > 0.0) || !isfinite(len)) {
        return false;
    }
    n[0] /= len;
    n[1] /= len;
    n[2] /= len;
    return true;
}

static sr_result validate_mesh(const sr_mesh *mesh)
{
    if (!mesh) {
        return SR_INVALID_ARG;
    }
    if (mesh->vertex_count > 0 && !mesh->positions) {
        return SR_INVALID_ARG;
    }
    if (mesh->triangle_count > 0 && !mesh->indices) {
        return SR_INVALID_ARG;
    }
    size_t index_count;
    if (__builtin_mul_overflow(mesh->triangle_count, (size_t)3, &index_count)) {
        return SR_INVALID_ARG;
    }
    for (size_t i = 0; i < index_count; i++) {
        if (mesh->indices[i] >= mesh->vertex_count) {
            return SR_INVALID_ARG;
        }
    }
    return SR_OK;
}

/* Vertices [v0, v1) of smooth_normals: the faces with a corner among
 * them add to those corners in face order, so a vertex sums the same
 * terms in the same order whichever range - or thread - it falls in, and
 * the normals are the same bits for any split. */
static void smooth_range(const sr_mesh *mesh, double *sum, float *normals, size_t v0, size_t v1)
{
    const float *p = mesh->positions;
    size_t span = v1 - v0;
    for (size_t t = 0; t < mesh->triangle_count; t++) {
        const uint32_t *tri = mesh->indices + 3 * t;
        bool mine[3];
        for (int k = 0; k < 3; k++) {
            mine[k] = tri[k] - v0 < span;   /* unsigned: below v0 wraps high */
        }
        if (!(mine[0] | mine[1] | mine[2])) {
            continue;
        }
        double fn[3];
        if (!face_normal(p + 3 * (size_t)tri[0], p + 3 * (size_t)tri[1],
                         p + 3 * (size_t)tri[2], fn)) {
            continue; /* degenerate: no direction to contribute */
        }
        for (int k = 0; k < 3; k++) {
            if (!mine[k]) {
                continue;
            }
            const float *v = p + 3 * (size_t)tri[k];
            const float *next = p + 3 * (size_t)tri[(k + 1) % 3];
            const float *prev = p + 3 * (size_t)tri[(k + 2) % 3];
            double e1[3], e2[3];
            sub3(next, v, e1);
            sub3(prev, v, e2);
            double w = corner_angle(e1, e2);
            double *s = sum + 3 * (size_t)tri[k];
            s[0] += fn[0] * w;
            s[1] += fn[1] * w;
            s[2] += fn[2] * w;
        }
    }
    for (size_t i = v0; i < v1; i++) {
        double *s = sum + 3 * i;
        double len = length3(s);
        /* Zero when no valid face touches the vertex, or when opposite
         * faces cancel (a two-sided sheet): no direction is better than
         * another, so take the fallback rather than divide by zero. */
        if (len > 1e-30 && isfinite(len)) {
            normals[3 * i + 0] = (float)(s[0] / len);
            normals[3 * i + 1] = (float)(s[1] / len);
            normals[3 * i + 2] = (float)(s[2] / len);
        } else {
            memcpy(normals + 3 * i, fallback_normal, sizeof fallback_normal);
        }
    }
}

typedef struct smooth_job {
    const sr_mesh *mesh;
    double *sum;
    float *normals;
    size_t ranges;
} smooth_job;

static void run_smooth_range(void *arg, int job, int thread)
{
    (void)thread;
    const smooth_job *j = arg;
    size_t n = j->mesh->vertex_count;
    smooth_range(j->mesh, j->sum, j->normals, n * (size_t)job / j->ranges,
                 n * ((size_t)job + 1) / j->ranges);
}

/* Angle-weighted vertex normals (Thuermer and Wuethrich): each face adds
 * its unit normal times the angle of its corner at the vertex.  Unlike
 * area or plain averaging, this does not depend on how a polygon was split
 * into triangles, so a cube corner gets exactly (1,1,1)/sqrt(3) whichever
 * diagonal each face was cut along.  With a pool, the vertices are cut
 * into two ranges a thread (smooth_range): each range's faces are found
 * by a pass over the indices, cheap beside the angles' atan2. */
static sr_result smooth_normals(sr_context *ctx, sr_mesh *mesh)
{
    struct sr_pool *pool = ctx->pool;
    size_t n = mesh->vertex_count;
    if (n == 0) {
        sr__free(ctx, mesh->normals);
        mesh->normals = NULL;
        return SR_OK;
    }
    size_t floats;
    if (__builtin_mul_overflow(n, (size_t)3, &floats)) {
        return SR_OUT_OF_MEMORY;
    }
    /* Accumulate in double: a vertex shared by thousands of thin faces
     * would otherwise lose the small contributions. */
    double *sum = sr__calloc(ctx, floats, sizeof *sum);
    float *normals = sr__alloc(ctx, floats * sizeof *normals);
    if (!sum || !normals) {
        sr__free(ctx, sum);
        sr__free(ctx, normals);
        return SR_OUT_OF_MEMORY;
    }
    sr__populate(normals, floats * sizeof *normals); /* written whole */
    size_t ranges = pool ? 2 * (size_t)ctx->threads : 1;
    if (ranges > n) {
        ranges = n;
    }
    smooth_job job = { .mesh = mesh, .sum = sum, .normals = normals, .ranges = ranges };
    sr__pool_run(pool, run_smooth_range, &job, (int)ranges);
    sr__free(ctx, sum);
    sr__free(ctx, mesh->normals);
    mesh->normals = normals;
    return SR_OK;
}

/* Every triangle gets three vertices of its own carrying the face normal,
 * so the normal does not blend across edges.  Colors and texcoords are
 * copied per corner; the mesh is only touched once every array exists. */
static sr_result flat_normals(sr_context *ctx, sr_mesh *mesh)
{
    size_t tris = mesh->triangle_count;
    if (tris == 0) {
        /* Splitting would drop every vertex; with no faces to be flat
         * against, keep the vertices and give them the fallback normal. */
        return smooth_normals(ctx, mesh);
    }
    size_t verts;
    if (__builtin_mul_overflow(tris, (size_t)3, &verts) || verts > UINT32_MAX) {
        return SR_TOO_LARGE; /* the split indices would not fit uint32 */
    }
    size_t bytes3;
    if (__builtin_mul_overflow(verts, 3 * sizeof(float), &bytes3)) {
        return SR_OUT_OF_MEMORY;
    }
    float *positions = sr__alloc(ctx, bytes3);
    float *normals = sr__alloc(ctx, bytes3);
    uint32_t *indices = sr__alloc(ctx, verts * sizeof *indices);
    float *colors = mesh->colors ? sr__alloc(ctx, verts * 4 * sizeof(float)) : NULL;
    float *texcoords = mesh->texcoords ? sr__alloc(ctx, verts * 2 * sizeof(float)) : NULL;
    if (!positions || !normals || !indices || (mesh->colors && !colors) ||
        (mesh->texcoords && !texcoords)) {
        sr__free(ctx, positions);
        sr__free(ctx, normals);
        sr__free(ctx, indices);
        sr__free(ctx, colors);
        sr__free(ctx, texcoords);
        return SR_OUT_OF_MEMORY;
    }
    const float *p = mesh->positions;
    for (size_t t = 0; t < tris; t++) {
        const uint32_t *tri = mesh->indices + 3 * t;
        double fn[3];
        float n[3];
        if (face_normal(p + 3 * (size_t)tri[0], p + 3 * (size_t)tri[1],
                        p + 3 * (size_t)tri[2], fn)) {
            n[0] = (float)fn[0];
            n[1] = (float)fn[1];
            n[2] = (float)fn[2];
        } else {
            memcpy(n, fallback_normal, sizeof n);
        }
        for (int k = 0; k < 3; k++) {
            size_t src = tri[k];
            size_t dst = 3 * t + (size_t)k;
            memcpy(positions + 3 * dst, p + 3 * src, 3 * sizeof(float));
            memcpy(normals + 3 * dst, n, sizeof n);
            if (colors) {
                memcpy(colors + 4 * dst, mesh->colors + 4 * src, 4 * sizeof(float));
            }
            if (texcoords) {
                memcpy(texcoords + 2 * dst, mesh->texcoords + 2 * src, 2 * sizeof(float));
            }
            indices[dst] = (uint32_t)dst;
        }
    }
    sr__free(ctx, mesh->positions);
    sr__free(ctx, mesh->normals);
    sr__free(ctx, mesh->colors);
    sr__free(ctx, mesh->texcoords);
    sr__free(ctx, mesh->indices);
    mesh->positions = positions;
    mesh->normals = normals;
    mesh->colors = colors;
    mesh->texcoords = texcoords;
    mesh->indices = indices;
    mesh->vertex_count = verts;
    return SR_OK;
}

sr_result sr_mesh_compute_normals(sr_context *ctx, sr_mesh *mesh, sr_normal_mode mode)
{
    static const char fn[] = "sr_mesh_compute_normals";
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_mesh_compute_normals: ctx is NULL");
    }
    if (validate_mesh(mesh) != SR_OK) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "%s: mesh is NULL, lacks an array it counts, or has an index >= "
                        "vertex_count", fn);
    }
    sr_result r;
    switch (mode) {
    case SR_NORMALS_SMOOTH:
        r = smooth_normals(ctx, mesh);
        break;
    case SR_NORMALS_FLAT:
        r = flat_normals(ctx, mesh);
        break;
    default:
        return sr__fail(ctx, SR_INVALID_ARG, "%s: mode %d is not an sr_normal_mode", fn,
                        (int)mode);
    }
    if (r != SR_OK) {
        return sr__fail(ctx, r, "%s: %s", fn,
                        r == SR_TOO_LARGE ? "the split vertices would not fit uint32 indices"
                                          : "no memory");
    }
    sr__ok(ctx);
    return SR_OK;
}
