/* test_cli_gltf_programs.c - `softrast render` of a glTF object whose
 * parts take turns among materials: a material's program is made for its
 * first part and kept for the next ones (apps/softrast/render_programs.c),
 * at most 32 at once, so some are replaced and made again.  The image must
 * be byte for byte that of the same object whose every part names a
 * material of its own (the same values), each drawn with a program made
 * for it alone. */
#include "batch_cli.h"
#include "gltf_write.h"

#include "softrast_io.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

SR_TEST_NEEDS(sr_io_have_gltf, "this build reads no glTF (jansson was not found)")

enum { COLUMNS = 10, ROWS = 7, PARTS = COLUMNS * ROWS, KINDS = 35 };

/* Material kind k: its own color, metalness and roughness. */
static int put_material(char *at, size_t cap, int k)
{
    return snprintf(at, cap,
                    "%s{\"pbrMetallicRoughness\":{\"baseColorFactor\":[%.3f,%.3f,%.3f,1],"
                    "\"metallicFactor\":%.2f,\"roughnessFactor\":%.3f}}",
                    at[-1] == '[' ? "" : ",", 0.1 + 0.8 * (k % 5) / 4.0,
                    0.1 + 0.8 * (k % 7) / 6.0, 0.9 - 0.8 * k / (KINDS - 1.0), k % 2 ? 0.8 : 0.1,
                    0.3 + 0.6 * k / (KINDS - 1.0));
}

/* The grid of parts, part q of material kind q % KINDS: named as such
 * (`own` false: KINDS materials, each for two parts), or each part its own
 * copy of it (PARTS materials). */
static char *parts_model(bool own)
{
    gltf_quad quads[PARTS];
    for (int q = 0; q < PARTS; q++) {
        float x = -1.0f + 2.0f * (float)(q % COLUMNS) / COLUMNS;
        float y = -0.7f + 1.4f * (float)(q / COLUMNS) / ROWS;
        quads[q] = (gltf_quad){ x + 0.02f, y + 0.02f, x + 0.18f, y + 0.18f,
                                own ? q : q % KINDS };
    }
    static char tail[PARTS * 160 + 32];
    size_t at = (size_t)snprintf(tail, sizeof tail, ",\"materials\":[");
    for (int m = 0; m < (own ? PARTS : KINDS); m++) {
        at += (size_t)put_material(tail + at, sizeof tail - at, m % KINDS);
    }
    snprintf(tail + at, sizeof tail - at, "]");
    return gltf_quads(quads, PARTS, tail);
}

SR_TEST(parts_sharing_programs_draw_as_parts_with_their_own)
{
    NEED_CLI();
    char dir[1024], model[2][1100], png[2][1100];
    fresh_dir("gltf_programs", dir, sizeof dir);
    uint8_t *px[2] = { NULL, NULL };
    int w[2] = { 0, 0 }, h[2] = { 0, 0 };
    for (int i = 0; i < 2; i++) {
        snprintf(model[i], sizeof model[i], "%s/%s.gltf", dir, i ? "shared" : "own");
        snprintf(png[i], sizeof png[i], "%s/%s.png", dir, i ? "shared" : "own");
        char *text = parts_model(i == 0);
        REQUIRE(text && write_text(model[i], text));
        free(text);
        run_result r;
        px[i] = render_read(ARGS("render", model[i], "--size", "200x140", "--camera",
                                 "eye=0,0,3,target=0,0,0", "-o", png[i]),
                            png[i], &w[i], &h[i], &r);
    }
    REQUIRE(px[0] && px[1]);
    CHECK_EQ(w[0], w[1]);
    CHECK_EQ(h[0], h[1]);
    if (w[0] == w[1] && h[0] == h[1] &&
        memcmp(px[0], px[1], (size_t)w[0] * (size_t)h[0] * 4) != 0) {
        FAILF("%s differs from %s", png[1], png[0]);
    }
    /* Not a blank image: the parts are there, in more than one color. */
    int colors = 0;
    for (size_t p = 1; p < (size_t)w[0] * (size_t)h[0]; p++) {
        colors += memcmp(px[1] + 4 * p, px[1] + 4 * (p - 1), 3) != 0;
    }
    CHECK(colors > 2 * PARTS);
    free(px[0]);
    free(px[1]);
}
