/* render_bump.c - the bump maps of an OBJ's materials (map_Bump, bump,
 * norm) as the physically based look's normal maps (docs/pbr.md): read,
 * turned from heights into normals where they are height maps, uploaded
 * to the job's context once per file.  Runs on the thread that loads the
 * model, before drawing. */
#include "render_bump.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static float texel_height(const uint8_t *px, int w, int h, int x, int y)
{
    x = (x % w + w) % w;
    y = (y % h + h) % h;
    const uint8_t *p = px + 4 * ((size_t)y * w + x);
    return (float)(p[0] + p[1] + p[2]) / (3.0f * 255.0f);
}

void render_bump_to_normals(uint8_t *height, int w, int h, float scale)
{
    float *hf = malloc((size_t)w * h * sizeof *hf);
    if (!hf) {
        return;
    }
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            hf[(size_t)y * w + x] = texel_height(height, w, h, x, y);
        }
    }
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            const float *row = hf + (size_t)y * w;
            float dx = (row[(x + 1) % w] - row[(x + w - 1) % w]) * 0.5f;
            /* Up the image is toward row 0. */
            float dy = (hf[(size_t)((y + h - 1) % h) * w + x] -
                        hf[(size_t)((y + 1) % h) * w + x]) * 0.5f;
            float n[3] = { -dx * scale, -dy * scale, 1.0f };
            float len = sqrtf(n[0] * n[0] + n[1] * n[1] + 1.0f);
            uint8_t *o = height + 4 * ((size_t)y * w + x);
            for (int k = 0; k < 3; k++) {
                o[k] = (uint8_t)lroundf((0.5f + 0.5f * n[k] / len) * 255.0f);
            }
            o[3] = 255;
        }
    }
    free(hf);
}

bool render_bump_is_normal_map(const uint8_t *rgba, int w, int h)
{
    size_t n = (size_t)w * h, unit = 0, gray = 0;
    for (size_t i = 0; i < n; i++) {
        const uint8_t *p = rgba + 4 * i;
        float v[3];
        for (int k = 0; k < 3; k++) {
            v[k] = p[k] / 127.5f - 1.0f;
        }
        float len = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        unit += fabsf(len - 1.0f) < 0.1f && v[2] > 0.3f;
        gray += p[0] == p[1] && p[1] == p[2];
    }
    /* Nearly every texel a unit vector out of the surface, and a height
     * map's gray levels for fewer than half of them. */
    return unit >= n - n / 20 && gray < n / 2;
}

/* Part p's bump map as a normal map into *out; NULL and a warning when
 * the file cannot be read.  Returns an exit status, or -1. */
static int read_bump(sr_context *ctx, const sr_mesh_material *m, sr_texture **out)
{
    int w, h;
    uint8_t *px = NULL;
    sr_io_error err;
    sr_result r = sr_read_image(m->bump_path, &w, &h, &px, &err);
    if (r != SR_OK) {
        if (r == SR_OUT_OF_MEMORY) {
            cli_message("%s", err.message);
            return EXIT_FAILURE_RUN;
        }
        cli_error("warning: %s (drawing its part without the bump map)", err.message);
        return -1;
    }
    if (!m->bump_is_normal && !render_bump_is_normal_map(px, w, h)) {
        render_bump_to_normals(px, w, h, m->bump_scale != 0.0f ? m->bump_scale : 1.0f);
    }
    r = sr_make_texture(ctx, &(sr_texture_desc){ .width = w, .height = h, .pixels = px }, out);
    free(px);
    if (r != SR_OK) {
        cli_error("%s: %s", m->bump_path, sr_context_error(ctx));
        return r == SR_OUT_OF_MEMORY ? EXIT_FAILURE_RUN : EXIT_USAGE;
    }
    return -1;
}

int render_bump_load(const render_opts *o, sr_context *ctx, cli_inputs *inputs, scene *s)
{
    scene_object *ob = &s->objects[0];
    size_t n = ob->mesh.part_count;
    if (!o->pbr || !o->model || s->count == 0 || n == 0 || !ob->mesh.texcoords) {
        return -1;
    }
    bool any = false;
    for (size_t p = 0; p < n; p++) {
        any |= ob->mesh.parts[p].material.bump_path != NULL;
    }
    if (!any) {
        return -1;
    }
    ob->part_normal_maps = calloc(n, sizeof *ob->part_normal_maps);
    ob->owned_normal_maps = calloc(n, sizeof *ob->owned_normal_maps);
    const sr_mesh_material **seen = calloc(n, sizeof *seen);
    if (!ob->part_normal_maps || !ob->owned_normal_maps || !seen) {
        free(seen);
        cli_error("render: out of memory");
        return EXIT_FAILURE_RUN;
    }
    int status = -1;
    for (size_t p = 0; p < n && status < 0; p++) {
        const sr_mesh_material *m = &ob->mesh.parts[p].material;
        if (!m->bump_path) {
            continue;
        }
        /* A file met before (with the same scale and kind) is read once. */
        size_t k = 0;
        while (k < ob->owned_normal_map_count &&
               !(strcmp(seen[k]->bump_path, m->bump_path) == 0 &&
                 seen[k]->bump_scale == m->bump_scale &&
                 seen[k]->bump_is_normal == m->bump_is_normal)) {
            k++;
        }
        if (k == ob->owned_normal_map_count) {
            seen[k] = m;
            ob->owned_normal_map_count++;
            cli_inputs_add(inputs, m->bump_path, "bump map");
            status = read_bump(ctx, m, &ob->owned_normal_maps[k]);
        }
        ob->part_normal_maps[p] = ob->owned_normal_maps[k];
    }
    free(seen);
    return status;
}

void render_bump_free(sr_context *ctx, scene *s)
{
    for (int i = 0; i < s->count; i++) {
        scene_object *ob = &s->objects[i];
        for (size_t k = 0; k < ob->owned_normal_map_count; k++) {
            sr_destroy_texture(ctx, ob->owned_normal_maps[k]);
        }
        free(ob->owned_normal_maps);
        free(ob->part_normal_maps);
        ob->owned_normal_maps = NULL;
        ob->part_normal_maps = NULL;
        ob->owned_normal_map_count = 0;
    }
}
