/* info_metadata.c - the part of `softrast info` that says what a glTF
 * file says about itself (sr_scene.metadata): its asset's version,
 * generator and copyright and the KHR_xmp_json_ld packet the asset
 * references, its licence and authorship properties in text, the packet
 * as the file gives it in JSON, for datasets that must keep the terms of
 * the models they use. */
#include "cli.h"
#include "info.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* "    label  text", the file's text made one line (no control byte
 * reaches the terminal). */
static void text_line(const char *label, int width, const char *value)
{
    char *copy = malloc(strlen(value) + 1);
    if (!copy) {
        printf("    %-*s  (out of memory)\n", width, label);
        return;
    }
    memcpy(copy, value, strlen(value) + 1);
    cli_one_line(copy);
    printf("    %-*s  %s\n", width, label, copy);
    free(copy);
}

void info_print_metadata_text(const sr_scene *sc)
{
    const sr_scene_metadata *m = &sc->metadata;
    if (!m->version) {
        return; /* not glTF */
    }
    char version[64];
    snprintf(version, sizeof version, "%s", m->version);
    cli_one_line(version);
    printf("  asset       glTF %s", version);
    if (m->min_version) {
        snprintf(version, sizeof version, "%s", m->min_version);
        cli_one_line(version);
        printf(" (minVersion %s)", version);
    }
    printf("\n");
    if (m->generator) {
        text_line("generator", 9, m->generator);
    }
    if (m->copyright) {
        text_line("copyright", 9, m->copyright);
    }
    if (m->xmp_packet_index < 0) {
        return;
    }
    printf("  metadata    KHR_xmp_json_ld packet %d, %zu propert%s shown (--json: all)\n",
           m->xmp_packet_index, m->property_count, m->property_count == 1 ? "y" : "ies");
    int width = 0;
    for (size_t i = 0; i < m->property_count; i++) {
        int len = (int)strlen(m->properties[i].name);
        width = len > width ? len : width;
    }
    for (size_t i = 0; i < m->property_count; i++) {
        text_line(m->properties[i].name, width, m->properties[i].value);
    }
}

static void json_member(const char *name, const char *value, bool last)
{
    printf("\"%s\": ", name);
    if (value) {
        info_json_string(value);
    } else {
        printf("null");
    }
    printf(last ? "" : ", ");
}

void info_print_metadata_json(const sr_scene *sc)
{
    const sr_scene_metadata *m = &sc->metadata;
    printf(" \"metadata\": {");
    json_member("version", m->version, false);
    json_member("min_version", m->min_version, false);
    json_member("generator", m->generator, false);
    json_member("copyright", m->copyright, false);
    if (m->xmp_packet) {
        /* the file's JSON, as jansson wrote it back: valid as it stands */
        printf("\"xmp_packet\": %d,\n  \"xmp\": %s},\n", m->xmp_packet_index, m->xmp_packet);
    } else {
        printf("\"xmp_packet\": null, \"xmp\": null},\n");
    }
}
