/* demo3d.h - shared by the 3D pipeline demos (gouraud-highlight,
 * perspective, zfight, normals, viewport, aa and the 3D half of clip): each
 * panel is a framebuffer, usually with a depth buffer, drawn by sr_draw and copied
 * into one labelled cell of a grid (demo3d_layout.h), optionally
 * magnified; plus the little geometry the scenes share. */
#ifndef SR_DEMO3D_H
#define SR_DEMO3D_H

#include "demo3d_layout.h"
#include "softrast.h"

#include <stdbool.h>
#include <stdint.h>

typedef struct demo3d {
    sr_context *ctx;
    const char *name;        /* for error messages */
    sr_framebuffer *out;     /* the whole image */
    demo3d_layout layout;
    int scale;               /* each panel pixel becomes scale x scale */
    int label_scale;         /* text size of the cell labels */
    sr_result error;         /* of the first blit that failed: finish reports it */
} demo3d;

/* Make the output image for `layout`; 0 or an exit status after one line.
 * scale 0 -> 1.  Labels are drawn at twice the font size when every label
 * in `labels` (count of them) fits a cell that way. */
int  demo3d_begin(demo3d *d, sr_context *ctx, const char *name, demo3d_layout layout,
                  int scale, const char *const *labels, int count);
/* A cell-sized panel framebuffer with the given depth format. */
sr_result demo3d_panel(demo3d *d, sr_depth_format depth, sr_framebuffer **out);
/* Copy `panel` (cell-sized) into cell `index` under `label`. */
void demo3d_blit(demo3d *d, int index, const sr_framebuffer *panel, const char *label);
/* Hand the image over (*out); returns EXIT_OK, or demo3d_fail's status
 * when a blit failed. */
int  demo3d_finish(demo3d *d, sr_framebuffer **out);
/* Report sr_context_error, free the image; returns EXIT_FAILURE_RUN. */
int  demo3d_fail(demo3d *d);

/* A UV sphere of radius 1 about the origin, y up: (stacks + 1) x
 * (slices + 1) vertices (positions = normals), counter-clockwise
 * triangles seen from outside.  Arrays are sized by the caller:
 * positions and normals 3 * demo3d_sphere_vertices floats, indices
 * 6 * stacks * slices entries. */
#define DEMO3D_SPHERE_VERTICES(stacks, slices) (((stacks) + 1) * ((slices) + 1))
#define DEMO3D_SPHERE_INDICES(stacks, slices) (6 * (stacks) * (slices))
void demo3d_sphere(int stacks, int slices, float *positions, float *normals, uint32_t *indices);

/* The pinhole (window) position of a world point under proj * view for
 * a viewport (x0, y0, w, h) - the divide and viewport S the pipeline does,
 * for 2D overlays.  false when the point is behind the eye. */
bool demo3d_project(const sr_mat4 *proj, const sr_mat4 *view, float x0, float y0, float w,
                    float h, sr_vec3 p, sr_point2 *out);

/* The 3D section of `softrast demo clip` (demo_clip3d.c), laid out as
 * DEMO3D_LAYOUT_CLIP at scale 1; 0 or an exit status after one line. */
int demo_clip3d_section(sr_context *ctx, sr_framebuffer **out);

#endif
