/*
 * softrast_io.h - files in and out: model readers (OBJ, PLY, STL, and other
 * formats through Assimp when the build found it), PNG images (libpng),
 * JPEG images (libjpeg-turbo, when the build found it) and SVG drawings
 * (expat, when the build found it).  Numbers in text files are read the
 * same whatever the C locale is.
 *
 * Errors: every function returns an sr_result and, on failure, fills an
 * sr_io_error with one line of the form "FILE:LINE: what is wrong" for text
 * files, "FILE: byte N: what is wrong" for binary ones, or "FILE: what is
 * wrong" when no position applies.  A FILE too long for the message is cut
 * from the left ("...tail/name.obj:4: ..."); the position and the reason are
 * always whole.  The same line is the calling thread's sr_last_error()
 * (softrast.h), err given or NULL; the calls that take no sr_io_error
 * (sr_scene_camera_matrices, sr_io_parse_color) leave theirs there alone,
 * naming the argument ("sr_scene_camera_matrices: camera->yfov 4 is not in
 * (0, pi)").  A call that succeeds leaves sr_last_error as it was, also
 * when its reader met a failure inside and carried on (a texture skipped
 * with a warning).  Nothing here prints or exits.
 */
#ifndef SOFTRAST_IO_H
#define SOFTRAST_IO_H

#include "softrast.h"

#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sr_io_error {
    char message[512];
} sr_io_error;

/* Documented limits, checked before anything is allocated from a count
 * read out of a file. */
#define SR_IO_MAX_FILE_BYTES    ((size_t)1 << 31)   /* 2 GiB */
#define SR_IO_MAX_VERTICES      ((size_t)1 << 28)
#define SR_IO_MAX_TRIANGLES     ((size_t)1 << 28)

typedef enum sr_model_format {
    SR_FORMAT_AUTO = 0,   /* from the file name's extension, then its content */
    SR_FORMAT_OBJ,
    SR_FORMAT_PLY,
    SR_FORMAT_STL,
    SR_FORMAT_ASSIMP,     /* anything else Assimp reads */
    SR_FORMAT_GLTF,       /* glTF 2.0, .gltf or .glb: sr_load_scene's own reader
                           * (Assimp in builds without jansson) */
} sr_model_format;

/* Which pose sr_load_scene places a glTF file's nodes in. */
typedef enum sr_load_pose {
    SR_POSE_DEFAULT = 0,  /* resolved to SR_POSE_REST */
    SR_POSE_REST,         /* the nodes' own translation, rotation, scale, matrix */
    SR_POSE_ANIMATION,    /* sr_load_desc.animation at sr_load_desc.animation_time */
} sr_load_pose;

typedef struct sr_load_desc {
    sr_model_format format;
    /* Optional: called with the path of every other file the reader opens
     * for the model (an OBJ's MTL files), e.g. so that a program never
     * writes its output over one of its inputs.  The model's own path and
     * the texture paths in the mesh are not reported (the caller has
     * them), nor the files Assimp opens itself. */
    void (*file_read)(void *user, const char *path);
    void *user;                  /* passed to file_read and warn */
    /* Optional: called with each warning of sr_load_scene, one line
     * "FILE: /json/pointer: what was skipped" (a points or lines
     * primitive, a texture without a PNG or JPEG source). */
    void (*warn)(void *user, const char *message);
    /* glTF's KHR_materials_variants: the variant whose materials to draw,
     * counted from 1 (sr_scene.variants[variant - 1]); 0 draws every
     * primitive's own material, as the extension asks when no variant is
     * active.  A primitive the variant does not map keeps its own.  A
     * variant the file does not have is SR_INVALID_ARG ("FILE:
     * sr_load_desc.variant: 3, but the file has 2 variants"); any other
     * format has none. */
    int variant;
    /* glTF: the pose the nodes are placed in (docs/gltf.md).  Zero: the
     * rest pose, each node's own transform; SR_POSE_ANIMATION: animation
     * number `animation` (0 first, as sr_scene.animations lists them)
     * sampled at `animation_time` seconds, its keys clamped at both ends.
     * A file without that animation, or a time that is not finite, is
     * refused (SR_INVALID_ARG). */
    sr_load_pose pose;
    int animation;
    float animation_time;
} sr_load_desc;

/* Load a model file into *out (which is zeroed first).  Faces with more than
 * three vertices are triangulated.  Normals are those of the file, or NULL.
 * glTF (.gltf, .glb, GLB's magic) is read by sr_load_scene's own reader
 * when the build has it (sr_io_have_gltf), else by Assimp: the default
 * scene's instances flattened into one mesh in world space (normals by
 * the inverse transpose, mirrored instances' winding turned back to
 * counter-clockwise); texture coordinates 0, and colors (the vertex's
 * times the material's base color) where present; the base color images'
 * encoded bytes as texture_data and parts.  SR_FORMAT_ASSIMP asks for
 * Assimp.
 * The mesh is allocated on ctx: release it with sr_destroy_mesh(ctx, out).
 * The readers' working memory (the file's bytes, growing arrays, Assimp's
 * own) comes from malloc and is freed before the call returns; the mesh
 * is copied onto ctx's allocator at the end. */
SR_API sr_result sr_load_mesh(sr_context *ctx, const char *path, const sr_load_desc *desc,
                              sr_mesh *out, sr_io_error *err);

/* The readers on a buffer already in memory (for tests and fuzzing), with
 * the same memory as sr_load_mesh.  `name` is used in messages.  `data`
 * need not be NUL-terminated. */
SR_API sr_result sr_parse_obj(sr_context *ctx, const char *name, const char *data, size_t size,
                              sr_mesh *out, sr_io_error *err);
SR_API sr_result sr_parse_ply(sr_context *ctx, const char *name, const uint8_t *data, size_t size,
                              sr_mesh *out, sr_io_error *err);
SR_API sr_result sr_parse_stl(sr_context *ctx, const char *name, const uint8_t *data, size_t size,
                              sr_mesh *out, sr_io_error *err);

/* Scenes: a model file flattened for drawing (docs/gltf.md).  glTF 2.0
 * (.gltf with external files or data: URIs, .glb) is read by softrast's own
 * reader with its node hierarchy, materials, textures and cameras; any
 * other format is sr_load_mesh's mesh as one primitive (a part per
 * texture) with a default dielectric material.  One call gives everything
 * to draw: for each primitive, its vertex arrays, triangles, world matrix
 * and material. */

/* One draw: a glTF mesh primitive as one node instances it.  Instances of
 * the same primitive share their arrays, except posed ones: a skinned
 * instance's positions, normals and tangents are its own, posed in world
 * space (its world is the identity), and so are a morphed one's when a
 * weight is not zero (docs/gltf.md).  Arrays hold vertex_count
 * entries of floats, or are NULL when the file has none (normals: compute
 * flat ones, as glTF asks; tangents: generate them).  Texture coordinates
 * follow sr_make_texture's convention ((0, 0) bottom-left): glTF's are
 * converted (v -> 1 - v), and the material's texture transforms with them.
 * Colors are linear RGBA (a VEC3 gets alpha 1). */
typedef struct sr_scene_primitive {
    float world[16];            /* object -> world, column-major */
    bool mirrored;              /* det(world) < 0: the transform mirrors, turning
                                 * front faces clockwise; draw it with
                                 * sr_state.front_face flipped */
    int material;               /* index into sr_scene.materials */
    int node, mesh;             /* where it came from (-1: not glTF) */
    size_t vertex_count;
    const float *positions;     /* 3 a vertex */
    const float *normals;       /* 3 a vertex, or NULL */
    const float *tangents;      /* 4 a vertex, or NULL; the bitangent is
                                 * cross(normal, tangent.xyz) * w, toward +v (the
                                 * image's top, a normal map's green), in object
                                 * space: where `mirrored`, w turns in world space */
    const float *texcoords0;    /* 2 a vertex, or NULL */
    const float *texcoords1;    /* 2 a vertex, or NULL */
    const float *colors;        /* 4 a vertex, or NULL */
    size_t triangle_count;      /* 0 for a node KHR_node_visibility hides (the
                                 * arrays stay, for a pose that shows it) */
    const uint32_t *indices;    /* 3 a triangle, counter-clockwise front faces
                                 * (strips and fans converted) */
    /* KHR_materials_variants: the material each variant draws on this
     * primitive, indexed as sr_load_desc.variant (sr_scene.variant_count
     * + 1 entries: [0] the primitive's own material, [v] variant v's, its
     * own where v maps none), or NULL when the primitive has no mappings.
     * `material` is already sr_load_desc.variant's; a program switching
     * variants without reading the file again takes these. */
    const int *variant_materials;
} sr_scene_primitive;

typedef enum sr_scene_camera_type {
    SR_SCENE_CAMERA_PERSPECTIVE = 0,
    SR_SCENE_CAMERA_ORTHOGRAPHIC,
} sr_scene_camera_type;

/* A camera as a node instances it.  It looks down its local -Z with +Y up;
 * world maps its local frame to world space (the inverse of the view
 * matrix E when it has no scale). */
typedef struct sr_scene_camera {
    sr_scene_camera_type type;
    float world[16];            /* camera -> world, column-major */
    float yfov;                 /* perspective: vertical field of view, radians */
    float aspect;               /* perspective: width / height; 0: the viewport's */
    float xmag, ymag;           /* orthographic: half the view's width and height */
    float znear;
    float zfar;                 /* 0: infinite (perspective only) */
    int camera, node;           /* its index in the file's cameras, and its node */
} sr_scene_camera;

/* A KHR_lights_punctual light as a node places it, in world space, ready
 * for sr_pbr_desc.lights (docs/gltf.md): `light.vector` is the direction
 * a directional light travels (its node's -Z) or the position of a point
 * or spot light, `light.direction` a spot light's axis (its node's -Z);
 * the file's color and intensity (lux for directional lights, candela
 * for the others), range (0: infinite) and cone angles.  A light of
 * intensity 0 or a black color is SR_LIGHT_OFF in `light` (sr_light's
 * zero values would mean white and 1); `type` keeps its kind, and its
 * color and intensity stay the file's (the zero says it is dark). */
typedef struct sr_scene_light {
    sr_light light;
    sr_light_type type;         /* the file's: directional, point or spot, lit or dark */
    float world[16];            /* light -> world, column-major; it shines down -Z */
    int light_index, node;      /* its index in the extension's lights, and its node */
} sr_scene_light;

/* One property of an XMP packet, as text: its name ("dc:creator") and
 * its value (a list or set its items joined by ", ", a language
 * alternative its texts, each but a lone one followed by its language in
 * brackets, a number or a boolean its JSON). */
typedef struct sr_scene_property {
    const char *name;
    const char *value;
} sr_scene_property;

/* What a glTF file says about itself (docs/gltf.md): its `asset`'s
 * version, minVersion, generator and copyright (UTF-8; NULL when the file
 * gives none, all NULL for other formats), and the KHR_xmp_json_ld
 * packet the asset references, as given (compact JSON text; NULL when
 * none, or when the reference is bad: a warning says so).  `properties`
 * are the packet's licence and authorship properties present, in this
 * order: dc:title, dc:creator, dc:contributor, dc:publisher, dc:date,
 * dc:description, dc:source, dc:rights, xmpRights:Owner,
 * xmpRights:UsageTerms, xmpRights:WebStatement, xmpRights:Marked,
 * cc:license, cc:attributionName, cc:attributionURL.  XMP is metadata
 * (no part of the drawing): nodes', meshes' and materials' packets are
 * not read. */
typedef struct sr_scene_metadata {
    const char *version;
    const char *min_version;
    const char *generator;
    const char *copyright;
    const char *xmp_packet;
    int xmp_packet_index;          /* in the file's packets; -1: none */
    const sr_scene_property *properties;
    size_t property_count;
} sr_scene_metadata;

/* A glTF animation, as sr_load_desc.animation chooses it. */
typedef struct sr_scene_animation {
    const char *name;             /* the file's name for it, or "" */
    size_t channel_count;
    float duration;               /* seconds: the last key time of its samplers */
} sr_scene_animation;

typedef struct sr_scene {
    sr_scene_primitive *primitives;
    size_t primitive_count;
    sr_pbr_material *materials;   /* every primitive's material is one of these: the
                                   * file's, then default_material's */
    size_t material_count;
    sr_texture **textures;        /* made on the context; the materials point here */
    size_t texture_count;
    sr_scene_camera *cameras;     /* in node order (depth first, as the file lists
                                   * children): what --camera-index counts */
    size_t camera_count;
    sr_vec3 bounds_min, bounds_max; /* of every primitive, world space; zero when none */
    int warning_count;            /* warnings given to sr_load_desc.warn */
    struct sr_scene_store *store; /* the arrays' memory (internal) */
    /* Members added later come after the ones above, so that a program
     * built against the older header reads those where they were (the
     * library allocates the scene). */
    sr_scene_light *lights;       /* KHR_lights_punctual, in node order as cameras; all of
                                   * them: a program takes the first SR_MAX_LIGHTS */
    size_t light_count;
    const char *const *variants;  /* KHR_materials_variants' names, in the file's order
                                   * (UTF-8; not necessarily unique) */
    size_t variant_count;
    sr_scene_animation *animations; /* the file's, in its order, whichever pose was asked */
    size_t animation_count;
    int animation;                /* the one the scene is posed by, or -1: the rest pose */
    float animation_time;         /* and the time it was sampled at, seconds */
    /* EXT_mesh_gpu_instancing: the draws its instances make (in
     * `primitives`, each instance one draw a primitive, sharing the
     * primitive's arrays) and the nodes that make them. */
    size_t instanced_draws;
    size_t instanced_nodes;
    /* The material the glTF reader adds after the file's for primitives
     * that name none (glTF's default: white, metallic 1, roughness 1), its
     * index (the last), whether any primitive draws with it or not; -1
     * when the scene has none (other formats). */
    int default_material;
    sr_scene_metadata metadata;   /* glTF's asset and its XMP packet */
} sr_scene;

/* Limits of the glTF reader, checked before allocating: at most this many
 * draws (node instances of primitives) drawing at most this many vertices
 * and triangles in all (instances counted each time: a few vertices
 * indexed by a long accessor and placed by many nodes cost their
 * triangles), and accessors decoded whose
 * elements sum to at most SR_SCENE_ELEMENTS_PER_BYTE per byte of input
 * (the JSON, its buffers) plus SR_SCENE_ELEMENTS_BASE, so that a small
 * file cannot ask for gigabytes with a large count and no data. */
#define SR_SCENE_MAX_DRAWS          ((size_t)1 << 20)
#define SR_SCENE_MAX_DRAWN_VERTICES ((size_t)1 << 27)
#define SR_SCENE_MAX_DRAWN_TRIANGLES ((size_t)1 << 28)
#define SR_SCENE_ELEMENTS_PER_BYTE  16
#define SR_SCENE_ELEMENTS_BASE      ((size_t)1 << 20)

/* Load `path` as a scene into *out (NULL on failure).  Format by desc's
 * format (SR_FORMAT_GLTF forces the glTF reader), by the name (.gltf,
 * .glb), by the content (GLB's magic, a JSON object), else through
 * sr_load_mesh.  glTF errors are one line "FILE: /json/pointer: what is
 * wrong"; bad JSON is "FILE:LINE: ...".  The scene and its arrays come
 * from malloc, the textures from ctx; release all with sr_destroy_scene on
 * the same ctx.  SR_UNSUPPORTED for glTF in a build without jansson. */
SR_API sr_result sr_load_scene(sr_context *ctx, const char *path, const sr_load_desc *desc,
                               sr_scene **out, sr_io_error *err);
/* A glTF 2.0 document in memory, JSON or GLB (told apart by GLB's magic);
 * `name` (may be NULL: "<memory>") is used in messages, and relative URIs
 * are read from the directory of `name` (absolute paths and schemes other
 * than data: are refused). */
SR_API sr_result sr_parse_gltf(sr_context *ctx, const char *name, const uint8_t *data, size_t size,
                               const sr_load_desc *desc, sr_scene **out, sr_io_error *err);
/* A scene camera's view matrix E (world -> camera: the inverse of its
 * world matrix with scale and shear taken out, as glTF asks) and its
 * projection P (OpenGL's clip space, z_ndc in [-1, 1]) for a viewport of
 * `aspect` = width / height: glTF's own matrices, the infinite one when
 * zfar is 0.  The vertical extent (yfov, ymag) is kept and the horizontal
 * one follows the viewport, so nothing is stretched whatever the file's
 * aspectRatio or xmag.  SR_INVALID_ARG (view and projection untouched)
 * for NULL, a non-finite or non-positive aspect, a type that is not an
 * sr_scene_camera_type, a degenerate or non-finite world matrix, a yfov
 * outside (0, pi), clip distances glTF would refuse, or values so large
 * (near FLT_MAX) that a matrix would not be finite. */
SR_API sr_result sr_scene_camera_matrices(const sr_scene_camera *camera, float aspect,
                                          sr_mat4 *view, sr_mat4 *projection);
/* Poses a scene read from a glTF file again, without reading the file:
 * SR_POSE_ANIMATION places its nodes by animation number `animation` (0
 * first, as sr_scene.animations lists them) at `time` seconds, keys
 * clamped at both ends; SR_POSE_REST (or zero) puts them back in their
 * own transforms.  The draws, materials, cameras, lights, bounds and
 * sr_scene.animation / animation_time come out with the very bytes
 * sr_load_scene gives with that sr_load_desc pose (docs/gltf.md): an
 * animation's KHR_animation_pointer channels write material, camera and
 * light values over the rest pose's, which the scene keeps, and
 * KHR_node_visibility empties the hidden nodes' draws.  A
 * scene read from a file with animations keeps what this takes: the
 * decoded key times and values, the nodes' rest transforms, the skins'
 * joints and inverse bind matrices, the morph targets and the skinning
 * weights.  Posed draws' positions, normals and tangents point to arrays
 * the scene makes on first need and reuses after (a draw whose morph
 * weights all become zero points to its mesh's arrays again), so posing
 * again and again does not grow its memory; the primitive, material,
 * camera and light arrays stay where they are (copy what is to outlive
 * the next pose).  Errors leave the scene as it was:
 * SR_INVALID_ARG for a NULL scene, a pose that is not an sr_load_pose,
 * an animation the scene does not have, a time that is not finite;
 * SR_BAD_FORMAT when the pose collapses a light's direction, as reading
 * in that pose would; SR_TOO_LARGE past the reader's limits for the
 * arrays posing makes; SR_OUT_OF_MEMORY.  A scene without animations (or
 * from another format) has only the rest pose: SR_OK, nothing changes.
 * err may be NULL.  Not while another thread draws from the scene. */
SR_API sr_result sr_scene_pose(sr_scene *scene, sr_load_pose pose, int animation, float time,
                               sr_io_error *err);
/* Frees the scene, its arrays and its textures; NULL is ignored. */
SR_API void sr_destroy_scene(sr_context *ctx, sr_scene *scene);
/* true when this build reads glTF (it found jansson). */
SR_API bool sr_io_have_gltf(void);

/* true when this build can read other formats through Assimp. */
SR_API bool sr_io_have_assimp(void);

/* The optional parts this build has, each resting on a library the build
 * found: a static string of names separated by single spaces, in this
 * order, each present only when built in - png (PNG files), jpeg, webp
 * (WebP images), gltf (glTF scenes), meshopt (EXT_meshopt_compression),
 * draco (KHR_draco_mesh_compression), svg (SVG drawings), svgz (gzipped
 * ones), text (SVG text and sr_text_path), bidi (bidirectional text),
 * assimp (other model formats).  "" when none. */
SR_API const char *sr_io_features(void);

/* Open a file for reading as the readers here do, for a program's own
 * inputs (a script, a drawing): only a regular file.  A directory, FIFO,
 * device or socket is refused at once - opening a FIFO would otherwise
 * wait for a writer, maybe forever - with one line naming the file
 * ("FILE: cannot open: ...", "FILE: is a directory, not KIND", "FILE: not
 * a regular file"), KIND saying what the file should be ("an event
 * script").  *size is the file's size in bytes; close *f with fclose. */
SR_API sr_result sr_open_file(const char *path, const char *kind, FILE **f, unsigned long long *size,
                              sr_io_error *err);

/* Memory limits: how much memory a program's images may take, so that it
 * can refuse a size in one line before allocating it.  Linux overcommits:
 * an image larger than the machine holds is rarely refused when it is
 * allocated, and the process is killed later, without a word, as its
 * pages are touched.  The limit is the environment variable
 * SR_MEMORY_LIMIT when set (bytes, or a binary multiple: 512M, 8G, 1.5T,
 * also written 8Gi, 8GiB, 8GB), else the physical memory, or less under an
 * address space or data size limit (ulimit -v, -d).  The softrast tool and
 * the Python package check their frames and images here.  Any thread. */
typedef struct sr_memory_limit_info {
    uint64_t bytes;             /* the limit; UINT64_MAX when nothing is known */
    bool from_environment;      /* SR_MEMORY_LIMIT set it */
    char source[128];           /* what sets it: "SR_MEMORY_LIMIT=8G", "the physical
                                 * memory", "the address space limit (ulimit -v)" */
} sr_memory_limit_info;

/* The limit now.  SR_INVALID_ARG for a NULL out, or when SR_MEMORY_LIMIT
 * is malformed (also 0): err says "SR_MEMORY_LIMIT: expected a size in
 * bytes such as 512M or 8G (got 'lots')".  err may be NULL. */
SR_API sr_result sr_query_memory_limit(sr_memory_limit_info *out, sr_io_error *err);

typedef struct sr_memory_check_desc {
    const char *what;           /* required: what needs the memory, starting the
                                 * message ("render: --size 8192x8192") */
    uint64_t bytes;             /* the estimate */
    const char *memory;         /* the kind of memory the message names
                                 * ("frame memory"); NULL -> "memory" */
    const char *lower;          /* required: how to need less, ending the message
                                 * ("give a smaller --size") */
} sr_memory_check_desc;

/* SR_OK when desc->bytes fit the limit.  SR_TOO_LARGE when they do not,
 * with err "WHAT needs about 8.5 GiB of MEMORY, more than
 * SR_MEMORY_LIMIT=1G allows: LOWER" or, without SR_MEMORY_LIMIT, "...,
 * more than the 7.8 GiB of the physical memory (SR_MEMORY_LIMIT sets
 * another limit): LOWER".  SR_INVALID_ARG as sr_query_memory_limit, or for
 * a NULL desc, what or lower.  err may be NULL. */
SR_API sr_result sr_check_memory(const sr_memory_check_desc *desc, sr_io_error *err);

/* PNG. */
typedef enum sr_png_channels {
    SR_PNG_CHANNELS_DEFAULT = 0, /* -> SR_PNG_RGBA */
    SR_PNG_RGBA,
    SR_PNG_RGB,                  /* alpha dropped */
} sr_png_channels;

typedef struct sr_png_write_desc {
    int compression_level;  /* zlib level; 0 -> SR_PNG_DEFAULT_LEVEL; -1 -> store */
    sr_png_channels channels;
    sr_allocator allocator; /* zero: malloc/free.  Every block the write
                             * allocates - its own and zlib's - comes from here,
                             * on the calling thread (except realpath's when
                             * `path` is a symbolic link); NULL from alloc makes
                             * the call return SR_OUT_OF_MEMORY with nothing
                             * left behind */
    sr_context *context;    /* optional: compress on this context's threads
                             * (bands of rows at once); the file's bytes are the
                             * same with or without it.  The context must not be
                             * in use on another thread meanwhile */
} sr_png_write_desc;

#define SR_PNG_DEFAULT_LEVEL 1

/* Write RGBA8 pixels (stride in bytes) to `path` atomically: a temporary
 * file in the same directory, fsync'd, then renamed over the target, so a
 * failed write never leaves a partial file or clobbers an existing one.
 * Writes retry after EINTR (a signal handler without SA_RESTART) and carry
 * on after a short write; the first real error (ENOSPC, EFBIG, EIO) fails
 * the call with SR_IO_ERROR and removes the temporary file. */
SR_API sr_result sr_write_png(const char *path, int width, int height,
                              const uint8_t *rgba, size_t stride,
                              const sr_png_write_desc *desc, sr_io_error *err);

/* Write `size` bytes (any file already encoded: an animated WebP, a
 * JSON sidecar) to `path` atomically, as sr_write_png does: the file
 * appears whole or not at all, an existing one keeps its bytes when the
 * write fails and its permissions when it succeeds, a symbolic link's
 * target is replaced.  SR_INVALID_ARG for a NULL or empty path or NULL
 * data with size > 0; SR_IO_ERROR (a directory, a full disk, ...). */
SR_API sr_result sr_write_file(const char *path, const void *data, size_t size,
                               sr_io_error *err);

/* Where an encoder's bytes go (stb_image_write's "_to_func"): called in
 * order with consecutive pieces of the file (a socket, a growing buffer);
 * return false to stop, and the encoder returns SR_IO_ERROR ("<memory>:
 * the write function failed") with every block it took released. */
typedef bool (*sr_write_fn)(void *user, const void *data, size_t size);

/* sr_write_png's bytes, the same ones, to `write` instead of a file
 * (messages name "<memory>"). */
SR_API sr_result sr_encode_png(sr_write_fn write, void *user, int width, int height,
                               const uint8_t *rgba, size_t stride, const sr_png_write_desc *desc,
                               sr_io_error *err);

typedef struct sr_png_read_desc {
    sr_allocator allocator; /* zero: malloc/free.  libpng's and zlib's blocks, the
                             * row table and the pixels come from here (release
                             * *pixels with allocator.free); only stdio's FILE does
                             * not.  NULL from alloc: SR_OUT_OF_MEMORY, nothing kept */
} sr_png_read_desc;

/* Read a PNG as RGBA8 (any bit depth, palette, gray and alpha expanded).
 * desc may be NULL: *pixels is then malloc'd; free it with free(). */
SR_API sr_result sr_read_png(const char *path, const sr_png_read_desc *desc, int *width,
                             int *height, uint8_t **pixels, sr_io_error *err);
/* sr_read_png on a file already in memory; `name` is used in messages. */
SR_API sr_result sr_decode_png(const char *name, const uint8_t *data, size_t size,
                               int *width, int *height, uint8_t **pixels, sr_io_error *err);

/* JPEG: baseline or progressive, gray, YCbCr/RGB or CMYK (Adobe's inverted
 * inks too), any chroma subsampling, read as RGBA8 with alpha 255; at
 * most 16384 pixels a side, like PNG, and SR_TOO_LARGE for a progressive
 * image whose decoding would take more than 512 MiB.  Data libjpeg would only patch
 * over with a warning (a truncated file's missing rows come out gray) is
 * an error with libjpeg's words: nothing partial is returned.  *pixels is
 * malloc'd; free it with free().  A build without libjpeg returns
 * SR_UNSUPPORTED (sr_io_have_jpeg says which). */
SR_API sr_result sr_read_jpeg(const char *path, int *width, int *height,
                              uint8_t **pixels, sr_io_error *err);
/* The same on a file already in memory; `name` is used in messages. */
SR_API sr_result sr_decode_jpeg(const char *name, const uint8_t *data, size_t size,
                                int *width, int *height, uint8_t **pixels, sr_io_error *err);
SR_API bool sr_io_have_jpeg(void);

/* Write RGBA8 pixels (stride in bytes) as a baseline JPEG with 4:2:0
 * chroma, alpha dropped, atomically as sr_write_png does (a failed write
 * leaves nothing and replaces nothing).  At most 65500 pixels a side. */
typedef struct sr_jpeg_write_desc {
    int quality;            /* 1..100; 0 -> SR_JPEG_DEFAULT_QUALITY */
} sr_jpeg_write_desc;

#define SR_JPEG_DEFAULT_QUALITY 90

SR_API sr_result sr_write_jpeg(const char *path, int width, int height,
                               const uint8_t *rgba, size_t stride,
                               const sr_jpeg_write_desc *desc, sr_io_error *err);
/* sr_write_jpeg's bytes to `write` instead of a file (see sr_write_fn). */
SR_API sr_result sr_encode_jpeg(sr_write_fn write, void *user, int width, int height,
                                const uint8_t *rgba, size_t stride, const sr_jpeg_write_desc *desc,
                                sr_io_error *err);

/* A PNG, a JPEG or a WebP (lossy or lossless, alpha kept; not animated),
 * told apart by the file's first bytes (not its name), read as RGBA8 by
 * sr_read_png, sr_read_jpeg or libwebp.  SR_UNSUPPORTED for a JPEG or a
 * WebP in a build without libjpeg or libwebp. */
SR_API sr_result sr_read_image(const char *path, int *width, int *height,
                               uint8_t **pixels, sr_io_error *err);
/* The same on bytes in memory (sr_mesh.texture_data, say). */
SR_API sr_result sr_decode_image(const char *name, const uint8_t *data, size_t size,
                                 int *width, int *height, uint8_t **pixels, sr_io_error *err);

/* Radiance RGBE pictures (.hdr, .pic), such as equirectangular
 * environment maps, read as linear float RGB: 3 floats a pixel, rows top
 * first, *pixels malloc'd (free it with free()).  The header must start
 * with #?RADIANCE or #?RGBE; FORMAT, when given, must be 32-bit_rle_rgbe
 * (XYZE is SR_UNSUPPORTED).  EXPOSURE and the other header variables are
 * ignored: the values are those stored, as three.js, Blender and stb_image
 * read them (scale with the tone mapper's exposure instead).  Resolution
 * lines "-Y H +X W" (the usual one), "+Y" (bottom row first) and "-X"
 * (right to left) are read; X before Y (column order) is SR_UNSUPPORTED.
 * Scanlines are new-style run-length or flat; old-style runs (a 1,1,1
 * pixel) are SR_UNSUPPORTED.  A pixel (m, e) is (m + 0.5) * 2^(e - 136),
 * 0 when e == 0, as Radiance's own reader converts it.  At most
 * SR_HDR_MAX_SIDE a side and SR_HDR_MAX_PIXELS pixels, checked, with the
 * file's length, before anything is allocated; bytes after the last
 * scanline are ignored. */
#define SR_HDR_MAX_SIDE   32768
#define SR_HDR_MAX_PIXELS ((size_t)1 << 27)   /* 1.5 GiB of floats */
SR_API sr_result sr_read_hdr(const char *path, int *width, int *height, float **pixels,
                             sr_io_error *err);
/* The same on a file already in memory; `name` is used in messages. */
SR_API sr_result sr_decode_hdr(const char *name, const uint8_t *data, size_t size, int *width,
                               int *height, float **pixels, sr_io_error *err);

/* SVG 1.1 drawings, rendered with the 2D toolkit: svg, g, path, rect,
 * circle, ellipse, line, polyline, polygon, image (PNG, JPEG); transforms;
 * fill and stroke with their opacities, rules, joins, caps and dashes;
 * markers, paint-order; shape-rendering; display and visibility; <style>
 * sheets and style attributes, currentColor, CSS colors; defs, use,
 * symbol, switch; linear and radial gradients, patterns; clip paths,
 * masks, group opacity, blend modes and filter effects (drawn in
 * layers); the table in
 * docs/draw2d.md says what else.  Anything else is skipped with one
 * warning per name; reference cycles (use, clip-path, mask, marker,
 * pattern, feImage, SVG images that include themselves) are refused.
 * The work is bounded by the size of the document and of the image (the
 * limits below, docs/robustness.md): a few hundred bytes cannot make the
 * renderer spin for seconds or allocate gigabytes. */
#define SR_SVG_MAX_INPUT_BYTES ((size_t)256 << 20) /* the document itself */
#define SR_SVG_MAX_PATH_POINTS (1 << 20)   /* flattened points of one shape */
#define SR_SVG_MAX_SUBPATHS    (1 << 14)   /* subpaths (moveto) of one shape */
/* Points handled in all - flattened paths, stroke outlines (estimated
 * before they are built), polygons filled - may reach SR_SVG_POINTS_BASE
 * plus SR_SVG_POINTS_PER_BYTE per byte of the document and of each SVG
 * document its images read. */
#define SR_SVG_POINTS_BASE     (1 << 19)
#define SR_SVG_POINTS_PER_BYTE 16
/* Fill work: the pixels of every filled polygon's bounding box (clipped to
 * the image) plus the image rows each of its edges crosses, summed over the
 * document, and the bytes of each SVG document its images read, may reach
 * SR_SVG_WORK_PER_PIXEL times the image's pixel count plus SR_SVG_WORK_BASE. */
#define SR_SVG_WORK_PER_PIXEL  16
#define SR_SVG_WORK_BASE       (1 << 24)

/* One warning, "NAME:LINE: warning: ..." (no newline), as it arises. */
typedef void (*sr_svg_warn_fn)(void *user, const char *message);

typedef struct sr_svg_desc {
    const char *name;        /* the document's name in messages, and the directory its
                              * <image> files are read from; NULL -> "<svg>", no files */
    int width, height;       /* the image size (the viewBox is fitted in), or 0:
                              * the drawing's own size times scale.  A root of
                              * zero or negative size is SR_BAD_FORMAT either way:
                              * SVG draws nothing of it */
    double scale;            /* 0 -> 1 */
    sr_rgba background;      /* the image is cleared to it first (zero: transparent);
                              * finite */
    int max_side;            /* largest image side; 0 -> SR_MAX_FRAMEBUFFER_SIZE */
    uint64_t max_layer_bytes; /* the most memory the drawing's layers may hold at
                              * once besides the image, or 0: no limit.  Group
                              * opacity, blend modes, clip paths, masks, nested
                              * viewports, pattern tiles and SVG images draw into
                              * layers of their own, nested up to 8 deep, each 6
                              * bytes a pixel while open (its RGBA, the coverages
                              * it is composited through) and 4 more for the
                              * composite's copy of the image; a filter's float
                              * images count too (16 bytes a pixel of its region
                              * each, as many as it holds at once); a layer or
                              * filter that would pass the limit fails the render
                              * with SR_TOO_LARGE.
                              * The softrast tool gives what SR_MEMORY_LIMIT leaves */
    sr_svg_warn_fn warn;     /* NULL: warnings are only counted */
    void *warn_user;
} sr_svg_desc;

/* What a render did, also when it failed: the work it counted against its
 * budgets (the "_used" never pass the budgets: an operation that would is
 * refused before it runs, and the render fails with SR_TOO_LARGE). */
typedef struct sr_svg_info {
    double points_used, points_budget;   /* points flattened, stroked and filled */
    double work_used, work_budget;       /* fill work, as defined above */
    int warnings;                        /* warnings given (at most 65) */
    bool over_layer_limit;               /* SR_TOO_LARGE came from max_layer_bytes
                                          * (memory), not from a work budget */
} sr_svg_info;

/* Render the SVG document in data[0..size) (need not be NUL-terminated)
 * into a new framebuffer on ctx (*out; sr_destroy_framebuffer it).  On
 * failure *out is NULL and err holds one line "NAME:LINE: what is wrong":
 * SR_BAD_FORMAT for a malformed document or a size outside 1..max_side,
 * SR_TOO_LARGE past a limit above, SR_OUT_OF_MEMORY, SR_INVALID_ARG for
 * bad arguments, SR_UNSUPPORTED in a build without expat.  info may be
 * NULL.  Nothing global: calls may run in parallel on different contexts. */
SR_API sr_result sr_render_svg(sr_context *ctx, const char *data, size_t size, const sr_svg_desc *desc,
                               sr_framebuffer **out, sr_svg_info *info, sr_io_error *err);
/* The same for a file (desc->name defaults to the path). */
SR_API sr_result sr_render_svg_file(sr_context *ctx, const char *path, const sr_svg_desc *desc,
                                    sr_framebuffer **out, sr_svg_info *info, sr_io_error *err);
/* true when this build reads SVG (it found expat). */
SR_API bool sr_io_have_svg(void);

/* ---- text as paths ----------------------------------------------------
 * The SVG reader's text (fontconfig, HarfBuzz, FreeType; docs/draw2d.md)
 * for programs: a line of text becomes glyph outlines in an sr_path, to
 * fill with sr_fill_path and friends like any path. */

typedef enum sr_text_anchor {
    SR_TEXT_ANCHOR_DEFAULT = 0,  /* resolved to SR_TEXT_ANCHOR_START */
    SR_TEXT_ANCHOR_START,        /* x is where the text starts (its end, right to left) */
    SR_TEXT_ANCHOR_MIDDLE,       /* x is the middle of its advance */
    SR_TEXT_ANCHOR_END,
} sr_text_anchor;

typedef struct sr_text_desc {
    const char *family;          /* a font-family list as CSS writes it; NULL -> "sans-serif" */
    const char *font_file;       /* a font file to use instead; NULL: fontconfig matches family */
    double size;                 /* the em in path units; 0 -> 16 */
    int weight;                  /* 1..1000; 0 -> 400 (bold is 700) */
    bool italic;
    double x, y;                 /* the pen's start on the baseline (y down) */
    sr_text_anchor anchor;
    bool rtl;                    /* the line's base direction is right to left (bidi) */
} sr_text_desc;

/* Append the outlines of utf8 (NUL-terminated, at most SR_TEXT_MAX_CHARS
 * characters, one line: newlines and tabs are spaces) shaped with the
 * font desc names to path; *advance (may be NULL) is the pen's advance.
 * Errors: SR_INVALID_ARG (NULL utf8 or path, bad UTF-8, a size not in
 * (0, SR_MAX_COORD2D], a weight beyond 1000), SR_BAD_FORMAT (the font
 * file does not read, no font is found), SR_TOO_LARGE (too many
 * characters), SR_OUT_OF_MEMORY, SR_UNSUPPORTED (a build without the
 * libraries: sr_io_have_text). */
#define SR_TEXT_MAX_CHARS 65536
SR_API sr_result sr_text_path(const char *utf8, const sr_text_desc *desc, sr_path *path,
                              double *advance, sr_io_error *err);
/* true when this build lays out text (fontconfig, HarfBuzz, FreeType). */
SR_API bool sr_io_have_text(void);
/* A CSS color as SVG reads one, alpha included: a keyword (the 147 of CSS
 * and SVG, "transparent"), #rgb, #rgba, #rrggbb, #rrggbbaa, rgb()/rgba()
 * and hsl()/hsla() (commas or blanks, numbers or percentages, an alpha
 * after ',' or '/'), ASCII case ignored, blanks around it allowed.  For
 * programs that take a color from their user the way SVG does (the Python
 * package's render_svg background).  Works in builds without expat.
 * SR_BAD_FORMAT for anything else ("none", "currentColor" and url(...)
 * are paints, not colors), SR_INVALID_ARG for NULL; *out is set only on
 * SR_OK. */
SR_API sr_result sr_io_parse_color(const char *text, sr_rgba *out);

/*
 * SVG path data, the `d` attribute of a <path>, appended to `path`: every
 * command (M L H V C S Q T A Z), absolute (upper case) and relative (lower
 * case), numbers repeated after a command as more of it (more pairs after
 * M or m are L or l), S and T reflecting the previous control point, arc
 * flags written together ("a1 1 0 01 5 5").  Numbers are read as SVG
 * writes them whatever the C locale is; one beyond double range is an
 * error.  As SVG's error handling says, an error in the data ends the
 * path there: the commands before it stay in `path` and the result is
 * SR_BAD_FORMAT, *error_offset the byte offset of the error in d and err
 * "path data: expected a number at offset 12".  A point the path refuses
 * (an infinite sum of relative numbers) gives that call's result (its
 * message on the path's context); SR_INVALID_ARG for a NULL d or path.
 * desc may be NULL; error_offset (-1 unless a call fails) and err may be
 * NULL.  Works in builds without expat; the SVG reader builds its paths
 * through this.
 */
typedef struct sr_io_path_data_desc {
    /* Called after each command is added, with its letter (for numbers
     * repeating a command, that command's; L or l after a moveto) and the
     * offset where the data goes on; anything but SR_OK stops the parse
     * and is returned (the SVG reader checks its limits here). */
    sr_result (*command)(void *user, char letter, long offset);
    void *user;
} sr_io_path_data_desc;

SR_API sr_result sr_io_parse_path_data(const char *d, sr_path *path,
                                       const sr_io_path_data_desc *desc, long *error_offset,
                                       sr_io_error *err);

#ifdef __cplusplus
}
#endif
#endif /* SOFTRAST_IO_H */
