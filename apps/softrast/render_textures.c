/* render_textures.c - the textures of a render job: found (--texture, the
 * model's own, or MODEL_texture.png beside it), read or decoded, and
 * uploaded to the job's context; each file read is listed among the
 * inputs no output may replace. */
#include "cli.h"
#include "render_textures.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static bool is_file(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

/* Decoded pixels px (freed here) into *out on ctx, for both texture
 * loaders; a failure names `name`.  Returns an exit status, or -1. */
static int upload_texture(const render_opts *o, sr_context *ctx, const char *name, int w, int h,
                          uint8_t *px, sr_texture **out)
{
    sr_result r = sr_make_texture(ctx, &(sr_texture_desc){ .width = w, .height = h, .pixels = px,
                                                            .srgb = o->texture_srgb || o->pbr },
                                  out);
    free(px);
    if (r != SR_OK) {
        cli_error("%s: %s", name, sr_context_error(ctx));
        return r == SR_OUT_OF_MEMORY ? EXIT_FAILURE_RUN : EXIT_USAGE;
    }
    return -1;
}

/* A texture into *out, for both texture loaders: the image file `path`,
 * or else the encoded bytes data[0 .. size) a model embeds, `name` in
 * messages.  One that cannot be read is a warning when `optional` (the
 * model brought it: "drawing `what`" says what goes on without it, *out
 * stays NULL), else an error.  Returns an exit status, or -1. */
static int read_texture(const render_opts *o, sr_context *ctx, const char *path,
                        const uint8_t *data, size_t size, const char *name, bool optional,
                        const char *what, sr_texture **out)
{
    int w, h;
    uint8_t *px = NULL;
    sr_io_error err;
    sr_result rr = path ? sr_read_image(path, &w, &h, &px, &err)
                        : sr_decode_image(name, data, size, &w, &h, &px, &err);
    if (rr != SR_OK) {
        if (optional && rr != SR_OUT_OF_MEMORY) {
            cli_error("warning: %s (drawing %s)", err.message, what);
            return -1;
        }
        cli_message("%s", err.message);
        return rr == SR_OUT_OF_MEMORY ? EXIT_FAILURE_RUN : EXIT_USAGE;
    }
    return upload_texture(o, ctx, path ? path : name, w, h, px, out);
}

/* Whether parts a and b take one image: the same file, or the same
 * embedded bytes (each part holds its own copy). */
static bool same_part_texture(const sr_mesh_part *a, const sr_mesh_part *b)
{
    if (a->texture_path || b->texture_path) {
        return a->texture_path && b->texture_path && strcmp(a->texture_path, b->texture_path) == 0;
    }
    return a->texture_size == b->texture_size &&
           memcmp(a->texture_data, b->texture_data, a->texture_size) == 0;
}

/* The textures of a model whose parts take different ones (sr_mesh.parts):
 * each image read or decoded once; one that is missing or unreadable is a
 * warning, and its parts are drawn without it.  Returns an exit status, or
 * -1. */
static int load_part_textures(const render_opts *o, sr_context *ctx, cli_inputs *inputs,
                              scene_object *ob)
{
    size_t n = ob->mesh.part_count;
    ob->part_textures = calloc(n, sizeof *ob->part_textures);
    ob->owned = calloc(n, sizeof *ob->owned);
    /* The images met so far, by the first part that takes each, with its
     * texture (NULL when unreadable): parts far outnumber images in a
     * model that switches back and forth. */
    const sr_mesh_part **seen = calloc(n, sizeof *seen);
    if (!ob->part_textures || !ob->owned || !seen) {
        free(seen);
        cli_error("render: out of memory");
        return EXIT_FAILURE_RUN;
    }
    int status = -1;
    for (size_t p = 0; p < n && status < 0; p++) {
        const sr_mesh_part *part = &ob->mesh.parts[p];
        const char *path = part->texture_path;
        bool textured = path || part->texture_data;
        size_t k = 0;
        while (textured && k < ob->owned_count && !same_part_texture(seen[k], part)) {
            k++;
        }
        if (!textured || k < ob->owned_count) {
            ob->part_textures[p] = textured ? ob->owned[k] : NULL;
            continue;
        }
        seen[k] = part;
        ob->owned_count++;
        cli_inputs_add(inputs, path, "texture");
        char name[4200];
        snprintf(name, sizeof name, "%s (its embedded texture of part %zu)", o->model, p + 1);
        status = read_texture(o, ctx, path, part->texture_data, part->texture_size, name, true,
                              "its part of the model without it", &ob->owned[k]);
        ob->part_textures[p] = ob->owned[k];
    }
    free(seen);
    return status;
}

/* The model's texture: --texture, else the file's own (OBJ map_Kd, or an
 * image a glTF or GLB file embeds), else MODEL_texture.png or .jpg beside
 * MODEL.ext.  One the user named must be read; one the model brings that
 * is missing or unreadable is reported in a warning and the model drawn
 * without it - a preview of the geometry beats no preview.  Returns an
 * exit status, or -1. */
int render_textures_load(const render_opts *o, sr_context *ctx, cli_inputs *inputs, scene *s)
{
    if (!o->model || s->count == 0) {
        if (o->texture) {
            cli_error("--texture: the built-in scene has no texture coordinates");
            return EXIT_USAGE;
        }
        return -1;
    }
    scene_object *ob = &s->objects[0];
    if (!o->texture && ob->mesh.part_count > 0 && ob->mesh.texcoords) {
        return load_part_textures(o, ctx, inputs, ob);
    }
    char guess[4096];
    const char *path = o->texture;
    const char *named = ob->mesh.texture_path;
    bool embedded = !path && ob->mesh.texture_data;
    if (!path && !embedded && named && is_file(named)) {
        path = named;
    }
    if (!path && !embedded) {
        const char *dot = strrchr(o->model, '.'), *slash = strrchr(o->model, '/');
        size_t stem = dot && (!slash || dot > slash) ? (size_t)(dot - o->model) : strlen(o->model);
        static const char *const suffixes[] = { "_texture.png", "_texture.jpg" };
        for (size_t i = 0; i < 2 && !path; i++) {
            if (stem + strlen(suffixes[i]) < sizeof guess) {
                memcpy(guess, o->model, stem);
                strcpy(guess + stem, suffixes[i]);
                path = is_file(guess) ? guess : NULL;
            }
        }
    }
    if (!path && !embedded) {
        if (named && ob->mesh.texcoords) {
            struct stat st;
            cli_error("warning: %s: %s, named by the model's material (drawing the model "
                      "without its texture)", named,
                      stat(named, &st) != 0 ? strerror(errno) : "not a regular file");
        }
        return -1;
    }
    cli_inputs_add(inputs, path, "texture");
    if (!ob->mesh.texcoords) {
        if (o->texture) {
            cli_error("--texture: %s has no texture coordinates", o->model);
            return EXIT_USAGE;
        }
        return -1; /* a texture found by name but nothing to map it with */
    }
    char name[4200];
    snprintf(name, sizeof name, "%s (its embedded texture)", o->model);
    return read_texture(o, ctx, embedded ? NULL : path, ob->mesh.texture_data,
                        ob->mesh.texture_size, name, !o->texture, "the model without its texture",
                        &ob->texture);
}

void render_textures_free(sr_context *ctx, scene *s)
{
    for (int i = 0; i < s->count; i++) {
        scene_object *ob = &s->objects[i];
        sr_destroy_texture(ctx, ob->texture);
        ob->texture = NULL;
        for (size_t k = 0; k < ob->owned_count; k++) {
            sr_destroy_texture(ctx, ob->owned[k]);
        }
        free(ob->owned);
        free(ob->part_textures);
        ob->owned = NULL;
        ob->part_textures = NULL;
        ob->owned_count = 0;
    }
}
