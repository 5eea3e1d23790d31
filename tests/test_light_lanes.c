/* test_light_lanes.c - sr__light_lanes, the four-lane lighting of the
 * Gouraud vertex stage and the Phong vector kernel, against sr__light, the
 * scalar function it restates: the same bits in every lane for random
 * states (directional and point lights, a local viewer or not, specular
 * or not, whole-number shininess) and inputs that reach every branch of
 * the scalar code - normals of zero length or facing away, a point light
 * at the vertex, the eye at the vertex, NaN. */
#include "sr_test.h"
#include "pipeline.h"
#include "fragment/light_lanes.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static float frand(float lo, float hi)
{
    return lo + (hi - lo) * (float)rand() / (float)RAND_MAX;
}

/* Same bits, or both NaN (a NaN's payload is not part of the contract). */
static bool same(float a, float b)
{
    return memcmp(&a, &b, sizeof a) == 0 || (isnan(a) && isnan(b));
}

/* A vertex: mostly ordinary, sometimes one of the scalar code's edge
 * cases. */
static void make_vertex(int kind, const sr_draw_state *ds, float n[3], float eye[3], float c[4])
{
    for (int k = 0; k < 3; k++) {
        n[k] = frand(-1, 1);
        eye[k] = frand(-3, 3);
    }
    for (int k = 0; k < 4; k++) {
        c[k] = frand(-0.2f, 1.2f);
    }
    switch (kind) {
    case 0: /* zero-length normal: n.l = 0, nothing but ambient */
        n[0] = n[1] = n[2] = 0.0f;
        break;
    case 1: /* at the first point light: zero light vector, skipped */
        for (int k = 0; k < 3; k++) {
            eye[k] = ds->lights[0].vec[k];
        }
        break;
    case 2: /* at the eye: the local viewer keeps v = (0, 0, 1) */
        eye[0] = eye[1] = eye[2] = 0.0f;
        break;
    case 3: /* NaN normal: the scalar code adds the NaN (n.l <= 0 is false) */
        n[1] = NAN;
        break;
    case 4: /* the normal facing the light's opposite way */
        for (int k = 0; k < 3; k++) {
            n[k] = -ds->lights[0].vec[k];
        }
        break;
    default:
        break;
    }
}

SR_TEST(four_lanes_give_sr_light_bits)
{
    static const int shininess[] = { 0, 1, 2, 7, 8, 32, 129 };
    srand(12345);
    long compared = 0, nan_lanes = 0;
    for (int s = 0; s < 400 && !sr_test_failed_now(); s++) {
        sr_draw_state ds;
        memset(&ds, 0, sizeof ds);
        for (int k = 0; k < 3; k++) {
            ds.ambient[k] = frand(0, 0.4f);
            ds.specular[k] = s % 3 == 0 ? 0.0f : frand(0, 1);
        }
        ds.local_viewer = s % 2;
        ds.shininess_int = shininess[s % 7];
        ds.shininess = (float)ds.shininess_int;
        ds.light_count = 1 + s % SR_MAX_LIGHTS;
        for (int i = 0; i < ds.light_count; i++) {
            sr_light_eye *lt = &ds.lights[i];
            lt->point = (s / 2 + i) % 2;
            for (int k = 0; k < 3; k++) {
                lt->vec[k] = frand(-2, 2);
                lt->color[k] = frand(0, 1.5f);
            }
            if (!lt->point) {
                float len = sqrtf(lt->vec[0] * lt->vec[0] + lt->vec[1] * lt->vec[1] +
                                  lt->vec[2] * lt->vec[2]);
                for (int k = 0; k < 3; k++) {
                    lt->vec[k] /= len;
                }
            }
        }
        for (int group = 0; group < 8; group++) {
            float n[4][3], eye[4][3], c[4][4];
            v4f vn[3], veye[3], vc[4], out[4];
            for (int lane = 0; lane < 4; lane++) {
                make_vertex(rand() % 10, &ds, n[lane], eye[lane], c[lane]);
                for (int k = 0; k < 3; k++) {
                    vn[k][lane] = n[lane][k];
                    veye[k][lane] = eye[lane][k];
                }
                for (int k = 0; k < 4; k++) {
                    vc[k][lane] = c[lane][k];
                }
            }
            sr__light_lanes(&ds, vn, veye, vc, out);
            for (int lane = 0; lane < 4; lane++) {
                float want[4];
                sr__light(&ds, n[lane], eye[lane], c[lane], want);
                for (int k = 0; k < 4; k++) {
                    if (!same(out[k][lane], want[k])) {
                        sr_test_fail(__FILE__, __LINE__, "state %d lane %d channel %d: %a, "
                                     "sr__light %a", s, lane, k, (double)out[k][lane],
                                     (double)want[k]);
                    }
                    compared++;
                }
                nan_lanes += isnan(want[0]);
            }
        }
    }
    CHECK_EQ(compared, 400L * 8 * 4 * 4);
    CHECK(nan_lanes > 0); /* the NaN case was reached */
}
