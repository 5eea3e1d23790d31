/* environment_studio.c - the built-in neutral studio (image-based light,
 * fragment stage): radiance as a function of direction, written into an
 * equirectangular image by bands of rows (any thread).  A grey room lit by
 * a large soft overhead panel and two softboxes, with a darker grey floor,
 * in the spirit of the "neutral" environments of glTF viewers: white
 * under it reads as light grey to white, and metals show recognisable
 * window-like highlights rather than a blank.  Colourless, so base colours
 * stay true.
 */
#include "fragment/environment.h"

#include <assert.h>

/* A rectangular light seen in direction `centre`: half extents as the
 * tangents of its half angles along `right` and along centre x right,
 * edges softened over `soft` of each half extent. */
typedef struct softbox {
    float centre[3], right[3];
    float half_u, half_v;
    float soft;
    float radiance;
} softbox;

static const softbox boxes[] = {
    /* the overhead key panel, tilted towards +Z (where a default camera stands) */
    { { 0.0f, 0.9578f, 0.2873f }, { 1.0f, 0.0f, 0.0f }, 0.70f, 0.45f, 0.35f, 2.2f },
    /* a tall softbox front left */
    { { -0.7518f, 0.2631f, 0.6014f }, { 0.6247f, 0.0f, 0.7809f }, 0.20f, 0.42f, 0.25f, 3.2f },
    /* a wider, dimmer one back right */
    { { 0.8345f, 0.2086f, -0.5100f }, { -0.5214f, 0.0f, -0.8533f }, 0.30f, 0.30f, 0.25f, 2.2f },
};

#define SKY_HORIZON   0.50f
#define SKY_ZENITH    0.62f
#define FLOOR_HORIZON 0.34f
#define FLOOR_NADIR   0.20f
#define HORIZON_BLEND 0.06f     /* the sky fades into the floor over |y| < this */

static float smoothstep(float e0, float e1, float x)
{
    float t = (x - e0) / (e1 - e0);
    t = t < 0.0f ? 0.0f : (t > 1.0f ? 1.0f : t);
    return t * t * (3.0f - 2.0f * t);
}

/* 1 inside |a| < half, fading to 0 over the outer `soft` part. */
static float soft_edge(float a, float half, float soft)
{
    return 1.0f - smoothstep(half * (1.0f - soft), half, fabsf(a));
}

float sr__studio_radiance(const float d[3])
{
    float y = d[1];
    float sky = SKY_HORIZON + (SKY_ZENITH - SKY_HORIZON) * (y > 0.0f ? y : 0.0f);
    float ground = FLOOR_HORIZON + (FLOOR_NADIR - FLOOR_HORIZON) * (y < 0.0f ? -y : 0.0f);
    float L = ground + (sky - ground) * smoothstep(-HORIZON_BLEND, HORIZON_BLEND, y);
    for (size_t b = 0; b < sizeof boxes / sizeof boxes[0]; b++) {
        const softbox *s = &boxes[b];
        const float *c = s->centre, *r = s->right;
        float dc = d[0] * c[0] + d[1] * c[1] + d[2] * c[2];
        if (dc <= 0.0f) {
            continue;
        }
        /* up = centre x right completes the panel's frame */
        float up[3] = { c[1] * r[2] - c[2] * r[1], c[2] * r[0] - c[0] * r[2],
                        c[0] * r[1] - c[1] * r[0] };
        /* gnomonic coordinates: where d meets the panel's plane at distance 1 */
        float pu = (d[0] * r[0] + d[1] * r[1] + d[2] * r[2]) / dc;
        float pv = (d[0] * up[0] + d[1] * up[1] + d[2] * up[2]) / dc;
        L += s->radiance * soft_edge(pu, s->half_u, s->soft) * soft_edge(pv, s->half_v, s->soft);
    }
    return L;
}

void sr__studio_rows(sr__equirect *e, int row0, int row1)
{
    enum { MAX_WIDTH = 1024 };
    assert(e->w <= MAX_WIDTH);
    float cos_phi[MAX_WIDTH], sin_phi[MAX_WIDTH];
    for (int i = 0; i < e->w; i++) {
        float phi = ((float)i + 0.5f) / (float)e->w * 2.0f * SR__PI - SR__PI;
        cos_phi[i] = cosf(phi);
        sin_phi[i] = sinf(phi);
    }
    for (int j = row0; j < row1; j++) {
        float theta = ((float)j + 0.5f) / (float)e->h * SR__PI;
        float st = sinf(theta), ct = cosf(theta);
        float *p = e->rgb + (size_t)j * e->w * 3;
        for (int i = 0; i < e->w; i++) {
            float d[3] = { st * cos_phi[i], ct, st * sin_phi[i] };
            float L = sr__studio_radiance(d);
            p[3 * i + 0] = L;
            p[3 * i + 1] = L;
            p[3 * i + 2] = L;
        }
    }
}
