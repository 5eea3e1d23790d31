/* gltf.h - the glTF 2.0 reader's shared state (src/io/gltf*.c), on jansson.
 * gltf.c reads the document, buffers, meshes, nodes and cameras;
 * gltf_accessor.c decodes accessors; gltf_material.c reads materials,
 * textures and images; gltf_lights.c reads KHR_lights_punctual;
 * gltf_variants.c reads KHR_materials_variants; gltf_metadata.c the
 * asset's metadata and its KHR_xmp_json_ld packet;
 * gltf_animation.c reads animations and poses the nodes;
 * gltf_pointer.c reads KHR_animation_pointer targets and
 * KHR_node_visibility;
 * gltf_meshopt.c and gltf_draco.c decode the compressed geometry;
 * gltf_morph.c and gltf_skin.c pose morphed and skinned primitives;
 * gltf_instancing.c reads EXT_mesh_gpu_instancing's instance transforms;
 * gltf_pose.c keeps what sr_scene_pose poses a scene again from;
 * scene_store.c holds the scene's memory.  Every
 * error is one line "NAME: /json/pointer: what is wrong", the first one
 * only.  Internal to src/io. */
#ifndef SR_IO_GLTF_H
#define SR_IO_GLTF_H

#include "io/io_util.h"
#include "io/scene.h"

#include <jansson.h>

/* Room for a JSON pointer in a message: three indices and a few member
 * names at most, far below this.  GCC cannot see that bound and warns
 * that the pointers built from pointers "may be truncated"; a cut one
 * would only shorten a message. */
#define GLTF_PTR 256
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wformat-truncation"
#endif

/* Where a buffer's bytes come from: the GLB's BIN chunk (borrowed), a
 * data: URI (decoded, owned) or an external file (owned, sr__free_file). */
typedef struct gltf_buffer {
    const uint8_t *data;
    size_t size;           /* the buffer's byteLength */
    char *owned;           /* to free, or NULL */
    size_t owned_size;
    bool from_file;        /* owned came from sr__read_file */
    bool loaded;
} gltf_buffer;

struct gltf_decoded_view;

/* An image's encoded bytes as sr_load_mesh hands them on (a block of the
 * scene's), or NULL when not read yet. */
typedef struct gltf_image_source {
    const uint8_t *bytes;
    size_t size;
} gltf_image_source;
/* A node's pose at the animation sr_load_desc asks for (gltf_animation.c):
 * which of its translation, rotation, scale and weights are animated
 * (bits 1 << 0 .. 1 << 3) and their sampled values. */
typedef struct gltf_node_pose {
    unsigned animated;
    float translation[3];
    float rotation[4];           /* x, y, z, w, normalized */
    float scale[3];
    float *weights;              /* one per morph target (scene memory), or NULL */
    size_t weight_count;
} gltf_node_pose;
enum { GLTF_POSE_TRANSLATION = 1, GLTF_POSE_ROTATION = 2, GLTF_POSE_SCALE = 4,
       GLTF_POSE_WEIGHTS = 8 };

typedef struct gltf_doc {
    sr_context *ctx;
    const char *name;            /* the file, in messages */
    const char *dir;             /* relative URIs start here ("" or ending in '/') */
    const sr_load_desc *desc;    /* may be NULL */
    sr_io_error *err;
    json_t *root;
    const uint8_t *bin;          /* the GLB's BIN chunk, or NULL */
    size_t bin_size;
    gltf_buffer *buffers;
    size_t buffer_count;
    size_t elements_left;        /* the decoding budget (SR_SCENE_ELEMENTS_*) */
    size_t input_bytes;          /* the document and the buffers read so far */
    size_t drawn_vertices;       /* over every draw, against SR_SCENE_MAX_DRAWN_VERTICES */
    size_t drawn_triangles;      /* and SR_SCENE_MAX_DRAWN_TRIANGLES */
    sr_scene *scene;
    /* Textures made so far, two per image (linear, sRGB); NULL: not yet. */
    sr_texture **image_textures;
    size_t image_count;
    /* for_mesh (sr__parse_gltf): the scene sr_load_mesh flattens, and
     * each image's encoded bytes once read and checked (NULL: not yet). */
    bool for_mesh;
    gltf_image_source *image_sources;
    long slot_image;             /* the image the last slot read names, or -1 */
    struct gltf_light *lights;   /* KHR_lights_punctual's, read (gltf_lights.c) */
    size_t light_count;
    /* bufferViews decoded from EXT_meshopt_compression (gltf_meshopt.c),
     * one slot per view; NULL until the first. */
    struct gltf_decoded_view *decoded;
    size_t decoded_count;
    /* The KHR_draco_mesh_compression primitive being read (gltf_draco.c):
     * its accessors' decoded bytes; NULL between primitives. */
    struct gltf_draco_primitive *draco;
    /* Every node's world matrix, found on first use (sr__gltf_node_world):
     * the nodes' parents (-1: a root), NULL until the walk starts. */
    size_t node_count;
    const long *node_parent;
    float *node_worlds;          /* 16 a node */
    unsigned char *node_world_known;
    long *node_chain;            /* room for a path to the root */
    /* The joint matrices of each skin, made on first use (gltf_skin.c). */
    struct gltf_skin_cache *skins;
    size_t skin_count;
    /* One entry per node when an animation poses the scene, else NULL. */
    gltf_node_pose *pose;
    /* What sr_scene_pose needs to pose the scene again (gltf_pose.c),
     * gathered while reading a file with animations; NULL otherwise. */
    struct gltf_posing *posing;
    /* The animation sr_load_desc poses by, for its pointer channels: the
     * posing record's, else held here (own). */
    const struct gltf_anim *applied;
    struct gltf_anim *applied_own;
} gltf_doc;

/* The error "NAME: POINTER: reason" (the pointer is part of fmt's
 * arguments: callers write "%s/count: ...", ptr).  Returns code. */
sr_result sr__gltf_fail(gltf_doc *d, sr_result code, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
/* A warning "NAME: reason" to desc->warn, counted in the scene. */
void sr__gltf_warn(gltf_doc *d, const char *fmt, ...) __attribute__((format(printf, 2, 3)));


/* Reading the JSON.  `ptr` is the JSON pointer of obj.  Absent members
 * leave *out at the caller's default and succeed, unless required. */
sr_result sr__gltf_index(gltf_doc *d, const json_t *obj, const char *ptr, const char *key,
                         size_t limit, bool required, long *out);
sr_result sr__gltf_size(gltf_doc *d, const json_t *obj, const char *ptr, const char *key,
                        size_t lo, size_t hi, bool required, size_t *out);
sr_result sr__gltf_number(gltf_doc *d, const json_t *obj, const char *ptr, const char *key,
                          float *out);
sr_result sr__gltf_numbers(gltf_doc *d, const json_t *obj, const char *ptr, const char *key,
                           size_t n, float *out);
/* root[key] when it is an array (*count its length); NULL and 0 when
 * absent; an error when present and not an array. */
sr_result sr__gltf_array(gltf_doc *d, const json_t *obj, const char *ptr, const char *key,
                         json_t **out, size_t *count);
/* An object member that must be an object when present (NULL when absent). */
sr_result sr__gltf_object(gltf_doc *d, const json_t *obj, const char *ptr, const char *key,
                          json_t **out);
/* obj.extensions[name] when it is an object, else NULL. */
json_t *sr__gltf_extension(const json_t *obj, const char *name);

/* The bytes of bufferView `view` (loading its buffer on first use): the
 * view's start and length, its byteStride (0: none). */
sr_result sr__gltf_buffer_view(gltf_doc *d, long view, const char *ptr, const uint8_t **data,
                               size_t *size, size_t *stride);

/* Buffer i's bytes (loaded on first use) and its byteLength. */
sr_result sr__gltf_buffer_bytes(gltf_doc *d, long i, const char *use, const uint8_t **data,
                                size_t *size);

/* gltf_meshopt.c: EXT_meshopt_compression.  The bytes of bufferView
 * `view` (JSON `ptr`, `length` bytes, byteStride `stride` or 0) whose
 * extension object is ext, decoded into memory the document owns; *data
 * NULL when the caller is to read the view's own buffer (the fallback, in
 * a build without meshoptimizer). */
sr_result sr__gltf_meshopt_view(gltf_doc *d, long view, const json_t *ext, const char *ptr,
                                size_t length, size_t stride, const uint8_t **data);
/* Whether buffer (a /buffers entry) is marked as a fallback buffer. */
bool sr__gltf_is_fallback_buffer(const json_t *buffer);
bool sr__gltf_have_meshopt(void);
void sr__gltf_meshopt_free(gltf_doc *d);

/* gltf_draco.c: KHR_draco_mesh_compression.  Before primitive `prim`
 * (JSON `ptr`) is read: when it has the extension (ext), its stream
 * decoded and each accessor it fills written as the accessor stores
 * elements, for sr__gltf_draco_accessor, until sr__gltf_draco_end; in a
 * build without libdraco, a check that the accessors hold the fallback.
 * *indices and *index_count: the triangles' corners when the primitive
 * has no indices accessor (NULL otherwise; owned until _end). */
sr_result sr__gltf_draco_begin(gltf_doc *d, const json_t *prim, const json_t *ext,
                               const char *ptr, const uint32_t **indices, size_t *index_count);
void sr__gltf_draco_end(gltf_doc *d);
/* The decoded bytes of accessor `index` in the primitive being read, or
 * NULL when it is not one of its Draco accessors. */
const uint8_t *sr__gltf_draco_accessor(const gltf_doc *d, long index, size_t *size);
bool sr__gltf_have_draco(void);

/* The bytes a URI (`ptr` in messages) names: a base64 data: URI decoded,
 * or a relative reference (percent-decoded) read from d->dir.  *owned is
 * the block to free (*from_file: with sr__free_file). */
sr_result sr__gltf_read_uri(gltf_doc *d, const char *uri, const char *ptr, char **owned,
                            size_t *size, bool *from_file);

/* gltf_accessor.c.  An accessor's element type, for checks. */
typedef struct gltf_accessor_info {
    size_t count;
    int components;        /* 1 SCALAR .. 16 MAT4 */
    bool matrix;           /* MAT2, MAT3 or MAT4 */
    int component_type;    /* 5120 .. 5126 */
    bool normalized;
} gltf_accessor_info;

/* Accessor `index` (named `ptr` in messages: the member that refers to
 * it) decoded into a malloc'd array of count * components floats
 * (normalized integers mapped to [0, 1] or [-1, 1], sparse values
 * applied); `allowed` lists the component counts the use accepts (a
 * bitmask, bit n for n components). */
sr_result sr__gltf_read_floats(gltf_doc *d, long index, const char *ptr, unsigned allowed,
                               gltf_accessor_info *info, float **out);
/* The accessor's description alone: nothing read, no budget charged. */
sr_result sr__gltf_accessor_info(gltf_doc *d, long index, const char *use,
                                 gltf_accessor_info *info);
/* The same for indices: a SCALAR of unsigned bytes, shorts or ints. */
sr_result sr__gltf_read_indices(gltf_doc *d, long index, const char *ptr,
                                gltf_accessor_info *info, uint32_t **out);

/* An accessor of MAT4 floats (inverse bind matrices) into a malloc'd
 * array of 16 floats a matrix, column-major. */
sr_result sr__gltf_read_mat4(gltf_doc *d, long index, const char *ptr, gltf_accessor_info *info,
                             float **out);

/* gltf.c: the matrix translation t * rotation q (x, y, z, w; normalized
 * here, a zero one the identity) * scale s, column-major, as glTF
 * composes a node's (and an instance's) transform. */
void sr__gltf_trs(const float t[3], const float q[4], const float s[3], float m[16]);

/* gltf_instancing.c: EXT_mesh_gpu_instancing.  Node `node` (JSON `ptr`,
 * mesh `mesh` or -1)'s instance transforms, T * R * S of each instance:
 * *count matrices of 16 floats into a malloc'd *out; NULL and 0 when the
 * node has no such extension.  At most `room` instances (the draws the
 * scene has left) are read; more is refused before any is decoded. */
sr_result sr__gltf_read_instances(gltf_doc *d, const json_t *node, const char *ptr, long mesh,
                                  size_t room, float **out, size_t *count);

/* gltf.c: node `node`'s world matrix (the product of its ancestors' local
 * matrices and its own), for nodes the walk does not reach too. */
sr_result sr__gltf_node_world(gltf_doc *d, long node, float world[16]);

/* What posing a primitive per node takes, read with its arrays (all
 * malloc'd, freed by sr__gltf_pose_free): its morph targets' deltas and
 * its skinning influences. */
typedef struct gltf_pose_source {
    size_t target_count;
    float **deltas;          /* 3 a target: POSITION, NORMAL, TANGENT deltas (3 floats a
                              * vertex each), NULL where the target lacks one */
    size_t influence_sets;   /* JOINTS_n / WEIGHTS_n pairs, 0: not skinnable */
    float *joints;           /* 4 * influence_sets a vertex, whole numbers */
    float *weights;          /* the same layout */
    size_t joint_max;        /* the largest joint index, found in */
    size_t joint_max_set, joint_max_vertex;   /* JOINTS_<set>, element <vertex> */
} gltf_pose_source;

void sr__gltf_pose_free(gltf_pose_source *src);
/* The memory of p's posed arrays (positions, and normals and tangents
 * where it has them), counted in the decoding budget like accessors'
 * elements: a small file drawing a mesh posed by many nodes cannot ask
 * for gigabytes.  `ptr` names the node in messages. */
sr_result sr__gltf_charge_posed(gltf_doc *d, const sr_scene_primitive *p, const char *ptr);

/* gltf_morph.c.  Primitive `ptr`'s targets (its JSON prim), checked
 * against its vertex_count, into src. */
sr_result sr__gltf_read_targets(gltf_doc *d, const json_t *prim, const char *ptr,
                                size_t vertex_count, gltf_pose_source *src);
/* Mesh `mesh` (JSON `ptr`): each primitive has as many targets as the
 * first, and the mesh's weights, if any, count them. */
sr_result sr__gltf_check_targets(gltf_doc *d, const json_t *mesh, const char *ptr);
/* The n morph weights node `node_index` draws mesh `mesh` with: the
 * animation's (sr_load_desc's pose), else the node's weights, else the
 * mesh's, else zeros. */
sr_result sr__gltf_node_weights(gltf_doc *d, long node_index, long mesh, float *out, size_t n);
/* The same without the animation's: the rest pose's weights. */
sr_result sr__gltf_node_rest_weights(gltf_doc *d, long node_index, long mesh, float *out,
                                     size_t n);
/* p's positions, normals and tangents moved by src's targets at the
 * given weights, into new arrays the scene owns (p's are left when every
 * weight is zero).  `ptr` names the node instance in messages. */
sr_result sr__gltf_morph(gltf_doc *d, const gltf_pose_source *src, const float *weights,
                         const char *ptr, sr_scene_primitive *p);

/* gltf_skin.c.  Primitive attributes JOINTS_n / WEIGHTS_n (`aptr`: its
 * attributes' pointer) into src, checked against vertex_count. */
sr_result sr__gltf_read_influences(gltf_doc *d, const json_t *attrs, const char *aptr,
                                   size_t vertex_count, gltf_pose_source *src);
/* p skinned by skin `skin` (named by `use`, the node's /skin): its
 * positions, normals and tangents posed in world space into new arrays
 * the scene owns, its world the identity.  `pptr` is the primitive's
 * pointer. */
sr_result sr__gltf_skin(gltf_doc *d, long skin, const char *use, const gltf_pose_source *src,
                        const char *pptr, sr_scene_primitive *p);
void sr__gltf_skins_free(gltf_doc *d);

/* gltf_material.c: every /materials entry into scene->materials, plus the
 * default material (glTF's: white, metallic 1, roughness 1) at the end
 * for primitives without one. */
sr_result sr__gltf_read_materials(gltf_doc *d);
/* KHR_texture_transform's offset o, rotation rot and scale s (the
 * file's, v down) into slot in sr_texture_slot's convention (v up);
 * false, slot untouched, where the conversion overflows a float. */
bool sr__gltf_slot_transform(sr_texture_slot *slot, const float o[2], float rot,
                             const float s[2]);
/* Whether the material extension `name` is one that must not be used on
 * a material with KHR_materials_pbrSpecularGlossiness (its README's
 * "Exclusions"): such a material draws none of it, nor animates it. */
bool sr__gltf_spec_gloss_excludes(const char *name);

/* gltf_metadata.c: the asset's version, generator and copyright and its
 * KHR_xmp_json_ld packet into sr_scene.metadata (a bad reference warns). */
sr_result sr__gltf_read_metadata(gltf_doc *d);

/* gltf_variants.c: KHR_materials_variants.  The document's variant names
 * into scene->variants (checking desc->variant against them); one
 * primitive's mappings (JSON `ptr`) checked into p->variant_materials,
 * p->material (its own, already set) replaced by desc->variant's. */
sr_result sr__gltf_read_variants(gltf_doc *d);
sr_result sr__gltf_primitive_variants(gltf_doc *d, const json_t *prim, const char *ptr,
                                      sr_scene_primitive *p);

/* gltf_lights.c: KHR_lights_punctual.  The document's lights checked and
 * read into d->lights (freed by the caller); one node's light, if it
 * names one, placed by its world matrix into scene->lights; after the
 * walk, the warning about lights beyond SR_MAX_LIGHTS. */
sr_result sr__gltf_read_lights(gltf_doc *d);
sr_result sr__gltf_place_light(gltf_doc *d, const json_t *node, const char *ptr, long node_index,
                               const float world[16]);
void sr__gltf_lights_done(gltf_doc *d);

/* gltf_animation.c: /animations checked and listed in scene->animations;
 * with sr_load_desc's SR_POSE_ANIMATION, the one it names sampled at its
 * time into d->pose, for the node walk. */
sr_result sr__gltf_read_animations(gltf_doc *d);
/* Node `node`'s morph weights as the animation sets them (*count of
 * them), or NULL when it does not set them (sr__gltf_node_weights then
 * takes the node's or the mesh's). */
const float *sr__gltf_node_pose_weights(const gltf_doc *d, long node, size_t *count);

/* ---- posing again (gltf_pose.c) -------------------------------------------
 * A scene read from a file with animations keeps what posing it takes
 * (sr_scene_pose): the nodes' rest transforms as the reader met them,
 * the animations' decoded samplers, the skins' joints and inverse bind
 * matrices, and for each morphed or skinned draw its mesh's arrays and
 * pose source.  The reader and sr_scene_pose share the arithmetic below,
 * so that a pose made again has the bytes a reading in that pose has. */

/* A sampler's keys decoded (gltf_animation.c): count times, and per key
 * `width` floats (times 3 for CUBICSPLINE: in-tangent, value,
 * out-tangent). */
typedef struct gltf_sampler {
    float *times;
    size_t count;
    float *values;
    size_t value_count;        /* elements of the output accessor */
    gltf_accessor_info out;    /* the output accessor's type */
    int interp;
} gltf_sampler;

/* What a channel animates: a node's transform or weights (`node`,
 * `path`), else through KHR_animation_pointer a node's visibility, a
 * mesh's default weights (`index` the mesh), or a material's, camera's or
 * light's property (`index` in its collection, `prop` a row of
 * gltf_pointer.c's tables). */
enum { GLTF_TARGET_NONE = -1, GLTF_TARGET_NODE, GLTF_TARGET_VISIBLE, GLTF_TARGET_MATERIAL,
       GLTF_TARGET_CAMERA, GLTF_TARGET_LIGHT, GLTF_TARGET_MESH_WEIGHTS };
enum { GLTF_INTERP_LINEAR, GLTF_INTERP_STEP, GLTF_INTERP_CUBIC };

/* A channel that animates: its sampler, its target and the floats a
 * key.  Node channels: the node's property (GLTF_POSE_* bit index). */
typedef struct gltf_channel {
    long sampler, node;
    int path;
    int kind;                  /* GLTF_TARGET_* */
    long index;
    int prop;
    size_t width;
    float *weights;            /* a weights channel's sampled values (width of them,
                                * scene memory); NULL for the others */
    bool mask;                 /* an alphaCutoff of a material the file makes MASK */
    long *users;               /* a mesh's weights: the nodes drawing it without their
                                * own weights (scene memory), user_count of them */
    size_t user_count;
} gltf_channel;

typedef struct gltf_anim {
    gltf_sampler *samplers;
    size_t sampler_count;
    gltf_channel *channels;    /* only those that animate a node */
    size_t channel_count;
} gltf_anim;

void sr__gltf_anim_free(gltf_anim *a);
/* Animation a sampled at time t into pose (one entry per node, its
 * `animated` bits cleared by the caller). */
void sr__gltf_anim_apply(const gltf_anim *a, float t, gltf_node_pose *pose);
/* Sampler s at time t into out (width floats), rotations normalized. */
void sr__gltf_sample(const gltf_sampler *s, bool rotation, size_t width, float t, float *out);

/* gltf_pointer.c: KHR_animation_pointer.  A "pointer" channel target
 * (JSON `tptr`) resolved: kind GLTF_TARGET_NONE (warned) for a pointer
 * softrast does not animate; a node's transform or weights (node_path:
 * their GLTF_POSE_* bit index) for the node checks; else the property,
 * its floats and whether it is a boolean.  Refused: a bad pointer, an
 * index out of range, a property the file does not define. */
typedef struct gltf_pointer {
    int kind;
    long index;
    int node_path, prop, width;
    bool boolean;
    bool mask;   /* the alphaCutoff of a material whose alphaMode is MASK */
} gltf_pointer;
sr_result sr__gltf_pointer_target(gltf_doc *d, const json_t *target, const char *tptr,
                                  gltf_pointer *out);
/* Sampler s (JSON `sptr`) against the property p resolves to. */
sr_result sr__gltf_pointer_check(gltf_doc *d, const gltf_pointer *p, const gltf_sampler *s,
                                 const char *sptr);
/* a's pointer channels at time t written into the scene's materials,
 * cameras and lights (clamped to the properties' ranges) and into
 * visible (one a node). */
void sr__gltf_anim_apply_pointers(const gltf_anim *a, float t, sr_scene *scene,
                                  unsigned char *visible);
/* After the walk (the nodes' parents known): the rest pose recorded for
 * sr_scene_pose, then the pointer channels of the animation sr_load_desc
 * poses by and the nodes' visibility applied to the scene. */
sr_result sr__gltf_pointers_finish(gltf_doc *d, const long *parent, size_t n);
/* KHR_node_visibility: the n nodes' own `visible` (1 when absent). */
sr_result sr__gltf_read_visibility(gltf_doc *d, unsigned char *visible, size_t n);
/* The draws of the hidden nodes (a node not visible or under one) made
 * empty (triangle_count 0) and their lights SR_LIGHT_OFF; state and chain
 * are room for n entries. */
void sr__gltf_hide(sr_scene *scene, const long *parent, size_t n, const unsigned char *visible,
                   unsigned char *state, long *chain);

/* Whether a world matrix mirrors (its upper 3x3's determinant < 0). */
bool sr__gltf_mirrors(const float world[16]);
/* src's targets at `weights` on n vertices: base[k] (positions, normals,
 * tangents; NULL where absent) into out[k]. */
void sr__gltf_morph_vertices(const gltf_pose_source *src, const float *weights, size_t n,
                             const float *const base[3], float *const out[3]);
/* Linear blend skinning of n vertices by the joint matrices: in[k] into
 * out[k]; returns how many vertices' blended matrices mirror. */
size_t sr__gltf_skin_vertices(const float *matrices, const gltf_pose_source *src, size_t n,
                              const float *const in[3], float *const out[3]);
/* A light placed by world (pos and direction from its -Z); false when a
 * directional or spot light's direction collapses. */
bool sr__gltf_aim_light(sr_scene_light *l, const float world[16]);

/* The reader's hooks, each a no-op when d->posing is NULL: the record
 * starts (a file with animations read for sr_load_scene), takes an
 * animation, a node's rest transform as local_matrix reads it, a skin's
 * joints and inverse bind matrices (NULL: identities), a posed draw
 * (scene primitive `primitive` of mesh primitive g, its node's rest morph
 * weights), and the meshes' pose sources when the walk ends.  false: out
 * of memory (the hooks free what they were handed). */
bool sr__gltf_posing_start(gltf_doc *d, size_t animation_count);
bool sr__gltf_posing_anim(gltf_doc *d, size_t index, gltf_anim *a);
/* After the walk: the scene's materials, cameras, lights, draws' triangle
 * counts and the nodes' visibility as the rest pose has them. */
bool sr__gltf_posing_rest(gltf_doc *d, const unsigned char *visible);
/* The animation taken at index (for the reader's own pose). */
const gltf_anim *sr__gltf_posing_anim_at(const gltf_doc *d, size_t index);
bool sr__gltf_posing_node(gltf_doc *d, long node, const float *matrix, const float t[3],
                          const float q[4], const float s[3]);
bool sr__gltf_posing_skin(gltf_doc *d, long skin, const long *joints, size_t count,
                          const float *inverse_bind);
bool sr__gltf_posing_draw(gltf_doc *d, size_t primitive, long skin, const sr_scene_primitive *g,
                          const gltf_pose_source *src, const float *rest_weights);
bool sr__gltf_posing_sources(gltf_doc *d, gltf_pose_source *sources, size_t count);
/* EXT_mesh_gpu_instancing made per draws of each of the node's `made`
 * draws from `first` on, the k-th of each placed by matrices[16 k]. */
bool sr__gltf_posing_instances(gltf_doc *d, size_t first, size_t made, size_t per,
                               const float *matrices);
/* At the end of a reading that succeeded: the record handed to the scene. */
bool sr__gltf_posing_finish(gltf_doc *d);
void sr__gltf_posing_abandon(gltf_doc *d);

#endif
