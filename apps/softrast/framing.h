/* framing.h - how `softrast render` frames and lights a model by default:
 * the camera position for a bounding sphere, near and far planes that hug
 * the scene, and the camera-relative key/fill/rim lights.  Shared with
 * softrast-bench so the benchmark draws exactly what the tool draws. */
#ifndef SR_FRAMING_H
#define SR_FRAMING_H

#include "softrast.h"

/* Default field of view across the smaller image side, degrees. */
#define FRAMING_FOV_DEG 35.0f

/* A three-quarter view from the front right, above, at the distance where
 * the sphere (centre, radius) fits fov_radians across the smaller image
 * side with a 4% margin. */
sr_vec3 framing_default_eye(sr_vec3 centre, float radius, float fov_radians);

/* Near and far planes holding the sphere (centre, radius) seen from eye. */
void framing_near_far(sr_vec3 eye, sr_vec3 centre, float radius, float *near_z, float *far_z);

/* The rotation that turns a model whose up axis is `axis` (+x, -x, +y, -y,
 * +z, -z: 0..5) upright, its up axis along +y. */
sr_mat4 framing_upright(int axis);

/* Key, fill and rim lights placed relative to the camera basis, so whatever
 * the view, the side facing the viewer is lit from the upper left and the
 * silhouette stands out from the background.  Writes 3 lights. */
int framing_default_lights(const sr_camera_basis *b, sr_light *lights);

#endif
