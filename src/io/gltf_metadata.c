/* gltf_metadata.c - what a glTF file says about itself, for
 * sr_scene.metadata: its asset's version, generator and copyright, and
 * the KHR_xmp_json_ld packet the asset references, kept as the file gives
 * it (compact JSON) with its licence and authorship properties as text.
 * The extension is metadata with no effect on the drawing, so a bad
 * reference is a warning and the model is still read.  Called by gltf.c
 * on the reading thread; internal to src/io. */
#include "io/gltf.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define EXT "KHR_xmp_json_ld"

/* The properties sr_scene_metadata lists, in its order. */
static const char *const shown_properties[] = {
    "dc:title",         "dc:creator",           "dc:contributor",         "dc:publisher",
    "dc:date",          "dc:description",       "dc:source",              "dc:rights",
    "xmpRights:Owner",  "xmpRights:UsageTerms", "xmpRights:WebStatement", "xmpRights:Marked",
    "cc:license",       "cc:attributionName",   "cc:attributionURL",
};
#define SHOWN_COUNT (sizeof shown_properties / sizeof *shown_properties)

static void put_value(FILE *f, const json_t *v);

static void put_json(FILE *f, const json_t *v)
{
    json_dumpf(v, f, JSON_COMPACT | JSON_ENCODE_ANY);
}

/* Member rdf:_i of a language alternative, or NULL. */
static const json_t *alternative(const json_t *v, size_t i)
{
    char key[32];
    snprintf(key, sizeof key, "rdf:_%zu", i);
    return json_object_get(v, key);
}

/* A language alternative (rdf:Alt): rdf:_1, rdf:_2, ... in turn, each
 * {"@language", "@value"}; the language in brackets unless there is one. */
static void put_alternatives(FILE *f, const json_t *v)
{
    size_t n = 0;
    while (alternative(v, n + 1)) {
        n++;
    }
    for (size_t i = 1; i <= n; i++) {
        const json_t *alt = alternative(v, i), *lang = json_object_get(alt, "@language");
        fputs(i > 1 ? ", " : "", f);
        put_value(f, json_object_get(alt, "@value") ? json_object_get(alt, "@value") : alt);
        if (n > 1 && json_is_string(lang)) {
            fprintf(f, " [%s]", json_string_value(lang));
        }
    }
}

/* An XMP value as text (sr_scene_property); a structure the extension
 * gives no simple reading of is its JSON. */
static void put_value(FILE *f, const json_t *v)
{
    const json_t *items = json_object_get(v, "@list");
    items = items ? items : json_object_get(v, "@set");
    const json_t *type = json_object_get(v, "@type");
    if (json_is_string(v)) {
        fputs(json_string_value(v), f);
    } else if (json_is_array(items)) {
        for (size_t i = 0; i < json_array_size(items); i++) {
            fputs(i ? ", " : "", f);
            put_value(f, json_array_get(items, i));
        }
    } else if (json_is_string(type) && strcmp(json_string_value(type), "rdf:Alt") == 0) {
        put_alternatives(f, v);
    } else if (json_is_object(v) && json_object_get(v, "@value")) {
        put_value(f, json_object_get(v, "@value"));
    } else {
        put_json(f, v);
    }
}

/* The text writer fills, a copy the scene owns; NULL when out of memory.
 * (A string of the file holds no NUL byte: jansson refuses \u0000.) */
static const char *scene_text(sr_scene *s, const json_t *v,
                              void (*writer)(FILE *, const json_t *))
{
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    if (!f) {
        return NULL;
    }
    writer(f, v);
    bool ok = !ferror(f);
    ok = fclose(f) == 0 && ok;
    char *copy = ok ? sr__scene_alloc(s, len + 1) : NULL;
    if (copy) {
        memcpy(copy, buf, len);
    }
    free(buf);
    return copy;
}

/* A copy of the string the scene owns, or NULL when out of memory. */
static const char *scene_string(sr_scene *s, const char *v, size_t len)
{
    char *copy = sr__scene_alloc(s, len + 1);
    if (copy) {
        memcpy(copy, v, len);
    }
    return copy;
}

/* asset[key] into *out when it is a string; warned and left out when it
 * is something else. */
static sr_result asset_string(gltf_doc *d, const json_t *asset, const char *key, const char **out)
{
    const json_t *v = json_object_get(asset, key);
    if (v && !json_is_string(v)) {
        sr__gltf_warn(d, "/asset/%s: not a string, left out", key);
        return SR_OK;
    }
    if (v && !(*out = scene_string(d->scene, json_string_value(v), json_string_length(v)))) {
        return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "/asset/%s: out of memory", key);
    }
    return SR_OK;
}

/* The packet the asset references, or NULL after a warning naming what
 * is wrong (a reference to no packet, or a packet that is not an object);
 * *index its index. */
static const json_t *asset_packet(gltf_doc *d, const json_t *ref, long *index)
{
    const char *ptr = "/asset/extensions/" EXT;
    const json_t *packet = json_object_get(ref, "packet");
    const json_t *packets = json_object_get(sr__gltf_extension(d->root, EXT), "packets");
    size_t n = json_array_size(packets);
    double v = json_number_value(packet);
    if (!json_is_object(ref)) {
        sr__gltf_warn(d, "%s: not an object, the asset's metadata is left out", ptr);
    } else if (!json_is_number(packet) || v != floor(v)) {
        sr__gltf_warn(d, "%s/packet: %s, the asset's metadata is left out", ptr,
                      packet ? "not an integer" : "missing");
    } else if (v < 0 || v >= (double)n) {
        sr__gltf_warn(d, "%s/packet: %.0f is not an index below %zu (/extensions/" EXT
                      "/packets), the asset's metadata is left out", ptr, v, n);
    } else if (!json_is_object(json_array_get(packets, (size_t)v))) {
        sr__gltf_warn(d, "/extensions/" EXT "/packets/%.0f: not an object, the asset's metadata "
                      "is left out", v);
    } else {
        *index = (long)v;
        return json_array_get(packets, (size_t)v);
    }
    return NULL;
}

/* The packet as text and its shown properties, into the scene. */
static sr_result keep_packet(gltf_doc *d, const json_t *packet, long index)
{
    sr_scene_metadata *m = &d->scene->metadata;
    sr_scene_property *props = sr__scene_alloc(d->scene, SHOWN_COUNT * sizeof *props);
    bool ok = props && (m->xmp_packet = scene_text(d->scene, packet, put_json));
    size_t n = 0;
    for (size_t i = 0; ok && i < SHOWN_COUNT; i++) {
        const json_t *v = json_object_get(packet, shown_properties[i]);
        if (v) {
            props[n].name = shown_properties[i];
            ok = (props[n++].value = scene_text(d->scene, v, put_value)) != NULL;
        }
    }
    if (!ok) {
        return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "/extensions/" EXT "/packets/%ld: out of memory",
                             index);
    }
    m->xmp_packet_index = (int)index;
    m->properties = props;
    m->property_count = n;
    return SR_OK;
}

sr_result sr__gltf_read_metadata(gltf_doc *d)
{
    const json_t *asset = json_object_get(d->root, "asset");
    sr_scene_metadata *m = &d->scene->metadata;
    sr_result r;
    if ((r = asset_string(d, asset, "version", &m->version)) != SR_OK ||
        (r = asset_string(d, asset, "minVersion", &m->min_version)) != SR_OK ||
        (r = asset_string(d, asset, "generator", &m->generator)) != SR_OK ||
        (r = asset_string(d, asset, "copyright", &m->copyright)) != SR_OK) {
        return r;
    }
    const json_t *ext = json_object_get(d->root, "extensions");
    const json_t *root_ext = json_object_get(ext, EXT);
    if (root_ext && !json_is_array(json_object_get(root_ext, "packets"))) {
        sr__gltf_warn(d, "/extensions/" EXT "/packets: %s, no metadata is read",
                      json_object_get(root_ext, "packets") ? "not an array" : "missing");
    }
    const json_t *ref = json_object_get(json_object_get(asset, "extensions"), EXT);
    long index = -1;
    const json_t *packet = ref ? asset_packet(d, ref, &index) : NULL;
    return packet ? keep_packet(d, packet, index) : SR_OK;
}
