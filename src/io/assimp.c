/*
 * assimp.c - io stage: every model format beyond OBJ, PLY and STL, read
 * through Assimp's C API when the build found it (SR_HAVE_ASSIMP).
 * Consumes a path; produces one sr_mesh with all of the scene's meshes
 * merged, node transforms applied.  Without Assimp it only explains how to
 * get it.  Any thread may call it (Assimp imports share no state).
 */
#include "io/io_util.h"
#include "io/readers.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* "off", or NULL when the name has no extension. */
static const char *extension_of(const char *path)
{
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    const char *dot = strrchr(base, '.');
    return dot && dot != base && dot[1] ? dot + 1 : NULL;
}

#ifndef SR_HAVE_ASSIMP

sr_result sr__load_assimp(const char *path, sr_mesh *out, sr_io_error *err)
{
    if (out) {
        memset(out, 0, sizeof *out);
    }
    const char *ext = extension_of(path);
    if (ext) {
        return sr__io_fail(err, SR_UNSUPPORTED, path, 0,
                           "format not supported (install libassimp-dev and rebuild "
                           "to read .%s files)", ext);
    }
    return sr__io_fail(err, SR_UNSUPPORTED, path, 0,
                       "format not supported (not OBJ, PLY or STL; install "
                       "libassimp-dev and rebuild to read other formats)");
}

bool sr__assimp_available(void)
{
    return false;
}

#else /* SR_HAVE_ASSIMP */

#include <assimp/cimport.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <dlfcn.h>
#include <pthread.h>

/* Assimp is a large C++ library: linking it makes every run of the tool
 * pay ~7 ms of dynamic relocation before main(), even for the OBJ, PLY and
 * STL files softrast reads itself.  So the headers come from the build,
 * but the library is opened with dlopen the first time a file needs it. */
static struct {
    const struct aiScene *(*import_file)(const char *, unsigned int);
    void (*release_import)(const struct aiScene *);
    const char *(*get_error_string)(void);
    enum aiReturn (*get_material_texture)(const struct aiMaterial *, enum aiTextureType,
                                          unsigned int, struct aiString *, enum aiTextureMapping *,
                                          unsigned int *, ai_real *, enum aiTextureOp *,
                                          enum aiTextureMapMode *, unsigned int *);
    aiBool (*is_extension_supported)(const char *);
    enum aiReturn (*get_material_color)(const struct aiMaterial *, const char *, unsigned int,
                                        unsigned int, struct aiColor4D *);
    enum aiReturn (*get_material_string)(const struct aiMaterial *, const char *, unsigned int,
                                         unsigned int, struct aiString *);
    bool loaded;
} api;
static pthread_once_t api_once = PTHREAD_ONCE_INIT;

static void open_assimp(void)
{
    static const char *const names[] = { "libassimp.so.5", "libassimp.so" };
    void *lib = NULL;
    for (size_t i = 0; i < sizeof names / sizeof names[0] && !lib; i++) {
        lib = dlopen(names[i], RTLD_NOW | RTLD_LOCAL);
    }
    if (!lib) {
        return;
    }
    *(void **)&api.import_file = dlsym(lib, "aiImportFile");
    *(void **)&api.release_import = dlsym(lib, "aiReleaseImport");
    *(void **)&api.get_error_string = dlsym(lib, "aiGetErrorString");
    *(void **)&api.get_material_texture = dlsym(lib, "aiGetMaterialTexture");
    *(void **)&api.is_extension_supported = dlsym(lib, "aiIsExtensionSupported");
    *(void **)&api.get_material_color = dlsym(lib, "aiGetMaterialColor");
    *(void **)&api.get_material_string = dlsym(lib, "aiGetMaterialString");
    api.loaded = api.import_file && api.release_import && api.get_error_string &&
                 api.get_material_texture && api.is_extension_supported &&
                 api.get_material_color && api.get_material_string;
}

bool sr__assimp_available(void)
{
    pthread_once(&api_once, open_assimp);
    return api.loaded;
}

#define aiImportFile(p, f) api.import_file((p), (f))
#define aiReleaseImport(s) api.release_import(s)
#define aiGetErrorString() api.get_error_string()
#define aiIsExtensionSupported(e) api.is_extension_supported(e)
#define aiGetMaterialTexture(m, t, i, s, ...) api.get_material_texture((m), (t), (i), (s), __VA_ARGS__)
/* Variadic: AI_MATKEY_* stand for three arguments only once expanded. */
#define aiGetMaterialColor(m, ...) api.get_material_color((m), __VA_ARGS__)
#define aiGetMaterialString(m, ...) api.get_material_string((m), __VA_ARGS__)

/* Triangulate polygons, share identical vertices, bake the node hierarchy
 * into vertex positions (we draw one mesh with one model matrix), and
 * split points and lines away from triangles so they can be skipped. */
#define IMPORT_FLAGS                                                         \
    (aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |               \
     aiProcess_PreTransformVertices | aiProcess_SortByPType |                \
     aiProcess_ValidateDataStructure)

static bool is_triangle_mesh(const struct aiMesh *m)
{
    return m->mNumVertices > 0 && m->mNumFaces > 0 &&
           (m->mPrimitiveTypes & aiPrimitiveType_TRIANGLE);
}

/* The diffuse color mesh m's material gives (glTF's base color factor,
 * FBX's DiffuseColor...), as OBJ's Kd: false when it has none, or is the
 * material Assimp makes up for a file that has none, whose gray would
 * stand in for softrast's own default. */
static bool material_color(const struct aiScene *scene, const struct aiMesh *m, float rgb[3])
{
    if (m->mMaterialIndex >= scene->mNumMaterials) {
        return false;
    }
    const struct aiMaterial *mat = scene->mMaterials[m->mMaterialIndex];
    struct aiString name;
    if (aiGetMaterialString(mat, AI_MATKEY_NAME, &name) == AI_SUCCESS &&
        strcmp(name.data, AI_DEFAULT_MATERIAL_NAME) == 0) {
        return false;
    }
    struct aiColor4D c;
    if (aiGetMaterialColor(mat, AI_MATKEY_COLOR_DIFFUSE, &c) != AI_SUCCESS ||
        !isfinite(c.r) || !isfinite(c.g) || !isfinite(c.b)) {
        return false;
    }
    rgb[0] = c.r;
    rgb[1] = c.g;
    rgb[2] = c.b;
    return true;
}

/* The embedded texture a material names: "*N" (Assimp's name for the
 * file's N-th image), or an image whose own file name it is (glTF binary
 * in later Assimp versions).  Only encoded images (mHeight == 0: PNG or
 * JPEG bytes) qualify; a raw texel array is left out. */
static const struct aiTexture *embedded_texture(const struct aiScene *scene, const char *name)
{
    const struct aiTexture *tex = NULL;
    if (name[0] == '*') {
        char *end;
        unsigned long k = strtoul(name + 1, &end, 10);
        if (end != name + 1 && *end == 0 && k < scene->mNumTextures) {
            tex = scene->mTextures[k];
        }
    } else {
        for (unsigned i = 0; i < scene->mNumTextures && !tex; i++) {
            if (strcmp(scene->mTextures[i]->mFilename.data, name) == 0) {
                tex = scene->mTextures[i];
            }
        }
    }
    return tex && tex->mHeight == 0 && tex->mWidth > 0 ? tex : NULL;
}

/* The diffuse texture mesh am's material names: an encoded image the file
 * embeds, or a file name, or neither (embedded and name.length both 0). */
typedef struct texture_ref {
    const struct aiTexture *embedded;
    struct aiString name;
} texture_ref;

static void texture_of(const struct aiScene *scene, const struct aiMesh *am, texture_ref *r)
{
    r->embedded = NULL;
    r->name.length = 0;
    r->name.data[0] = 0;
    struct aiString name;
    if (am->mMaterialIndex >= scene->mNumMaterials ||
        aiGetMaterialTexture(scene->mMaterials[am->mMaterialIndex], aiTextureType_DIFFUSE, 0,
                             &name, NULL, NULL, NULL, NULL, NULL, NULL) != AI_SUCCESS ||
        name.length == 0) {
        return;
    }
    r->embedded = embedded_texture(scene, name.data);
    if (!r->embedded && name.data[0] != '*') { /* "*N" not an encoded image: none */
        r->name = name;
    }
}

static bool has_texture(const texture_ref *r)
{
    return r->embedded || r->name.length > 0;
}

/* Whether two meshes take one image: the same embedded one, or the same
 * file name (two materials may name one file). */
static bool same_texture(const texture_ref *a, const texture_ref *b)
{
    if (a->embedded || b->embedded) {
        return a->embedded == b->embedded;
    }
    return a->name.length == b->name.length &&
           memcmp(a->name.data, b->name.data, a->name.length) == 0;
}

/* r's texture into *path (its file name joined to the model's directory,
 * as the OBJ reader does with map_Kd) or *data and *size (a copy of the
 * embedded bytes).  False when out of memory. */
static bool copy_texture(const texture_ref *r, const char *model_path, char **path,
                         uint8_t **data, size_t *size)
{
    if (r->embedded) {
        *data = malloc(r->embedded->mWidth);
        if (!*data) {
            return false;
        }
        memcpy(*data, r->embedded->pcData, r->embedded->mWidth);
        *size = r->embedded->mWidth;
        return true;
    }
    if (r->name.length == 0) {
        return true;
    }
    const char *name = r->name.data;
    const char *slash = strrchr(model_path, '/');
    bool absolute = name[0] == '/' || name[0] == '\\';
    size_t dir = absolute || !slash ? 0 : (size_t)(slash - model_path) + 1;
    *path = malloc(dir + r->name.length + 1);
    if (!*path) {
        return false;
    }
    memcpy(*path, model_path, dir);
    /* Windows exporters write "textures\wood.png". */
    for (size_t k = 0; k < r->name.length; k++) {
        (*path)[dir + k] = name[k] == '\\' ? '/' : name[k];
    }
    (*path)[dir + r->name.length] = 0;
    return true;
}

/* Triangles mesh am adds to the model (its faces of three corners). */
static size_t triangles_of(const struct aiMesh *am)
{
    size_t n = 0;
    for (unsigned f = 0; f < am->mNumFaces; f++) {
        n += am->mFaces[f].mNumIndices == 3;
    }
    return n;
}

/* The model's textures: the first one named for the whole mesh (sr_mesh
 * .texture_path or .texture_data), and, when its meshes take different
 * ones or some take none, its parts - runs of meshes that take the same
 * image, as the OBJ reader makes them of usemtl runs.  False when out of
 * memory. */
static bool diffuse_textures(const struct aiScene *scene, const char *model_path, sr_mesh *m)
{
    /* Count the runs, and find the first texture named. */
    texture_ref r, prev, first;
    size_t runs = 0;
    bool any = false;
    for (unsigned i = 0; i < scene->mNumMeshes; i++) {
        const struct aiMesh *am = scene->mMeshes[i];
        if (!is_triangle_mesh(am) || triangles_of(am) == 0) {
            continue;
        }
        texture_of(scene, am, &r);
        runs += runs == 0 || !same_texture(&r, &prev);
        if (has_texture(&r) && !any) {
            first = r;
            any = true;
        }
        prev = r;
    }
    if (!any) {
        return true;
    }
    if (!copy_texture(&first, model_path, &m->texture_path, &m->texture_data,
                      &m->texture_size)) {
        return false;
    }
    if (runs < 2) {
        return true; /* one texture serves the whole mesh */
    }
    m->parts = calloc(runs, sizeof *m->parts);
    if (!m->parts) {
        return false;
    }
    m->part_count = runs;
    size_t n = 0, t = 0;
    for (unsigned i = 0; i < scene->mNumMeshes; i++) {
        const struct aiMesh *am = scene->mMeshes[i];
        size_t tris = is_triangle_mesh(am) ? triangles_of(am) : 0;
        if (tris == 0) {
            continue;
        }
        texture_of(scene, am, &r);
        if (n == 0 || !same_texture(&r, &prev)) {
            sr_mesh_part *p = &m->parts[n++];
            p->first_triangle = t;
            if (!copy_texture(&r, model_path, &p->texture_path, &p->texture_data,
                              &p->texture_size)) {
                return false; /* sr__free_malloc_mesh frees what the parts hold */
            }
        }
        m->parts[n - 1].triangle_count += tris;
        t += tris;
        prev = r;
    }
    return true;
}

sr_result sr__load_assimp(const char *path, sr_mesh *out, sr_io_error *err)
{
    if (out) {
        memset(out, 0, sizeof *out);
    }
    if (!path || !out) {
        return sr__io_fail(err, SR_INVALID_ARG, path ? path : "<null>", 0,
                           "no file name or output mesh given");
    }
    if (!sr__assimp_available()) {
        return sr__io_fail(err, SR_UNSUPPORTED, path, 0,
                           "format not supported (the Assimp library, libassimp5, could not be "
                           "loaded)");
    }
    const char *ext = extension_of(path);
    if (ext) {
        char dotted[64];
        snprintf(dotted, sizeof dotted, ".%s", ext);
        if (!aiIsExtensionSupported(dotted)) {
            return sr__io_fail(err, SR_UNSUPPORTED, path, 0,
                               "format not supported (neither softrast nor Assimp reads "
                               ".%s files)", ext);
        }
    }
    const struct aiScene *scene = aiImportFile(path, IMPORT_FLAGS);
    if (!scene) {
        return sr__io_fail(err, SR_BAD_FORMAT, path, 0, "Assimp: %s", aiGetErrorString());
    }

    /* First pass: totals, and which attributes every mesh has.  An
     * attribute some meshes lack is dropped for all, rather than made up
     * for part of the model - but for color, which, as in the OBJ reader,
     * is the vertex's own, else its material's diffuse color, else white,
     * wherever any mesh has either. */
    size_t verts = 0, tris = 0;
    bool normals = true, colors = false, texcoords = true;
    for (unsigned i = 0; i < scene->mNumMeshes; i++) {
        const struct aiMesh *m = scene->mMeshes[i];
        if (!is_triangle_mesh(m)) {
            continue;
        }
        verts += m->mNumVertices;
        tris += triangles_of(m);
        normals &= m->mNormals != NULL;
        float rgb[3];
        colors |= m->mColors[0] != NULL || material_color(scene, m, rgb);
        texcoords &= m->mTextureCoords[0] != NULL;
    }
    sr_result res = SR_OK;
    if (tris == 0) {
        res = sr__io_fail(err, SR_BAD_FORMAT, path, 0, "contains no faces");
    } else if (verts > SR_IO_MAX_VERTICES || tris > SR_IO_MAX_TRIANGLES) {
        res = sr__io_fail(err, SR_TOO_LARGE, path, 0,
                          "%zu vertices and %zu triangles exceed the limits (%zu, %zu)",
                          verts, tris, (size_t)SR_IO_MAX_VERTICES,
                          (size_t)SR_IO_MAX_TRIANGLES);
    }
    if (res != SR_OK) {
        aiReleaseImport(scene);
        return res;
    }

    sr_mesh m;
    if (!sr__alloc_malloc_mesh(&m, verts, tris, normals, colors, texcoords)) {
        aiReleaseImport(scene);
        return sr__io_fail(err, SR_OUT_OF_MEMORY, path, 0, "out of memory for %zu vertices",
                           verts);
    }

    size_t base = 0, t = 0;
    for (unsigned i = 0; i < scene->mNumMeshes && res == SR_OK; i++) {
        const struct aiMesh *am = scene->mMeshes[i];
        if (!is_triangle_mesh(am)) {
            continue;
        }
        float mat_rgb[3] = { 1.0f, 1.0f, 1.0f };
        material_color(scene, am, mat_rgb);
        for (unsigned v = 0; v < am->mNumVertices; v++) {
            size_t o = base + v;
            const struct aiVector3D *p = &am->mVertices[v];
            if (!isfinite(p->x) || !isfinite(p->y) || !isfinite(p->z)) {
                res = sr__io_fail(err, SR_BAD_FORMAT, path, 0,
                                  "mesh %u, vertex %u: position is not finite", i, v);
                break;
            }
            m.positions[3 * o + 0] = p->x;
            m.positions[3 * o + 1] = p->y;
            m.positions[3 * o + 2] = p->z;
            if (normals) {
                m.normals[3 * o + 0] = am->mNormals[v].x;
                m.normals[3 * o + 1] = am->mNormals[v].y;
                m.normals[3 * o + 2] = am->mNormals[v].z;
            }
            if (colors && am->mColors[0]) {
                m.colors[4 * o + 0] = am->mColors[0][v].r;
                m.colors[4 * o + 1] = am->mColors[0][v].g;
                m.colors[4 * o + 2] = am->mColors[0][v].b;
                m.colors[4 * o + 3] = am->mColors[0][v].a;
            } else if (colors) {
                memcpy(&m.colors[4 * o], mat_rgb, sizeof mat_rgb);
                m.colors[4 * o + 3] = 1.0f;
            }
            if (texcoords) {
                m.texcoords[2 * o + 0] = am->mTextureCoords[0][v].x;
                m.texcoords[2 * o + 1] = am->mTextureCoords[0][v].y;
            }
        }
        for (unsigned f = 0; f < am->mNumFaces && res == SR_OK; f++) {
            const struct aiFace *face = &am->mFaces[f];
            if (face->mNumIndices != 3) {
                continue; /* a point or line left in a mixed mesh */
            }
            for (int k = 0; k < 3; k++) {
                unsigned idx = face->mIndices[k];
                if (idx >= am->mNumVertices) {
                    res = sr__io_fail(err, SR_BAD_FORMAT, path, 0,
                                      "mesh %u, face %u: vertex index %u out of range",
                                      i, f, idx);
                    break;
                }
                m.indices[3 * t + (size_t)k] = (uint32_t)(base + idx);
            }
            t++;
        }
        base += am->mNumVertices;
    }
    if (res == SR_OK && !diffuse_textures(scene, path, &m)) {
        res = sr__io_fail(err, SR_OUT_OF_MEMORY, path, 0, "out of memory for its texture");
    }
    aiReleaseImport(scene);
    if (res != SR_OK) {
        sr__free_malloc_mesh(&m);
        return res;
    }
    *out = m;
    return SR_OK;
}

#endif /* SR_HAVE_ASSIMP */
