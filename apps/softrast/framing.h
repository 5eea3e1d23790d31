/* framing.h - how `softrast render` frames and lights a model by default:
 * the model turned upright, the camera placed so the model's projection
 * fills the image to a margin and near and far planes that hug the scene
 * (its lights are the library's sr_default_lights).  Shared with
 * softrast-bench so the benchmark draws exactly what the tool draws. */
#ifndef SR_FRAMING_H
#define SR_FRAMING_H

#include "softrast.h"

/* Default field of view across the smaller image side, degrees. */
#define FRAMING_FOV_DEG 35.0f

/* The default view direction, from the model towards the eye: a
 * three-quarter view from the front right, above. */
sr_vec3 framing_default_direction(void);

/* A view along framing_default_direction at the distance where the sphere
 * (centre, radius) fits fov_radians across the smaller image side with a
 * 4% margin: the fallback when framing_fit cannot fit the points. */
sr_vec3 framing_default_eye(sr_vec3 centre, float radius, float fov_radians);

/* The margin framing_fit keeps on each side of the image, a fraction of
 * the image's width or height. */
#define FRAMING_MARGIN 0.05f

/* Some vertices to frame: count x, y, z triples, placed by `model`. */
typedef struct framing_points {
    const float *xyz;
    size_t count;
    const sr_mat4 *model;
} framing_points;

typedef struct framing_view {
    sr_vec3 eye, target;
    float half_w, half_h;   /* ortho: the view volume's half extents at the target */
} framing_view;

/* The camera looking along -framing_default_direction() with up +y that
 * frames the points tightly in a width x height image with fov_radians
 * across its smaller side: the projected points span the image less
 * FRAMING_MARGIN on each side in the limiting dimension, and are centred
 * in the other.  Perspective (as sr_perspective projects with
 * sr_fit_fovy), or orthographic (half_w, half_h set; the eye where the
 * perspective camera would stand); the target is the point of the gaze
 * nearest `centre`.  False when the points give no frame (none, all in
 * one point, or not finite). */
bool framing_fit(const framing_points *sets, int set_count, sr_vec3 centre, float fov_radians,
                 int width, int height, bool ortho, framing_view *out);

/* Near and far planes holding the sphere (centre, radius) seen from eye. */
void framing_near_far(sr_vec3 eye, sr_vec3 centre, float radius, float *near_z, float *far_z);

/* The rotation that turns a model whose up axis is `axis` (+x, -x, +y, -y,
 * +z, -z: 0..5) upright, its up axis along +y. */
sr_mat4 framing_upright(int axis);

#endif
