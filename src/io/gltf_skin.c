/*
 * gltf_skin.c - io stage: glTF skins (the specification's 3.7.3), drawn
 * in the pose the nodes give.  Consumes a skin's joints and inverse bind
 * matrices, the joints' world matrices (gltf.c) and a primitive's
 * JOINTS_n / WEIGHTS_n; produces the node instance's positions, normals
 * and tangents in world space by linear blend skinning.  Called by the
 * thread reading the document.
 */
#include "io/gltf.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A skin's joint matrices (jointWorld x inverseBind), made once for every
 * node the skin poses. */
typedef struct gltf_skin_cache {
    float *matrices;         /* 16 a joint, column-major */
    size_t count;
    bool made;
} gltf_skin_cache;

void sr__gltf_skins_free(gltf_doc *d)
{
    for (size_t i = 0; d->skins && i < d->skin_count; i++) {
        free(d->skins[i].matrices);
    }
    free(d->skins);
    d->skins = NULL;
    d->skin_count = 0;
}

sr_result sr__gltf_read_influences(gltf_doc *d, const json_t *attrs, const char *aptr,
                                   size_t vertex_count, gltf_pose_source *src)
{
    size_t sets = 0;
    char name[32];
    for (;; sets++) {
        snprintf(name, sizeof name, "JOINTS_%zu", sets);
        bool joints = json_object_get(attrs, name) != NULL;
        snprintf(name, sizeof name, "WEIGHTS_%zu", sets);
        bool weights = json_object_get(attrs, name) != NULL;
        if (!joints && !weights) {
            break;
        }
        if (joints != weights) {
            return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: JOINTS_%zu without WEIGHTS_%zu or the "
                                 "other way round", aptr, sets, sets);
        }
    }
    if (sets == 0) {
        return SR_OK;
    }
    size_t per = 4 * sets, total;
    if (!sr__mul_ok(vertex_count, per * sizeof(float), &total)) {
        return sr__gltf_fail(d, SR_TOO_LARGE, "%s/JOINTS_0: too many vertices", aptr);
    }
    src->joints = malloc(total);
    src->weights = malloc(total);
    if (!src->joints || !src->weights) {
        return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory", aptr);
    }
    src->influence_sets = sets;
    src->joint_max = 0;
    for (size_t s = 0; s < sets; s++) {
        for (int k = 0; k < 2; k++) {
            char ptr[GLTF_PTR];
            long index = -1;
            snprintf(name, sizeof name, "%s_%zu", k == 0 ? "JOINTS" : "WEIGHTS", s);
            snprintf(ptr, sizeof ptr, "%s/%s", aptr, name);
            sr_result r = sr__gltf_index(d, attrs, aptr, name, (size_t)-1 / 2, true, &index);
            gltf_accessor_info info;
            float *f = NULL;
            if (r == SR_OK) {
                r = sr__gltf_read_floats(d, index, ptr, 1u << 4, &info, &f);
            }
            if (r != SR_OK) {
                free(f);
                return r;
            }
            bool unsigned_int = info.component_type == 5121 || info.component_type == 5123;
            const char *bad = NULL;
            if (k == 0 && (!unsigned_int || info.normalized)) {
                bad = "unsigned bytes or shorts (not normalized)";
            } else if (k == 1 && info.component_type != 5126 &&
                       !(unsigned_int && info.normalized)) {
                bad = "floats or normalized unsigned bytes or shorts";
            }
            if (bad || info.count != vertex_count) {
                free(f);
                return bad ? sr__gltf_fail(d, SR_BAD_FORMAT, "%s: accessor %ld is not of %s", ptr,
                                           index, bad)
                           : sr__gltf_fail(d, SR_BAD_FORMAT,
                                           "%s: accessor %ld has %zu elements, POSITION %zu", ptr,
                                           index, info.count, vertex_count);
            }
            float *dst = k == 0 ? src->joints : src->weights;
            for (size_t v = 0; v < vertex_count; v++) {
                memcpy(dst + v * per + 4 * s, f + 4 * v, 4 * sizeof *f);
                for (int c = 0; k == 0 && c < 4; c++) {
                    size_t j = (size_t)f[4 * v + (size_t)c];
                    if (j > src->joint_max || (v == 0 && s == 0 && c == 0)) {
                        src->joint_max = j;
                        src->joint_max_set = s;
                        src->joint_max_vertex = v;
                    }
                }
            }
            free(f);
        }
    }
    return SR_OK;
}

/* Skin `skin`'s joint matrices, made on first use. */
static sr_result joint_matrices(gltf_doc *d, long skin, const char *use, gltf_skin_cache **out)
{
    json_t *skins = json_object_get(d->root, "skins");
    if (!d->skins) {
        d->skin_count = json_array_size(skins);
        d->skins = calloc(d->skin_count ? d->skin_count : 1, sizeof *d->skins);
        if (!d->skins) {
            d->skin_count = 0;
            return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "/skins: out of memory");
        }
    }
    if (skin < 0 || (size_t)skin >= d->skin_count) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: skin %ld does not exist (%zu of them)", use,
                             skin, d->skin_count);
    }
    gltf_skin_cache *c = &d->skins[skin];
    *out = c;
    if (c->made) {
        return c->matrices ? SR_OK : SR_BAD_FORMAT;
    }
    c->made = true;
    char ptr[GLTF_PTR], iptr[GLTF_PTR];
    json_t *s = json_array_get(skins, (size_t)skin), *joints;
    size_t n;
    sr_result r;
    snprintf(ptr, sizeof ptr, "/skins/%ld", skin);
    if (!json_is_object(s)) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: not an object", ptr);
    }
    if ((r = sr__gltf_array(d, s, ptr, "joints", &joints, &n)) != SR_OK) {
        return r;
    }
    if (n == 0) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/joints: missing or empty", ptr);
    }
    long ibm = -1;
    if ((r = sr__gltf_index(d, s, ptr, "inverseBindMatrices", (size_t)-1 / 2, false, &ibm)) !=
        SR_OK) {
        return r;
    }
    float *inverse_bind = NULL;
    gltf_accessor_info info = { 0 };
    snprintf(iptr, sizeof iptr, "%s/inverseBindMatrices", ptr);
    if (ibm >= 0) {
        if ((r = sr__gltf_read_mat4(d, ibm, iptr, &info, &inverse_bind)) != SR_OK) {
            return r;
        }
        if (info.count < n) {
            free(inverse_bind);
            return sr__gltf_fail(d, SR_BAD_FORMAT,
                                 "%s: accessor %ld has %zu matrices, fewer than the %zu joints",
                                 iptr, ibm, info.count, n);
        }
    }
    float *m = malloc(n * 16 * sizeof *m);
    unsigned char *used = calloc(d->node_count ? d->node_count : 1, 1);
    long *nodes = malloc(n * sizeof *nodes);
    r = m && used && nodes ? SR_OK
                           : sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory", ptr);
    for (size_t j = 0; j < n && r == SR_OK; j++) {
        json_t *v = json_array_get(joints, j);
        json_int_t node = json_is_integer(v) ? json_integer_value(v) : -1;
        if (node < 0 || (size_t)node >= d->node_count) {
            r = sr__gltf_fail(d, SR_BAD_FORMAT, "%s/joints/%zu: not a node index below %zu", ptr,
                              j, d->node_count);
        } else if (used[node]) {
            r = sr__gltf_fail(d, SR_BAD_FORMAT, "%s/joints/%zu: node %lld is listed twice", ptr,
                              j, (long long)node);
        } else {
            static const float identity[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
            float world[16];
            used[node] = 1;
            nodes[j] = (long)node;
            r = sr__gltf_node_world(d, (long)node, world);
            if (r == SR_OK) {
                sr__mat4_mul(world, inverse_bind ? inverse_bind + 16 * j : identity, m + 16 * j);
            }
        }
    }
    free(used);
    if (r == SR_OK && !sr__gltf_posing_skin(d, skin, nodes, n, inverse_bind)) {
        r = sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory", ptr);
    }
    free(nodes);
    free(inverse_bind);
    if (r != SR_OK) {
        free(m);
        return r;
    }
    c->matrices = m;
    c->count = n;
    return SR_OK;
}

/* b += w * the upper three rows of the column-major matrix m. */
static void add_weighted(double *b, const float *m, double w)
{
    for (int col = 0; col < 4; col++) {
        for (int row = 0; row < 3; row++) {
            b[col * 3 + row] += w * m[col * 4 + row];
        }
    }
}

static void cross(const double *a, const double *b, double *out)
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

/* v (3 floats) normalized into out; left as is when it has no length. */
static void store_unit(const double *v, float *out)
{
    double len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int c = 0; c < 3; c++) {
        out[c] = (float)(len > 0 ? v[c] / len : v[c]);
    }
}

sr_result sr__gltf_skin(gltf_doc *d, long skin, const char *use, const gltf_pose_source *src,
                        const char *pptr, sr_scene_primitive *p)
{
    if (src->influence_sets == 0) {
        return sr__gltf_fail(d, SR_BAD_FORMAT,
                             "%s/attributes: no JOINTS_0 and WEIGHTS_0, but %s skins it", pptr,
                             use);
    }
    gltf_skin_cache *c = NULL;
    sr_result r = joint_matrices(d, skin, use, &c);
    if (r != SR_OK) {
        return r;
    }
    if (src->joint_max >= c->count) {
        return sr__gltf_fail(d, SR_BAD_FORMAT,
                             "%s/attributes/JOINTS_%zu: element %zu names joint %zu, but "
                             "/skins/%ld has %zu joints (%s)", pptr, src->joint_max_set,
                             src->joint_max_vertex, src->joint_max, skin, c->count, use);
    }
    size_t n = p->vertex_count, work;
    if (!sr__mul_ok(n, src->influence_sets, &work) ||
        work > SR_SCENE_MAX_DRAWN_VERTICES - d->drawn_vertices) {
        return sr__gltf_fail(d, SR_TOO_LARGE, "%s: more than %zu vertices to draw in all", use,
                             SR_SCENE_MAX_DRAWN_VERTICES);
    }
    d->drawn_vertices += work;
    if ((r = sr__gltf_charge_posed(d, p, use)) != SR_OK) {
        return r;
    }
    float *pos = sr__scene_alloc(d->scene, n * 3 * sizeof *pos);
    float *nrm = p->normals ? sr__scene_alloc(d->scene, n * 3 * sizeof *nrm) : NULL;
    float *tan = p->tangents ? sr__scene_alloc(d->scene, n * 4 * sizeof *tan) : NULL;
    if (!pos || (p->normals && !nrm) || (p->tangents && !tan)) {
        return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory", use);
    }
    const float *in[3] = { p->positions, p->normals, p->tangents };
    float *out[3] = { pos, nrm, tan };
    size_t mirrored = sr__gltf_skin_vertices(c->matrices, src, n, in, out);
    static const float identity[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
    memcpy(p->world, identity, sizeof identity);
    /* The vertices are in world space now; a mirroring pose turns the
     * winding, decided by most of the vertices' blended matrices. */
    p->mirrored = 2 * mirrored > n;
    p->positions = pos;
    p->normals = nrm;
    p->tangents = tan;
    return SR_OK;
}

size_t sr__gltf_skin_vertices(const float *matrices, const gltf_pose_source *src, size_t n,
                              const float *const in[3], float *const out[3])
{
    float *pos = out[0], *nrm = out[1], *tan = out[2];
    size_t per = 4 * src->influence_sets, mirrored = 0;
    for (size_t i = 0; i < n; i++) {
        /* The blended matrix's upper three rows, column-major. */
        double b[12] = { 0 };
        for (size_t k = 0; k < per; k++) {
            double w = src->weights[i * per + k];
            if (w != 0) {
                add_weighted(b, matrices + 16 * (size_t)src->joints[i * per + k], w);
            }
        }
        const float *v = in[0] + 3 * i;
        for (int row = 0; row < 3; row++) {
            pos[3 * i + (size_t)row] =
                (float)(b[row] * v[0] + b[3 + row] * v[1] + b[6 + row] * v[2] + b[9 + row]);
        }
        /* Normals take the inverse transpose: its columns are the
         * cross products of the matrix's columns over the determinant. */
        double c0[3], c1[3], c2[3];
        cross(b + 3, b + 6, c0);
        cross(b + 6, b, c1);
        cross(b, b + 3, c2);
        double det = b[0] * c0[0] + b[1] * c0[1] + b[2] * c0[2];
        mirrored += det < 0;
        double sign = det < 0 ? -1 : 1;
        if (nrm) {
            const float *nv = in[1] + 3 * i;
            double o[3];
            for (int row = 0; row < 3; row++) {
                o[row] = sign * (c0[row] * nv[0] + c1[row] * nv[1] + c2[row] * nv[2]);
            }
            store_unit(o, nrm + 3 * i);
        }
        if (tan) {
            const float *tv = in[2] + 4 * i;
            double o[3];
            for (int row = 0; row < 3; row++) {
                o[row] = b[row] * tv[0] + b[3 + row] * tv[1] + b[6 + row] * tv[2];
            }
            store_unit(o, tan + 4 * i);
            tan[4 * i + 3] = tv[3];
        }
    }
    return mirrored;
}
