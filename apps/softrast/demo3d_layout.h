/* demo3d_layout.h - where the panels of the 3D pipeline demos sit in
 * their images.  Shared by the demos (demo3d.c) and by
 * tests/test_demo3d.c, which measures each phenomenon inside the panels
 * it knows the position of.  Header only, no library calls. */
#ifndef SR_DEMO3D_LAYOUT_H
#define SR_DEMO3D_LAYOUT_H

#define DEMO3D_GAP 12      /* output pixels between cells and around the grid */
#define DEMO3D_LABEL_H 28  /* output pixels above each cell for its label */

/* A grid of cols x rows cells, each a cell_w x cell_h panel (before the
 * --scale magnification), filled row by row. */
typedef struct demo3d_layout {
    int cols, rows, cell_w, cell_h;
} demo3d_layout;

/* The layouts of the 3D demos (panel order in each demo's file comment). */
#define DEMO3D_LAYOUT_GOURAUD     ((demo3d_layout){ 2, 2, 300, 210 })
#define DEMO3D_LAYOUT_PERSPECTIVE ((demo3d_layout){ 2, 2, 300, 210 })
#define DEMO3D_LAYOUT_ZFIGHT      ((demo3d_layout){ 3, 5, 220, 124 })
#define DEMO3D_LAYOUT_NORMALS     ((demo3d_layout){ 2, 2, 300, 210 })
#define DEMO3D_LAYOUT_VIEWPORT    ((demo3d_layout){ 3, 2, 236, 224 })
/* `softrast demo aa`: small panels shown magnified (DEMO3D_AA_SCALE by
 * default) so the pixels show. */
#define DEMO3D_LAYOUT_AA          ((demo3d_layout){ 4, 3, 64, 36 })
#define DEMO3D_AA_SCALE 5
#define DEMO3D_LAYOUT_PAINTER      ((demo3d_layout){ 2, 2, 300, 210 })
#define DEMO3D_LAYOUT_ORIENTATION  ((demo3d_layout){ 3, 2, 200, 200 })
#define DEMO3D_LAYOUT_DEPTH_RANGE  ((demo3d_layout){ 2, 2, 300, 210 })
/* The 3D section under the 2D panels of `softrast demo clip` (not scaled). */
#define DEMO3D_LAYOUT_CLIP        ((demo3d_layout){ 2, 2, 300, 210 })

static inline int demo3d_grid_width(demo3d_layout l, int scale)
{
    return l.cols * l.cell_w * scale + (l.cols + 1) * DEMO3D_GAP;
}

static inline int demo3d_grid_height(demo3d_layout l, int scale)
{
    return l.rows * (l.cell_h * scale + DEMO3D_LABEL_H) + (l.rows + 1) * DEMO3D_GAP;
}

/* Top-left output pixel of cell `index` (row-major) of a grid whose top
 * edge is at output row `top`. */
static inline void demo3d_cell_origin(demo3d_layout l, int scale, int top, int index,
                                      int *x, int *y)
{
    *x = DEMO3D_GAP + (index % l.cols) * (l.cell_w * scale + DEMO3D_GAP);
    *y = top + DEMO3D_GAP + (index / l.cols) * (l.cell_h * scale + DEMO3D_LABEL_H + DEMO3D_GAP) +
         DEMO3D_LABEL_H;
}

#endif
