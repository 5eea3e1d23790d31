/* test_images.c - the main job end to end: `softrast render` of the
 * built-in scene (every shading mode) and of each shared model, compared
 * with committed reference PNGs in tests/ref/.
 *
 * Tolerance: a pixel differs when a channel is off by more than 3, and at
 * most 0.5% of the pixels may differ.  On one machine the output is
 * bit-exact; the slack absorbs libm differences (powf, sqrtf in lighting)
 * between C libraries and compilers.  A failure writes the actual image and
 * a diff image into the build's tests/out/. */
#include "image_compare.h"
#include "softrast_io.h"
#include "sr_test.h"

#include <stdlib.h>
#include <string.h>

#define CHANNEL_TOL 3


static void check_render(const char *name, const char *const *extra)
{
    char out[1024];
    snprintf(out, sizeof out, "%s/%s.png", sr_test_out_dir(), name);
    const char *args[24] = { "render" };
    int n = 1;
    for (int i = 0; extra[i]; i++) {
        args[n++] = extra[i];
    }
    args[n++] = "-o";
    args[n++] = out;
    args[n] = NULL;
    int status = sr_test_run_cli(args);
    CHECK_EQ(status, 0);
    if (status != 0) {
        return;
    }
    int w, h;
    uint8_t *px = NULL;
    sr_io_error err;
    if (sr_read_png(out, NULL, &w, &h, &px, &err) != SR_OK) {
        sr_test_fail(__FILE__, __LINE__, "reading %s: %s", out, err.message);
        return;
    }
    long allowed = (long)w * h / 200;
    sr_test_check_image(name, px, w, h, CHANNEL_TOL, allowed);
    free(px);
}

/* The default output (the physically based look), antialiased, and the
 * classic Blinn-Phong look.  The other checks turn antialiasing off
 * unless it is what they check, and ask for Phong where the pipeline
 * feature, not the look, is what they hold to a reference. */
SR_TEST(builtin_scene_matches_reference)
{
    check_render("builtin_pbr", (const char *[]){ "--size", "240x160", NULL });
    check_render("builtin_phong", (const char *[]){ "--size", "240x160", "--shading", "phong", NULL });
}

/* The physically based look's options: ACES and a stop brighter; the
 * sky-and-ground hemisphere instead of the built-in studio environment. */
SR_TEST(builtin_scene_tone_mapped_matches_reference)
{
    check_render("builtin_pbr_hemisphere", (const char *[]){ "--size", "160x120", "--environment",
                                                             "hemisphere", "--aa", "none", NULL });
    check_render("builtin_pbr_aces_ev1", (const char *[]){ "--size", "160x120", "--tonemap", "aces",
                                                           "--exposure", "1", "--aa", "none", NULL });
}

/* The thumbnail look: the teapot over a --ground shadow catcher (its
 * soft shadow, down and right, away from the key light at the upper
 * left), the studio environment behind it, sharp and blurred. */
SR_TEST(builtin_scene_over_a_shadow_catcher_matches_reference)
{
    check_render("builtin_ground_studio", (const char *[]){ "--size", "160x120", "--ground",
                                                            "--environment", "studio",
                                                            "--background", "environment",
                                                            NULL });
    check_render("builtin_ground_blur", (const char *[]){ "--size", "160x120", "--ground",
                                                          "--environment", "studio",
                                                          "--background", "blur", NULL });
}

SR_TEST(builtin_scene_in_every_shading_mode_matches_reference)
{
    const char *modes[] = { "flat", "gouraud", "normals", "depth", "unlit" };
    for (int i = 0; i < 5; i++) {
        char name[64];
        snprintf(name, sizeof name, "builtin_%s", modes[i]);
        check_render(name, (const char *[]){ "--size", "160x120", "--shading", modes[i], "--aa",
                                             "none", NULL });
    }
}

SR_TEST(builtin_scene_supersampled_matches_reference)
{
    check_render("builtin_ssaa3_gaussian", (const char *[]){ "--size", "160x120", "--aa", "ssaa3",
                                                             "--filter", "gaussian", "--shading",
                                                             "phong", NULL });
}

/* 4x and 16x multisampling, and the hidden-line outlines multisampled
 * (lines as rectangles covered per sample). */
SR_TEST(builtin_scene_multisampled_matches_reference)
{
    check_render("builtin_msaa4", (const char *[]){ "--size", "160x120", "--aa", "msaa4",
                                                    "--shading", "phong", NULL });
    check_render("builtin_msaa16_hidden_line",
                 (const char *[]){ "--size", "160x120", "--aa", "msaa16", "--hidden-line", NULL });
}

/* A translucent teapot drawn after the ground, back to front: Phong, and
 * the physically based look's BLEND. */
SR_TEST(builtin_scene_translucent_matches_reference)
{
    check_render("builtin_opacity", (const char *[]){ "--size", "160x120", "--opacity", "0.5",
                                                      "--aa", "none", "--shading", "phong", NULL });
    check_render("builtin_opacity_pbr", (const char *[]){ "--size", "160x120", "--opacity", "0.5",
                                                          "--aa", "none", NULL });
}

SR_TEST(builtin_scene_orthographic_and_affine_match_reference)
{
    check_render("builtin_ortho",
                 (const char *[]){ "--size", "160x120", "--ortho", "--aa", "none", "--shading",
                                   "phong", NULL });
    check_render("builtin_affine", (const char *[]){ "--size", "160x120", "--projection-interp",
                                                     "affine", "--shading", "unlit", "--aa",
                                                     "none", NULL });
}

SR_TEST(shared_models_match_reference)
{
    const char *dir = sr_test_models_dir();
    if (!dir) {
        SKIP("../shared/models not found (set SR_MODELS_DIR)");
    }
    const char *models[] = { "stanford-bunny", "spot", "teapot", "suzanne", "cow", "fandisk" };
    for (int i = 0; i < 6; i++) {
        char path[1024], name[64];
        snprintf(path, sizeof path, "%s/%s.obj", dir, models[i]);
        snprintf(name, sizeof name, "model_%s", models[i]);
        check_render(name, (const char *[]){ path, "--size", "160x120", "--aa", "none",
                                             "--shading", "phong", NULL });
        snprintf(name, sizeof name, "model_pbr_%s", models[i]);
        check_render(name, (const char *[]){ path, "--size", "160x120", "--aa", "none", NULL });
    }
}

/* Spot with its texture, found beside the model as spot_texture.png. */
SR_TEST(textured_model_matches_reference)
{
    const char *dir = sr_test_models_dir();
    if (!dir) {
        SKIP("../shared/models not found (set SR_MODELS_DIR)");
    }
    char path[1024];
    snprintf(path, sizeof path, "%s/spot.obj", dir);
    check_render("model_spot_textured", (const char *[]){ path, "--size", "160x120", "--turn",
                                                          "200", "--aa", "none", "--shading",
                                                          "phong", NULL });
    check_render("model_spot_textured_pbr", (const char *[]){ path, "--size", "160x120", "--turn",
                                                              "200", "--aa", "none", NULL });
    check_render("model_spot_textured_nearest",
                 (const char *[]){ path, "--size", "160x120", "--turn", "200", "--texture-filter",
                                   "nearest", "--shading", "flat", "--aa", "none", NULL });
}

SR_TEST(wireframe_and_hidden_line_renders_match_reference)
{
    check_render("builtin_edges",
                 (const char *[]){ "--size", "160x120", "--edges", "--aa", "none", "--shading",
                                   "phong", NULL });
    const char *dir = sr_test_models_dir();
    if (!dir) {
        SKIP("../shared/models not found (set SR_MODELS_DIR)");
    }
    const char *models[] = { "stanford-bunny", "spot", "teapot", "suzanne", "cow", "fandisk" };
    for (int i = 0; i < 6; i++) {
        char path[1024], name[64];
        snprintf(path, sizeof path, "%s/%s.obj", dir, models[i]);
        snprintf(name, sizeof name, "wire_%s", models[i]);
        check_render(name,
                     (const char *[]){ path, "--size", "160x120", "--wireframe", "--aa", "none", NULL });
        snprintf(name, sizeof name, "hidden_%s", models[i]);
        check_render(name, (const char *[]){ path, "--size", "160x120", "--hidden-line", "--aa",
                                             "none", NULL });
    }
}
