/*
 * softrast.h - a CPU graphics pipeline in C11.
 *
 * softrast is the raster pipeline of a graphics course made exact: object
 * coordinates go through the model, camera and projection matrices (M_O, E,
 * P), are clipped in homogeneous clip space (or, on request, in view space
 * against the six planes of the view volume), divided by w, mapped to pixels
 * by the viewport matrix S, snapped to 8 sub-pixel bits and scan-converted
 * with integer edge functions under the top-left fill rule.  Attributes are
 * interpolated perspective-correctly, depth is tested against a z-buffer,
 * and fragments are shaded flat, Gouraud or Phong.
 *
 * What it does not do: it opens no windows, reads no files (see
 * softrast_io.h for that) and never prints.  It depends on libc, libm and
 * pthreads only.
 *
 * Lines follow the diamond-exit rule (a segment covers a pixel when it
 * leaves the diamond |x - x_c| + |y - y_c| < 1/2 around the pixel's centre;
 * the last pixel is not drawn, so strips join without gaps or doubles);
 * points are squares covering the pixel centres inside them.
 *
 * Use: a complete program (examples/hello.c, which the tests build, run
 * and compare with this text).
 *
 *     #include <softrast.h>
 *
 *     #include <stdio.h>
 *
 *     int main(int argc, char **argv)
 *     {
 *         const char *path = argc > 1 ? argv[1] : "hello.ppm";
 *         enum { W = 64, H = 48 };
 *         sr_context *ctx;
 *         if (sr_make_context(&(sr_context_desc){0}, &ctx) != SR_OK) {
 *             return 1;
 *         }
 *         sr_framebuffer *fb = NULL;
 *         sr_framebuffer_desc fb_desc = { .width = W, .height = H };  // depth D24 by default
 *         sr_result r = sr_make_framebuffer(ctx, &fb_desc, &fb);
 *         if (r == SR_OK) {
 *             // Color to dark gray; depth to the far value, ready for the LESS test.
 *             sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0.1f, 0.1f, 0.1f, 1 } });
 *             const float xyz[] = { -0.8f, -0.8f, 0, 0.8f, -0.8f, 0, 0, 0.8f, 0 };
 *             const float rgb[] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
 *             // A zeroed state draws unlit, depth-tested, every channel written.
 *             r = sr_draw(ctx, fb, &(sr_state){0},
 *                         &(sr_draw_desc){ .positions = xyz, .vertex_count = 3,
 *                                          .colors = rgb, .color_size = 3 });
 *         }
 *         if (r == SR_OK) {
 *             const uint8_t *rgba = sr_framebuffer_pixels(fb);  // row 0 at the top
 *             FILE *f = fopen(path, "wb");
 *             if (f) {
 *                 fprintf(f, "P6\n%d %d\n255\n", W, H);
 *                 for (int i = 0; i < W * H; i++) {
 *                     fwrite(rgba + 4 * i, 1, 3, f);
 *                 }
 *             }
 *             if (!f || fclose(f) != 0) {
 *                 perror(path);
 *                 r = SR_IO_ERROR;
 *             }
 *         } else {
 *             fprintf(stderr, "hello: %s\n", sr_context_error(ctx));
 *         }
 *         sr_destroy_framebuffer(ctx, fb);
 *         sr_destroy_context(ctx);
 *         return r == SR_OK ? 0 : 1;
 *     }
 *
 * API map: every function, one a line, in the order of the sections below.
 *
 *   results
 *     sr_result_name             the enum name of a result ("SR_OUT_OF_MEMORY")
 *     sr_result_text             what a result means ("allocation failed")
 *     sr_last_error              the message of this thread's last failed call
 *     sr_set_last_error          sets or clears that message
 *   math
 *     sr_vec3_make               a vector from x, y, z
 *     sr_vec3_add                a + b
 *     sr_vec3_sub                a - b
 *     sr_vec3_scale              a * s
 *     sr_vec3_dot                a . b
 *     sr_vec3_cross              a x b
 *     sr_vec3_length             |a|
 *     sr_vec3_normalize          a / |a| (zero stays zero)
 *     sr_mat4_identity           I
 *     sr_mat4_mul                a * b
 *     sr_mat4_mul_vec4           m * v
 *     sr_mat4_transpose          m^T
 *     sr_mat4_invert             m^-1, false if singular
 *     sr_mat4_translate          model transform: translation
 *     sr_mat4_scale              model transform: scaling
 *     sr_mat4_rotate             model transform: rotation about an axis
 *     sr_camera_frame            the camera basis u, v, w from eye, gaze and up
 *     sr_camera_matrix           the camera matrix E from that basis
 *     sr_look_at                 E looking from an eye at a target
 *     sr_ortho                   orthographic projection P
 *     sr_frustum                 perspective projection P from a frustum
 *     sr_perspective             perspective projection P from a field of view
 *     sr_fit_fovy                the vertical field of view that fits a viewport
 *     sr_viewport_matrix         the viewport matrix S
 *     sr_normal_matrix           inverse transpose of a model-view matrix
 *   context
 *     sr_make_context            a context: allocator, threads, error message
 *     sr_destroy_context         frees it and everything made on it
 *     sr_context_error           the message of the last failed call
 *     sr_context_threads         how many threads draw
 *     sr_context_arena_peak      the high-water mark of its fixed arena
 *     sr_run_jobs                runs independent jobs on its threads
 *     sr_context_simd            which vector kernels it runs
 *   framebuffers
 *     sr_make_framebuffer        color, depth, stencil; optionally multisampled
 *     sr_destroy_framebuffer     frees it
 *     sr_framebuffer_width       its width
 *     sr_framebuffer_height      its height
 *     sr_framebuffer_depth_format  its depth format
 *     sr_framebuffer_samples     its samples per pixel
 *     sr_framebuffer_has_stencil whether it has a stencil buffer
 *     sr_framebuffer_pixels      its RGBA8 pixels, read-only
 *     sr_sample_position         where sample i of an n-sample pixel lies
 *     sr_resolve                 multisampled -> single-sampled, box average
 *     sr_clear                   clear, or keep, color, depth and stencil
 *     sr_read_pixels             copy out a rectangle of RGBA8
 *     sr_write_pixels            copy a rectangle of RGBA8 in
 *     sr_read_depth              copy out depth as floats
 *     sr_read_stencil            copy out stencil values
 *     sr_render_bands            a frame drawn band by band, each band to a callback
 *   textures
 *     sr_make_texture            a mipmapped texture from RGBA8 pixels
 *     sr_destroy_texture         frees it
 *     sr_texture_levels          its number of mip levels
 *   supersampling
 *     sr_downsample              a supersampled image filtered down
 *   tone mapping
 *     sr_tonemap                 linear float pixels to RGBA8 sRGB: exposure, curve, encode
 *     sr_tonemap_rgb             one colour through a tone curve
 *     sr_srgb_encode8            a display-linear value to its 8-bit sRGB code
 *   image-based light
 *     sr_make_environment        an equirectangular or built-in environment, prefiltered
 *     sr_destroy_environment     frees it
 *     sr_environment_irradiance  diffuse light for a normal, as E/pi
 *     sr_environment_irradiance4 the same for 4 normals
 *     sr_environment_specular    prefiltered radiance for a direction and roughness
 *     sr_environment_specular4   the same for 4 directions and roughnesses
 *     sr_environment_background  the environment seen in a direction, sharp or blurred
 *     sr_brdf_table              the split-sum BRDF scale and bias
 *     sr_brdf_table4             the same for 4 (N.V, roughness) pairs
 *   programmable stages
 *     sr_make_builtin_program    a built-in shading model as a program
 *     sr_builtin_program         the sr_program to draw it with
 *     sr_destroy_builtin_program frees it
 *   physically based shading
 *     sr_pbr_default_material    glTF's default material
 *     sr_texture_slot_uv         texture coordinates through a slot's KHR_texture_transform
 *     sr_default_lights          softrast render's key, fill and rim lights for a camera
 *     sr_pbr_default_lighting    those lights as radiance, and its sky and ground
 *     sr_pbr_scene_lights        a scene's own lights in their place, or before them
 *     sr_make_pbr_program        the metallic-roughness model as a program
 *     sr_pbr_program             the sr_program to draw it with
 *     sr_destroy_pbr_program     frees it
 *   drawing
 *     sr_draw                    primitives through the whole pipeline
 *     sr_last_draw_info          counts of the last draw
 *   vertex buffers
 *     sr_make_buffer             a copy of vertex or index data on the context
 *     sr_destroy_buffer          frees it
 *     sr_buffer_update           overwrite a range of it
 *     sr_buffer_data             its memory
 *     sr_buffer_size             its size in bytes
 *   meshes
 *     sr_make_mesh               a copy of caller arrays as a mesh on the context
 *     sr_destroy_mesh            frees a mesh's arrays
 *     sr_mesh_compute_normals    smooth or flat normals
 *     sr_mesh_compute_tangents   tangents for normal maps (MikkTSpace conventions)
 *     sr_sort_back_to_front      triangles in blending order, farthest first
 *     sr_mean_view_depth         a mesh's mean distance from the eye, to order meshes
 *     sr_order_back_to_front     meshes in blending order by those distances
 *     sr_mesh_bounds             the axis-aligned bounding box
 *     sr_newell_normal           a polygon's normal by Newell's method
 *   built-in geometry
 *     sr_make_bezier_mesh        bicubic Bezier patches tessellated
 *     sr_make_teapot             the Utah teapot
 *     sr_make_ground_mesh        a ground plane under a scene's bounds
 *   framing
 *     sr_framing_direction       the default view direction, model towards eye
 *     sr_fit_camera              the default camera: vertices fitted to an image
 *   shadows
 *     sr_make_shadow_map         a directional light's shadow map fitted to bounds
 *     sr_destroy_shadow_map      frees it
 *     sr_shadow_map_clear        empties it for a new frame
 *     sr_shadow_map_draw         occluders into it, their depth
 *     sr_query_shadow_map        its light matrices and texel size
 *     sr_shadow_visibility       how lit a world-space point is, filtered
 *     sr_shadow_visibility4      the same for the four lanes of a fragment quad
 *     sr_draw_shadow_catcher     a ground showing only the shadow, over the image
 *   2D raster API
 *     sr_draw_text               a label in the built-in 5x7 font
 *     sr_text_width              its width in pixels
 *   2D polygon fill
 *     sr_fill_polygon            a polygon, aliased or antialiased
 *     sr_polygon_coverage        its coverage as a mask
 *     sr_draw_coverage           a color blended through a mask
 *     sr_draw_layer              an RGBA8 image blended through a mask
 *   region filling
 *     sr_flood_fill              recolor the region matching a pixel
 *     sr_boundary_fill           recolor up to a boundary color
 *   blur
 *     sr_blur_image              Gaussian blur of a float image, in place
 *   2D polygon clipping
 *     sr_clip_polygon_rect       Sutherland-Hodgman against a rectangle
 *     sr_clip_polygon_convex     Sutherland-Hodgman against a convex window
 *   curves
 *     sr_draw_ellipse            midpoint ellipse, outline or filled
 *     sr_draw_circle             midpoint circle, outline or filled
 *     sr_fill_implicit           the region F(x, y) < 0
 *     sr_flatten_quadratic       a quadratic Bezier as points
 *     sr_flatten_cubic           a cubic Bezier as points
 *     sr_flatten_arc             an SVG arc as points
 *   Gouraud-shaded 2D polygons
 *     sr_fill_triangle_gouraud   a triangle with a color at each vertex
 *     sr_fill_polygon_gouraud    a polygon with a color at each vertex
 *     sr_fill_gouraud            either, direct or incremental (FillPoly)
 *   paths and strokes
 *     sr_make_path               an empty path
 *     sr_destroy_path            frees it
 *     sr_path_clear              empties it
 *     sr_path_move_to            starts a subpath
 *     sr_path_line_to            a line
 *     sr_path_quad_to            a quadratic Bezier
 *     sr_path_cubic_to           a cubic Bezier
 *     sr_path_arc_to             an SVG arc
 *     sr_path_close              closes the subpath
 *     sr_path_polygon            the flattened path as a polygon
 *     sr_path_subpath_closed     whether a subpath was closed
 *     sr_path_length             its flattened length
 *     sr_path_dash               its dashes, as SVG's stroke-dasharray
 *     sr_path_cull_curves        curves far outside a view taken as lines
 *     sr_path_length_in_view     its length within a view
 *     sr_path_dash_in_view       its dashes within a view
 *     sr_fill_path               fills it
 *     sr_fill_path_paint         fills it with a gradient or a pattern
 *     sr_fill_polygon_paint      a polygon so filled
 *     sr_stroke_path             strokes it
 *     sr_make_stroke_outline     the stroke's outline polygon
 *     sr_destroy_stroke_outline  frees that outline
 *   2D lines
 *     sr_draw_line               a segment by one of the line algorithms
 *     sr_line_steps              a Wu line's steps: the two pixels and weights of each
 *     sr_line_area_pixels        an area-sampled line's pixels and their covered areas
 *     sr_smooth_line_pixels      a smooth 3D line's pixels and their coverage
 *     sr_clip_line_cohen_sutherland  Cohen-Sutherland clipping to a rectangle
 *     sr_clip_line_liang_barsky  Liang-Barsky clipping to a rectangle
 *
 * Conventions:
 *  - Descriptor structs: a field left at zero takes its documented default,
 *    so `{0}` is always valid where a desc is optional, and means what a
 *    first program wants: a zeroed sr_clear_desc clears depth to the far
 *    value, a zeroed sr_state tests and writes depth and every channel.
 *    Features that are on unless turned off are sr_switch fields (SR_OFF).
 *  - Lifecycle: what the caller owns is made by sr_make_X and released by
 *    sr_destroy_X(ctx, x) on the context that made it.
 *  - Framebuffer coordinates: x right, y down, row 0 at the top (PNG order).
 *    Pixel (x, y) covers [x, x+1) x [y, y+1); it is sampled at its centre.
 *  - Matrices are column-major float[16] (OpenGL layout): m[col*4 + row].
 *  - Clip space follows OpenGL (z_ndc in [-1, 1]) unless
 *    sr_state.depth_zero_to_one is set.
 *  - Triangles that look counter-clockwise on screen are front-facing by
 *    default (sr_state.front_face).
 *
 * Errors: every function that can fail returns an sr_result.  SR_OK is 0.
 * A failure comes with one line naming the function and the argument or
 * field that is wrong ("sr_sample_position: samples 3 must be 1, 2, 4, 8
 * or 16", "sr_framebuffer_desc.width must be > 0"), in two places:
 *  - sr_context_error(ctx), for a call given a context: until the next
 *    call on that context ("" after a success);
 *  - sr_last_error(), for any call, with or without a context (the calls
 *    that take none, sr_tonemap_rgb, sr_path_line_to on a NULL path, a
 *    failed sr_make_context, have only this one): the message of the
 *    calling thread's last failed call, softrast_io's included.  As with
 *    errno, only failures set it and a success leaves it as it was: read
 *    it when a call returns something other than SR_OK.  Each thread has
 *    its own (one for the whole program in the embedded profile, which
 *    has one thread).
 * Functions returning bool (sr_mat4_invert, sr_camera_frame...) answer a
 * question and set no message.  Nothing is drawn by a call that fails
 * validation.  A caller's image of
 * rows `stride` bytes apart (pixels, depth, masks, texels) must be
 * addressable: a stride so large that its last row would lie past the
 * end of memory is SR_INVALID_ARG too, before any byte is touched.
 *
 * Memory: every allocation this library makes goes through
 * sr_context_desc.allocator, meshes included (softrast_io.h says which of
 * its calls work in malloc'd memory).  Left
 * zero, blocks under 1 MiB come from malloc and larger ones are mapped with
 * their pages populated up front (cheaper than faulting them in one by
 * one).  A custom allocator is also called from the context's worker
 * threads, so it must be thread-safe.  Scratch memory for drawing is kept
 * across draw calls and freed with the context.
 *
 * Threads: a context and the framebuffers drawn with it are used by one
 * thread at a time.  Internally the front end works on chunks of
 * primitives and the back end on 128x128 screen tiles; sr_context_desc.threads
 * sets how many threads share that work.  The output is the same bytes for
 * any thread count, and for any of the three triangle rasterizers.
 *
 * Clears are deferred: sr_clear marks tiles; a tile is cleared when it is
 * next drawn, read or written (sr_framebuffer_pixels, sr_read_pixels,
 * sr_read_depth, sr_write_pixels carry out what is pending), so a pointer
 * from sr_framebuffer_pixels is valid until the next draw, clear or write.
 */
#ifndef SOFTRAST_H
#define SOFTRAST_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* SR_API marks the functions libsoftrast and libsoftrast-io export: the
 * libraries are built with every other symbol hidden, so only what this
 * header and softrast_io.h declare is visible to a program. */
#ifndef SR_API
#  if defined(__GNUC__)
#    define SR_API __attribute__((visibility("default")))
#  else
#    define SR_API
#  endif
#endif

#define SR_VERSION_MAJOR 0
#define SR_VERSION_MINOR 1
#define SR_VERSION_PATCH 0
#define SR_VERSION_STRING "0.1.0"

#define SR_MAX_FRAMEBUFFER_SIZE 8192
#define SR_MAX_LIGHTS 8

/* ---- results ------------------------------------------------------------ */

/* One list generates the enum and its strings, so they never drift apart. */
#define SR_RESULT_LIST(X)                                                   \
    X(OK,            "success")                                             \
    X(INVALID_ARG,   "invalid argument")                                    \
    X(OUT_OF_MEMORY, "allocation failed")                                   \
    X(TOO_LARGE,     "size exceeds a documented limit")                     \
    X(UNSUPPORTED,   "feature not supported by this build")                 \
    X(IO_ERROR,      "file could not be read or written")                   \
    X(BAD_FORMAT,    "malformed input data")

typedef enum sr_result {
#define SR__X(name, text) SR_##name,
    SR_RESULT_LIST(SR__X)
#undef SR__X
    SR_RESULT_COUNT
} sr_result;

SR_API const char *sr_result_name(sr_result r); /* "SR_OUT_OF_MEMORY" */
SR_API const char *sr_result_text(sr_result r); /* "allocation failed" */
/* The message of the last call on this thread that failed, "" when none
 * has (see Errors above).  The string belongs to the thread: valid until
 * its next failure, sr_set_last_error, or the thread's end. */
SR_API const char *sr_last_error(void);
/* Sets this thread's message (cut to 511 bytes); NULL or "" clears it.
 * For libraries layered on softrast (softrast_io reports through it) and
 * for programs that clear it before a call, as with errno = 0. */
SR_API void sr_set_last_error(const char *message);

/* ---- math --------------------------------------------------------------- */

typedef struct sr_vec3 { float x, y, z; } sr_vec3;
typedef struct sr_vec4 { float x, y, z, w; } sr_vec4;
typedef struct sr_mat4 { float m[16]; } sr_mat4; /* column-major */
/* A NULL matrix (or camera basis) argument is the identity, as a NULL
 * sr_draw_desc.model is; a NULL output makes a bool function return
 * false. */

SR_API sr_vec3 sr_vec3_make(float x, float y, float z);
SR_API sr_vec3 sr_vec3_add(sr_vec3 a, sr_vec3 b);
SR_API sr_vec3 sr_vec3_sub(sr_vec3 a, sr_vec3 b);
SR_API sr_vec3 sr_vec3_scale(sr_vec3 a, float s);
SR_API float   sr_vec3_dot(sr_vec3 a, sr_vec3 b);
SR_API sr_vec3 sr_vec3_cross(sr_vec3 a, sr_vec3 b);
SR_API float   sr_vec3_length(sr_vec3 a);
SR_API sr_vec3 sr_vec3_normalize(sr_vec3 a); /* zero vector stays zero */

SR_API sr_mat4 sr_mat4_identity(void);
SR_API sr_mat4 sr_mat4_mul(const sr_mat4 *a, const sr_mat4 *b); /* a * b */
SR_API sr_vec4 sr_mat4_mul_vec4(const sr_mat4 *m, sr_vec4 v);
SR_API sr_mat4 sr_mat4_transpose(const sr_mat4 *m);
/* General inverse; returns false (and leaves *out as identity) if singular. */
SR_API bool    sr_mat4_invert(const sr_mat4 *m, sr_mat4 *out);

/* Model transforms (M_O). */
SR_API sr_mat4 sr_mat4_translate(float x, float y, float z);
SR_API sr_mat4 sr_mat4_scale(float x, float y, float z);
SR_API sr_mat4 sr_mat4_rotate(float angle_radians, sr_vec3 axis); /* right-handed */

/* The camera frame from eye e, gaze g and view-up t:
 *   w = -g/|g|,  u = t x w / |t x w|,  v = w x u.
 * sr_camera_frame returns false if g is zero or t is parallel to g. */
typedef struct sr_camera_basis { sr_vec3 u, v, w, e; } sr_camera_basis;
SR_API bool    sr_camera_frame(sr_vec3 eye, sr_vec3 gaze, sr_vec3 up, sr_camera_basis *out);
/* E = M_cam^-1, written directly from the orthonormal basis (rows u, v, w,
 * translation -u.e, -v.e, -w.e); no general inverse. */
SR_API sr_mat4 sr_camera_matrix(const sr_camera_basis *b);
/* Convenience: the frame looking from eye at target. */
SR_API sr_mat4 sr_look_at(sr_vec3 eye, sr_vec3 target, sr_vec3 up);

/* Projections (P) in the OpenGL convention, z_ndc in [-1, 1].  With
 * zero_to_one the depth row maps near to 0 and far to 1 instead.  Near and far
 * are positive distances in front of the eye. */
SR_API sr_mat4 sr_ortho(float left, float right, float bottom, float top,
                        float near_z, float far_z, bool zero_to_one);
SR_API sr_mat4 sr_frustum(float left, float right, float bottom, float top,
                          float near_z, float far_z, bool zero_to_one);
SR_API sr_mat4 sr_perspective(float fovy_radians, float aspect,
                              float near_z, float far_z, bool zero_to_one);

/* Aspect-ratio preservation: given the field of view wanted across the
 * *smaller* viewport dimension, the vertical field of view to pass to
 * sr_perspective so that a sphere stays round and fits in a wide or tall
 * viewport. */
SR_API float   sr_fit_fovy(float fov_radians, int width, int height);

/* The viewport matrix S.  It maps NDC x, y in [-1, 1] onto the pixel *edges*
 * of the viewport rectangle (x0, y0, width, height), with y pointing down
 * (NDC y = +1 is the top row), and z_ndc onto [depth_near, depth_far].
 * Where pixel x1..x2 are counted from their centres (pixel x covering
 * [x - 1/2, x + 1/2)), x_S = x1 - 1/2 + (x+1)/2 (x2-x1+1); softrast's
 * pixel-edge coordinate is that value + 1/2 (docs/raster-rules.md). */
SR_API sr_mat4 sr_viewport_matrix(float x0, float y0, float width, float height,
                                  float depth_near, float depth_far, bool zero_to_one);

/* The normal matrix: inverse transpose of the upper 3x3 of the model-view
 * matrix, returned in the upper 3x3 of a mat4.  false if singular. */
SR_API bool    sr_normal_matrix(const sr_mat4 *model_view, sr_mat4 *out);

/* ---- memory ------------------------------------------------------------- */

typedef struct sr_allocator {
    void *(*alloc)(size_t size, void *user); /* NULL on failure */
    void (*free)(void *ptr, void *user);
    void *user;
} sr_allocator;

/* ---- context ------------------------------------------------------------ */

typedef struct sr_context sr_context;

/* Which vector kernels a context runs.  Every level draws the same bytes;
 * they differ only in speed.  A level above what the CPU runs is capped to
 * the widest it does. */
typedef enum sr_simd_level {
    SR_SIMD_DEFAULT = 0, /* the SR_SIMD env var, else the widest the CPU runs */
    SR_SIMD_OFF,         /* scalar loops only (SR_SIMD=off) */
    SR_SIMD_BASE,        /* the baseline instruction set: SSE2 on x86-64, NEON on
                            aarch64, the widest level there (SR_SIMD=base) */
    SR_SIMD_AVX2,        /* SR_SIMD=avx2 */
    SR_SIMD_AVX512,      /* SR_SIMD=avx512 */
} sr_simd_level;

/* Environment variables, read once by sr_make_context (never per draw) and
 * only for a field left at 0:
 *   SR_THREADS=N                     sr_context_desc.threads (1 .. 64; others ignored)
 *   SR_SIMD=off|base|avx2|avx512     sr_context_desc.simd; any other value
 *                                    means the widest level the CPU runs */
typedef struct sr_context_desc {
    sr_allocator allocator; /* zero: malloc/free */
    int threads;            /* 0: SR_THREADS env var, else online CPUs; 1: no worker threads */
    sr_simd_level simd;     /* 0: SR_SIMD env var, else the widest the CPU runs */
    /* Primitives set up before the tiles are drawn: larger batches pass
     * over each tile fewer times (faster for big meshes) and keep more
     * set-up records (about 250 bytes each).  0: SR_BATCH_DEFAULT;
     * otherwise SR_BATCH_MIN .. SR_BATCH_MAX. */
    int batch_primitives;
    /* A fixed arena for systems without malloc: with arena non-NULL, the
     * context and everything made with it (framebuffers, meshes, draw
     * scratch) take their memory from these arena_size bytes and from
     * nowhere else, and a request the arena cannot meet fails with
     * SR_OUT_OF_MEMORY.  The memory must outlive the context; it needs no
     * alignment (an arena_size that would run past the end of memory is
     * SR_INVALID_ARG).  An arena is not locked, so such a context has one
     * thread (threads 0 or 1) and excludes `allocator`.  Its indexed
     * draws transform their vertices into a window of 128 at a time
     * (as every context of the embedded profile does), so that the draw
     * scratch does not grow with the mesh. */
    void *arena;
    size_t arena_size;
    /* The memory the context may keep in the prefiltered radiance maps its
     * pbr programs share (64 KiB each, one per environment and roughness;
     * docs/performance.md): past it the least recently asked-for map no
     * live program reads is freed, or, where the scene asks for more maps
     * in turn than fit, the new one is not kept.  0:
     * SR_RADIANCE_CACHE_DEFAULT; below one map's size, none kept (each
     * program builds its own), as in a context with an arena.  Shared or
     * built, the maps are the same: it changes the time, never a pixel. */
    size_t radiance_cache_bytes;
} sr_context_desc;

/* The embedded profile (SR_EMBEDDED, docs/portability.md) sets up few
 * primitives at a time: its memory is counted in kilobytes. */
#ifdef SR_EMBEDDED
#define SR_BATCH_DEFAULT 64
#define SR_BATCH_MIN     16
#else
#define SR_BATCH_DEFAULT 98304
#define SR_BATCH_MIN     1024
#endif
#define SR_BATCH_MAX     (1 << 22)
/* 256 radiance maps (32 in the embedded profile): a scene of as many
 * roughnesses drawn in turn reuses them all. */
#ifdef SR_EMBEDDED
#define SR_RADIANCE_CACHE_DEFAULT ((size_t)2 << 20)
#else
#define SR_RADIANCE_CACHE_DEFAULT ((size_t)16 << 20)
#endif

SR_API sr_result   sr_make_context(const sr_context_desc *desc, sr_context **out);
SR_API void        sr_destroy_context(sr_context *ctx);
/* Message for the last failed call on ctx ("" after a success). */
SR_API const char *sr_context_error(const sr_context *ctx);
SR_API int         sr_context_threads(const sr_context *ctx);
/* The arena's high-water mark: the most bytes from its start ever in use,
 * bookkeeping included (0 for a context without an arena). */
SR_API size_t      sr_context_arena_peak(const sr_context *ctx);
/* Runs fn(arg, job, thread) for job = 0 .. count-1 on ctx's threads and
 * returns when all are done: thread is 0 for the caller, 1 .. threads-1 for
 * the context's workers.  The jobs must be independent of each other.
 * With ctx NULL every job runs on the calling thread.  softrast_io
 * compresses a PNG's bands this way. */
typedef void (*sr_job_fn)(void *arg, int job, int thread);
SR_API sr_result   sr_run_jobs(sr_context *ctx, sr_job_fn fn, void *arg, int count);
/* The vector kernels ctx runs: its desc's or SR_SIMD's level, capped by the
 * CPU (never SR_SIMD_DEFAULT; SR_SIMD_OFF for NULL). */
SR_API sr_simd_level sr_context_simd(const sr_context *ctx);

/* ---- framebuffers ------------------------------------------------------- */

/* The depth buffer's format.  The test compares the quantized values (k
 * for k / (2^n - 1), or D32F's float); a sample takes 2 bytes of memory
 * with D16 and 4 with the others. */
typedef enum sr_depth_format {
    SR_DEPTH_DEFAULT = 0, /* -> SR_DEPTH_D24 */
    SR_DEPTH_NONE,
    SR_DEPTH_D16,         /* 16-bit unsigned normalized, 2 bytes a sample */
    SR_DEPTH_D24,         /* 24-bit unsigned normalized, in 4 bytes */
    SR_DEPTH_D32,         /* 32-bit unsigned normalized */
    SR_DEPTH_D32F,        /* 32-bit float */
} sr_depth_format;

typedef struct sr_framebuffer sr_framebuffer;

typedef struct sr_framebuffer_desc {
    int width, height;            /* required, 1 .. SR_MAX_FRAMEBUFFER_SIZE */
    sr_depth_format depth_format;
    /* Multisampling (MSAA): 0 or 1 -> one sample at the pixel centre;
     * 2, 4, 8 or 16 -> that many samples per pixel at the standard
     * positions (sr_sample_position), each with its own color, depth and
     * stencil.  Coverage and depth are decided per sample, shading once per
     * pixel per triangle; reading pixels resolves (box average). */
    int samples;
    bool stencil;                 /* an 8-bit stencil buffer (per sample) */
} sr_framebuffer_desc;

SR_API sr_result sr_make_framebuffer(sr_context *ctx, const sr_framebuffer_desc *desc,
                                     sr_framebuffer **out);
SR_API void      sr_destroy_framebuffer(sr_context *ctx, sr_framebuffer *fb);

SR_API int             sr_framebuffer_width(const sr_framebuffer *fb);
SR_API int             sr_framebuffer_height(const sr_framebuffer *fb);
SR_API sr_depth_format sr_framebuffer_depth_format(const sr_framebuffer *fb);
SR_API int             sr_framebuffer_samples(const sr_framebuffer *fb);   /* 1, 2, 4, 8 or 16 */
SR_API bool            sr_framebuffer_has_stencil(const sr_framebuffer *fb);
/* RGBA8, row-major, row 0 at the top, stride = 4 * width bytes.  Carries
 * out pending clears first (and, multisampled, resolves into a buffer the
 * framebuffer keeps); valid until the next draw or clear.  Read-only: the
 * framebuffer remembers which tiles already hold the clear color (a clear
 * to the same color then leaves them alone), and a write through this
 * pointer would go unseen: write pixels with sr_write_pixels. */
SR_API const uint8_t  *sr_framebuffer_pixels(const sr_framebuffer *fb);

/* The standard sample positions (Direct3D and Vulkan; docs/raster-rules.md):
 * sample `index` of a `samples`-sample pixel at (*x, *y) in [0, 1) from
 * the pixel's upper-left corner, y down.  Every position is a multiple of
 * 1/16 px, so coverage at it stays exact in 8 sub-pixel bits. */
SR_API sr_result sr_sample_position(int samples, int index, float *x, float *y);

/* Resolve a multisampled framebuffer into a single-sampled one of the same
 * size: each channel the rounded box average of the pixel's samples,
 * (sum + n/2) / n.  A single-sampled source is copied. */
SR_API sr_result sr_resolve(sr_context *ctx, const sr_framebuffer *src, sr_framebuffer *dst);

/* What sr_clear does to each buffer (sokol's pass actions).  The default
 * clears color to .color, depth to the far value 1.0 and stencil to 0, so
 * a zeroed sr_clear_desc readies a framebuffer for the default LESS test. */
typedef enum sr_clear_action {
    SR_ACTION_DEFAULT = 0, /* color: clear to .color; depth: clear to 1.0; stencil: to 0 */
    SR_ACTION_CLEAR,       /* clear to the given value (.color, .depth, .stencil) */
    SR_ACTION_KEEP,        /* leave the buffer untouched */
} sr_clear_action;

typedef struct sr_clear_desc {
    sr_clear_action color_action;
    float color[4];               /* RGBA in [0, 1] */
    sr_clear_action depth_action;
    float depth;                  /* in [0, 1], used by SR_ACTION_CLEAR; with the default
                                   * action it must be 0 or 1 (a value it would ignore is
                                   * refused, so a forgotten action cannot go unseen) */
    sr_clear_action stencil_action;
    uint8_t stencil;              /* used by SR_ACTION_CLEAR; 0 with the default action */
} sr_clear_desc;

SR_API sr_result sr_clear(sr_context *ctx, sr_framebuffer *fb, const sr_clear_desc *desc);

/* Copy a rectangle of RGBA8 pixels out (stride in bytes, >= 4*w);
 * multisampled framebuffers are resolved first. */
SR_API sr_result sr_read_pixels(sr_context *ctx, const sr_framebuffer *fb,
                                int x, int y, int w, int h, uint8_t *out, size_t stride);
/* Copy a rectangle of RGBA8 pixels in (stride in bytes, >= 4*w): the
 * counterpart of sr_read_pixels, for images composed on the CPU (a page
 * of panels, a magnified cell).  Pending clears of the rest of the
 * framebuffer still happen; a multisampled framebuffer takes each pixel's
 * value in all its samples, so sr_read_pixels gives the same bytes back.
 * Depth and stencil are left as they are.  rgba may be
 * sr_framebuffer_pixels(fb) itself (a rectangle moved within the image):
 * the pixels are read as they were before the call. */
SR_API sr_result sr_write_pixels(sr_context *ctx, sr_framebuffer *fb, int x, int y, int w, int h,
                                 const uint8_t *rgba, size_t stride);
/* Copy depth values out as floats in [0, 1] (dequantized); multisampled:
 * each pixel's sample 0.  sr_read_stencil: the stored values (sample 0). */
SR_API sr_result sr_read_depth(sr_context *ctx, const sr_framebuffer *fb,
                               int x, int y, int w, int h, float *out, size_t stride_floats);
SR_API sr_result sr_read_stencil(sr_context *ctx, const sr_framebuffer *fb,
                                 int x, int y, int w, int h, uint8_t *out, size_t stride);

/* ---- band rendering ----------------------------------------------------- */

/* A frame drawn as a sequence of horizontal bands through one small band
 * framebuffer, each finished band handed to a callback (an SPI display
 * driver, say): the working memory is a band's, not a frame's.  For each
 * band, top to bottom, sr_render_bands readies the band framebuffer as a
 * fresh one (a pending clear to transparent black, the far depth and
 * stencil 0), calls `draw`, which issues the frame's clears and draws on
 * it exactly as it would on a whole framebuffer (same viewport, same
 * scissor, in frame coordinates), then resolves the band and calls
 * `output` with its pixels.  The band framebuffer is width x height for
 * every call and holds only the band's rows: draws and clears stop at the
 * band's edges, sr_read_pixels and its kin accept only rectangles inside
 * the band, sr_framebuffer_pixels gives NULL, and the 2D toolkit,
 * sr_resolve and sr_downsample refuse it.  Every band's pixels are the
 * bytes the same draws give on a whole framebuffer. */
/* The formats a band is handed over in.  The small ones round each 8-bit
 * channel c to n bits as (c * (2^n - 1) + 127) / 255, the nearest value
 * (never a tie), and drop alpha. */
typedef enum sr_pixel_format {
    SR_PIXEL_DEFAULT = 0, /* -> SR_PIXEL_RGBA8 */
    SR_PIXEL_RGBA8,       /* 4 bytes r, g, b, a (sr_framebuffer_pixels' layout) */
    /* 2 bytes, the high one first: rrrrrggg gggbbbbb, the order display
     * controllers such as the ILI9341 and ST7789 take over SPI, the
     * same bytes on every machine. */
    SR_PIXEL_RGB565,
    SR_PIXEL_RGB332,      /* 1 byte: rrrgggbb */
} sr_pixel_format;

typedef struct sr_band {
    int y, rows;             /* the frame's rows [y, y + rows) */
    int width;               /* pixels per row (the frame's width) */
    const uint8_t *pixels;   /* row y first; valid during the callback only */
    size_t stride;           /* bytes from one row to the next */
    sr_pixel_format format;  /* resolved: never SR_PIXEL_DEFAULT */
} sr_band;

typedef struct sr_bands_desc {
    int width, height;            /* the frame, required, 1 .. SR_MAX_FRAMEBUFFER_SIZE */
    int band_rows;                /* rows per band, 1 .. height (the last band may be shorter) */
    sr_depth_format depth_format; /* as sr_framebuffer_desc */
    int samples;
    bool stencil;
    sr_pixel_format format;       /* of the pixels handed to `output` */
    /* Issues the frame's clears and draws on fb; called once per band.  A
     * result other than SR_OK stops the frame and is returned. */
    sr_result (*draw)(sr_context *ctx, sr_framebuffer *fb, const sr_band *band, void *user);
    /* Takes a finished band (its pixels in `format`).  Required. */
    void (*output)(const sr_band *band, void *user);
    void *user;                   /* passed to both callbacks */
} sr_bands_desc;

SR_API sr_result sr_render_bands(sr_context *ctx, const sr_bands_desc *desc);

/* ---- textures ----------------------------------------------------------- */

typedef struct sr_texture sr_texture;

typedef enum sr_texture_filter {
    SR_FILTER_DEFAULT = 0,   /* -> SR_FILTER_TRILINEAR */
    SR_FILTER_NEAREST,       /* the nearest texel of the full-size image */
    SR_FILTER_BILINEAR,      /* the four nearest texels of the full-size image */
    SR_FILTER_TRILINEAR,     /* bilinear in the two mip levels around the level of detail */
} sr_texture_filter;

typedef enum sr_texture_wrap {
    SR_WRAP_DEFAULT = 0,     /* -> SR_WRAP_REPEAT */
    SR_WRAP_REPEAT,
    SR_WRAP_CLAMP,           /* clamp to the edge texels */
    SR_WRAP_MIRROR,          /* mirrored repeat */
} sr_texture_wrap;

typedef struct sr_texture_desc {
    int width, height;          /* 1 .. 16384 */
    const uint8_t *pixels;      /* RGBA8, row 0 at the top (PNG order) */
    size_t stride;              /* bytes per row; 0 -> 4 * width */
    bool srgb;                  /* texels are sRGB: filter in linear light */
} sr_texture_desc;

/* Copies the pixels and builds the mip chain (each level the 2x2 box
 * average of the one above, in linear light for sRGB textures, down to
 * 1x1).  Texture coordinates follow OpenGL and OBJ: (0, 0) is the
 * bottom-left corner of the image, (1, 1) the top-right, so the texcoords
 * of an OBJ file apply as they are. */
SR_API sr_result sr_make_texture(sr_context *ctx, const sr_texture_desc *desc, sr_texture **out);
SR_API void sr_destroy_texture(sr_context *ctx, sr_texture *tex);
SR_API int sr_texture_levels(const sr_texture *tex);

/* ---- supersampling ------------------------------------------------------ */

/* Reconstruction filters for downsampling a supersampled image
 * (unweighted and weighted area sampling).  Radii in destination pixels. */
typedef enum sr_resample_filter {
    SR_RESAMPLE_DEFAULT = 0, /* -> SR_RESAMPLE_BOX */
    SR_RESAMPLE_BOX,         /* unweighted area sampling: the mean of each k x k block */
    SR_RESAMPLE_TENT,        /* triangle, radius 1 */
    SR_RESAMPLE_GAUSSIAN,    /* sigma 1/2, cut at radius 3/2 */
    SR_RESAMPLE_MITCHELL,    /* Mitchell-Netravali B = C = 1/3, radius 2 (negative lobes) */
} sr_resample_filter;

/* SSAA's resolve: dst (w x h) from src (k w x k h, k = 1..16), each
 * destination pixel a normalized weighted sum of the source samples whose
 * centres lie within the filter's support around its centre (edges
 * clamped), in the bytes' own space, rounded and clamped. */
SR_API sr_result sr_downsample(sr_context *ctx, const sr_framebuffer *src, sr_framebuffer *dst,
                               sr_resample_filter filter);

/* ---- tone mapping ------------------------------------------------------- */

/* Tone curves from linear light (Rec. 709 primaries, any non-negative
 * value) to display-linear [0, 1] (docs/tonemap.md). */
typedef enum sr_tonemap_op {
    SR_TONEMAP_DEFAULT = 0,  /* -> SR_TONEMAP_PBR_NEUTRAL */
    SR_TONEMAP_PBR_NEUTRAL,  /* Khronos PBR Neutral: base colours stay true, highlights compress */
    SR_TONEMAP_ACES,         /* ACES filmic, Stephen Hill's RRT+ODT fit, input / 0.6 (three.js) */
    SR_TONEMAP_NONE,         /* clamp to [0, 1] */
} sr_tonemap_op;

typedef struct sr_tonemap_desc {
    sr_tonemap_op op;
    float exposure;          /* EV: the input times 2^exposure first; -64..64, 0 = as is */
    int channels;            /* floats a pixel: 3 (RGB, alpha out 255) or 4 (RGBA); 0 -> 4 */
} sr_tonemap_desc;

/* Linear-light float pixels (width x height, `stride` bytes a row, 0 =
 * packed) to RGBA8 sRGB in `out` (`out_stride` bytes a row, 0 = 4 width):
 * exposure, tone curve, then the exact piecewise sRGB OETF rounded to the
 * nearest code (sr_srgb_encode8).  NaN and negative values become 0, +inf
 * the brightest white; alpha is clamped to [0, 1] and scaled, not
 * encoded.  `pixels` and `out` must not overlap (SR_INVALID_ARG).  desc may be NULL (the
 * defaults).  Rows run on the context's threads; the bytes are the same
 * for any thread count. */
SR_API sr_result sr_tonemap(sr_context *ctx, const float *pixels, int width, int height, size_t stride,
                            uint8_t *out, size_t out_stride, const sr_tonemap_desc *desc);
/* One colour through a tone curve (no exposure, no encode): out in [0, 1]. */
SR_API sr_result sr_tonemap_rgb(sr_tonemap_op op, const float in[3], float out[3]);
/* A display-linear value to its 8-bit sRGB code: the OETF (12.92 x up to
 * 0.0031308, 1.055 x^(1/2.4) - 0.055 above), times 255, rounded to
 * nearest; NaN and values <= 0 give 0, values >= 1 give 255. */
SR_API uint8_t sr_srgb_encode8(float linear);

/* ---- image-based light -------------------------------------------------- */

/* An environment: light arriving from every direction, given as an
 * equirectangular image, prefiltered once for the physically based
 * shading of glTF's metallic-roughness model with the split-sum
 * approximation (docs/ibl.md):
 *   diffuse  = c_diff * irradiance(n)                 (irradiance is E/pi)
 *   specular = specular(r, roughness) * (F0 * A + B)  (A, B from sr_brdf_table)
 * with r = reflect(-v, n) and (A, B) = sr_brdf_table(N.V, roughness).
 *
 * Conventions: directions are in world space, need not be unit length
 * (zero gives the +Y value), +Y is up.  An equirectangular image's column
 * u in [0, 1] (left to right) is u = 1/2 + atan2(z, x) / 2 pi and its row
 * t in [0, 1] (top to bottom) is t = 1/2 - asin(y) / pi, the mapping of
 * three.js's equirectUv: the image's centre is +X, u = 1/4 is -Z (what a
 * default camera looks at), u = 3/4 is +Z, the left and right edges -X,
 * the top row +Y.  Radiance is linear RGB, Rec. 709 primaries.
 *
 * An environment is read-only once made: the query functions may be
 * called from any number of threads at once. */
typedef struct sr_environment sr_environment;

#define SR_ENVIRONMENT_MAX_SIDE   32768
#define SR_ENVIRONMENT_MAX_PIXELS ((size_t)1 << 27)
/* Roughness levels of the prefiltered specular chain: roughness k / (n - 1). */
#define SR_ENVIRONMENT_LEVELS     6

typedef struct sr_environment_desc {
    /* An equirectangular image, linear RGB, 3 floats a pixel, rows top
     * first (as sr_read_hdr gives it): every value finite and >= 0, at
     * most SR_ENVIRONMENT_MAX_SIDE a side and SR_ENVIRONMENT_MAX_PIXELS
     * pixels.  NULL (with width and height 0): the built-in neutral
     * studio, a soft overhead light, two softboxes and a grey floor. */
    const float *pixels;
    int width, height;
    float intensity;         /* radiance scale; 0 -> 1; must be finite and >= 0 */
    float rotation;          /* radians about +Y, right-handed: 0 keeps the image's
                              * mapping, pi/2 moves what was at +X to -Z */
} sr_environment_desc;

/* Prefilter an environment: the source's solid-angle-weighted mip chain,
 * the diffuse irradiance as 9 spherical-harmonic coefficients (Ramamoorthi
 * and Hanrahan) and the specular levels, the source convolved with the GGX
 * lobe of each level's roughness (docs/ibl.md).  Runs on ctx's
 * threads; the result is the same for any thread count.  desc may be NULL
 * (the built-in studio, whose levels and SH were computed when the library
 * was built: making it only copies them).  Release it with
 * sr_destroy_environment and the same ctx, which also frees the
 * prefiltered radiance maps ctx's pbr programs made of it (a map a live
 * program reads, when that program is destroyed).  Programs made with
 * another context leave theirs in that context's cache until they make
 * way for new maps: at most what the cache holds (docs/performance.md). */
SR_API sr_result sr_make_environment(sr_context *ctx, const sr_environment_desc *desc,
                                     sr_environment **out);
SR_API void      sr_destroy_environment(sr_context *ctx, sr_environment *env);

/* Four lanes of 3-vectors or colours, structure of arrays. */
typedef struct sr_vec3x4 { float x[4], y[4], z[4]; } sr_vec3x4;

/* The irradiance E at a surface facing `normal`, divided by pi: the
 * outgoing radiance of a white Lambertian surface, so multiply by the
 * diffuse colour and nothing else.  A uniform environment of radiance L
 * gives L for every normal.  env NULL gives black. */
SR_API void sr_environment_irradiance(const sr_environment *env, const float normal[3],
                                      float out[3]);
SR_API void sr_environment_irradiance4(const sr_environment *env, const sr_vec3x4 *normal,
                                       sr_vec3x4 *out);
/* The environment's radiance around `dir` convolved with the GGX lobe of
 * `roughness` (perceptual, alpha = roughness^2, clamped to [0, 1]), under
 * the split sum's N = V = R assumption: bilinear within a level,
 * linear between the two levels around roughness.  Roughness 0 is the
 * source image itself (the built-in studio's own function, sharp at any
 * size).  A uniform environment of radiance L gives L. */
SR_API void sr_environment_specular(const sr_environment *env, const float dir[3],
                                    float roughness, float out[3]);
SR_API void sr_environment_specular4(const sr_environment *env, const sr_vec3x4 *dir,
                                     const float roughness[4], sr_vec3x4 *out);
/* What a camera sees of the environment in `dir` (a background):
 * blur 0 is the image itself, blur in (0, 1] the specular level of that
 * roughness. */
SR_API void sr_environment_background(const sr_environment *env, const float dir[3],
                                      float blur, float out[3]);

/* The split-sum BRDF table (Karis): the directional albedo of the GGX,
 * height-correlated-Smith specular BRDF with Schlick's Fresnel is
 * F0 * out[0] + out[1] (scale, bias) for a view at N.V and a perceptual
 * roughness, both clamped to [0, 1]; bilinear in a 32 x 32 table
 * computed when the library was built.  out[0] + out[1] <= 1. */
SR_API void sr_brdf_table(float n_dot_v, float roughness, float out[2]);
SR_API void sr_brdf_table4(const float n_dot_v[4], const float roughness[4], float scale[4],
                           float bias[4]);

/* ---- pipeline state ----------------------------------------------------- */

/* A feature that is on unless turned off. */
typedef enum sr_switch {
    SR_SWITCH_DEFAULT = 0, /* -> SR_ON */
    SR_ON,
    SR_OFF,
} sr_switch;

typedef enum sr_cull_mode {
    SR_CULL_DEFAULT = 0, /* -> SR_CULL_NONE */
    SR_CULL_NONE,
    SR_CULL_BACK,
    SR_CULL_FRONT,
    SR_CULL_FRONT_AND_BACK,
} sr_cull_mode;

typedef enum sr_front_face {
    SR_FRONT_DEFAULT = 0, /* -> SR_FRONT_CCW */
    SR_FRONT_CCW,         /* counter-clockwise on screen is front */
    SR_FRONT_CW,
} sr_front_face;

typedef enum sr_depth_func {
    SR_DEPTH_FUNC_DEFAULT = 0, /* -> SR_LESS */
    SR_NEVER,
    SR_LESS,
    SR_EQUAL,
    SR_LEQUAL,
    SR_GREATER,
    SR_NOTEQUAL,
    SR_GEQUAL,
    SR_ALWAYS,
} sr_depth_func;

typedef enum sr_shading {
    SR_SHADING_DEFAULT = 0, /* -> SR_SHADING_UNLIT */
    SR_SHADING_UNLIT,       /* vertex (or material diffuse) color, interpolated */
    SR_SHADING_FLAT,        /* one lit color per triangle: face normal, provoking vertex */
    SR_SHADING_GOURAUD,     /* lighting per vertex, colors interpolated */
    SR_SHADING_PHONG,       /* normals interpolated and renormalized, lighting per pixel */
    SR_SHADING_NORMALS,     /* eye-space normal as color, n*0.5+0.5 */
    SR_SHADING_DEPTH,       /* distance as gray: black at the near plane, white at the far
                             * plane, linear in eye space (window depth for orthographic) */
    SR_SHADING_ATTRIBUTE,   /* the generic attribute as color: 1 float -> gray, 2 -> red and
                             * green, 3 -> RGB, 4 -> RGBA; interpolated perspective-correctly */
} sr_shading;

typedef enum sr_interpolation {
    SR_INTERP_DEFAULT = 0,  /* -> SR_INTERP_PERSPECTIVE */
    SR_INTERP_PERSPECTIVE,  /* interpolate a/w and 1/w: correct */
    SR_INTERP_AFFINE,       /* screen-space linear: wrong under perspective, for teaching */
} sr_interpolation;

typedef enum sr_provoking_vertex {
    SR_PROVOKING_DEFAULT = 0, /* -> SR_PROVOKING_FIRST */
    SR_PROVOKING_FIRST,       /* Vulkan / Direct3D */
    SR_PROVOKING_LAST,        /* OpenGL's default */
} sr_provoking_vertex;

/* Which depth range sr_state maps z_ndc onto.  An enum rather than a
 * special pair of values: [0, 0] is a range like any other. */
typedef enum sr_depth_range_mode {
    SR_DEPTH_RANGE_DEFAULT = 0, /* [0, 1]; depth_near and depth_far must be left 0 */
    SR_DEPTH_RANGE_SET,         /* [depth_near, depth_far], whatever the two values */
} sr_depth_range_mode;

/* The triangle rasterizers.  All three give exactly the same pixels. */
typedef enum sr_rasterizer {
    SR_RASTER_DEFAULT = 0,   /* -> SR_RASTER_HALFSPACE */
    SR_RASTER_HALFSPACE,     /* edge functions by tiles and 8x8 blocks (the fast one) */
    SR_RASTER_SCANLINE,      /* edge walking between the left and right edges */
    SR_RASTER_BARYCENTRIC,   /* bounding box, barycentric test per pixel */
} sr_rasterizer;

/* Where triangles are clipped (docs/clipping.md).  Both give the same
 * pixels up to the float rounding of the new vertices. */
typedef enum sr_clipper {
    SR_CLIPPER_DEFAULT = 0,    /* -> SR_CLIPPER_HOMOGENEOUS */
    SR_CLIPPER_HOMOGENEOUS,    /* clip space, before the divide, with a guard band */
    SR_CLIPPER_VIEW_VOLUME,    /* view space, the six planes of the view volume;
                                  built-in shading only (no program), and the
                                  projection must be invertible */
} sr_clipper;

/* How hidden surfaces are removed (docs/raster-rules.md §6.5). */
typedef enum sr_visibility {
    SR_VISIBILITY_DEFAULT = 0, /* -> SR_VISIBILITY_Z_BUFFER */
    SR_VISIBILITY_Z_BUFFER,    /* per sample, by the depth test and depth_func */
    SR_VISIBILITY_PAINTER,     /* the painter's algorithm: the draw's triangles sorted
                                  back to front by their farthest vertex in eye space
                                  (then their nearest, then their order) and drawn
                                  in that order with no depth test or write.  Wrong
                                  where triangles overlap cyclically or
                                  interpenetrate.  Triangle lists of the built-in
                                  shading only (no program) */
} sr_visibility;

typedef enum sr_light_type {
    SR_LIGHT_OFF = 0,
    SR_LIGHT_DIRECTIONAL,    /* `vector` is the direction the light travels */
    SR_LIGHT_POINT,          /* `vector` is the light's position */
    SR_LIGHT_SPOT,           /* `vector` is the light's position, `direction` the cone's
                              * axis; the PBR program only (sr_pbr_desc) */
} sr_light_type;

/* Lights live in world space: the view matrix is applied to them.  The
 * fields after `intensity` came with KHR_lights_punctual (docs/pbr.md) and
 * are the PBR program's: the classic shading refuses a spot light or a
 * range. */
typedef struct sr_light {
    sr_light_type type;
    sr_vec3 vector;
    sr_vec3 color;           /* zero -> white (1, 1, 1) */
    float intensity;         /* zero -> 1 */
    sr_vec3 direction;       /* spot: the way the light points, any length > 0 */
    float inner_cone;        /* spot: radians, full intensity inside; 0 <= inner < outer */
    float outer_cone;        /* spot: radians, no light outside; zero -> pi/4; <= pi/2 */
    float range;             /* point, spot: the distance where the light ends, with
                              * glTF's smooth window; zero -> infinite */
} sr_light;

typedef struct sr_material {
    sr_vec3 ambient;         /* multiplied by sr_state.ambient; zero -> diffuse */
    sr_vec3 diffuse;         /* zero -> (0.8, 0.8, 0.8) */
    sr_vec3 specular;        /* reflectance of highlights, may be zero */
    float shininess;         /* Blinn-Phong exponent; zero -> 32 */
    float opacity;           /* written to alpha; zero -> 1 */
    sr_switch vertex_color;  /* the draw's colors array, where it has one, is the diffuse;
                              * SR_OFF: the material's diffuse whatever the draw carries */
} sr_material;

/* ---- physically based materials ----------------------------------------- */

/* glTF 2.0's metallic-roughness material (its specification's Appendix B),
 * drawn by the PBR program.  Factors are taken as written: a zeroed
 * material is a black, smooth dielectric, and sr_pbr_default_material()
 * gives glTF's defaults (white, metallic 1, roughness 1). */
typedef enum sr_alpha_mode {
    SR_ALPHA_OPAQUE = 0,     /* alpha ignored: written as 1 */
    SR_ALPHA_MASK,           /* fragments with alpha < alpha_cutoff are discarded */
    SR_ALPHA_BLEND,          /* blended over what is behind (the caller sorts) */
} sr_alpha_mode;

/* A texture as a material reads it: glTF's textureInfo with its sampler
 * and KHR_texture_transform.  uv' = T(offset) R(rotation) S(scale) uv. */
typedef struct sr_texture_slot {
    const sr_texture *texture;     /* NULL: the slot is empty */
    int texcoord;                  /* which coordinate set: 0 or 1 */
    sr_texture_filter filter;
    sr_texture_wrap wrap_u, wrap_v;
    float offset[2];
    float rotation;                /* radians, counter-clockwise in uv */
    float scale[2];                /* {0, 0} -> {1, 1} unless scale_set */
    bool scale_set;                /* true: the scale as given, {0, 0} collapsing
                                    * the texture to the texel at the offset
                                    * (as KHR_texture_transform has it) */
} sr_texture_slot;

/* The slot's KHR_texture_transform applied to `count` (u, v) pairs of
 * `uv` into `out` (which may be uv): the coordinates the physically based
 * program samples the slot at, with the same arithmetic, for a pipeline
 * without per-fragment transforms (the classic shading models, a mesh's
 * texcoords).  Exact where the coordinates are interpolated linearly
 * after it, since the transform is affine.  The texture, the coordinate
 * set and the sampler are the caller's to honour.  SR_INVALID_ARG for a
 * NULL slot or array (with count > 0) or a transform that is not
 * finite. */
SR_API sr_result sr_texture_slot_uv(sr_context *ctx, const sr_texture_slot *slot,
                                    const float *uv, size_t count, float *out);

typedef struct sr_pbr_material {
    float base_color[4];           /* linear RGBA, times the texture and vertex color */
    sr_texture_slot base_color_texture;          /* sRGB */
    float metallic, roughness;     /* 0..1, times the texture's B and G */
    sr_texture_slot metallic_roughness_texture;  /* linear */
    sr_texture_slot normal_texture;              /* tangent space, linear */
    float normal_scale;            /* scales the map's x and y */
    sr_texture_slot occlusion_texture;           /* R channel, linear */
    float occlusion_strength;      /* 0: none, 1: the full map */
    float emissive[3];             /* linear RGB */
    float emissive_strength;       /* KHR_materials_emissive_strength; 0 -> 1
                                    * unless emissive_strength_set */
    bool emissive_strength_set;    /* true: the strength as given, 0 being
                                    * no emission (the extension's) */
    sr_texture_slot emissive_texture;            /* sRGB */
    /* KHR_materials_transmission and KHR_materials_volume (docs/pbr.md):
     * the share of the dielectric's diffuse lobe that passes through,
     * showing sr_pbr_desc.transmission_source refracted and tinted by
     * the base color.  Zero transmission (and no texture): none. */
    float transmission;                          /* 0..1, times the texture's R */
    sr_texture_slot transmission_texture;        /* linear */
    float thickness;                             /* >= 0, object space, times the
                                                  * texture's G; 0: thin-walled */
    sr_texture_slot thickness_texture;           /* linear */
    float attenuation_color[3];                  /* linear, 0..1: white light's color
                                                  * after attenuation_distance */
    float attenuation_distance;                  /* > 0, world units; 0: no absorption */
    sr_alpha_mode alpha_mode;
    float alpha_cutoff;            /* for SR_ALPHA_MASK; 0 -> 0.5 */
    bool double_sided;             /* back faces drawn, lit with the flipped normal */
    bool unlit;                    /* KHR_materials_unlit: the base color, no lights
                                    * (still exposed and tone mapped) */
    /* The physically based extensions KHR_materials_ior, _specular,
     * _clearcoat and _sheen (docs/pbr.md).  Every field zero means the
     * extension is absent, so a material filled before they existed draws
     * as it did; sr_pbr_default_material() leaves them zero.  Factors must
     * be finite and in their ranges; textures multiply their factors. */
    float ior;                     /* > 1 (F0 ((ior - 1) / (ior + 1))^2), 1 (none); 0 -> 1.5 */
    bool specular_set;             /* false: specular 1 and specular_color white */
    float specular;                /* 0..1: the dielectric's F0 and F90 scale */
    sr_texture_slot specular_texture;            /* A channel, linear */
    float specular_color[3];       /* >= 0: tints the dielectric's F0 (clamped to 1) */
    sr_texture_slot specular_color_texture;      /* sRGB */
    float clearcoat;               /* 0..1: the coat's weight; 0: no coat */
    sr_texture_slot clearcoat_texture;           /* R channel, linear */
    float clearcoat_roughness;     /* 0..1 */
    sr_texture_slot clearcoat_roughness_texture; /* G channel, linear */
    sr_texture_slot clearcoat_normal_texture;    /* tangent space; empty: the geometry's normal */
    float clearcoat_normal_scale;  /* scales the map's x and y; 0 -> 1 */
    float sheen_color[3];          /* 0..1 linear RGB; all 0: no sheen */
    sr_texture_slot sheen_color_texture;         /* sRGB */
    float sheen_roughness;         /* 0..1 */
    sr_texture_slot sheen_roughness_texture;     /* A channel, linear */
    /* KHR_materials_anisotropy and _iridescence (docs/pbr.md), zero as
     * absent like the block above.  Anisotropy stretches the base's
     * highlight along a direction in the tangent frame (the draw's
     * tangents, else the texture coordinates' derivatives); iridescence
     * is a thin film whose interference tints the base's Fresnel. */
    float anisotropy_strength;     /* 0..1; 0: isotropic */
    float anisotropy_rotation;     /* radians, counter-clockwise from the tangent */
    sr_texture_slot anisotropy_texture;          /* RG direction, B strength, linear */
    float iridescence;             /* 0..1: the film's weight; 0: no film */
    sr_texture_slot iridescence_texture;         /* R channel, linear */
    float iridescence_ior;         /* >= 1, the film's index; 0 -> 1.3 */
    bool iridescence_thickness_set;              /* false: both thicknesses 0 -> 100 and
                                                  * 400 nm; true: as given, 0 nm being
                                                  * no film (as the extension has it) */
    float iridescence_thickness_min;             /* nm, >= 0, at the texture's G = 0 */
    float iridescence_thickness_max;             /* nm, >= 0, at G = 1 and without a
                                                  * texture */
    sr_texture_slot iridescence_thickness_texture; /* G channel, linear */
    /* KHR_materials_dispersion and _diffuse_transmission (docs/pbr.md),
     * zero as absent like the blocks above.  Dispersion spreads a
     * transmissive volume's ior over the color channels, so that each
     * refracts on its own; diffuse transmission turns that share of the
     * diffuse lobe into a Lambert lobe lit from behind the surface (-N),
     * for leaves, paper, lamp shades and wax. */
    float dispersion;              /* >= 0, 20 / the Abbe number; needs a thickness */
    float diffuse_transmission;    /* 0..1, times the texture's A */
    sr_texture_slot diffuse_transmission_texture;       /* A channel, linear */
    float diffuse_transmission_color[3];                /* 0..1 linear RGB: the light let
                                                         * through (not tinted by the base) */
    sr_texture_slot diffuse_transmission_color_texture; /* sRGB */
    /* KHR_materials_pbrSpecularGlossiness (docs/pbr.md), false as absent.
     * When set, the surface is a dielectric whose base_color (and its
     * texture) is the diffuse color, whose F0 is the specular color below
     * (F90 1) and whose roughness is 1 - glossiness, its diffuse lobe
     * weighted by 1 - max(F0) as the extension asks; metallic, roughness,
     * their texture, ior and the specular fields are not read. */
    bool specular_glossiness;
    float sg_specular[3];          /* 0..1 linear: F0, times the texture's RGB */
    float glossiness;              /* 0..1, times the texture's A */
    sr_texture_slot specular_glossiness_texture; /* sRGB RGB, linear A */
} sr_pbr_material;

typedef struct sr_polygon_offset {
    float factor;            /* times the depth slope m = max(|dz/dx|, |dz/dy|) */
    float units;             /* times r, the format's smallest step */
    float clamp;             /* 0: none; > 0: min(o, clamp); < 0: max(o, clamp) */
    bool fill, line, point;  /* which polygon modes are offset */
} sr_polygon_offset;

/* How a triangle is drawn once it has been clipped and culled
 * (glPolygonMode): filled, as its outline of lines, or as its vertices. */
typedef enum sr_polygon_mode {
    SR_POLYGON_DEFAULT = 0, /* -> SR_POLYGON_FILL */
    SR_POLYGON_FILL,
    SR_POLYGON_LINE,
    SR_POLYGON_POINT,
} sr_polygon_mode;

/* Blending: result = src * src_factor  (op)  dst * dst_factor, per channel,
 * with OpenGL's factors and equations (MIN and MAX ignore the factors). */
typedef enum sr_blend_factor {
    SR_BLEND_FACTOR_DEFAULT = 0,  /* ONE for the source, ZERO for the destination */
    SR_BLEND_ZERO,
    SR_BLEND_ONE,
    SR_BLEND_SRC_COLOR,
    SR_BLEND_ONE_MINUS_SRC_COLOR,
    SR_BLEND_SRC_ALPHA,
    SR_BLEND_ONE_MINUS_SRC_ALPHA,
    SR_BLEND_DST_ALPHA,
    SR_BLEND_ONE_MINUS_DST_ALPHA,
    SR_BLEND_DST_COLOR,
    SR_BLEND_ONE_MINUS_DST_COLOR,
    SR_BLEND_CONSTANT_COLOR,
    SR_BLEND_ONE_MINUS_CONSTANT_COLOR,
    SR_BLEND_CONSTANT_ALPHA,
    SR_BLEND_ONE_MINUS_CONSTANT_ALPHA,
    SR_BLEND_SRC_ALPHA_SATURATE,
} sr_blend_factor;

typedef enum sr_blend_op {
    SR_BLEND_OP_DEFAULT = 0,      /* -> ADD */
    SR_BLEND_ADD,
    SR_BLEND_SUBTRACT,            /* src - dst */
    SR_BLEND_REVERSE_SUBTRACT,    /* dst - src */
    SR_BLEND_MIN,
    SR_BLEND_MAX,
} sr_blend_op;

typedef struct sr_blend {
    bool enabled;
    sr_blend_factor src_rgb, dst_rgb, src_alpha, dst_alpha;
    sr_blend_op op_rgb, op_alpha;
    float constant[4];            /* for the CONSTANT factors */
} sr_blend;

/* The color channels the fragment stage writes (sokol's color mask): a
 * set of SR_COLOR_MASK_R/G/B/A bits; zero writes all four. */
typedef enum sr_color_mask {
    SR_COLOR_MASK_DEFAULT = 0,    /* -> SR_COLOR_MASK_RGBA */
    SR_COLOR_MASK_R = 0x1,
    SR_COLOR_MASK_G = 0x2,
    SR_COLOR_MASK_B = 0x4,
    SR_COLOR_MASK_A = 0x8,
    SR_COLOR_MASK_RGB = 0x7,
    SR_COLOR_MASK_RGBA = 0xf,
    SR_COLOR_MASK_NONE = 0x10,    /* no channel written */
} sr_color_mask;

/* Stencil operations (glStencilOp) on the 8-bit stored value. */
typedef enum sr_stencil_op {
    SR_STENCIL_KEEP = 0,
    SR_STENCIL_ZERO,
    SR_STENCIL_REPLACE,      /* the reference value */
    SR_STENCIL_INCR,         /* +1, saturating at 255 */
    SR_STENCIL_DECR,         /* -1, saturating at 0 */
    SR_STENCIL_INVERT,       /* bitwise not */
    SR_STENCIL_INCR_WRAP,    /* +1, 255 wraps to 0 */
    SR_STENCIL_DECR_WRAP,    /* -1, 0 wraps to 255 */
} sr_stencil_op;

/* One face's stencil state (glStencilFuncSeparate, glStencilOpSeparate,
 * glStencilMaskSeparate).  The test passes iff
 * (ref & read_mask) FUNC (stored & read_mask); the op chosen by the
 * outcome is written through write_mask. */
typedef struct sr_stencil_face {
    sr_depth_func func;      /* DEFAULT -> SR_ALWAYS (the GL default) */
    uint8_t ref;
    bool masked;             /* false: read_mask = write_mask = 0xff */
    uint8_t read_mask, write_mask;
    sr_stencil_op fail;      /* the stencil test fails */
    sr_stencil_op depth_fail;/* stencil passes, depth fails */
    sr_stencil_op pass;      /* both pass (or no depth test) */
} sr_stencil_face;

typedef struct sr_stencil {
    bool enabled;            /* needs a framebuffer with a stencil buffer */
    sr_stencil_face front;
    sr_stencil_face back;    /* used only when `separate` */
    bool separate;           /* false: back faces use `front` too */
} sr_stencil;

typedef struct sr_scissor {
    bool enabled;
    int x, y, width, height;      /* pixels, y from the top */
} sr_scissor;

typedef struct sr_viewport {
    int x, y, width, height; /* pixels, y from the top; width 0 -> the framebuffer */
} sr_viewport;

/* ---- programmable stages ------------------------------------------------ */

/* Vertex and fragment shaders as C functions (docs/shaders.md).  A program
 * replaces the built-in shading models: the vertex shader writes the clip
 * position and up to 16 varyings per vertex, the pipeline clips, sets up
 * and interpolates them, and the fragment shader colors a 2x2 quad of
 * fragments at a time. */
#define SR_SHADER_MAX_VARYINGS 16

typedef enum sr_varying_mode {
    SR_VARYING_SMOOTH = 0,     /* perspective-correct (the default) */
    SR_VARYING_NOPERSPECTIVE,  /* linear in screen space (triangles) */
    SR_VARYING_FLAT,           /* the provoking vertex's value, constant */
} sr_varying_mode;

/* What a vertex shader reads: the draw's arrays at one vertex.  Absent
 * arrays read as zero (color and generic alpha as 1). */
typedef struct sr_vertex_input {
    uint32_t index;            /* the vertex's index into the arrays */
    float position[4];         /* w = 1 when position_size is 3 */
    float normal[3];
    float color[4];
    float texcoord[2];
    float generic[4];
    bool has_normal, has_color, has_texcoord, has_generic;   /* which arrays the draw has */
} sr_vertex_input;

/* Writes the vertex's clip-space position and program.varying_count
 * varyings. */
typedef void (*sr_vertex_shader)(const void *uniforms, const sr_vertex_input *in,
                                 float clip[4], float *varyings);

/* A 2x2 quad of fragments: lane 0 (x, y), 1 (x+1, y), 2 (x, y+1),
 * 3 (x+1, y+1).  Every lane's varyings are interpolated - lanes not in
 * `mask` are helpers, extrapolated from the same plane - so differences
 * between lanes are the screen-space derivatives. */
typedef struct sr_fragment_quad {
    unsigned mask;             /* lanes that are fragments (bit i = lane i) */
    int x, y;                  /* lane 0's pixel */
    bool front;                /* the primitive faces the viewer */
    float z[4];                /* window depth in the depth range; write it back
                                * when the program's writes_depth is set */
    float varyings[SR_SHADER_MAX_VARYINGS][4];   /* varying k of lane i: [k][i] */
    float color[4][4];         /* out: red, green, blue, alpha of lane i: [c][i] */
    unsigned discard;          /* out: lanes to drop (bit i = lane i) */
} sr_fragment_quad;

typedef void (*sr_fragment_shader)(const void *uniforms, sr_fragment_quad *q);

typedef struct sr_program {
    sr_vertex_shader vertex;       /* required */
    sr_fragment_shader fragment;   /* required */
    const void *uniforms;          /* passed to both, read-only, shared by every thread */
    int varying_count;             /* 0 .. SR_SHADER_MAX_VARYINGS */
    sr_varying_mode modes[SR_SHADER_MAX_VARYINGS];
    bool writes_depth;             /* the fragment shader sets z[]: depth is tested after it */
    bool may_discard;              /* the fragment shader may set discard: likewise */
    /* Each lane's color depends on that lane's inputs alone (no lane
     * differences, no x, y): a triangle's fragments may then fill the
     * lanes of one call from several quads, x, y being lane 0's pixel. */
    bool independent_lanes;
} sr_program;

typedef struct sr_state {
    sr_viewport viewport;
    sr_scissor scissor;            /* also trims the viewport: nothing outside is touched */
    sr_blend blend;
    sr_color_mask color_mask;
    /* Depth range: z_ndc maps onto [0, 1], or with depth_range =
     * SR_DEPTH_RANGE_SET onto [depth_near, depth_far].  As glDepthRange,
     * each is clamped to [0, 1] (infinities too; NaN is refused), and
     * depth_near > depth_far is allowed: it inverts depth, nearer
     * fragments getting larger values. */
    sr_depth_range_mode depth_range;
    float depth_near, depth_far;
    bool depth_zero_to_one;        /* clip space z in [0, w] (D3D/Vulkan), not [-w, w] */

    sr_cull_mode cull;
    sr_front_face front_face;
    sr_rasterizer rasterizer;
    sr_clipper clipper;            /* triangles only: lines and points clip homogeneously */
    sr_visibility visibility;      /* z-buffer or painter's algorithm */
    sr_polygon_mode polygon_mode_front;
    sr_polygon_mode polygon_mode_back;
    float line_width;              /* whole pixels, 1..64; 0 -> 1 (runs across the minor axis) */
    float point_size;              /* pixels, > 0 and <= 1024; 0 -> 1 (a square) */
    bool round_points;             /* discs of diameter point_size instead of squares */
    /* Antialiased lines and points: each pixel near the primitive gets its
     * coverage (from its centre's distance to the segment or the point,
     * a one-pixel ramp) as alpha and is blended source-over; depth is
     * tested as usual and written only where coverage is full.  Smooth
     * lines have round ends and any width (line_width, not rounded). */
    bool smooth_lines;
    bool smooth_points;

    /* Both on by default when the framebuffer has a depth buffer. */
    sr_switch depth_test;
    sr_switch depth_write;
    sr_depth_func depth_func;
    sr_polygon_offset offset;

    sr_shading shading;
    sr_interpolation interpolation;
    sr_provoking_vertex provoking;
    sr_material material;
    sr_vec3 ambient;               /* global ambient light */
    sr_light lights[SR_MAX_LIGHTS];
    bool two_sided;                /* light back faces with the flipped normal */

    /* A texture modulates the surface color (GL_MODULATE): unlit and
     * Gouraud colors and the flat color are multiplied by the texel, Phong
     * multiplies the diffuse color before lighting.  Needs texcoords. */
    const sr_texture *texture;
    sr_texture_filter texture_filter;
    sr_texture_wrap wrap_u, wrap_v;

    /* Stencil test and update, per sample, before the depth test.  Lines
     * and points count as front-facing. */
    sr_stencil stencil;
    /* Multisampled targets: the shaded alpha also decides how many of the
     * pixel's samples are covered (round(alpha x n) of them, in a fixed
     * order), before the stencil and depth tests. */
    bool alpha_to_coverage;

    /* A program replaces `shading`, the material, lights and texture; the
     * draw's model, view and projection are not applied (the vertex
     * shader transforms, with matrices in its uniforms). */
    const sr_program *program;
} sr_state;

/* The built-in shading models as programs: `state`'s model (unlit, flat,
 * Gouraud, Phong, normals or depth), material, lights and texture, with
 * the model, view and projection matrices in the uniforms.  Drawn with
 * .program = sr_builtin_program(b), it gives the built-in pixels (exactly,
 * except flat shading and trilinear filtering, which take their face
 * normal and level of detail from the quad: within rounding).  sr_draw
 * keeps its specialized fast paths for the built-ins themselves; these
 * are the same models to start a program from (docs/shaders.md).
 * SR_INVALID_ARG for a state sr_draw would refuse (an unknown light type,
 * a NaN material, ...), one that already has a program or whose shading
 * has no program form (SR_SHADING_ATTRIBUTE), and a matrix with a NaN or
 * infinite entry (NULL ones are the identity). */
typedef struct sr_builtin sr_builtin;
SR_API sr_result sr_make_builtin_program(sr_context *ctx, const sr_state *state,
                                         const sr_mat4 *model, const sr_mat4 *view,
                                         const sr_mat4 *projection, sr_builtin **out);
SR_API const sr_program *sr_builtin_program(const sr_builtin *b);
SR_API void sr_destroy_builtin_program(sr_context *ctx, sr_builtin *b);

/* ---- physically based shading ------------------------------------------- */

/* glTF's metallic-roughness model (its specification's Appendix B) as a
 * program (docs/pbr.md): base color, metallic and roughness, GGX
 * distribution, height-correlated Smith visibility, Schlick Fresnel,
 * Lambert diffuse; normal, occlusion and emissive maps; alpha modes;
 * double-sided and unlit materials; punctual lights, a hemisphere or an
 * environment's image-based light, and a shadow map for the key light.
 * Shading is in world space and linear light; each fragment's color is
 * scaled by 2^exposure, tone mapped and sRGB-encoded into the RGBA8 target
 * (as three.js draws to a canvas), so blending happens on the encoded
 * values.  Unlit materials skip exposure
 * and the tone curve: their base color is shown as it is, encoded.
 *
 * The draw gives positions, normals (needed), colors (multiplied into the
 * base color when `vertex_color` is not SR_OFF), texcoords (set 0).  Set 1
 * and tangents are not in sr_draw_desc: they come from the arrays below,
 * read at sr_vertex_input.index.  Texture coordinates follow sr_texture (v
 * up): a glTF reader flips the file's v, and each slot's
 * KHR_texture_transform is applied in the file's frame (v down), so the
 * file's offset, rotation and scale mean what they say there.
 *
 * Draw state the material needs is the caller's: SR_CULL_BACK unless
 * double_sided; for SR_ALPHA_BLEND, source-over blending (SR_BLEND_SRC_ALPHA,
 * SR_BLEND_ONE_MINUS_SRC_ALPHA), depth writes off and the primitives sorted
 * back to front. */
typedef struct sr_pbr_desc {
    const sr_pbr_material *material;   /* NULL -> sr_pbr_default_material(); textures
                                        * must outlive the program */
    const sr_mat4 *model;              /* object -> world; NULL -> identity */
    const sr_mat4 *view;               /* world -> eye;    NULL -> identity */
    const sr_mat4 *projection;         /* NULL -> identity; all three finite */
    /* Punctual lights in world space (KHR_lights_punctual): radiance
     * color x intensity (sr_light's zero defaults: white, 1), so a
     * directional light's intensity is in lux and a point or spot light's
     * in candela, one unit of radiance being one nit before `exposure`.
     * Point and spot lights fall off with the inverse square of the
     * distance, times (with a range) clamp(1 - (d / range)^4, 0, 1)^2;
     * spot lights by the cosine of the angle to their axis, t = (cos -
     * cos outer) / (cos inner - cos outer) clamped to [0, 1], as t^2. */
    sr_light lights[SR_MAX_LIGHTS];
    /* Ambient light from a hemisphere: radiance `sky` from world +y down to
     * `ground` from -y, blended by direction, for diffuse (by the normal)
     * and specular (by the reflected ray, weighted by the split-sum BRDF's
     * analytic fit).  Occlusion maps darken it.  Both zero: no ambient. */
    sr_vec3 sky, ground;
    /* Image-based light (docs/ibl.md) in place of the hemisphere:
     * (1 - Es) c_diff E(N) + Es L(R, roughness), Es = F0 A + B from the
     * split-sum table, times the occlusion.  Must outlive the program. */
    const sr_environment *environment;
    /* What a transmissive material (sr_pbr_material.transmission) sees
     * through itself: the opaque scene drawn before it with the same view
     * and projection, SR_TONEMAP_NONE and the same exposure, as an sRGB
     * texture (rows top down as sr_framebuffer_pixels gives them; its mip
     * levels blur it for rough materials).  NULL: `environment` in the
     * direction the ray leaves the surface (refracted in a volume,
     * straight on through a thin wall), prefiltered for the roughness;
     * without either, black.  Must outlive the program. */
    const sr_texture *transmission_source;
    /* The key light's shadow (docs/shadows.md): lights[0], which should
     * be the map's directional light, is scaled by the filtered visibility
     * at each fragment (looked up with the interpolated vertex normal).
     * Must outlive the program and be drawn before the program's draws. */
    const struct sr_shadow_map *shadow;   /* declared with the shadows below */
    float exposure;                    /* EV: radiance times 2^exposure; -64..64 */
    sr_tonemap_op tonemap;             /* DEFAULT -> Khronos PBR Neutral */
    sr_switch vertex_color;            /* SR_OFF: ignore the draw's colors (4 varyings fewer) */
    /* Per-vertex arrays the draw does not carry, `vertex_count` entries
     * each (needed when either is given; indices past it read zero).
     * Tangents: xyz in object space, w = +1 or -1 the bitangent's sign
     * (B = w N x T) in object space: under a model matrix that mirrors
     * (negative determinant) the program flips it, as the mirror turns
     * N x T; NULL: the normal map's frame comes from the screen-space
     * derivatives of position and texcoords. */
    size_t vertex_count;
    const float *tangents;             /* 4 floats a vertex */
    size_t tangent_stride;             /* bytes; 0 -> packed */
    const float *texcoords1;           /* 2 floats a vertex: texcoord set 1 */
    size_t texcoord1_stride;
} sr_pbr_desc;

/* glTF's defaults: base color white, metallic 1, roughness 1, normal scale
 * and occlusion strength 1, no emission, opaque, cutoff 0.5, single-sided,
 * empty slots (scale 1), no transmission, attenuation color white,
 * diffuse transmission color white. */
SR_API sr_pbr_material sr_pbr_default_material(void);

/* softrast render's default lighting (docs/pbr.md), for programs that
 * want to look like it.  sr_default_lights writes the key, fill and rim
 * directional lights placed relative to a camera basis (sr_camera_frame),
 * so that whatever the view the side facing the viewer is lit from the
 * upper left and the silhouette stands out: key from (-0.55 u + 0.70 v +
 * 0.45 w), fill from (0.80 u + 0.05 v + 0.60 w), rim from (0.10 u + 0.55 v
 * - 0.85 w), intensities 0.95, 0.35, 0.45, a warm white (1, 0.98, 0.95);
 * lights[3 ..] are SR_LIGHT_OFF.  SR_INVALID_ARG for NULL or a basis
 * whose u, v, w are not finite unit vectors.
 * sr_pbr_default_lighting sets desc's lights to `lights` (SR_MAX_LIGHTS,
 * the classic sr_state lights: the rig above or the caller's) as radiance,
 * each intensity (zero -> 1) times SR_PBR_LIGHT_SCALE, so that a white
 * surface facing the key light looks about as bright as the Blinn-Phong
 * models show it; and its hemisphere: sky (0.16, 0.165, 0.18) over ground
 * (0.05, 0.048, 0.045).  SR_INVALID_ARG (desc untouched) for NULL or a
 * light whose type is not an sr_light_type or whose vector, color or
 * intensity is not finite. */
#define SR_DEFAULT_LIGHT_COUNT 3
#define SR_PBR_LIGHT_SCALE 1.6f
/* softrast render's shadow of the key light (docs/shadows.md): an
 * sr_shadow_desc with the key light's direction, the box of the
 * occluders, .size = SR_DEFAULT_SHADOW_SIZE (1024: a 1080p picture looks
 * as it does with 2048, for half the draw) and .light_radius =
 * SR_DEFAULT_SHADOW_LIGHT_RADIUS (soft away from the contact). */
#define SR_DEFAULT_SHADOW_SIZE 1024
#define SR_DEFAULT_SHADOW_LIGHT_RADIUS 0.04f
SR_API sr_result sr_default_lights(const sr_camera_basis *basis, sr_light lights[SR_MAX_LIGHTS]);
SR_API sr_result sr_pbr_default_lighting(const sr_light lights[SR_MAX_LIGHTS], sr_pbr_desc *desc);
/* softrast render's --lights file|both (docs/pbr.md, "Lights"):
 * sr_pbr_scene_lights replaces `lights` (SR_MAX_LIGHTS, the rig as
 * sr_pbr_default_lighting made it) by a scene's own `count` lights
 * (KHR_lights_punctual's, in their units; SR_LIGHT_OFF ones skipped, the
 * first SR_MAX_LIGHTS lit ones kept in their order but for the strongest
 * directional one, by color channel times intensity, moved first so that
 * it casts the shadow) and, with keep_rig, the rig's lit lights in the
 * slots left - first when none of the scene's is directional, so that the
 * key casts the shadow.  SR_INVALID_ARG (lights untouched) for NULL
 * lights, NULL scene_lights with a count, or a type that is not an
 * sr_light_type. */
SR_API sr_result sr_pbr_scene_lights(const sr_light *scene_lights, size_t count, bool keep_rig,
                                     sr_light lights[SR_MAX_LIGHTS]);

typedef struct sr_pbr sr_pbr;
SR_API sr_result sr_make_pbr_program(sr_context *ctx, const sr_pbr_desc *desc, sr_pbr **out);
SR_API const sr_program *sr_pbr_program(const sr_pbr *p);
SR_API void sr_destroy_pbr_program(sr_context *ctx, sr_pbr *p);

/* ---- drawing ------------------------------------------------------------ */

typedef enum sr_primitive {
    SR_PRIM_DEFAULT = 0, /* -> SR_PRIM_TRIANGLES */
    SR_PRIM_TRIANGLES,
    SR_PRIM_TRIANGLE_STRIP,
    SR_PRIM_TRIANGLE_FAN,
    SR_PRIM_LINES,           /* pairs of vertices */
    SR_PRIM_LINE_STRIP,
    SR_PRIM_LINE_LOOP,       /* a strip closed back to the first vertex */
    SR_PRIM_POINTS,
} sr_primitive;

typedef enum sr_index_type {
    SR_INDEX_NONE = 0,   /* vertices used in order */
    SR_INDEX_U8,
    SR_INDEX_U16,
    SR_INDEX_U32,
} sr_index_type;

/* ---- vertex buffers ----------------------------------------------------- */

/* A copy of an application's arrays in memory the context allocates, as a
 * GL buffer object made with GL_STATIC_DRAW: pointers into sr_buffer_data
 * may be given as any array or the indices of an sr_draw_desc.  With the
 * default allocator a buffer of 4 MiB and more lies in 2 MiB pages, so a
 * large draw's front end does not wait on a page-table walk every 4 KiB
 * (a million triangles from malloc'd arrays: docs/performance.md).  The
 * data is aligned as the context's allocator aligns it (64 bytes with the
 * default) and may be written through sr_buffer_data between draws. */
typedef struct sr_buffer sr_buffer;

/* Copies `bytes` bytes from data, or zeroes them when data is NULL: 0
 * bytes is SR_INVALID_ARG, more than SR_BUFFER_MAX (16 GiB, the most a
 * draw of 2^28 vertices can read of one array; SIZE_MAX where size_t has
 * 32 bits) SR_TOO_LARGE before any allocation. */
#define SR_BUFFER_MAX ((size_t)(SIZE_MAX >> 31 >> 3 ? (uint64_t)1 << 34 : SIZE_MAX))
SR_API sr_result sr_make_buffer(sr_context *ctx, const void *data, size_t bytes, sr_buffer **out);
SR_API void sr_destroy_buffer(sr_context *ctx, sr_buffer *buf);
/* Copies `bytes` bytes from data to offset `offset` of the buffer, as
 * glBufferSubData: the range must lie inside it.  data may point into
 * the buffer itself (the bytes move as memmove moves them). */
SR_API sr_result sr_buffer_update(sr_context *ctx, sr_buffer *buf, size_t offset, const void *data,
                                  size_t bytes);
SR_API void *sr_buffer_data(sr_buffer *buf);       /* NULL for a NULL buffer */
SR_API size_t sr_buffer_size(const sr_buffer *buf); /* 0 for a NULL buffer */

/* An indexed face set.  Strides are in bytes; 0 means tightly packed.
 * Arrays and strides must be multiples of 4 bytes (indices: of their size). */
typedef struct sr_draw_desc {
    sr_primitive primitive;
    size_t vertex_count;        /* entries in each vertex array */

    const float *positions;     /* required: position_size floats per vertex */
    int position_size;          /* 3 (w = 1) or 4; 0 -> 3 */
    size_t position_stride;
    const float *normals;       /* optional, 3 floats; needed by Gouraud and Phong */
    size_t normal_stride;
    const float *colors;        /* optional, color_size floats (RGB or RGBA) */
    int color_size;             /* 3 or 4; 0 -> 4 */
    size_t color_stride;
    const float *texcoords;     /* optional, 2 floats */
    size_t texcoord_stride;
    const float *generic;       /* optional, generic_size floats: any per-vertex quantity */
    int generic_size;           /* 1..4; 0 -> 4 */
    size_t generic_stride;

    const void *indices;        /* optional */
    sr_index_type index_type;
    size_t index_count;

    const sr_mat4 *model;       /* M_O; NULL -> identity */
    const sr_mat4 *view;        /* E;   NULL -> identity */
    const sr_mat4 *projection;  /* P;   NULL -> identity */
} sr_draw_desc;

/* Statistics of the last draw on a context. */
typedef struct sr_draw_info {
    uint64_t triangles_in;      /* assembled primitives */
    uint64_t triangles_clipped; /* triangles that needed clipping */
    uint64_t triangles_culled;  /* culled or zero area */
    uint64_t triangles_drawn;   /* set up and binned */
    uint64_t fragments;         /* samples that passed the depth test and were written */
    uint64_t vertices_shaded;   /* vertices the vertex stage ran for: an indexed draw's
                                   range of indices, not its whole array */
} sr_draw_info;

SR_API sr_result sr_draw(sr_context *ctx, sr_framebuffer *fb, const sr_state *state,
                         const sr_draw_desc *draw);
SR_API sr_draw_info sr_last_draw_info(const sr_context *ctx);

/* ---- meshes ------------------------------------------------------------- */

/* A run of a mesh's triangles that takes a diffuse texture of its own
 * (OBJ: the faces after a `usemtl` whose material's map_Kd differs from
 * the run before; glTF, FBX and the other Assimp formats: the meshes whose
 * material names a different image from the meshes before). */
/* A run's surface as the model file describes it beside its color and
 * texture (OBJ's MTL statements; docs/pbr.md says how the physically based
 * look maps them).  Each has_ flag says whether the file gave the value. */
typedef struct sr_mesh_material {
    bool has_specular, has_shininess, has_opacity, has_metallic, has_roughness;
    float specular[3];     /* Ks */
    float shininess;       /* Ns, the Phong exponent */
    float opacity;         /* d, or 1 - Tr */
    float metallic;        /* Pm (the PBR extension of MTL) */
    float roughness;       /* Pr */
    char *bump_path;       /* map_Bump, bump or norm: the image file, or NULL */
    bool bump_is_normal;   /* norm: a tangent-space normal map; else a height map */
    float bump_scale;      /* -bm, the height map's scale; 0 -> 1 */
} sr_mesh_material;

typedef struct sr_mesh_part {
    size_t first_triangle, triangle_count;
    char *texture_path;    /* this run's texture file, or NULL */
    /* Or its encoded bytes (PNG or JPEG, for sr_decode_image) when the
     * file embeds the image, or NULL.  Each part owns its own copy; both
     * NULL: the run takes no texture. */
    uint8_t *texture_data;
    size_t texture_size;
    sr_mesh_material material;   /* all zero: the file says nothing more */
} sr_mesh_part;

/* A triangle mesh as the model readers and the built-in generators produce
 * it.  Its arrays and strings belong to the mesh and come from the
 * allocator of the context it was made on; release them with
 * sr_destroy_mesh on that context. */
typedef struct sr_mesh {
    size_t vertex_count;
    float *positions;      /* 3 per vertex */
    float *normals;        /* 3 per vertex, or NULL */
    float *colors;         /* 4 per vertex (RGBA), or NULL */
    float *texcoords;      /* 2 per vertex, or NULL */
    size_t triangle_count;
    uint32_t *indices;     /* 3 per triangle, counter-clockwise front faces */
    char *texture_path;    /* diffuse texture named by the file (OBJ map_Kd), or NULL */
    /* The diffuse texture's encoded bytes (PNG or JPEG, for sr_decode_image)
     * when the file embeds it instead of naming one (glTF, GLB), or NULL. */
    uint8_t *texture_data;
    size_t texture_size;
    /* When the triangles take different textures (or some take none):
     * runs in triangle order that cover every triangle, each with its own
     * texture; texture_path or texture_data is then the first one named.
     * NULL and 0 when one texture, or none, serves the whole mesh. */
    sr_mesh_part *parts;
    size_t part_count;
} sr_mesh;

/* A mesh on ctx holding copies of src's arrays, strings and parts (src
 * stays the caller's): how a program hands its own geometry to the mesh
 * functions.  SR_INVALID_ARG (out zeroed, src untouched) for NULL, out ==
 * src, an array missing that a count needs, an index >= vertex_count, a
 * texture_size without texture_data, or parts that are not runs covering
 * every triangle in order; SR_TOO_LARGE for counts whose arrays would
 * overflow size_t (checked before any element is read). */
SR_API sr_result sr_make_mesh(sr_context *ctx, const sr_mesh *src, sr_mesh *out);
/* Frees the mesh's arrays and zeroes *mesh (the struct itself is the
 * caller's).  Every mesh function takes the context the mesh was made on. */
SR_API void sr_destroy_mesh(sr_context *ctx, sr_mesh *mesh);

typedef enum sr_normal_mode {
    SR_NORMALS_SMOOTH = 0, /* angle-weighted vertex normals */
    SR_NORMALS_FLAT,       /* vertices split, one normal per face */
} sr_normal_mode;

/* Replace mesh->normals with computed ones (flat: the vertices split, so
 * colors, texcoords and indices are replaced too), on ctx's allocator;
 * smooth ones are computed on ctx's threads, the same bits for any
 * thread count. */
SR_API sr_result sr_mesh_compute_normals(sr_context *ctx, sr_mesh *mesh, sr_normal_mode mode);
/* Tangents for tangent-space normal maps, 4 floats a vertex into
 * `tangents` (the caller's, mesh->vertex_count entries), with MikkTSpace's
 * conventions: each triangle's tangent and bitangent from its texcoord
 * derivatives (dP/du, dP/dv), summed per vertex, the tangent made
 * orthogonal to the normal (Gram-Schmidt) and normalized, w = +1 when
 * (N x T) . B > 0 and -1 otherwise.  Needs normals and texcoords; a
 * vertex no triangle gives a direction to gets any unit vector orthogonal
 * to its normal. */
SR_API sr_result sr_mesh_compute_tangents(sr_context *ctx, const sr_mesh *mesh, float *tangents);
/* Blending order (SR_ALPHA_BLEND, translucent materials): what is drawn
 * over what is behind it must be drawn after it, so see-through surfaces
 * go back to front.  sr_sort_back_to_front writes the triangles of
 * indices[0 .. 3 triangle_count) into out (the caller's, as many
 * indices; it may be indices itself, to sort in place) farthest first by the eye-space depth of their centroid
 * (model_view takes positions to an eye looking down -z), equal depths
 * in their first order; sr_mean_view_depth gives the mean eye-space
 * distance (-z) of the corners of those triangles, and
 * sr_order_back_to_front the order of `count` meshes or parts by such
 * distances, farthest first, ties in their first order (order[k] the
 * index of the k-th to draw).  Positions are 3 floats a vertex,
 * vertex_count of them.  SR_INVALID_ARG for NULL arrays, an index past
 * vertex_count, a non-finite matrix or a NaN distance;
 * SR_OUT_OF_MEMORY. */
SR_API sr_result sr_sort_back_to_front(sr_context *ctx, const float *positions,
                                       size_t vertex_count, const uint32_t *indices,
                                       size_t triangle_count, const sr_mat4 *model_view,
                                       uint32_t *out);
SR_API sr_result sr_mean_view_depth(const float *positions, size_t vertex_count,
                                    const uint32_t *indices, size_t triangle_count,
                                    const sr_mat4 *model_view, float *out);
SR_API sr_result sr_order_back_to_front(sr_context *ctx, const float *distances, size_t count,
                                        size_t *order);
/* Axis-aligned bounding box; false for an empty mesh. */
SR_API bool sr_mesh_bounds(const sr_mesh *mesh, sr_vec3 *min, sr_vec3 *max);

/* Newell's method: the normal of the polygon points[0..count-1] (closed,
 * planar or not), unnormalized.  It computes, over the edges i -> j = i + 1
 * (mod count),
 *     out.x = sum (y_i - y_j)(z_i + z_j)
 *     out.y = sum (z_i - z_j)(x_i + x_j)
 *     out.z = sum (x_i - x_j)(y_i + y_j)
 * each twice the signed area of the polygon projected on one axis plane.
 * For a planar polygon, out is normal to its plane, points to the side from
 * which the corners run counter-clockwise (reversing them negates it), and
 * |out| is twice its area; sr_vec3_normalize(out) is the unit normal.  For a
 * non-planar polygon it is the best-fit plane's normal.  Sums run in double,
 * relative to points[0].  A degenerate polygon (collinear or repeated
 * corners, or projected areas that cancel, as in a figure eight) has zero
 * area: out is the zero vector and the result SR_OK, so test |out| before
 * normalizing.  SR_INVALID_ARG for NULL, count < 3 or a non-finite
 * coordinate (out zeroed when not NULL); SR_TOO_LARGE if a component
 * overflows float. */
SR_API sr_result sr_newell_normal(const sr_vec3 *points, int count, sr_vec3 *out);

/* ---- built-in geometry -------------------------------------------------- */

/* Tessellate bicubic Bezier patches (16 control points each, row-major
 * [u][v], as float xyz) into a mesh of detail x detail quads per patch
 * (detail 1..256), evaluated by forward differences, with normals from the
 * patch derivatives.  Release with sr_destroy_mesh. */
SR_API sr_result sr_make_bezier_mesh(sr_context *ctx, const float (*patches)[16][3],
                                     size_t patch_count, int detail, sr_mesh *out);
/* The Utah teapot (32 patches), y up, standing on y = 0, spout towards +x.
 * Release with sr_destroy_mesh. */
SR_API sr_result sr_make_teapot(sr_context *ctx, int detail, sr_mesh *out);

/* A ground plane for a scene (docs/shadows.md): a square of side
 * `scale` x the largest extent of the bounds across `up`, centred under
 * the bounds' centre, in the plane through the bounds' lowest corner
 * along `up` (moved down by `drop` x that extent), facing `up`, with
 * normals and texcoords (0..1 over the square).  Two triangles,
 * counter-clockwise seen from above. */
typedef struct sr_ground_desc {
    sr_vec3 bounds_min, bounds_max;  /* the scene's world-space box, min <= max */
    sr_vec3 up;                      /* zero -> +Y; any length > 0 */
    float scale;                     /* 0 -> 4; 0.01 .. 1000 */
    float drop;                      /* 0 -> none; 0 .. 1 */
} sr_ground_desc;
SR_API sr_result sr_make_ground_mesh(sr_context *ctx, const sr_ground_desc *desc, sr_mesh *out);

/* ---- framing ------------------------------------------------------------ */
/*
 * The default camera of a model, as `softrast render` and the Python
 * package place it when given none (docs/pipeline.md, "The default
 * camera"): looking along
 * -sr_framing_direction() (a three-quarter view from the front right,
 * above) with +y up, from where the vertices' projections span the image
 * less SR_FRAMING_MARGIN of its width or height on each side in the
 * limiting dimension and are centred in the other.  The target is the
 * point of the line of sight nearest the centre of the vertices' world
 * box.  Perspective as sr_perspective(info.fovy, width / height, ...)
 * projects, or orthographic (half extents set; the eye where the
 * perspective camera would stand, the view as tight).
 */
#define SR_FRAMING_FOV_DEG 35.0f   /* default field of view across the smaller side */
#define SR_FRAMING_MARGIN  0.05f   /* of the image's width or height, each side */

/* From the model towards the eye: normalize(0.62, 0.48, 1). */
SR_API sr_vec3 sr_framing_direction(void);

typedef struct sr_framing_points {
    const float *positions;          /* x, y, z a vertex; required when count > 0 */
    size_t count;                    /* vertices (NaN coordinates are skipped) */
    const sr_mat4 *model;            /* places them in the world; NULL -> identity */
} sr_framing_points;

typedef struct sr_framing_desc {
    const sr_framing_points *sets;   /* required: the vertices to frame */
    int set_count;                   /* >= 1 */
    int width, height;               /* the image, required, 1 .. SR_MAX_FRAMEBUFFER_SIZE */
    float fov;                       /* radians across the smaller side, in (0, pi);
                                      * 0 -> SR_FRAMING_FOV_DEG */
    bool ortho;                      /* fit an orthographic view */
} sr_framing_desc;

typedef struct sr_framing_info {
    sr_vec3 eye, target, up;         /* for sr_look_at; up is +y */
    float fovy;                      /* vertical field of view: sr_fit_fovy(fov, width, height) */
    float half_width, half_height;   /* ortho: the view's half extents (0 for perspective) */
    sr_vec3 centre;                  /* the centre of the vertices' world box */
} sr_framing_info;

/* The camera framing desc's vertices (ctx keeps the message of a failure;
 * it may be NULL).  SR_INVALID_ARG (out zeroed) for a
 * field out of range, a NULL array, a non-finite model matrix, or vertices
 * that give no frame: none, all in one point, none finite, or so far out
 * that the fit overflows float. */
SR_API sr_result sr_fit_camera(sr_context *ctx, const sr_framing_desc *desc, sr_framing_info *out);

/* ---- shadows ------------------------------------------------------------ */
/*
 * A shadow map for a directional key light (docs/shadows.md).  The light's
 * orthographic view is fitted to a world-space box that holds every
 * occluder: its depth range to the box's extent along the light, its
 * rectangle to the box's outline as the light sees it (plus a margin for
 * the filter).  Each frame: sr_shadow_map_clear, sr_shadow_map_draw for
 * every occluder (a mesh's positions with its model matrix; the draw's
 * view and projection are replaced by the light's), then look the map up
 * from the shaders with sr_shadow_visibility or sr_shadow_visibility4.
 *
 * Occluders are drawn into its depth through sr_draw with both faces kept and
 * slope-scaled polygon offset (sr_polygon_offset: factor x the depth slope
 * of each triangle, plus units x the format's step), so a lit surface does
 * not shadow itself where the map's depth is a rasterized approximation of
 * it.  The lookup moves the receiver along its normal by a few texels
 * (more where it is steep to the light) before comparing: the filter's
 * outer taps compare against texels up to (radius + 1/2) sqrt 2 texels
 * away, which the offset at the caster alone would have to cover with a
 * larger bias (and more peter-panning).  The lookup is percentage-closer filtering:
 * the fraction of the map's texels, weighted by how much of each a box of
 * half-width filter_radius texels around the point covers, that lie
 * farther from the light than the point, so the penumbra is continuous
 * and monotonic across an edge.  Points outside the map are lit.
 *
 * Lookups only read the map: shaders on every thread may call them at
 * once between draws, and they give the same value for the same point.
 */
typedef struct sr_shadow_map sr_shadow_map;

typedef struct sr_shadow_desc {
    sr_vec3 direction;               /* required: the direction the light travels,
                                      * from the light to the scene (as the vector of
                                      * an SR_LIGHT_DIRECTIONAL sr_light); any length > 0 */
    sr_vec3 bounds_min, bounds_max;  /* world-space box of the occluders, min <= max */
    int size;                        /* texels a side: 0 -> 2048; 16 .. SR_MAX_FRAMEBUFFER_SIZE */
    float offset_factor;             /* polygon offset of the occluders: 0 -> 1.5 */
    float offset_units;              /* 0 -> 2 */
    float filter_radius;             /* PCF half-width, texels: 0 -> 1.5; 0.5 .. 8 */
    /* The receiver moves along its normal by (normal_offset + 1.5
     * filter_radius) texels times the sine of the angle between normal
     * and light: 0 -> 1; 0 .. 64 (a NULL normal at lookup: no move). */
    float normal_offset;
    /* The light's angular radius, radians, for shadows that are sharp
     * where they touch their caster and soften with distance from it
     * (percentage-closer soft shadows): 0 -> a fixed filter of
     * filter_radius; > 0 (at most 0.5) -> a penumbra of half-width
     * (distance to the blockers) x tan(light_radius), from filter_radius
     * up to 8 texels. */
    float light_radius;
} sr_shadow_desc;

/* The light's transform as the map uses it. */
typedef struct sr_shadow_info {
    sr_mat4 view;                    /* world -> light eye space (looking along direction) */
    sr_mat4 projection;              /* orthographic, depth in [0, 1] (zero_to_one) */
    int size;                        /* texels a side */
    float texel_size;                /* world units a texel spans */
    float filter_radius, normal_offset;  /* resolved */
} sr_shadow_info;

SR_API sr_result sr_make_shadow_map(sr_context *ctx, const sr_shadow_desc *desc, sr_shadow_map **out);
SR_API void      sr_destroy_shadow_map(sr_context *ctx, sr_shadow_map *sm);
/* Empties the map (every point lit) for a new frame. */
SR_API sr_result sr_shadow_map_clear(sr_context *ctx, sr_shadow_map *sm);
/* Draws draw's triangles into the map as occluders: positions and model
 * (other arrays ignored), the light's view and projection. */
SR_API sr_result sr_shadow_map_draw(sr_context *ctx, sr_shadow_map *sm, const sr_draw_desc *draw);
SR_API sr_result sr_query_shadow_map(const sr_shadow_map *sm, sr_shadow_info *out);
/* Visibility of the world-space point pos[0..2] in [0, 1]: 0 in shadow,
 * 1 lit.  normal (may be NULL: no normal offset) is the surface's
 * world-space geometric normal (the interpolated vertex normal, not a
 * normal map's), any length; a point that is not finite is lit. */
SR_API sr_result sr_shadow_visibility(const sr_shadow_map *sm, const float pos[3],
                                      const float normal[3], float *out);
/* Four points at once, laid out as three varyings of an sr_fragment_quad:
 * pos[0..3] the x of lanes 0..3, pos[4..7] their y, pos[8..11] their z;
 * normal likewise (or NULL); out[i] the visibility of lane i, the same
 * value sr_shadow_visibility gives for it. */
SR_API sr_result sr_shadow_visibility4(const sr_shadow_map *sm, const float *pos,
                                       const float *normal, float out[4]);

/* A shadow catcher (docs/shadows.md): the ground square drawn black with
 * alpha 0.6 x (1 - visibility) x a fade over the outer half of the square,
 * blended source-over with depth writes off and both faces, so that where
 * the ground is lit the framebuffer keeps its bytes.  Only the part of the
 * square where the map's box can cast a shadow is drawn (nothing when the
 * light does not come from above).  `state` gives the depth test and the
 * rest; its program, cull, depth writes and blending are replaced.  Draw
 * it after the opaque objects, whose depth hides the ground behind them,
 * and before translucent ones.  SR_INVALID_ARG, whether or not anything
 * would be drawn, for a state sr_draw would refuse, a zero or non-finite
 * direction, bounds with min > max, or a non-finite view or projection. */
typedef struct sr_shadow_catcher_desc {
    const sr_mesh *ground;           /* required: a +Y-up sr_make_ground_mesh square */
    const sr_shadow_map *map;        /* required: drawn for this frame */
    sr_vec3 direction;               /* the light's, as the map was made with */
    sr_vec3 bounds_min, bounds_max;  /* the occluders' box, as the map was made with */
    const sr_mat4 *view, *projection;  /* required: world -> eye -> clip */
} sr_shadow_catcher_desc;
SR_API sr_result sr_draw_shadow_catcher(sr_context *ctx, sr_framebuffer *fb, const sr_state *state,
                                        const sr_shadow_catcher_desc *desc);

/* ---- 2D raster API ------------------------------------------------------ */
/*
 * Vector drawing straight into a framebuffer's color, in pixel coordinates
 * (x right, y down, pixel (x, y) = [x, x+1) x [y, y+1), sampled at its
 * centre).  These calls ignore depth.  Colors are straight RGBA in [0, 1];
 * a color with alpha < 1 is blended source-over.  Sections below are added
 * by the 2D toolkit and the line algorithms.
 */

typedef struct sr_point2 { double x, y; } sr_point2;

typedef struct sr_rgba { float r, g, b, a; } sr_rgba;

/* Text labels for demos and overlays, in softrast's own 5x7 pixel font
 * (printable ASCII; other bytes draw as a box).  (x, y) is the top-left
 * corner; each glyph cell is 6 x 8 pixels times `scale` (>= 1). */
SR_API sr_result sr_draw_text(sr_context *ctx, sr_framebuffer *fb, int x, int y, int scale,
                              const char *text, sr_rgba color);
/* Width in pixels that sr_draw_text would use. */
SR_API int sr_text_width(const char *text, int scale);

/* ---- 2D polygon fill ---------------------------------------------------- */
/*
 * Polygons are one or more closed contours (concave, self-intersecting,
 * holes as further contours).  Vertices are snapped to 1/256 pixel.
 * Aliased fills use the scan-line algorithm with an edge table and an
 * active edge table: a pixel is filled when its centre is inside, edges
 * are half-open in y and spans [x_l, x_r) left-inclusive, so polygons
 * sharing an edge fill each pixel exactly once.  Antialiased fills take
 * the exact area of polygon and pixel (signed-area accumulation), or count
 * n x n samples.  Vertices beyond SR_MAX_COORD2D (finite: NaN and
 * infinities are SR_INVALID_ARG) are drawn, clipped: each contour is cut
 * to the target grown by a guard band first (docs/raster-rules.md §2.2);
 * the Gouraud fills refuse them (SR_TOO_LARGE).
 */

/* |x|, |y| of a 2D vertex the converters take as it is, in pixels */
#define SR_MAX_COORD2D 262144.0

typedef enum sr_fill_rule {
    SR_FILL_RULE_DEFAULT = 0, /* -> SR_NONZERO (SVG's default) */
    SR_NONZERO,               /* inside where the winding number is not 0 */
    SR_EVENODD,               /* inside where it is odd (parity) */
} sr_fill_rule;

typedef enum sr_antialias {
    SR_AA_DEFAULT = 0,  /* -> SR_AA_NONE */
    SR_AA_NONE,         /* point sampling at pixel centres (edge table) */
    SR_AA_AREA,         /* exact area coverage; where contours overlap inside one
                         * pixel the winding integral is clamped (nonzero) or
                         * folded (even-odd), an approximation */
    SR_AA_SUPERSAMPLE,  /* samples x samples ordered grid per pixel, exact per sample */
} sr_antialias;

typedef struct sr_polygon2 {
    const sr_point2 *points;    /* every contour's vertices, back to back */
    int point_count;
    const int *contour_counts;  /* vertices per contour; NULL -> one contour */
    int contour_count;          /* entries in contour_counts */
} sr_polygon2;

typedef struct sr_fill_desc {
    sr_fill_rule rule;
    sr_antialias antialias;
    int samples;        /* SR_AA_SUPERSAMPLE: 0 -> 4; 1..16 */
    bool linear_light;  /* blend partial coverage in linear light (sRGB decoded) */
} sr_fill_desc;

/* Fill a polygon with a color (desc may be NULL: nonzero, aliased). */
SR_API sr_result sr_fill_polygon(sr_context *ctx, sr_framebuffer *fb, const sr_polygon2 *poly,
                                 sr_rgba color, const sr_fill_desc *desc);
/* Coverage only: 0..255 per pixel of the w x h window whose top-left pixel
 * is (x0, y0), written to mask (stride bytes per row; the window is
 * zeroed first).  Aliased coverage is 0 or 255.  SR_TOO_LARGE for a window
 * reaching beyond +-SR_MAX_COORD2D, where no edge can be snapped. */
SR_API sr_result sr_polygon_coverage(sr_context *ctx, const sr_polygon2 *poly,
                                     const sr_fill_desc *desc, int x0, int y0, int w, int h,
                                     uint8_t *mask, size_t stride);
/* Blend `color` into fb through a coverage mask (0..255 per pixel, w x h,
 * stride bytes per row) whose top-left pixel lands on (x, y), clipped to
 * the framebuffer, source-over as the fills blend.  Coverage computed
 * once by sr_polygon_coverage can so be drawn many times (cached glyphs
 * of a text overlay). */
SR_API sr_result sr_draw_coverage(sr_context *ctx, sr_framebuffer *fb, int x, int y, int w, int h,
                                  const uint8_t *mask, size_t stride, sr_rgba color);

/* How sr_draw_layer blends. */
typedef struct sr_layer_desc {
    const uint8_t *mask;    /* 0..255 per layer pixel, w x h; NULL -> full coverage */
    size_t mask_stride;     /* bytes from a mask row to the next; 0 -> w */
    float opacity;          /* in [0, 1]; 0 -> 1, as sr_paint's */
} sr_layer_desc;

/* Blend a w x h RGBA8 image (straight alpha, stride bytes per row: a layer
 * drawn apart, transparent where nothing was drawn) into fb with its
 * top-left pixel on (x, y), clipped to the framebuffer: each pixel
 * source-over as the fills blend, at its alpha times desc->opacity times
 * its mask coverage / 255.  Drawing into a transparent layer and blending
 * it through a clip's coverage (sr_polygon_coverage) is how SVG's
 * clip-path and group opacity draw (the SVG reader's layers blend so).
 * desc may be NULL. */
SR_API sr_result sr_draw_layer(sr_context *ctx, sr_framebuffer *fb, int x, int y, int w, int h,
                               const uint8_t *rgba, size_t stride, const sr_layer_desc *desc);

/* ---- region filling ----------------------------------------------------- */
/*
 * Region fills on the pixels already in the framebuffer.  Flood fill
 * recolours the connected region of pixels matching the start pixel's
 * color; boundary fill recolours the connected region of pixels that do
 * not match a boundary color.  Both are span fills with an explicit stack
 * (no recursion, memory bounded by the image): a whole horizontal run is
 * filled, then the rows above and below are scanned across it for new
 * runs.  The fill color replaces the pixels (no blending).
 */

typedef enum sr_connectivity {
    SR_CONNECT_DEFAULT = 0, /* -> SR_CONNECT_4 */
    SR_CONNECT_4,           /* neighbours (+-1, 0), (0, +-1) */
    SR_CONNECT_8,           /* and the four diagonals */
} sr_connectivity;

typedef struct sr_region_fill_desc {
    sr_connectivity connectivity;
    int tolerance;          /* 0..255: colors match when every RGBA8 channel
                             * differs by at most this much; 0 = exact */
} sr_region_fill_desc;

/* (x, y) must be inside the framebuffer; desc may be NULL; filled (may be
 * NULL) receives the number of pixels recoloured. */
SR_API sr_result sr_flood_fill(sr_context *ctx, sr_framebuffer *fb, int x, int y, sr_rgba fill,
                               const sr_region_fill_desc *desc, size_t *filled);
SR_API sr_result sr_boundary_fill(sr_context *ctx, sr_framebuffer *fb, int x, int y, sr_rgba fill,
                                  sr_rgba boundary, const sr_region_fill_desc *desc, size_t *filled);

/* ---- blur --------------------------------------------------------------- */
/*
 * A Gaussian blur of an image of floats (1 to 4 channels interleaved,
 * rows of width * channels floats, premultiplied when there is alpha),
 * in place: each row, then each column.  A deviation below 2 pixels
 * uses the exact sampled kernel (3 deviations each side, normalized);
 * from 2 up, SVG's three box blurs of size d = floor(sigma * 3 *
 * sqrt(2 pi) / 4 + 0.5) (two of d shifted half a pixel each way and one
 * of d + 1 when d is even), whose cost does not grow with the deviation.
 * A deviation of 0 leaves that axis as it is.  What lies beyond the
 * image is chosen by the edge mode.
 */

typedef enum sr_blur_edge {
    SR_BLUR_EDGE_DEFAULT = 0,   /* -> SR_BLUR_EDGE_NONE */
    SR_BLUR_EDGE_NONE,          /* zeros (transparent black) */
    SR_BLUR_EDGE_DUPLICATE,     /* the edge pixels repeated */
    SR_BLUR_EDGE_WRAP,          /* the opposite edge's pixels */
} sr_blur_edge;

typedef struct sr_blur_desc {
    double sigma_x, sigma_y;    /* standard deviations in pixels, >= 0 */
    sr_blur_edge edge;
} sr_blur_desc;

SR_API sr_result sr_blur_image(sr_context *ctx, float *pixels, int width, int height,
                               int channels, const sr_blur_desc *desc);

/* ---- 2D polygon clipping ------------------------------------------------ */
/*
 * Sutherland-Hodgman: the polygon is clipped against one edge of the clip
 * window after another.  For each polygon edge (first point, second point):
 * both inside -> output the second point; inside to outside -> the
 * intersection; both outside -> nothing; outside to inside -> the
 * intersection and the second point.  Points on a clip edge are inside.
 * Intersections are computed from the inside point, so two polygons that
 * share an edge get the same clipped vertices.  A concave polygon that the
 * window cuts into pieces comes out as one polygon whose pieces are joined
 * along the window border (zero-area bridges), which fills correctly.
 */

/* Called with the polygon after each clip edge (edge 0 first). */
typedef void (*sr_clip_stage_fn)(void *user, int clip_edge, const sr_point2 *poly, int count);

typedef struct sr_polygon_clip_desc {
    sr_clip_stage_fn on_stage;  /* optional */
    void *user;
} sr_polygon_clip_desc;

/* Clip against the rectangle xmin <= x <= xmax, ymin <= y <= ymax, edges in
 * the order left, bottom (y = ymax, the bottom of the screen), right, top.
 * out receives up to `capacity` points; *out_count is the clipped polygon's
 * size (0 when nothing is left).  When capacity is too small the call
 * returns SR_TOO_LARGE with *out_count the size needed (call again with a
 * larger buffer).  desc may be NULL. */
SR_API sr_result sr_clip_polygon_rect(sr_context *ctx, const sr_point2 *in, int count, double xmin,
                                      double ymin, double xmax, double ymax,
                                      const sr_polygon_clip_desc *desc, sr_point2 *out, int capacity,
                                      int *out_count);
/* Clip against a convex window polygon (either orientation, at least 3
 * vertices, non-zero area); its edges are used in order. */
SR_API sr_result sr_clip_polygon_convex(sr_context *ctx, const sr_point2 *in, int count,
                                        const sr_point2 *window, int window_count,
                                        const sr_polygon_clip_desc *desc, sr_point2 *out, int capacity,
                                        int *out_count);

/* ---- curves ------------------------------------------------------------- */
/*
 * Ellipses and circles by the midpoint method: the decision variable is the
 * implicit function F(x, y) = ry^2 (x - cx)^2 + rx^2 (y - cy)^2 - rx^2 ry^2
 * at pixel centres, in exact integers (centre and radii snapped to 1/256
 * pixel) and stepped from pixel to pixel by forward differences.  A pixel
 * is inside when F < 0 at its centre; the outline is the set of inside
 * pixels with an outside 4-neighbour, so the octants meet without gaps or
 * doubled pixels for any centre and radius.
 */

/* rx, ry >= 0; |cx|, |cy|, rx, ry <= SR_MAX_COORD2D.  Aliased. */
SR_API sr_result sr_draw_ellipse(sr_context *ctx, sr_framebuffer *fb, double cx, double cy, double rx,
                                 double ry, sr_rgba color, bool filled);
SR_API sr_result sr_draw_circle(sr_context *ctx, sr_framebuffer *fb, double cx, double cy, double r,
                                sr_rgba color, bool filled);

/* An implicit region F(x, y) < 0.  The function returns F at (x, y) in
 * pixel coordinates; when grad is not NULL it may store dF/dx, dF/dy there
 * (left untouched, central differences are used). */
typedef double (*sr_implicit_fn)(void *user, double x, double y, double grad[2]);

typedef struct sr_implicit_desc {
    sr_implicit_fn f;           /* required */
    void *user;
    double x0, y0, x1, y1;      /* the box to evaluate, pixels; all zero -> the framebuffer */
    bool antialias;             /* coverage clamp(1/2 - F / |grad F|, 0, 1): the signed
                                 * distance to the curve, to first order */
    bool linear_light;
} sr_implicit_desc;

SR_API sr_result sr_fill_implicit(sr_context *ctx, sr_framebuffer *fb, const sr_implicit_desc *desc,
                                  sr_rgba color);

/* Bezier curves flattened by forward differencing: n steps of 1/n in t,
 * with n chosen so the chords stay within `tolerance` pixels of the curve
 * (from the bound |B''| h^2 / 8 on the chord error).  out receives the n
 * points after p0 (the last is exactly the end point).  Capacity too small:
 * SR_TOO_LARGE and *out_count = n. */
SR_API sr_result sr_flatten_quadratic(sr_context *ctx, sr_point2 p0, sr_point2 p1, sr_point2 p2,
                                      double tolerance, sr_point2 *out, int capacity, int *out_count);
SR_API sr_result sr_flatten_cubic(sr_context *ctx, sr_point2 p0, sr_point2 p1, sr_point2 p2,
                                  sr_point2 p3, double tolerance, sr_point2 *out, int capacity,
                                  int *out_count);
/* An SVG elliptical arc from `from` to `to` (radii, x-axis rotation in
 * degrees, large-arc and sweep flags; out-of-range radii are scaled up as
 * SVG 1.1 F.6.6 says, zero radii give a straight line).  Same output
 * convention as the Bezier calls. */
SR_API sr_result sr_flatten_arc(sr_context *ctx, sr_point2 from, double rx, double ry,
                                double rotation_deg, bool large_arc, bool sweep, sr_point2 to,
                                double tolerance, sr_point2 *out, int capacity, int *out_count);

/* ---- Gouraud-shaded 2D polygons ----------------------------------------- */
/*
 * The same pixels as sr_fill_polygon (aliased edge-table fill), colored by
 * interpolation.  Triangles: barycentric weights of the pixel centre times
 * the vertex colors.  Polygons (any, as sr_polygon2): the colors are
 * interpolated along each edge to where it crosses the scanline, then
 * along the span between the two crossings (bilinear interpolation, which
 * depends on the polygon's orientation for more than three vertices).
 * Colors with alpha < 1 blend source-over.
 */
SR_API sr_result sr_fill_triangle_gouraud(sr_context *ctx, sr_framebuffer *fb, const sr_point2 v[3],
                                          const sr_rgba colors[3]);
/* colors: one per polygon point; rule: SR_FILL_RULE_DEFAULT -> nonzero. */
SR_API sr_result sr_fill_polygon_gouraud(sr_context *ctx, sr_framebuffer *fb, const sr_polygon2 *poly,
                                         const sr_rgba *colors, sr_fill_rule rule);

/* How sr_fill_gouraud finds each pixel's color.  Both cover the pixels of
 * sr_fill_polygon (the same edge-table converter). */
typedef enum sr_gouraud_method {
    SR_GOURAUD_DEFAULT = 0,     /* -> SR_GOURAUD_DIRECT */
    SR_GOURAUD_DIRECT,          /* each pixel from scratch, in double: a one-contour
                                 * triangle as sr_fill_triangle_gouraud, anything else as
                                 * sr_fill_polygon_gouraud */
    SR_GOURAUD_INCREMENTAL,     /* the notes' FillPoly / FillSpan: along each edge x steps
                                 * by 1/m and the color by dI/dy per scanline (for a
                                 * triangle: edges AB then BC beside AC, split at the
                                 * middle vertex B), along each span the color steps by
                                 * (I_R - I_L) / (x_R - x_L) per pixel, summed in float.
                                 * Each walk starts at its first sample (y + 1/2, x + 1/2).
                                 * Colors within one 8-bit step of DIRECT's: the sums
                                 * accumulate rounding (docs/draw2d.md) */
} sr_gouraud_method;

typedef struct sr_gouraud_desc {
    sr_fill_rule rule;          /* SR_FILL_RULE_DEFAULT -> nonzero */
    sr_gouraud_method method;
} sr_gouraud_desc;

/* colors: one per polygon point; desc NULL: all defaults. */
SR_API sr_result sr_fill_gouraud(sr_context *ctx, sr_framebuffer *fb, const sr_polygon2 *poly,
                                 const sr_rgba *colors, const sr_gouraud_desc *desc);

/* ---- paths and strokes -------------------------------------------------- */
/*
 * A path is a list of subpaths built from lines, Beziers and arcs, flattened
 * to polylines as they are added (within the path's tolerance).  Filling
 * closes every subpath; stroking builds the outline polygon of the stroke
 * (a quadrilateral per segment, join pieces, cap pieces, all wound the same
 * way) and fills it with the nonzero rule.
 */
typedef struct sr_path sr_path;

/* tolerance: flattening error in pixels; 0 -> 0.1. */
SR_API sr_result sr_make_path(sr_context *ctx, double tolerance, sr_path **out);
SR_API void      sr_destroy_path(sr_context *ctx, sr_path *path); /* ctx: the one that made it */
SR_API void      sr_path_clear(sr_path *path);
SR_API sr_result sr_path_move_to(sr_path *path, double x, double y);
SR_API sr_result sr_path_line_to(sr_path *path, double x, double y);
SR_API sr_result sr_path_quad_to(sr_path *path, double x1, double y1, double x, double y);
SR_API sr_result sr_path_cubic_to(sr_path *path, double x1, double y1, double x2, double y2,
                                  double x, double y);
SR_API sr_result sr_path_arc_to(sr_path *path, double rx, double ry, double rotation_deg,
                                bool large_arc, bool sweep, double x, double y);
SR_API sr_result sr_path_close(sr_path *path);
/* The flattened path as a polygon (valid until the path changes). */
SR_API sr_polygon2 sr_path_polygon(const sr_path *path);
/* Whether subpath i (0 .. contour_count - 1 of the polygon) was closed by
 * sr_path_close; false for a NULL path or an i out of range. */
SR_API bool      sr_path_subpath_closed(const sr_path *path, int i);
/* The length of the flattened path, closing segments included; 0 for NULL. */
SR_API double    sr_path_length(const sr_path *path);

/* Values in a dash list, at most. */
#define SR_MAX_DASHES 32

/*
 * Dashes, as SVG's stroke-dasharray and stroke-dashoffset: appends to out
 * (made by the caller, not `path` itself) the dashes of `path`, each an
 * open subpath, for sr_stroke_path to stroke with caps at both ends.
 * dashes[0 .. count) are the lengths of dashes and gaps in turn along the
 * flattened path, each finite and >= 0; an odd count is repeated once
 * (5, 3, 2 means 5, 3, 2, 5, 3, 2).  The pattern starts `offset` into
 * itself (finite, wrapped by its period; negative: that much before it)
 * at the start of every subpath.  A closed subpath is dashed across its
 * closing segment, and a dash over its start point joins the first one
 * (no caps there).  A zero-length dash is a subpath of one point (round
 * and square caps draw it).  count 0 or a list of zeros copies the path
 * (SVG strokes it solid).  SR_INVALID_ARG naming the argument (NULL, a
 * count outside 0 .. SR_MAX_DASHES, a negative or non-finite value or
 * offset), SR_TOO_LARGE when the dashes would pass a path's 2^26 points
 * (about length / period * count of them; nothing is appended then).
 */
SR_API sr_result sr_path_dash(sr_context *ctx, const sr_path *path, const double *dashes,
                              int count, double offset, sr_path *out);

/*
 * Where a path far larger than its target is seen: m (a, b, c, d, e, f:
 * x' = a x + c y + e, y' = b x + d y + f) maps path coordinates to device
 * pixels, where [x0, x1] x [y0, y1] holds every pixel drawn, grown by how
 * far a stroke reaches from the path (half its width times the miter
 * limit or sqrt 2 for square caps, whichever is larger).
 */
typedef struct sr_path_view {
    double m[6];
    double x0, y0, x1, y1;
} sr_path_view;

/*
 * From now on (until sr_path_clear, or view NULL), a quadratic or cubic
 * segment whose control polygon, mapped, lies wholly beyond one side of
 * the view's rectangle is appended as a line to its end point; one that
 * crosses the rectangle's edge is halved until each half is outside,
 * inside or under 4096 px, and only those are flattened.  An elliptical
 * arc is culled so by quarter turns, each held by the triangle of its
 * ends and their tangents' meeting point, halved by angle.  A segment
 * inside is flattened as without a view.  Fills and strokes within the
 * rectangle do not change; the path's length and bounds do.
 * SR_INVALID_ARG for a NULL path, a non-finite m or an empty rectangle.
 */
SR_API sr_result sr_path_cull_curves(sr_path *path, const sr_path_view *view);
/* sr_path_length of the parts of the segments within the view's
 * rectangle (NULL: all of it); 0 for a NULL path. */
SR_API double    sr_path_length_in_view(const sr_path *path, const sr_path_view *view);
/*
 * sr_path_dash making only the dashes within the view's rectangle (view
 * NULL: all of them): over the rest the pattern moves on without dashes,
 * its phase kept, and a dash the rectangle's edge cuts ends there and
 * starts again where the path comes back; the limit counts the length
 * within.  SR_INVALID_ARG as sr_path_dash, and for a view with a
 * non-finite m or an empty rectangle.
 */
SR_API sr_result sr_path_dash_in_view(sr_context *ctx, const sr_path *path, const double *dashes,
                                      int count, double offset, const sr_path_view *view,
                                      sr_path *out);

typedef enum sr_stroke_join {
    SR_STROKE_JOIN_DEFAULT = 0, /* -> SR_STROKE_JOIN_MITER (SVG's default) */
    SR_STROKE_JOIN_MITER,       /* bevel where the miter exceeds the limit */
    SR_STROKE_JOIN_ROUND,
    SR_STROKE_JOIN_BEVEL,
} sr_stroke_join;

typedef enum sr_stroke_cap {
    SR_STROKE_CAP_DEFAULT = 0,  /* -> SR_STROKE_CAP_BUTT */
    SR_STROKE_CAP_BUTT,
    SR_STROKE_CAP_ROUND,
    SR_STROKE_CAP_SQUARE,
} sr_stroke_cap;

typedef struct sr_stroke_desc {
    double width;               /* 0 -> 1 pixel */
    sr_stroke_join join;
    sr_stroke_cap cap;
    double miter_limit;         /* miter length / width; 0 -> 4; >= 1 */
    sr_antialias antialias;     /* as sr_fill_desc; note SR_AA_AREA slightly
                                 * over-covers where stroke pieces overlap inside a
                                 * pixel, SR_AA_SUPERSAMPLE does not */
    int samples;
    bool linear_light;
} sr_stroke_desc;

SR_API sr_result sr_fill_path(sr_context *ctx, sr_framebuffer *fb, const sr_path *path, sr_rgba color,
                              const sr_fill_desc *desc);
SR_API sr_result sr_stroke_path(sr_context *ctx, sr_framebuffer *fb, const sr_path *path,
                                sr_rgba color, const sr_stroke_desc *desc);
/* The stroke outline itself: out->points and out->contour_counts are
 * allocated on ctx; release them with sr_destroy_stroke_outline. */
SR_API sr_result sr_make_stroke_outline(sr_context *ctx, const sr_path *path,
                                        const sr_stroke_desc *desc, sr_polygon2 *out);
SR_API void      sr_destroy_stroke_outline(sr_context *ctx, sr_polygon2 *outline);

/* ---- paint: gradients and patterns -------------------------------------- */
/*
 * A fill's paint other than a flat color, as cairo's and SVG's paint
 * servers: a linear or radial gradient or a repeated image.  The geometry
 * is in paint space, which `transform` maps to pixels (NULL: paint space
 * is pixels).  The same code paints the SVG reader's gradients, patterns
 * and images, so a paint gives the bytes sr_render_svg gives for the
 * equivalent document.  Blending is source-over in straight alpha with
 * the paint quantized to RGBA8, as the color fills blend.
 */
#define SR_MAX_GRADIENT_STOPS 256

typedef enum sr_paint_kind {
    SR_PAINT_COLOR = 0,         /* `color` (alpha times opacity): sr_fill_polygon's bytes */
    SR_PAINT_LINEAR_GRADIENT,   /* t = 0 at (x1, y1), 1 at (x2, y2), constant across */
    SR_PAINT_RADIAL_GRADIENT,   /* the cone from the focal circle to the end circle */
    SR_PAINT_PATTERN,           /* `image` repeated; paint space is its texels */
} sr_paint_kind;

/* Where t leaves [0, 1]. */
typedef enum sr_gradient_spread {
    SR_SPREAD_PAD = 0,          /* the end colors continue */
    SR_SPREAD_REFLECT,          /* back and forth */
    SR_SPREAD_REPEAT,           /* again from 0 */
} sr_gradient_spread;

typedef struct sr_gradient_stop {
    double offset;              /* in [0, 1], each >= the one before */
    sr_rgba color;              /* straight alpha, components finite */
} sr_gradient_stop;

/* A 2D affine map: x' = a x + c y + e, y' = b x + d y + f (SVG's matrix()). */
typedef struct sr_affine2 { double a, b, c, d, e, f; } sr_affine2;

typedef struct sr_paint {
    sr_paint_kind kind;
    sr_rgba color;              /* SR_PAINT_COLOR: the color (finite) */
    /* gradients: geometry in paint space, finite */
    double x1, y1, x2, y2;      /* linear: the gradient vector (a point: t = 0 everywhere) */
    double cx, cy, r;           /* radial: the end circle (t = 1), r > 0 */
    const sr_point2 *focal;     /* radial: the focal point (t = 0); NULL -> (cx, cy);
                                 * outside the end circle it is moved just inside */
    double fr;                  /* radial: the focal circle's radius, >= 0 */
    const sr_gradient_stop *stops; /* required for gradients */
    int stop_count;             /* gradients: 1 .. SR_MAX_GRADIENT_STOPS */
    sr_gradient_spread spread;
    /* SR_PAINT_PATTERN: RGBA8 rows, straight alpha, sampled bilinearly at
     * texel centres; texel (i, j) covers [i, i+1) x [j, j+1) of paint space */
    const uint8_t *image;       /* required for patterns */
    int image_width, image_height; /* 1 .. SR_MAX_FRAMEBUFFER_SIZE each */
    size_t image_stride;        /* bytes from a row to the next; 0 -> 4 * image_width */
    sr_texture_wrap image_wrap; /* SR_WRAP_REPEAT (default) or SR_WRAP_CLAMP (the
                                 * edge texels extend); SR_WRAP_MIRROR is refused */
    const sr_affine2 *transform;/* paint space -> pixels, invertible; NULL -> identity */
    float opacity;              /* multiplies the paint's alpha, in [0, 1]; 0 -> 1
                                 * (no fill at all is no call) */
} sr_paint;

/* Fill a polygon or a path with a paint (desc may be NULL: nonzero,
 * aliased).  Every field of the paint is checked, SR_INVALID_ARG naming
 * the first that is not valid; desc->linear_light is for SR_PAINT_COLOR
 * only.  Named after sr_fill_polygon and sr_fill_path, whose sr_rgba the
 * sr_paint replaces. */
SR_API sr_result sr_fill_polygon_paint(sr_context *ctx, sr_framebuffer *fb,
                                       const sr_polygon2 *poly, const sr_paint *paint,
                                       const sr_fill_desc *desc);
SR_API sr_result sr_fill_path_paint(sr_context *ctx, sr_framebuffer *fb, const sr_path *path,
                                    const sr_paint *paint, const sr_fill_desc *desc);

/* ---- 2D lines ----------------------------------------------------------- */
/*
 * A segment from a to b in pixel coordinates, drawn with one of the line
 * algorithms of the course (docs/lines.md).  The aliased ones snap the
 * endpoints to 1/256 px first; the antialiased ones blend coverage in
 * linear light (sRGB decoded, mixed, encoded).  Every line is clipped to
 * the framebuffer first, so a line from -1e9 to +1e9 costs only its
 * visible length, and the clipped line draws exactly the pixels the
 * unclipped one would have drawn inside the framebuffer.
 *
 * SR_LINE_BRESENHAM is the diamond-exit rule of GL/VK/D3D, exact: a
 * boundary tie goes to the smaller minor index (D3D), and the pixels do
 * not depend on the direction except at the ends: a->b draws the pixel
 * whose diamond owns a and leaves out the one whose diamond owns b.
 *
 * Errors: NaN or infinite coordinates give SR_INVALID_ARG (nothing drawn);
 * coordinates beyond +-1e12 px give SR_TOO_LARGE.  a == b draws nothing
 * (except SR_LINE_AREA and SR_LINE_WIDE with square or round caps, which
 * draw the cap).
 */
typedef enum sr_line_algorithm {
    SR_LINE_DEFAULT = 0,      /* -> SR_LINE_BRESENHAM */
    SR_LINE_DDA_NAIVE,        /* v = v1 + m (u - u1) per major step, rounded */
    SR_LINE_DDA_INCREMENTAL,  /* v += m per major step (32 fraction bits) */
    SR_LINE_BRESENHAM,        /* midpoint / diamond exit, exact: integer
                                 decisions; the end pixel is left out */
    SR_LINE_WU,               /* Xiaolin Wu antialiased: 2 pixels per step */
    SR_LINE_AREA,             /* exact area coverage of the width-w rectangle */
    SR_LINE_WIDE,             /* aliased, runs of round(w) pixels per step */
} sr_line_algorithm;

typedef enum sr_line_cap {    /* SR_LINE_AREA and SR_LINE_WIDE */
    SR_LINE_CAP_DEFAULT = 0,  /* -> SR_LINE_CAP_BUTT */
    SR_LINE_CAP_BUTT,         /* ends exactly at a and b */
    SR_LINE_CAP_SQUARE,       /* extended by w/2 past each end */
    SR_LINE_CAP_ROUND,        /* a half disk of diameter w at each end */
} sr_line_cap;

typedef enum sr_line_clipper {
    SR_LINE_CLIP_DEFAULT = 0, /* -> SR_LINE_CLIP_LIANG_BARSKY */
    SR_LINE_CLIP_COHEN_SUTHERLAND,
    SR_LINE_CLIP_LIANG_BARSKY,
} sr_line_clipper;

typedef struct sr_line_desc {
    sr_line_algorithm algorithm;
    double width;             /* 0 -> 1; SR_LINE_AREA: any width in (0, 4096];
                                 SR_LINE_WIDE: rounded to 1..1024 pixels */
    sr_line_cap cap;
    sr_line_clipper clipper;
} sr_line_desc;

/* Draw a->b into fb's color.  desc may be NULL (Bresenham, width 1). */
SR_API sr_result sr_draw_line(sr_context *ctx, sr_framebuffer *fb, sr_point2 a, sr_point2 b,
                              sr_rgba color, const sr_line_desc *desc);

/* One major step of an SR_LINE_WU line, as sr_draw_line takes it: the
 * column (a row when the line is y-major) whose centre the line crosses
 * at `intersection` on the minor axis, and the two pixels straddling that
 * point, each weighted by its closeness to it (1 - f and f, f the
 * intersection's distance past the first pixel's centre), times the
 * column's weight: 1, or at an end the part of the column the segment
 * covers.  A pixel is drawn, with exactly `coverage` as its opacity, when
 * `drawn` says so (its weight is above 0 and it lies in the rectangle). */
typedef struct sr_line_step_info {
    bool y_major;             /* |dy| > |dx|: major axis y, minor x */
    bool first_end, last_end; /* the end column with the smaller, larger major index */
    int major;                /* the column's index on the major axis */
    double gradient;          /* d minor / d major, |gradient| <= 1 */
    double intersection;      /* the minor coordinate at the column's centre
                                 (pixel coordinates: centres at + 1/2); a
                                 line within one column: at its midpoint */
    double weight;            /* the column's weight, in [0, 1] */
    int x[2], y[2];           /* the two pixels, the smaller minor index first */
    float coverage[2];        /* their weights, clamped to [0, 1] */
    bool drawn[2];
} sr_line_step_info;

typedef void (*sr_line_step_fn)(void *user, const sr_line_step_info *step);

/* The steps sr_draw_line takes for a->b (desc->algorithm SR_LINE_WU; the
 * other algorithms have none: SR_INVALID_ARG) in a width x height
 * framebuffer, in order of the major index, through the same code that
 * draws the line: the steps it visits (the visible ones and a few beyond,
 * see docs/lines.md) and the pixels it blends.  Errors as sr_draw_line. */
SR_API sr_result sr_line_steps(sr_context *ctx, int width, int height, sr_point2 a, sr_point2 b,
                               const sr_line_desc *desc, sr_line_step_fn fn, void *user);

/* One pixel of an SR_LINE_AREA line, as sr_draw_line computes it
 * (unweighted area sampling: a pixel's intensity is the area of its
 * square the thickened line covers).  The line's polygon - the width-w
 * rectangle around a->b with its caps, round caps as chords within
 * 1/1024 px of the circle - is cut to the pixel row [y, y + 1], the
 * row's `strip`; the area of the strip left of x is A(x), and the pixel's
 * area is A(x + 1) - A(x).  Each row's pixels come in order of x, every
 * pixel of the strip's bounding box inside the framebuffer; sr_draw_line
 * blends those `drawn` with `coverage` as the opacity (8 bits:
 * round(coverage * 255)). */
typedef struct sr_line_area_info {
    int x, y;
    double left;              /* A(x), px^2 */
    double right;             /* A(x + 1) */
    double area;              /* right - left: of the pixel square, covered */
    float coverage;           /* area clamped to [0, 1]; 0 when not drawn */
    bool drawn;               /* area above 1e-9 px^2: below is the rounding
                                 of the subtraction */
    const sr_point2 *strip;   /* the row's strip, a convex polygon (pixels,
                                 y down), valid during the call only */
    int strip_count;
} sr_line_area_info;

typedef void (*sr_line_area_fn)(void *user, const sr_line_area_info *pixel);

/* The pixels sr_draw_line visits for a->b (desc->algorithm SR_LINE_AREA;
 * any other: SR_INVALID_ARG) in a width x height framebuffer, row by row
 * from the top, through the same code that draws the line: each with its
 * covered area.  desc's width, cap and clipper are sr_draw_line's.
 * Errors as sr_draw_line. */
SR_API sr_result sr_line_area_pixels(sr_context *ctx, int width, int height, sr_point2 a,
                                     sr_point2 b, const sr_line_desc *desc, sr_line_area_fn fn,
                                     void *user);

/* One pixel of an antialiased line of the 3D pipeline (sr_state's
 * smooth_lines), as sr_draw rasterizes it: the line's ends snapped to
 * 1/256 px, the pixel's centre projected onto the segment (t, clamped to
 * the ends, which makes them round), and its coverage the distance from
 * that point subtracted from the reach, half the width plus half a pixel
 * (a one-pixel ramp across the edge), clamped to 1.  The pipeline
 * blends the fragment with the coverage as alpha. */
typedef struct sr_line_pixel_info {
    bool y_major;             /* |dy| > |dx|: the pixels are walked row by row */
    int x, y;
    int major;                /* the column (x-major) or row it was walked in */
    double t;                 /* the projection on a->b, in [0, 1] */
    double distance;          /* from the pixel's centre to that point, pixels */
    double reach;             /* half the width plus half a pixel */
    float coverage;           /* reach - distance, in (0, 1] */
} sr_line_pixel_info;

typedef void (*sr_line_pixel_fn)(void *user, const sr_line_pixel_info *pixel);

/* The pixels sr_draw covers for a smooth line a->b of `line_width` (as
 * sr_state.line_width: (0, 64], 0 -> 1) in a width x height framebuffer
 * whose viewport maps window coordinates 1:1, column by column, through
 * the rasterizer's own walk.  a and b are window coordinates (pixels, y
 * down), finite and within +-2^20 px. */
SR_API sr_result sr_smooth_line_pixels(sr_context *ctx, int width, int height, sr_point2 a,
                                       sr_point2 b, double line_width, sr_line_pixel_fn fn,
                                       void *user);

/* Clip the segment *a-*b to the closed rectangle [rmin.x, rmax.x] x
 * [rmin.y, rmax.y], moving the endpoints onto its border.  Returns false
 * (points unchanged) when no part of it is inside, or when a coordinate
 * is not finite or the rectangle is empty.  The ends it moves are finite
 * for any finite input, however far apart (to a double's precision at
 * that scale). */
SR_API bool sr_clip_line_cohen_sutherland(sr_point2 rmin, sr_point2 rmax, sr_point2 *a, sr_point2 *b);
SR_API bool sr_clip_line_liang_barsky(sr_point2 rmin, sr_point2 rmax, sr_point2 *a, sr_point2 *b);

#ifdef __cplusplus
}
#endif
#endif /* SOFTRAST_H */
