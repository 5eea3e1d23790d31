/* svg_blend.c - the SVG reader's blend modes (mix-blend-mode, from CSS
 * Compositing and Blending): the color a layer's pixel takes over its
 * backdrop before it is composited source-over.  Pure functions; used by
 * svg.c and by feBlend (svg_filter.c). */
#include "io/svg.h"

#include <math.h>
#include <string.h>

static const char *const mode_names[SVG_BLEND_COUNT] = {
    "normal", "multiply", "screen", "overlay", "darken", "lighten", "color-dodge",
    "color-burn", "hard-light", "soft-light", "difference", "exclusion", "hue", "saturation",
    "color", "luminosity",
};

int svg_blend_mode(const char *name)
{
    for (int i = 0; i < SVG_BLEND_COUNT; i++) {
        if (strcmp(name, mode_names[i]) == 0) {
            return i;
        }
    }
    return -1;
}

static float hard_light(float b, float s)
{
    return s <= 0.5f ? b * 2 * s : b + (2 * s - 1) - b * (2 * s - 1); /* multiply : screen */
}

/* B(cb, cs) of a separable mode, one channel. */
static float separable(svg_blend_kind m, float b, float s)
{
    switch (m) {
    case SVG_BLEND_MULTIPLY: return b * s;
    case SVG_BLEND_SCREEN: return b + s - b * s;
    case SVG_BLEND_OVERLAY: return hard_light(s, b);
    case SVG_BLEND_DARKEN: return fminf(b, s);
    case SVG_BLEND_LIGHTEN: return fmaxf(b, s);
    case SVG_BLEND_COLOR_DODGE:
        return b <= 0 ? 0 : s >= 1 ? 1 : fminf(1, b / (1 - s));
    case SVG_BLEND_COLOR_BURN:
        return b >= 1 ? 1 : s <= 0 ? 0 : 1 - fminf(1, (1 - b) / s);
    case SVG_BLEND_HARD_LIGHT: return hard_light(b, s);
    case SVG_BLEND_SOFT_LIGHT: {
        if (s <= 0.5f) {
            return b - (1 - 2 * s) * b * (1 - b);
        }
        float d = b <= 0.25f ? ((16 * b - 12) * b + 4) * b : sqrtf(b);
        return b + (2 * s - 1) * (d - b);
    }
    case SVG_BLEND_DIFFERENCE: return fabsf(b - s);
    case SVG_BLEND_EXCLUSION: return b + s - 2 * b * s;
    default: return s;
    }
}

static float lum(const float c[3])
{
    return 0.3f * c[0] + 0.59f * c[1] + 0.11f * c[2];
}

static void clip_color(float c[3])
{
    float l = lum(c), n = fminf(c[0], fminf(c[1], c[2])), x = fmaxf(c[0], fmaxf(c[1], c[2]));
    for (int i = 0; i < 3; i++) {
        if (n < 0 && l - n > 0) {
            c[i] = l + (c[i] - l) * l / (l - n);
        }
        if (x > 1 && x - l > 0) {
            c[i] = l + (c[i] - l) * (1 - l) / (x - l);
        }
    }
}

static void set_lum(float c[3], float l)
{
    float d = l - lum(c);
    for (int i = 0; i < 3; i++) {
        c[i] += d;
    }
    clip_color(c);
}

static float sat(const float c[3])
{
    return fmaxf(c[0], fmaxf(c[1], c[2])) - fminf(c[0], fminf(c[1], c[2]));
}

static void set_sat(float c[3], float s)
{
    int mx = 0, mn = 0;
    for (int i = 1; i < 3; i++) {
        mx = c[i] > c[mx] ? i : mx;
        mn = c[i] < c[mn] ? i : mn;
    }
    if (mx == mn) {
        c[0] = c[1] = c[2] = 0;
        return;
    }
    int mid = 3 - mx - mn;
    float range = c[mx] - c[mn];
    c[mid] = (c[mid] - c[mn]) * s / range;
    c[mx] = s;
    c[mn] = 0;
}

void svg_blend_mix(svg_blend_kind mode, const float b[3], const float s[3], float r[3])
{
    if (mode >= SVG_BLEND_HUE) {
        float t[3];
        memcpy(t, mode == SVG_BLEND_LUMINOSITY ? b : s, sizeof t);
        if (mode == SVG_BLEND_HUE || mode == SVG_BLEND_SATURATION) {
            memcpy(t, mode == SVG_BLEND_HUE ? s : b, sizeof t);
            set_sat(t, sat(mode == SVG_BLEND_HUE ? b : s));
        }
        set_lum(t, lum(mode == SVG_BLEND_LUMINOSITY ? s : b));
        memcpy(r, t, sizeof t);
    } else {
        for (int i = 0; i < 3; i++) {
            r[i] = separable(mode, b[i], s[i]);
        }
    }
}

sr_rgba svg_blend_color(svg_blend_kind mode, const uint8_t backdrop[4], sr_rgba src)
{
    float b[3] = { backdrop[0] / 255.0f, backdrop[1] / 255.0f, backdrop[2] / 255.0f };
    float s[3] = { src.r, src.g, src.b }, r[3];
    svg_blend_mix(mode, b, s, r);
    /* Where the backdrop is transparent the source shows as it is. */
    float ab = backdrop[3] / 255.0f;
    return (sr_rgba){ (1 - ab) * s[0] + ab * r[0], (1 - ab) * s[1] + ab * r[1],
                      (1 - ab) * s[2] + ab * r[2], src.a };
}
