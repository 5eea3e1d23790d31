/* view_camera.c - the orbit camera of `softrast view`: mouse drags and the
 * wheel turned into the eye, target and up that `softrast render --camera`
 * takes.  Azimuth and elevation are recomputed from the eye each time, so
 * the state is nothing but the three vectors a render command can repeat. */
#include "view.h"

#include <math.h>

#define DEG (3.14159265358979f / 180.0f)
#define ORBIT_DEG_PER_PIXEL 0.25f
#define MAX_ELEVATION_DEG 89.0f   /* never straight along up: the frame stays defined */
#define ZOOM_PER_NOTCH 0.9f

void view_camera_init(view_camera *c, const render_job *job)
{
    render_job_camera(job, &c->home_eye, &c->home_target, &c->home_up);
    render_job_bounds(job, &c->centre, &c->radius);
    c->fov = render_job_fov(job);
    if (!(c->radius > 0.0f)) {
        c->radius = 1.0f;
    }
    view_camera_reset(c);
}

void view_camera_reset(view_camera *c)
{
    c->eye = c->home_eye;
    c->target = c->home_target;
    c->up = c->home_up;
}

static sr_vec3 orbit_point(sr_vec3 target, float dist, float az, float el)
{
    return sr_vec3_add(target, (sr_vec3){ dist * cosf(el) * sinf(az), dist * sinf(el),
                                          dist * cosf(el) * cosf(az) });
}

void view_camera_orbit(view_camera *c, float dx, float dy)
{
    sr_vec3 off = sr_vec3_sub(c->eye, c->target);
    float dist = sr_vec3_length(off);
    if (!(dist > 0.0f)) {
        return;
    }
    float az = atan2f(off.x, off.z), el = asinf(fmaxf(-1.0f, fminf(1.0f, off.y / dist)));
    /* Dragging right turns the model right: the eye goes left. */
    az -= dx * ORBIT_DEG_PER_PIXEL * DEG;
    el += dy * ORBIT_DEG_PER_PIXEL * DEG;
    el = fmaxf(-MAX_ELEVATION_DEG * DEG, fminf(MAX_ELEVATION_DEG * DEG, el));
    c->eye = orbit_point(c->target, dist, az, el);
    c->up = (sr_vec3){ 0, 1, 0 };
}

void view_camera_pan(view_camera *c, float dx, float dy, int short_side)
{
    sr_vec3 w = sr_vec3_sub(c->eye, c->target);
    float dist = sr_vec3_length(w);
    if (!(dist > 0.0f) || short_side < 1) {
        return;
    }
    w = sr_vec3_scale(w, 1.0f / dist);
    sr_vec3 u = sr_vec3_normalize(sr_vec3_cross(c->up, w));
    sr_vec3 v = sr_vec3_cross(w, u);
    /* World units per pixel in the plane of the target. */
    float s = 2.0f * dist * tanf(c->fov * 0.5f) / (float)short_side;
    sr_vec3 move = sr_vec3_add(sr_vec3_scale(u, -dx * s), sr_vec3_scale(v, dy * s));
    c->eye = sr_vec3_add(c->eye, move);
    c->target = sr_vec3_add(c->target, move);
}

void view_camera_zoom(view_camera *c, float notches)
{
    sr_vec3 off = sr_vec3_sub(c->eye, c->target);
    float dist = sr_vec3_length(off);
    if (!(dist > 0.0f)) {
        return;
    }
    float nd = dist * powf(ZOOM_PER_NOTCH, notches);
    /* Stay outside a tiny sphere around the target and within reach. */
    nd = fmaxf(c->radius * 0.02f, fminf(c->radius * 200.0f, nd));
    c->eye = sr_vec3_add(c->target, sr_vec3_scale(off, nd / dist));
}

void view_camera_fit(view_camera *c)
{
    sr_vec3 dir = sr_vec3_normalize(sr_vec3_sub(c->eye, c->target));
    if (sr_vec3_length(dir) == 0.0f) {
        dir = (sr_vec3){ 0, 0, 1 };
    }
    /* The distance framing_default_eye uses: the sphere fills the smaller
     * side with a 4% margin. */
    float dist = c->radius / sinf(c->fov * 0.5f) * 1.04f;
    c->target = c->centre;
    c->eye = sr_vec3_add(c->centre, sr_vec3_scale(dir, dist));
}
