/* test_cli_lights.c - `softrast render --lights`: a glTF file's own lights
 * (KHR_lights_punctual) light it by default, the rig with `default`, both
 * with `both`; a request the model or the shading cannot meet is a
 * warning, an unknown choice a usage error. */
#include "batch_cli.h"
#include "gltf_write.h"

#include "softrast_io.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A quad in z = 0 facing +z with the extension's `lights` (the array's
 * items) placed by `nodes` (the nodes after the quad's node 0, each a
 * root), or no lights (NULL). */
static char *lit_model(const char *lights, const char *nodes, int node_count)
{
    static const gltf_quad q = { -1, -1, 1, 1, 0 };
    char tail[600] = ",\"materials\":[{\"pbrMetallicRoughness\":{\"metallicFactor\":0}}]";
    if (lights) {
        snprintf(tail + strlen(tail), sizeof tail - strlen(tail),
                 ",\"extensionsUsed\":[\"KHR_lights_punctual\"],"
                 "\"extensions\":{\"KHR_lights_punctual\":{\"lights\":[%s]}}",
                 lights);
    }
    char *json = gltf_quads(&q, 1, tail);
    const char *plain = "\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}]";
    char *at = json ? strstr(json, plain) : NULL;
    if (!lights || !at) {
        return json;
    }
    char lit[1200], roots[200] = "0";
    for (int i = 1; i <= node_count; i++) {
        snprintf(roots + strlen(roots), sizeof roots - strlen(roots), ",%d", i);
    }
    snprintf(lit, sizeof lit, "\"nodes\":[{\"mesh\":0},%s],\"scenes\":[{\"nodes\":[%s]}]",
             nodes, roots);
    size_t head = (size_t)(at - json), cap = strlen(json) + strlen(lit) + 1;
    char *out = malloc(cap);
    if (out) {
        snprintf(out, cap, "%.*s%s%s", (int)head, json, lit, at + strlen(plain));
    }
    free(json);
    return out;
}

/* The quad with one light 1 in front of its centre, or none. */
static char *quad_model(const char *light)
{
    return lit_model(light,
                     "{\"translation\":[0,0,1],"
                     "\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}}",
                     1);
}

/* Renders model with the options and reads back the image's centre
 * pixel, which the quad covers.  false after a failed check. */
static bool centre(const char *dir, const char *model, const char *lights, uint8_t rgb[3],
                   run_result *r)
{
    char out[1200];
    snprintf(out, sizeof out, "%s/%s.png", dir, lights ? lights : "auto");
    const char *const args_auto[] = { "render", model, "--size", "48x48", "--environment",
                                      "hemisphere", "-o", out, NULL };
    const char *const args_src[] = { "render", model, "--size", "48x48", "--environment",
                                     "hemisphere", "--lights", lights, "-o", out, NULL };
    if (!run(lights ? args_src : args_auto, r) || r->status != 0) {
        FAILF("render %s: status %d: %s", lights ? lights : "", r->status, r->err);
        return false;
    }
    int w, h;
    uint8_t *px = NULL;
    sr_io_error err;
    if (sr_read_png(out, NULL, &w, &h, &px, &err) != SR_OK) {
        FAILF("%s", err.message);
        return false;
    }
    memcpy(rgb, px + 4 * ((size_t)(h / 2) * (size_t)w + (size_t)(w / 2)), 3);
    free(px);
    return true;
}

SR_TEST(a_gltf_files_own_light_replaces_the_rig_unless_asked)
{
    NEED_CLI();
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson");
    }
    char dir[1024], model[1100];
    fresh_dir("lights", dir, sizeof dir);
    snprintf(model, sizeof model, "%s/red.gltf", dir);
    /* A red point light 1 in front of the quad: 2 candela give the
     * centre an irradiance of 2 lux, far above the rig's. */
    char *json = quad_model("{\"type\":\"point\",\"color\":[1,0,0],\"intensity\":2}");
    REQUIRE(json && write_text(model, json));
    free(json);
    run_result r;
    uint8_t autos[3], file[3], rig[3], both[3];
    REQUIRE(centre(dir, model, NULL, autos, &r));
    CHECK(strstr(r.err, "warning") == NULL);
    REQUIRE(centre(dir, model, "file", file, &r));
    REQUIRE(centre(dir, model, "default", rig, &r));
    REQUIRE(centre(dir, model, "both", both, &r));
    CHECK(memcmp(autos, file, 3) == 0);       /* the file's lights by default */
    CHECK(file[0] > file[1] + 80);            /* red */
    CHECK(rig[0] < rig[1] + 16);              /* the rig's warm white */
    CHECK(both[0] > both[1] + 40);            /* red, and the rig's white on top */
    CHECK(both[1] > file[1]);
}

SR_TEST(lights_the_model_or_the_shading_cannot_give_are_a_warning)
{
    NEED_CLI();
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson");
    }
    char dir[1024], model[1100], out[1200];
    fresh_dir("lights_warn", dir, sizeof dir);
    snprintf(model, sizeof model, "%s/dark.gltf", dir);
    snprintf(out, sizeof out, "%s/out.png", dir);
    char *json = quad_model(NULL);
    REQUIRE(json && write_text(model, json));
    free(json);
    run_result r;
    REQUIRE(run(ARGS("render", model, "--size", "16x16", "--lights", "file", "-o", out), &r));
    CHECK_EQ(r.status, 0);
    CHECK_EQ(count_lines(r.err), 1);
    CHECK_STR_CONTAINS(r.err, "warning: --lights file: ");
    CHECK_STR_CONTAINS(r.err, "dark.gltf has no lights of its own (KHR_lights_punctual)");
    /* classic shading reads glTF with softrast's reader too, Assimp or not */
    REQUIRE(run(ARGS("render", model, "--size", "16x16", "--shading", "phong", "--lights",
                     "both", "-o", out),
                &r));
    CHECK_EQ(r.status, 0);
    CHECK_STR_CONTAINS(r.err, "warning: --lights has no effect with --shading phong");
    REQUIRE(run(ARGS("render", model, "--lights", "sun", "-o", out), &r));
    CHECK_EQ(r.status, 2);
    CHECK_EQ(count_lines(r.err), 1);
    CHECK_STR_CONTAINS(r.err, "--lights");
}

SR_TEST(the_files_strongest_directional_light_casts_the_shadow)
{
    /* A weak light leaning toward +z and a strong one toward -z: listed
     * in either order, the strong one goes first and casts the shadow on
     * the ground, so the two files give the same image; with the first
     * one casting it, the shadow would fall on either side. */
    NEED_CLI();
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson");
    }
    char dir[1024], a[1100], b[1100], pa[1200], pb[1200];
    fresh_dir("lights_shadow", dir, sizeof dir);
    snprintf(a, sizeof a, "%s/weak_first.gltf", dir);
    snprintf(b, sizeof b, "%s/strong_first.gltf", dir);
    snprintf(pa, sizeof pa, "%s/weak_first.png", dir);
    snprintf(pb, sizeof pb, "%s/strong_first.png", dir);
    /* -Z turned to (0, -1, +1) / sqrt 2 (-135 degrees about x) or to
     * (0, -1, -1) / sqrt 2 (-45 degrees). */
    const char *toward_z = "{\"rotation\":[-0.9238795,0,0,0.3826834],"
                           "\"extensions\":{\"KHR_lights_punctual\":{\"light\":%d}}}";
    const char *away_z = "{\"rotation\":[-0.3826834,0,0,0.9238795],"
                         "\"extensions\":{\"KHR_lights_punctual\":{\"light\":%d}}}";
    char nodes_a[600], nodes_b[600], fmt[600];
    snprintf(fmt, sizeof fmt, "%s,%s", toward_z, away_z);
    snprintf(nodes_a, sizeof nodes_a, fmt, 0, 1);
    snprintf(fmt, sizeof fmt, "%s,%s", away_z, toward_z);
    snprintf(nodes_b, sizeof nodes_b, fmt, 0, 1);
    char *ja = lit_model("{\"type\":\"directional\",\"intensity\":0.3},"
                         "{\"type\":\"directional\",\"intensity\":3}",
                         nodes_a, 2);
    char *jb = lit_model("{\"type\":\"directional\",\"intensity\":3},"
                         "{\"type\":\"directional\",\"intensity\":0.3}",
                         nodes_b, 2);
    REQUIRE(ja && jb && write_text(a, ja) && write_text(b, jb));
    free(ja);
    free(jb);
    run_result r;
    REQUIRE(run(ARGS("render", a, "--size", "48x48", "--ground", "--cull", "none", "-o", pa),
                &r));
    CHECK_EQ(r.status, 0);
    REQUIRE(run(ARGS("render", b, "--size", "48x48", "--ground", "--cull", "none", "-o", pb),
                &r));
    CHECK_EQ(r.status, 0);
    CHECK(same_file_bytes(pa, pb));
}
