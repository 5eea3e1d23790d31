/* gltf_variants.c - KHR_materials_variants for the glTF reader: the
 * document's variant names read once into sr_scene.variants
 * (sr__gltf_read_variants), then each primitive's mappings checked into
 * its variant_materials, and sr_load_desc.variant's material chosen, as
 * gltf.c reads the primitive (sr__gltf_primitive_variants).  Called by
 * gltf.c on the reading thread; internal to src/io. */
#include "io/gltf.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define EXT "KHR_materials_variants"

sr_result sr__gltf_read_variants(gltf_doc *d)
{
    json_t *ext = sr__gltf_extension(d->root, EXT), *list;
    size_t n = 0;
    sr_result r;
    const char *ptr = "/extensions/" EXT;
    if (ext && (r = sr__gltf_array(d, ext, ptr, "variants", &list, &n)) != SR_OK) {
        return r;
    }
    const char **names = n ? sr__scene_alloc(d->scene, n * sizeof *names) : NULL;
    if (n && !names) {
        return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory", ptr);
    }
    for (size_t i = 0; i < n; i++) {
        json_t *v = json_array_get(list, i), *name = json_object_get(v, "name");
        if (!json_is_object(v)) {
            return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/variants/%zu: not an object", ptr, i);
        }
        if (!json_is_string(name)) {
            return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/variants/%zu/name: missing or not a string",
                                 ptr, i);
        }
        size_t len = json_string_length(name);
        char *copy = sr__scene_alloc(d->scene, len + 1);
        if (!copy) {
            return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory", ptr);
        }
        memcpy(copy, json_string_value(name), len);
        names[i] = copy;
    }
    d->scene->variants = names;
    d->scene->variant_count = n;
    int want = d->desc ? d->desc->variant : 0;
    if (want < 0 || (size_t)want > n) {
        return sr__gltf_fail(d, SR_INVALID_ARG,
                             "sr_load_desc.variant: %d, but the file has %zu variant%s (1..%zu, "
                             "or 0 for none)",
                             want, n, n == 1 ? "" : "s", n);
    }
    return SR_OK;
}

/* Mapping i of a primitive's extension (JSON eptr): its material set as
 * mat[v + 1] for each variant v it lists, taken[v + 1] the mapping that
 * did (from 1), n the document's variants. */
static sr_result read_mapping(gltf_doc *d, const json_t *m, const char *eptr, size_t i, size_t n,
                              size_t *taken, int *mat)
{
    sr_result r;
    char mptr[GLTF_PTR], vptr[GLTF_PTR];
    json_t *vars;
    size_t k;
    long material = -1;
    sr__json_pointer(mptr, sizeof mptr, "%s/mappings/%zu", eptr, i);
    if (!json_is_object(m)) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: not an object", mptr);
    }
    /* The last material is the reader's default one, not the file's. */
    if ((r = sr__gltf_index(d, m, mptr, "material", d->scene->material_count - 1, true,
                            &material)) != SR_OK ||
        (r = sr__gltf_array(d, m, mptr, "variants", &vars, &k)) != SR_OK) {
        return r;
    }
    json_t *name = json_object_get(m, "name");
    if (name && !json_is_string(name)) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/name: not a string", mptr);
    }
    if (!vars || k == 0) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/variants: missing or empty", mptr);
    }
    sr__json_pointer(vptr, sizeof vptr, "%s/variants", mptr);
    for (size_t j = 0; j < k; j++) {
        json_t *e = json_array_get(vars, j);
        json_int_t v = json_is_integer(e) ? json_integer_value(e) : -1;
        if (v < 0 || (size_t)v >= n) {
            return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/%zu: not a variant index below %zu",
                                 vptr, j, n);
        }
        /* "Across the entire mappings array, each variant index must be
         * used no more than one time." */
        if (taken[v + 1]) {
            return sr__gltf_fail(d, SR_BAD_FORMAT,
                                 "%s/%zu: variant %lld is already mapped by mappings/%zu "
                                 "(each variant at most once per primitive)",
                                 vptr, j, (long long)v, taken[v + 1] - 1);
        }
        taken[v + 1] = i + 1;
        mat[v + 1] = (int)material;
    }
    return SR_OK;
}

sr_result sr__gltf_primitive_variants(gltf_doc *d, const json_t *prim, const char *ptr,
                                      sr_scene_primitive *p)
{
    json_t *ext = json_object_get(json_object_get(prim, "extensions"), EXT), *maps;
    size_t count, n = d->scene->variant_count;
    sr_result r;
    char eptr[GLTF_PTR];
    sr__json_pointer(eptr, sizeof eptr, "%s/extensions/" EXT, ptr);
    if (!ext) {
        return SR_OK;
    }
    if (!json_is_object(ext)) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: not an object", eptr);
    }
    if ((r = sr__gltf_array(d, ext, eptr, "mappings", &maps, &count)) != SR_OK) {
        return r;
    }
    if (!maps) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/mappings: missing", eptr);
    }
    if (count > 0 && n == 0) {
        return sr__gltf_fail(d, SR_BAD_FORMAT,
                             "%s/mappings: the document defines no variants (/extensions/" EXT
                             "/variants)",
                             eptr);
    }
    int *mat = sr__scene_alloc(d->scene, (n + 1) * sizeof *mat);
    /* Which mapping took each variant (0: none yet), for the message. */
    size_t *taken = calloc(n + 1, sizeof *taken);
    if (!mat || !taken) {
        free(taken);
        return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory", eptr);
    }
    for (size_t v = 0; v <= n; v++) {
        mat[v] = p->material;
    }
    r = SR_OK;
    for (size_t i = 0; i < count && r == SR_OK; i++) {
        r = read_mapping(d, json_array_get(maps, i), eptr, i, n, taken, mat);
    }
    free(taken);
    if (r != SR_OK) {
        return r;
    }
    p->variant_materials = mat;
    p->material = mat[d->desc ? d->desc->variant : 0];
    return SR_OK;
}
