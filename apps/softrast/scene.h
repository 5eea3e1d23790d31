/* scene.h - what `softrast render` draws: objects (a mesh, its material
 * and model matrix M_O), the built-in teapot scene, camera framing and the
 * default lights. */
#ifndef SR_SCENE_H
#define SR_SCENE_H

#include "framing.h"
#include "softrast.h"

#define SCENE_MAX_OBJECTS 4

typedef struct scene_object {
    sr_mesh mesh;
    sr_material material;
    sr_mat4 model;
    bool frame;          /* the camera frames this object; it casts the key light's shadow */
    bool catcher;        /* a ground that shows only the shadow (render_shadow.c) */
    sr_texture *texture; /* owned by the context that made it, or NULL */
    /* With mesh.parts: each part's texture (NULL: none, or unreadable),
     * pointing into `owned`, one entry a distinct file (NULL when it could
     * not be read); else NULL. */
    sr_texture **part_textures;
    sr_texture **owned;
    size_t owned_count;
    /* With mesh.parts, under pbr: each part's normal map from its
     * material's bump map (render_bump.c; NULL: none), pointing into
     * `owned_normal_maps`, one entry a distinct file; else NULL. */
    sr_texture **part_normal_maps;
    sr_texture **owned_normal_maps;
    size_t owned_normal_map_count;
    /* A glTF scene merged into this object (render_gltf.c): each part is
     * a primitive, in world space, with its material in scene.gltf. */
    int *part_material;            /* mesh.part_count entries (malloc'd), or NULL */
    float *tangents, *texcoords1;  /* 4 and 2 a vertex (malloc'd), or NULL */
    /* Where the classic models sample each part's base color texture
     * (render_gltf_base_uv), 2 a vertex (malloc'd), or NULL: the
     * texcoords as they are. */
    float *base_uv;
} scene_object;

typedef struct scene {
    scene_object objects[SCENE_MAX_OBJECTS];
    int count;
    struct sr_scene *gltf;         /* the glTF file's scene (materials, textures,
                                    * cameras), on the mesh context, or NULL */
    /* scene_cache_bounds: the two spheres of scene_bounds and the framed
     * objects' box, kept once the objects and their matrices are final
     * ([0] framed only, [1] all). */
    bool bounds_cached;
    sr_vec3 cached_centre[2];
    float cached_radius[2];
    sr_vec3 box_min, box_max;      /* the framed objects' world-space box */
    /* render.c's default camera, fitted to the vertices, for the image
     * size, field of view and projection it was fitted for; reset by
     * scene_cache_bounds. */
    bool fit_cached, fit_ok, fit_ortho;
    int fit_width, fit_height;
    float fit_fov_deg;
    sr_framing_info fit;
} scene;

/* The Utah teapot at `detail` standing on a checkered ground plane, its
 * meshes made on ctx. */
sr_result scene_builtin(sr_context *ctx, scene *s, int detail);
/* Destroys the meshes, on the context they were made on. */
void scene_free(sr_context *ctx, scene *s);

/* Bounding sphere of the objects with `frame` set (or of all objects),
 * after their model matrices. */
void scene_bounds(const scene *s, bool framed_only, sr_vec3 *centre, float *radius);
/* Compute both spheres once and answer scene_bounds from them: the viewer
 * frames the camera every frame, and a pass over every vertex was a fifth
 * of a bunny frame.  Call again after changing objects or matrices. */
void scene_cache_bounds(scene *s);

#endif
