/* test_last_error_io.c - sr_last_error for softrast_io (src/io/io_util.c):
 * its calls that take neither a context nor an sr_io_error leave their
 * message there, those given a NULL err too, a failure's message is err's
 * own, and a call that succeeds after meeting a failure inside (SVG path
 * data that ends early, an image it skips) leaves the message as it was. */
#include "last_error.h"
#include "sr_test.h"
#include "softrast_io.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

SR_TEST(calls_without_err_name_the_argument)
{
    sr_rgba c;
    CHECK_FAILS(sr_io_parse_color(NULL, &c), SR_INVALID_ARG, "sr_io_parse_color: text is NULL");
    CHECK_FAILS(sr_io_parse_color("red", NULL), SR_INVALID_ARG, "sr_io_parse_color: out is NULL");
    CHECK_FAILS(sr_io_parse_color("reddish", &c), SR_BAD_FORMAT,
                "sr_io_parse_color: 'reddish' is not a color");

    sr_scene_camera cam = { .type = SR_SCENE_CAMERA_PERSPECTIVE, .yfov = 0.8f, .znear = 0.1f,
                            .zfar = 100 };
    for (int i = 0; i < 16; i++) {
        cam.world[i] = i % 5 == 0 ? 1.0f : 0.0f;
    }
    sr_mat4 view, proj;
    REQUIRE(sr_scene_camera_matrices(&cam, 1.5f, &view, &proj) == SR_OK);
    CHECK_FAILS(sr_scene_camera_matrices(NULL, 1.5f, &view, &proj), SR_INVALID_ARG,
                "sr_scene_camera_matrices: camera is NULL");
    CHECK_FAILS(sr_scene_camera_matrices(&cam, 1.5f, &view, NULL), SR_INVALID_ARG,
                "sr_scene_camera_matrices: projection is NULL");
    CHECK_FAILS(sr_scene_camera_matrices(&cam, 0.0f, &view, &proj), SR_INVALID_ARG,
                "sr_scene_camera_matrices: aspect 0 is not");
    sr_scene_camera bad = cam;
    bad.yfov = 4;
    CHECK_FAILS(sr_scene_camera_matrices(&bad, 1.5f, &view, &proj), SR_INVALID_ARG,
                "sr_scene_camera_matrices: camera->yfov 4 is not in (0, pi)");
    bad = cam;
    bad.zfar = 0.05f;
    CHECK_FAILS(sr_scene_camera_matrices(&bad, 1.5f, &view, &proj), SR_INVALID_ARG,
                "sr_scene_camera_matrices: camera->zfar 0.05 is not 0 or beyond znear 0.1");
    bad = cam;
    bad.world[5] = NAN;
    CHECK_FAILS(sr_scene_camera_matrices(&bad, 1.5f, &view, &proj), SR_INVALID_ARG,
                "sr_scene_camera_matrices: camera->world[5] is not finite");
    bad = cam;
    bad.type = (sr_scene_camera_type)9;
    CHECK_FAILS(sr_scene_camera_matrices(&bad, 1.5f, &view, &proj), SR_INVALID_ARG,
                "sr_scene_camera_matrices: camera->type 9");

    sr_path *path = NULL;
    REQUIRE(sr_make_path(sr_test_ctx(), 0, &path) == SR_OK);
    long at = 0;
    CHECK_FAILS(sr_io_parse_path_data("M 0 0 L 4 x", path, NULL, &at, NULL), SR_BAD_FORMAT,
                "path data: expected a number at offset 10");
    CHECK_FAILS(sr_io_parse_path_data(NULL, path, NULL, NULL, NULL), SR_INVALID_ARG,
                "sr_io_parse_path_data: d is NULL");
    CHECK_FAILS(sr_text_path(NULL, NULL, path, NULL, NULL), SR_INVALID_ARG, "sr_text_path: utf8");
    sr_destroy_path(sr_test_ctx(), path);

    CHECK_FAILS(sr_query_memory_limit(NULL, NULL), SR_INVALID_ARG,
                "sr_query_memory_limit: out is NULL");
    CHECK_FAILS(sr_check_memory(NULL, NULL), SR_INVALID_ARG, "sr_check_memory: desc is NULL");
}

/* With or without err, a reader's failure is the thread's message; with
 * err, the very same line. */
SR_TEST(readers_set_it_with_or_without_err)
{
    int w, h;
    uint8_t *px = NULL;
    CHECK_FAILS(sr_read_image("/nonexistent/dir/picture.png", &w, &h, &px, NULL), SR_IO_ERROR,
                "/nonexistent/dir/picture.png: cannot open");
    sr_io_error err = { { 0 } };
    static const uint8_t junk[] = "not an image at all";
    sr_set_last_error(NULL);
    CHECK(sr_decode_image("junk.bin", junk, sizeof junk - 1, &w, &h, &px, &err) != SR_OK);
    CHECK_STR_CONTAINS(err.message, "junk.bin");
    CHECK(strcmp(sr_last_error(), err.message) == 0);

    sr_mesh mesh;
    static const char obj[] = "v 0 0 0\nv 1 0 0\nf 1 2 7\n";
    sr_set_last_error(NULL);
    CHECK(sr_parse_obj(sr_test_ctx(), "tri.obj", obj, sizeof obj - 1, &mesh, &err) != SR_OK);
    CHECK_STR_CONTAINS(err.message, "tri.obj:3:");
    CHECK(strcmp(sr_last_error(), err.message) == 0);
}

SR_TEST(success_after_inner_failures_leaves_it)
{
    if (!sr_io_have_svg()) {
        SKIP("softrast was built without expat");
    }
    /* SVG draws path data up to its error and carries on; a broken
     * data: image is skipped with a warning: the render succeeds. */
    static const char doc[] =
        "<svg xmlns='http://www.w3.org/2000/svg' width='8' height='8'>"
        "<path d='M 0 0 L 8 0 L 8 8 L x' fill='red'/>"
        "<image href='data:image/png;base64,AAAA' width='4' height='4'/>"
        "</svg>";
    sr_set_last_error("before the render");
    sr_framebuffer *fb = NULL;
    sr_io_error err = { { 0 } };
    sr_test_warnings warnings = { 0 };
    CHECK_EQ(sr_render_svg(sr_test_ctx(), doc, sizeof doc - 1,
                           &(sr_svg_desc){ .name = "inner.svg", .warn = sr_test_collect_warning,
                                           .warn_user = &warnings },
                           &fb, NULL, &err),
             SR_OK);
    CHECK(warnings.count >= 1);
    CHECK(strcmp(sr_last_error(), "before the render") == 0);
    sr_destroy_framebuffer(sr_test_ctx(), fb);

    /* A failed render: the thread's message is err's. */
    static const char broken[] = "<svg xmlns='http://www.w3.org/2000/svg' width='8'";
    CHECK(sr_render_svg(sr_test_ctx(), broken, sizeof broken - 1,
                        &(sr_svg_desc){ .name = "broken.svg" }, &fb, NULL, &err) != SR_OK);
    CHECK_STR_CONTAINS(err.message, "broken.svg");
    CHECK(strcmp(sr_last_error(), err.message) == 0);
}
