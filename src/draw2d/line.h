/* line.h - draw2d stage, internal: the 2D line rasterizers behind
 * sr_draw_line.  They consume a segment (1/256-px fixed point for the
 * aliased ones, doubles for the antialiased ones) and a clip rectangle,
 * and produce pixels through a plot callback, each pixel once, already
 * inside the rectangle.  sr_draw_line blends them; the tests collect them.
 * Pure functions of their arguments: any thread may call them.
 *
 * line.c      naive and incremental DDA, midpoint/Bresenham (the exact
 *             diamond-exit closed form and its integer fast path), wide
 *             aliased lines with butt, square and round caps
 * line_aa.c   Xiaolin Wu lines, exact area-coverage lines of any width
 * lineclip.c  Cohen-Sutherland and Liang-Barsky (public)
 *
 * Clipping never changes pixels: the clipper only bounds which major
 * steps are visited (with a margin), and every pixel is computed from the
 * original endpoints, so a clipped line draws exactly the pixels of the
 * unclipped one that lie inside the rectangle. */
#ifndef SR_DRAW2D_LINE_H
#define SR_DRAW2D_LINE_H

#include "softrast.h"

#include <stdbool.h>
#include <stdint.h>

/* Coordinates beyond +-SR__LINE_MAX_COORD px are refused (SR_TOO_LARGE):
 * in 1/256 px they stay below 2^48, so the one-off setup products of the
 * closed form (two 49-bit deltas times a 48-bit coordinate) fit in 128
 * bits and the per-step remainders fit in 64. */
#define SR__LINE_MAX_COORD 1e12

/* A clip rectangle in whole pixels: [x0, x1) x [y0, y1). */
typedef struct sr__irect { int x0, y0, x1, y1; } sr__irect;

/* Receives every pixel once; coverage in [0, 1] (1 for aliased lines). */
typedef void (*sr__plot_fn)(void *user, int x, int y, float coverage);

/* Endpoints snapped to 1/256 px (round to nearest even): a = start, b = end. */
typedef struct sr__line_q8 { int64_t ax, ay, bx, by; } sr__line_q8;

/* Visit every major step the line has, ignoring the clipper: the
 * unclipped reference the tests compare clipped lines against. */
#define SR__LINE_CLIP_NONE ((sr_line_clipper)99)

/* Snap a finite coordinate (|v| <= SR__LINE_MAX_COORD) to 1/256 px. */
int64_t sr__line_snap_q8(double v);

/* Midpoint/Bresenham: the diamond-exit closed form of docs/raster-rules.md §7.1
 * (D3D ties: a boundary point belongs to the smaller minor index; the end
 * pixel is left out).  Uses the integer fast path when both endpoints are
 * on pixel centres, unless `closed_form_only`. */
void sr__line_bresenham(const sr__line_q8 *l, sr__irect clip, sr_line_clipper clipper,
                        bool closed_form_only, sr__plot_fn plot, void *user);
/* The integer midpoint fast path alone; false (nothing plotted) unless
 * both endpoints are on pixel centres. */
bool sr__line_bresenham_centres(const sr__line_q8 *l, sr__irect clip, sr_line_clipper clipper,
                                sr__plot_fn plot, void *user);
/* DDA: one pixel per major step k whose centre lies in the half-open
 * major range [start, end), at minor index floor(v(centre)).
 * Naive: v = v_a + m (u - u_a) in double per step.  Incremental:
 * v += m in fixed point with 32 fraction bits. */
void sr__line_dda(const sr__line_q8 *l, bool incremental, sr__irect clip,
                  sr_line_clipper clipper, sr__plot_fn plot, void *user);
/* Wide aliased line: the Bresenham line offset by -(w-1)/2 along the
 * minor axis, each pixel widened into a run of w along the minor axis
 * (GL); square caps extend the segment by w/2, round caps add the pixels
 * whose centres lie in the disk of diameter w around each endpoint. */
void sr__line_wide(const sr__line_q8 *l, int w, sr_line_cap cap, sr__irect clip,
                   sr_line_clipper clipper, sr__plot_fn plot, void *user);

/* Xiaolin Wu: two pixels per major step, weighted by distance. */
void sr__line_wu(sr_point2 a, sr_point2 b, sr__irect clip, sr_line_clipper clipper,
                 sr__plot_fn plot, void *user);
/* The same line as its major steps (sr_line_steps): sr__line_wu draws
 * the pixels these steps mark drawn, with their coverage. */
void sr__line_wu_steps(sr_point2 a, sr_point2 b, sr__irect clip, sr_line_clipper clipper,
                       sr_line_step_fn step, void *user);
/* Exact area coverage of the width-w rectangle around a->b (with its
 * caps) inside each pixel square: sr__line_area plots the pixels that
 * sr__line_area_cells hands out as drawn (sr_line_area_pixels), from the
 * same walk.  `strip` (SR__LINE_AREA_STRIP_MAX points) receives each
 * row's strip, which the cells name. */
#define SR__LINE_AREA_STRIP_MAX 1040
void sr__line_area_cells(sr_point2 a, sr_point2 b, double width, sr_line_cap cap,
                         sr__irect clip, sr_line_clipper clipper, sr_line_area_fn cell,
                         void *user, sr_point2 *strip);
void sr__line_area(sr_point2 a, sr_point2 b, double width, sr_line_cap cap, sr__irect clip,
                   sr_line_clipper clipper, sr__plot_fn plot, void *user);

/* Clip a->b to [xmin, xmax] x [ymin, ymax] with the chosen clipper
 * (SR__LINE_CLIP_NONE: only reject non-finite input). */
bool sr__clip_line(sr_line_clipper clipper, double xmin, double ymin, double xmax, double ymax,
                   sr_point2 *a, sr_point2 *b);

#endif
