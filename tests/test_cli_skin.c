/* test_cli_skin.c - `softrast render` of a figure posed by a skin and
 * morph targets, the one tools/threejs-compare/make-assets.mjs writes as
 * skinned-figure.glb: a blue body bent at the chest, an orange arm swung
 * out and bent up at the elbow, a head stretched taller with a nose.
 * Drawn unposed, the body would lie on its back at x = 3 and the arm
 * float twice its size.  Compared with tests/ref/gltf_skinned_figure.png
 * within 3 codes on 0.5% of the pixels (test_images.c's tolerance:
 * libm), and the same bytes from one thread and from three. */
#include "batch_cli.h"
#include "gltf_write.h"

#include "softrast_io.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SLICES 24
#define STACKS 16
#define VERTS ((SLICES + 1) * (STACKS + 1))
#define PI 3.14159265358979

typedef struct bytes {
    uint8_t *p;
    size_t n;
} bytes;

static size_t put(bytes *b, const void *src, size_t count, size_t size)
{
    return gltf_put(b->p, &b->n, src, count, size);
}

/* make-assets.mjs's sphere: unit normals from the north pole down. */
static void sphere_normal(int i, int j, float *n)
{
    double th = PI * i / STACKS, ph = 2 * PI * j / SLICES;
    n[0] = (float)(sin(th) * sin(ph));
    n[1] = (float)cos(th);
    n[2] = (float)(sin(th) * cos(ph));
}

static size_t sphere_indices(bytes *b, size_t *count)
{
    size_t at = b->n;
    *count = 0;
    for (int i = 0; i < STACKS; i++) {
        for (int j = 0; j < SLICES; j++) {
            uint16_t a = (uint16_t)(i * (SLICES + 1) + j), c = (uint16_t)(a + SLICES + 1);
            if (i > 0) {
                uint16_t t[3] = { a, c, (uint16_t)(a + 1) };
                le_copy(b->p + b->n, t, 3, 2);
                b->n += 6, *count += 3;
            }
            if (i < STACKS - 1) {
                uint16_t t[3] = { (uint16_t)(a + 1), c, (uint16_t)(c + 1) };
                le_copy(b->p + b->n, t, 3, 2);
                b->n += 6, *count += 3;
            }
        }
    }
    b->n = (b->n + 3) & ~(size_t)3;
    return at;
}

static double smoothstep(double a, double b, double x)
{
    double t = fmin(1, fmax(0, (x - a) / (b - a)));
    return t * t * (3 - 2 * t);
}

/* An ellipsoid about (0, cy, 0) of radii rx, ry, rx, skinned to joints
 * j0 and j1 (j1's weight rising from y0 to y1): its POSITION, NORMAL,
 * JOINTS_0 and WEIGHTS_0 offsets into at[0..4). */
static void ellipsoid(bytes *b, double cy, double rx, double ry, int j0, int j1, double y0,
                      double y1, size_t at[4])
{
    float pos[3 * VERTS], nrm[3 * VERTS], wts[4 * VERTS];
    uint8_t jts[4 * VERTS];
    for (int i = 0, v = 0; i <= STACKS; i++) {
        for (int j = 0; j <= SLICES; j++, v++) {
            float n[3];
            sphere_normal(i, j, n);
            pos[3 * v] = (float)(n[0] * rx);
            pos[3 * v + 1] = (float)(cy + n[1] * ry);
            pos[3 * v + 2] = (float)(n[2] * rx);
            double m[3] = { n[0] / rx, n[1] / ry, n[2] / rx };
            double l = sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
            for (int k = 0; k < 3; k++) {
                nrm[3 * v + k] = (float)(m[k] / l);
            }
            double w1 = smoothstep(y0, y1, cy + n[1] * ry);
            uint8_t jv[4] = { (uint8_t)j0, (uint8_t)j1, 0, 0 };
            float wv[4] = { (float)(1 - w1), (float)w1, 0, 0 };
            memcpy(jts + 4 * v, jv, 4);
            memcpy(wts + 4 * v, wv, sizeof wv);
        }
    }
    at[0] = put(b, pos, 3 * VERTS, 4);
    at[1] = put(b, nrm, 3 * VERTS, 4);
    at[2] = put(b, jts, 4 * VERTS, 1);
    at[3] = put(b, wts, 4 * VERTS, 4);
}

/* The figure as a .gltf (make-assets.mjs's figure()); malloc'd. */
static char *figure_model(void)
{
    bytes b = { malloc(VERTS * 200 + STACKS * SLICES * 12 + 1024), 0 };
    if (!b.p) {
        return NULL;
    }
    size_t body[4], arm[4], head[4], idx_count;
    ellipsoid(&b, 1, 0.35, 1, 0, 1, 0.8, 1.3, body);
    ellipsoid(&b, 2.4, 0.12, 0.65, 2, 3, 2.25, 2.55, arm);
    size_t idx = sphere_indices(&b, &idx_count);
    float hp[3 * VERTS], hn[3 * VERTS], tall[3 * VERTS], nose[3 * VERTS];
    for (int i = 0, v = 0; i <= STACKS; i++) {
        for (int j = 0; j <= SLICES; j++, v++) {
            sphere_normal(i, j, hn + 3 * v);
            for (int k = 0; k < 3; k++) {
                hp[3 * v + k] = hn[3 * v + k] * 0.32f;
                tall[3 * v + k] = nose[3 * v + k] = 0;
            }
            tall[3 * v + 1] = 0.5f * 0.32f * hn[3 * v + 1];
            float nz = hn[3 * v + 2];
            nose[3 * v + 2] = nz > 0.85f ? 0.25f * (nz - 0.85f) / 0.15f : 0;
        }
    }
    head[0] = put(&b, hp, 3 * VERTS, 4);
    head[1] = put(&b, hn, 3 * VERTS, 4);
    head[2] = put(&b, tall, 3 * VERTS, 4);
    head[3] = put(&b, nose, 3 * VERTS, 4);
    float ibm[64] = { 0 };
    const float ibm_y[4] = { 0, -1, -1.75f, -2.4f };
    for (int j = 0; j < 4; j++) {
        ibm[16 * j] = ibm[16 * j + 5] = ibm[16 * j + 10] = ibm[16 * j + 15] = 1;
        ibm[16 * j + 13] = ibm_y[j];
    }
    size_t ibm_at = put(&b, ibm, 64, 4);
    char *b64 = malloc(4 * (b.n / 3 + 1) + 1);
    char *json = b64 ? malloc(4 * (b.n / 3 + 1) + 8192) : NULL;
    if (!json) {
        free(b.p);
        free(b64);
        return NULL;
    }
    gltf_base64(b.p, b.n, b64);
    /* Quaternions of turns about +z by 15, -110 and 60 degrees, and of
     * 90 degrees about +x. */
    double q15 = 7.5 * PI / 180, q110 = -55 * PI / 180, q60 = 30 * PI / 180;
    sprintf(json,
            "{\"asset\":{\"version\":\"2.0\"},"
            "\"buffers\":[{\"byteLength\":%zu,\"uri\":\"data:application/octet-stream;base64,%s\"}],"
            "\"bufferViews\":[{\"buffer\":0,\"byteLength\":%zu}],"
            "\"accessors\":["
            /* 0-3 body, 4-7 arm */
            "{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5126,\"count\":%d,\"type\":\"VEC3\"},"
            "{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5126,\"count\":%d,\"type\":\"VEC3\"},"
            "{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5121,\"count\":%d,\"type\":\"VEC4\"},"
            "{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5126,\"count\":%d,\"type\":\"VEC4\"},"
            "{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5126,\"count\":%d,\"type\":\"VEC3\"},"
            "{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5126,\"count\":%d,\"type\":\"VEC3\"},"
            "{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5121,\"count\":%d,\"type\":\"VEC4\"},"
            "{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5126,\"count\":%d,\"type\":\"VEC4\"},"
            /* 8 indices, 9-12 head, 13 inverse binds */
            "{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5123,\"count\":%zu,\"type\":\"SCALAR\"},"
            "{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5126,\"count\":%d,\"type\":\"VEC3\"},"
            "{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5126,\"count\":%d,\"type\":\"VEC3\"},"
            "{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5126,\"count\":%d,\"type\":\"VEC3\"},"
            "{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5126,\"count\":%d,\"type\":\"VEC3\"},"
            "{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5126,\"count\":4,\"type\":\"MAT4\"}],"
            "\"nodes\":[{\"children\":[1]},"
            "{\"translation\":[0,1,0],\"rotation\":[0,0,%.17g,%.17g],\"children\":[2,6]},"
            "{\"translation\":[0,0.75,0],\"rotation\":[0,0,%.17g,%.17g],\"children\":[3]},"
            "{\"translation\":[0,0.65,0],\"rotation\":[0,0,%.17g,%.17g]},"
            "{\"mesh\":0,\"skin\":0,\"translation\":[3,0,0],"
            "\"rotation\":[0.70710678118654752,0,0,0.70710678118654752]},"
            "{\"mesh\":1,\"skin\":0,\"scale\":[2,2,2]},"
            "{\"mesh\":2,\"translation\":[0,1.3,0],\"weights\":[0.5,1]}],"
            "\"scenes\":[{\"nodes\":[0,4,5]}],\"scene\":0,"
            "\"skins\":[{\"joints\":[0,1,2,3],\"inverseBindMatrices\":13,\"skeleton\":0}],"
            "\"meshes\":["
            "{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1,\"JOINTS_0\":2,"
            "\"WEIGHTS_0\":3},\"indices\":8,\"material\":0}]},"
            "{\"primitives\":[{\"attributes\":{\"POSITION\":4,\"NORMAL\":5,\"JOINTS_0\":6,"
            "\"WEIGHTS_0\":7},\"indices\":8,\"material\":1}]},"
            "{\"primitives\":[{\"attributes\":{\"POSITION\":9,\"NORMAL\":10},\"indices\":8,"
            "\"material\":2,\"targets\":[{\"POSITION\":11},{\"POSITION\":12}]}],"
            "\"weights\":[0.3,0]}],"
            "\"materials\":["
            "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.15,0.3,0.8,1],"
            "\"metallicFactor\":0,\"roughnessFactor\":0.6}},"
            "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.9,0.45,0.15,1],"
            "\"metallicFactor\":0,\"roughnessFactor\":0.5}},"
            "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.95,0.72,0.58,1],"
            "\"metallicFactor\":0,\"roughnessFactor\":0.7}}]}",
            b.n, b64, b.n, body[0], VERTS, body[1], VERTS, body[2], VERTS, body[3], VERTS,
            arm[0], VERTS, arm[1], VERTS, arm[2], VERTS, arm[3], VERTS, idx, idx_count, head[0],
            VERTS, head[1], VERTS, head[2], VERTS, head[3], VERTS, ibm_at, sin(q15), cos(q15),
            sin(q110), cos(q110), sin(q60), cos(q60));
    free(b64);
    free(b.p);
    return json;
}

SR_TEST(skinned_and_morphed_figure_is_drawn_posed)
{
    NEED_CLI();
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson");
    }
    check_model_render("skinned_figure", "figure.gltf", figure_model(), "160x160", NULL,
                       "gltf_skinned_figure");
}
