/* scenes.h - the benchmark scenes (bench): geometry, matrices, lights and
 * pipeline state built once before timing, in a form both renderers consume
 * unchanged (softrast through sr_draw, llvmpipe through legacy GL vertex
 * arrays).  Single-threaded; a scene is read-only while frames are drawn. */
#ifndef SR_BENCH_SCENES_H
#define SR_BENCH_SCENES_H

#include "softrast.h"

#include <stddef.h>
#include <stdint.h>

typedef enum bench_kind {
    BENCH_MESH,     /* a model file, framed like `softrast render` frames it */
    BENCH_SMALL,    /* a million tiny triangles in NDC */
    BENCH_FILL,     /* full-screen quads, back to front */
    BENCH_LINES,    /* random line segments */
    BENCH_POLYFILL, /* a 10,000-edge polygon in 2D, aliased (bench/polyfill.c) */
    BENCH_POLYFILL_AA, /* the same with exact area antialiasing */
    BENCH_CLI,      /* the whole `softrast render` process */
    BENCH_SHAPES2D, /* bl_bench-like 2D shapes and paints against cairo (bench/shapes2d.c) */
    BENCH_ICONS,    /* an icon theme's SVGs against rsvg-convert (bench/icons.c) */
} bench_kind;

typedef enum bench_look {
    BENCH_LOOK_GOURAUD = 0, /* Blinn-Phong per vertex, `softrast render --shading gouraud` */
    BENCH_LOOK_PHONG,       /* Blinn-Phong per pixel */
    BENCH_LOOK_PBR,         /* the metallic-roughness program, `--environment hemisphere` */
    BENCH_LOOK_PBR_STUDIO,  /* the same lit by the built-in studio: the CLI's default look */
    BENCH_LOOK_PBR_TEXTURED,/* a glTF file's own material (its maps), the studio
                             * and the key light's shadow map */
} bench_look;

typedef struct bench_scene_info {
    const char *name;
    bench_kind kind;
    const char *model_file;  /* BENCH_MESH and BENCH_CLI: file in the models directory
                              * (BENCH_LOOK_PBR_TEXTURED: in the build's bench
                              * directory, written by softrast-pbr-asset) */
    int samples;             /* MSAA samples per pixel; 0: one */
    const char *texture_file;/* BENCH_MESH: a PNG in the models directory that
                              * modulates the lit color (trilinear), or NULL */
    bench_look look;         /* BENCH_MESH: how it is shaded */
} bench_scene_info;

/* Every scene in the order a run without SCENE arguments uses. */
extern const bench_scene_info bench_scene_list[];
extern const int bench_scene_count;
const bench_scene_info *bench_find_scene(const char *name);

typedef struct bench_scene {
    const bench_scene_info *info;
    int width, height;

    /* Geometry, shared by both renderers. */
    size_t vertex_count;
    const float *positions;
    int position_size;          /* 3 or 4 floats */
    const float *normals;       /* 3 floats, or NULL */
    const float *colors;        /* 4 floats (RGBA), or NULL */
    const float *texcoords;     /* 2 floats, or NULL (textured scenes only) */
    const uint32_t *indices;    /* NULL: vertices in order */
    size_t index_count;
    size_t triangle_count;      /* primitives: triangles, or segments for BENCH_LINES */
    sr_primitive primitive;     /* 0: triangles */

    sr_mat4 model, view, projection;
    sr_state state;             /* shading, lights, material, cull, depth */
    float clear_color[4];

    uint64_t fragments_per_frame;  /* what mpix_s counts: W*H, or 100*W*H for fill */

    /* Textured scenes: the image as read (RGBA8, row 0 at the top, as PNG
     * stores it), NULL otherwise.  Each renderer makes its own texture
     * from it (state.texture stays NULL here: a texture lives on a
     * context, which the scene does not know). */
    uint8_t *texture_pixels;
    int texture_w, texture_h;

    /* Storage owned by the scene. */
    sr_context *mesh_ctx;  /* owns mesh (one thread: the normals are made once) */
    sr_mesh mesh;
    sr_pbr *pbr;           /* BENCH_LOOK_PBR: the program state.program points into */
    sr_environment *env;   /* and the environment it lights with */
    sr_shadow_map *shadow; /* BENCH_LOOK_PBR_TEXTURED: the key light's map, drawn
                            * from the mesh at the start of every frame */
    struct sr_scene *gltf; /* BENCH_LOOK_PBR_TEXTURED: the file, for its material */
    float *own_positions, *own_colors;
    uint32_t *own_indices;
} bench_scene;

/* The directory the model files are read from: $SR_MODELS_DIR, else the
 * shared models directory next to the source tree. */
const char *bench_models_dir(void);

/* Build a scene of kind BENCH_MESH, BENCH_SMALL or BENCH_FILL at width x
 * height.  On failure returns the error and writes one line to msg. */
sr_result bench_scene_make(const bench_scene_info *info, int width, int height,
                           bench_scene *out, char *msg, size_t msg_size);
void bench_scene_free(bench_scene *s);

#endif
