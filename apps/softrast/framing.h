/* framing.h - how `softrast render` frames and lights a model by default:
 * the model turned upright, the camera the library's sr_fit_camera places
 * (or, when it cannot, one that frames the bounding sphere) and near and
 * far planes that hug the scene (its lights are the library's
 * sr_default_lights).  Shared with softrast-bench so the benchmark draws
 * exactly what the tool draws. */
#ifndef SR_FRAMING_H
#define SR_FRAMING_H

#include "softrast.h"

/* A view along sr_framing_direction at the distance where the sphere
 * (centre, radius) fits fov_radians across the smaller image side with a
 * 4% margin: the fallback when sr_fit_camera cannot fit the points. */
sr_vec3 framing_default_eye(sr_vec3 centre, float radius, float fov_radians);

/* Near and far planes holding the sphere (centre, radius) seen from eye. */
void framing_near_far(sr_vec3 eye, sr_vec3 centre, float radius, float *near_z, float *far_z);

/* The rotation that turns a model whose up axis is `axis` (+x, -x, +y, -y,
 * +z, -z: 0..5) upright, its up axis along +y. */
sr_mat4 framing_upright(int axis);

#endif
