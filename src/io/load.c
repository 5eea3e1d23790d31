/*
 * load.c - io stage: sr_load_mesh, the one entry point for model files.
 * Consumes a path (and an optional format); picks a reader by the name's
 * extension, then by the first bytes of the file (glTF to softrast's own
 * reader when the build has it), then hands anything else to Assimp.
 * Produces the reader's sr_mesh, copied onto the caller's context (the
 * readers grow arrays with realloc, which sr_allocator does not offer).
 * Also the public readers on memory.  Any thread may call these with a
 * context of its own.
 */
#include "io/io_util.h"
#include "io/readers.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

void sr__free_malloc_mesh(sr_mesh *mesh)
{
    free(mesh->positions);
    free(mesh->normals);
    free(mesh->colors);
    free(mesh->texcoords);
    free(mesh->indices);
    free(mesh->texture_path);
    free(mesh->texture_data);
    for (size_t i = 0; mesh->parts && i < mesh->part_count; i++) {
        free(mesh->parts[i].texture_path);
        free(mesh->parts[i].texture_data);
        free(mesh->parts[i].material.bump_path);
    }
    free(mesh->parts);
    memset(mesh, 0, sizeof *mesh);
}

bool sr__alloc_malloc_mesh(sr_mesh *m, size_t verts, size_t tris, bool normals, bool colors,
                           bool texcoords)
{
    *m = (sr_mesh){ .vertex_count = verts, .triangle_count = tris };
    m->positions = malloc(verts * 3 * sizeof(float));
    m->normals = normals ? malloc(verts * 3 * sizeof(float)) : NULL;
    m->colors = colors ? malloc(verts * 4 * sizeof(float)) : NULL;
    m->texcoords = texcoords ? malloc(verts * 2 * sizeof(float)) : NULL;
    m->indices = malloc(tris * 3 * sizeof(uint32_t));
    if (!m->positions || (normals && !m->normals) || (colors && !m->colors) ||
        (texcoords && !m->texcoords) || !m->indices) {
        sr__free_malloc_mesh(m);
        return false;
    }
    return true;
}

/* The reader's result `res` on a malloc'd mesh m, handed out as *out: a
 * copy on ctx, m freed. */
static sr_result hand_out(sr_context *ctx, const char *name, sr_result res, sr_mesh *m,
                          sr_mesh *out, sr_io_error *err)
{
    if (res == SR_OK && sr_make_mesh(ctx, m, out) != SR_OK) {
        res = sr__io_fail(err, SR_OUT_OF_MEMORY, name, 0,
                          "out of memory (copying the mesh onto the context)");
    }
    sr__free_malloc_mesh(m);
    return res;
}

static sr_result check_ctx(sr_context *ctx, const char *name, sr_mesh *out, sr_io_error *err)
{
    if (out) {
        memset(out, 0, sizeof *out);
    }
    if (!ctx) {
        return sr__io_fail(err, SR_INVALID_ARG, name ? name : "<input>", 0, "no context given");
    }
    return SR_OK;
}

static sr_result parse_obj_bytes(const char *name, const uint8_t *data, size_t size,
                                 sr_mesh *out, sr_io_error *err)
{
    return sr__parse_obj(name, (const char *)data, size, out, err);
}

/* A reader on memory, its mesh handed out on ctx. */
static sr_result parse_on(sr_context *ctx, sr_parse_fn parse, const char *name,
                          const uint8_t *data, size_t size, sr_mesh *out, sr_io_error *err)
{
    sr_result res = check_ctx(ctx, name, out, err);
    if (res != SR_OK) {
        return res;
    }
    sr_mesh m = {0};
    res = parse(name, data, size, out ? &m : NULL, err);
    return out ? hand_out(ctx, name ? name : "<input>", res, &m, out, err) : res;
}

sr_result sr_parse_obj(sr_context *ctx, const char *name, const char *data, size_t size,
                       sr_mesh *out, sr_io_error *err)
{
    return parse_on(ctx, parse_obj_bytes, name, (const uint8_t *)data, size, out, err);
}

sr_result sr_parse_ply(sr_context *ctx, const char *name, const uint8_t *data, size_t size,
                       sr_mesh *out, sr_io_error *err)
{
    return parse_on(ctx, sr__parse_ply, name, data, size, out, err);
}

sr_result sr_parse_stl(sr_context *ctx, const char *name, const uint8_t *data, size_t size,
                       sr_mesh *out, sr_io_error *err)
{
    return parse_on(ctx, sr__parse_stl, name, data, size, out, err);
}

bool sr_io_have_assimp(void)
{
#ifdef SR_HAVE_ASSIMP
    return sr__assimp_available();
#else
    return false;
#endif
}

/* The extension after the last '.' of the last path component, or NULL. */
static const char *extension(const char *path)
{
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    const char *dot = strrchr(base, '.');
    /* ".hidden" is a name, not an extension. */
    return dot && dot != base && dot[1] ? dot + 1 : NULL;
}

static sr_model_format format_from_extension(const char *path)
{
    const char *ext = extension(path);
    if (!ext) {
        return SR_FORMAT_AUTO;
    }
    if (strcasecmp(ext, "obj") == 0) {
        return SR_FORMAT_OBJ;
    }
    if (strcasecmp(ext, "ply") == 0) {
        return SR_FORMAT_PLY;
    }
    if (strcasecmp(ext, "stl") == 0) {
        return SR_FORMAT_STL;
    }
    if (strcasecmp(ext, "gltf") == 0 || strcasecmp(ext, "glb") == 0) {
        return SR_FORMAT_GLTF;
    }
    return SR_FORMAT_AUTO;
}

/* Recognize PLY, STL and GLB by content, for files named otherwise.  Reads
 * only the first 84 bytes.  SR_FORMAT_AUTO when none matches; open errors
 * (a FIFO or a directory too) are left for the code that runs next to
 * report. */
static sr_model_format format_from_content(const char *path)
{
    FILE *f;
    unsigned long long size;
    if (sr__open_regular(path, "a model file", &f, &size, NULL) != SR_OK) {
        return SR_FORMAT_AUTO;
    }
    unsigned char head[84];
    size_t n = fread(head, 1, sizeof head, f);
    fclose(f);

    if ((n >= 4 && memcmp(head, "ply\n", 4) == 0) ||
        (n >= 5 && memcmp(head, "ply\r\n", 5) == 0)) {
        return SR_FORMAT_PLY;
    }
    if (n >= 4 && memcmp(head, "glTF", 4) == 0) {
        return SR_FORMAT_GLTF;
    }
    if (n >= 5 && strncasecmp((const char *)head, "solid", 5) == 0) {
        return SR_FORMAT_STL;
    }
    /* A binary STL has no magic, but its size is exactly 84 + 50 per
     * triangle as counted at byte 80. */
    if (n == sizeof head) {
        unsigned long long count = (unsigned long long)head[80] | (unsigned long long)head[81] << 8 |
                                   (unsigned long long)head[82] << 16 |
                                   (unsigned long long)head[83] << 24;
        if (84 + 50 * count == size) {
            return SR_FORMAT_STL;
        }
    }
    return SR_FORMAT_AUTO;
}

/* The reader for path, by desc's format, the name, the content, or Assimp. */
static sr_result load_malloc_mesh(sr_context *ctx, const char *path, const sr_load_desc *desc,
                                  sr_mesh *out, sr_io_error *err)
{
    sr_model_format format = desc ? desc->format : SR_FORMAT_AUTO;
    sr_result res = sr__check_load_pose(desc, path, err);
    if (res != SR_OK) {
        return res;
    }
    if (format == SR_FORMAT_AUTO) {
        format = format_from_extension(path);
    }
    if (format == SR_FORMAT_AUTO) {
        format = format_from_content(path);
    }
    if (desc && desc->variant != 0 && !(format == SR_FORMAT_GLTF && sr_io_have_gltf())) {
        return sr__io_fail(err, SR_INVALID_ARG, path, 0,
                           "sr_load_desc.variant: %d, but the file has 0 variants (only glTF "
                           "files read by softrast's own reader have them)",
                           desc->variant);
    }
    /* Only the glTF reader poses a model; another format has no
     * animation to sample, which the caller asked for. */
    if (desc && desc->pose == SR_POSE_ANIMATION &&
        (format != SR_FORMAT_GLTF || !sr_io_have_gltf())) {
        return sr__io_fail(err, SR_INVALID_ARG, path, 0,
                           "sr_load_desc.pose asks for an animation, which only glTF files "
                           "have");
    }
    switch (format) {
    case SR_FORMAT_OBJ:
        return sr__load_obj(path, desc, out, err);
    case SR_FORMAT_PLY:
        return sr__load_ply(path, out, err);
    case SR_FORMAT_STL:
        return sr__load_stl(path, out, err);
    case SR_FORMAT_GLTF:
        /* Assimp misreads some of what the own reader decodes (docs/gltf.md);
         * it stays the reader of builds without jansson. */
        if (sr_io_have_gltf()) {
            return sr__load_gltf_mesh(ctx, path, desc, out, err);
        }
        break;
    case SR_FORMAT_AUTO:
    case SR_FORMAT_ASSIMP:
        break;
    default:
        return sr__io_fail(err, SR_INVALID_ARG, path, 0,
                           "sr_load_desc.format %d is not a known format", (int)format);
    }
    /* Before blaming the format, make sure the file is there and readable,
     * so a typo in the name is reported as such - and a FIFO is refused
     * here, before Assimp could wait on it for a writer. */
    FILE *f;
    unsigned long long size;
    res = sr__open_regular(path, "a model file", &f, &size, err);
    if (res != SR_OK) {
        return res;
    }
    fclose(f);
    return sr__load_assimp(path, out, err);
}

static sr_result load_mesh(sr_context *ctx, const char *path, const sr_load_desc *desc,
                           sr_mesh *out, sr_io_error *err)
{
    if (out) {
        memset(out, 0, sizeof *out);
    }
    if (!path) {
        return sr__io_fail(err, SR_INVALID_ARG, "<null>", 0, "no file name given");
    }
    if (!out) {
        return sr__io_fail(err, SR_INVALID_ARG, path, 0, "no output mesh given");
    }
    sr_result res = check_ctx(ctx, path, out, err);
    if (res != SR_OK) {
        return res;
    }
    sr_mesh m = {0};
    res = load_malloc_mesh(ctx, path, desc, &m, err);
    return hand_out(ctx, path, res, &m, out, err);
}

sr_result sr_load_mesh(sr_context *ctx, const char *path, const sr_load_desc *desc,
                       sr_mesh *out, sr_io_error *err)
{
    sr_io_error saved;
    sr__last_error_save(&saved);
    return sr__last_error_keep(load_mesh(ctx, path, desc, out, err), &saved);
}
