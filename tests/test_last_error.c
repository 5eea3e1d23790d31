/* test_last_error.c - sr_last_error (src/error.c): every call that takes
 * no context, given a bad argument, leaves a message naming the function
 * and the argument; so do a failed sr_make_context and context calls given
 * a NULL context; context calls' messages are the context's too; a
 * success leaves the message as it was (errno-like); and each thread has
 * its own (except in the embedded profile, which has one thread). */
#define _POSIX_C_SOURCE 200809L
#include "last_error.h"
#include "sr_test.h"
#include "softrast.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#if !defined(SR_EMBEDDED) && !defined(__EMSCRIPTEN__)
#include <pthread.h>
#define HAVE_THREADS 1
#endif

SR_TEST(contextless_calls_name_the_argument)
{
    float x = 0, y = 0;
    CHECK_FAILS(sr_sample_position(3, 0, &x, &y), SR_INVALID_ARG,
                "sr_sample_position: samples 3 must be 1, 2, 4, 8 or 16");
    CHECK_FAILS(sr_sample_position(4, 4, &x, &y), SR_INVALID_ARG,
                "sr_sample_position: index 4 is not in 0..3");
    CHECK_FAILS(sr_sample_position(4, 0, NULL, &y), SR_INVALID_ARG,
                "sr_sample_position: x is NULL");
    CHECK_FAILS(sr_sample_position(4, 0, &x, NULL), SR_INVALID_ARG,
                "sr_sample_position: y is NULL");

    const float in[3] = { 0.5f, 0.5f, 0.5f };
    float out[3];
    CHECK_FAILS(sr_tonemap_rgb((sr_tonemap_op)99, in, out), SR_INVALID_ARG,
                "sr_tonemap_rgb: op 99 is not an operator");
    CHECK_FAILS(sr_tonemap_rgb(SR_TONEMAP_ACES, NULL, out), SR_INVALID_ARG,
                "sr_tonemap_rgb: in is NULL");
    CHECK_FAILS(sr_tonemap_rgb(SR_TONEMAP_ACES, in, NULL), SR_INVALID_ARG,
                "sr_tonemap_rgb: out is NULL");

    sr_light lights[SR_MAX_LIGHTS];
    sr_camera_basis basis;
    REQUIRE(sr_camera_frame((sr_vec3){ 0, 0, 5 }, (sr_vec3){ 0, 0, -1 }, (sr_vec3){ 0, 1, 0 },
                            &basis));
    CHECK_FAILS(sr_default_lights(NULL, lights), SR_INVALID_ARG,
                "sr_default_lights: basis is NULL");
    CHECK_FAILS(sr_default_lights(&basis, NULL), SR_INVALID_ARG,
                "sr_default_lights: lights is NULL");
    sr_camera_basis long_v = basis;
    long_v.v = sr_vec3_scale(long_v.v, 2);
    CHECK_FAILS(sr_default_lights(&long_v, lights), SR_INVALID_ARG,
                "sr_default_lights: basis->v is not a unit vector");

    REQUIRE(sr_default_lights(&basis, lights) == SR_OK);
    sr_pbr_desc pbr = { 0 };
    CHECK_FAILS(sr_pbr_default_lighting(NULL, &pbr), SR_INVALID_ARG,
                "sr_pbr_default_lighting: lights is NULL");
    CHECK_FAILS(sr_pbr_default_lighting(lights, NULL), SR_INVALID_ARG,
                "sr_pbr_default_lighting: desc is NULL");
    sr_light odd[SR_MAX_LIGHTS];
    memcpy(odd, lights, sizeof odd);
    odd[2].intensity = NAN;
    CHECK_FAILS(sr_pbr_default_lighting(odd, &pbr), SR_INVALID_ARG,
                "sr_pbr_default_lighting: lights[2].intensity is not finite");
    memcpy(odd, lights, sizeof odd);
    odd[1].type = SR_LIGHT_SPOT;
    CHECK_FAILS(sr_pbr_default_lighting(odd, &pbr), SR_INVALID_ARG,
                "sr_pbr_default_lighting: lights[1].type");

    CHECK_FAILS(sr_pbr_scene_lights(NULL, 2, false, lights), SR_INVALID_ARG,
                "sr_pbr_scene_lights: scene_lights is NULL");
    CHECK_FAILS(sr_pbr_scene_lights(odd, 1, false, NULL), SR_INVALID_ARG,
                "sr_pbr_scene_lights: lights is NULL");
    sr_light bad_type = { .type = (sr_light_type)77 };
    CHECK_FAILS(sr_pbr_scene_lights(&bad_type, 1, false, lights), SR_INVALID_ARG,
                "sr_pbr_scene_lights: scene_lights[0].type 77");

    const float pos[9] = { 0, 0, 0, 1, 0, 0, 0, 1, 0 };
    const uint32_t idx[3] = { 0, 1, 5 };
    sr_mat4 mv = sr_mat4_identity();
    float depth;
    CHECK_FAILS(sr_mean_view_depth(pos, 3, idx, 1, &mv, &depth), SR_INVALID_ARG,
                "sr_mean_view_depth: indices[2] = 5 is not below vertex_count 3");
    CHECK_FAILS(sr_mean_view_depth(NULL, 3, idx, 1, &mv, &depth), SR_INVALID_ARG,
                "sr_mean_view_depth: positions is NULL");
    CHECK_FAILS(sr_mean_view_depth(pos, 3, idx, 1, &mv, NULL), SR_INVALID_ARG,
                "sr_mean_view_depth: out is NULL");
    sr_mat4 nan_mv = mv;
    nan_mv.m[14] = NAN;
    CHECK_FAILS(sr_mean_view_depth(pos, 3, (const uint32_t[]){ 0, 1, 2 }, 1, &nan_mv, &depth),
                SR_INVALID_ARG, "sr_mean_view_depth: model_view->m[14] is not finite");

    sr_vec3 pts[3] = { { 0, 0, 0 }, { NAN, 0, 0 }, { 0, 1, 0 } }, n;
    CHECK_FAILS(sr_newell_normal(pts, 2, &n), SR_INVALID_ARG, "sr_newell_normal: count 2");
    CHECK_FAILS(sr_newell_normal(pts, 3, &n), SR_INVALID_ARG,
                "sr_newell_normal: points[1] is not finite");
    CHECK_FAILS(sr_newell_normal(NULL, 3, &n), SR_INVALID_ARG,
                "sr_newell_normal: points is NULL");
    CHECK_FAILS(sr_newell_normal(pts, 3, NULL), SR_INVALID_ARG, "sr_newell_normal: out is NULL");
    const sr_vec3 huge[3] = { { 0, 0, 0 }, { 3e30f, 0, 0 }, { 0, 3e30f, 0 } };
    CHECK_FAILS(sr_newell_normal(huge, 3, &n), SR_TOO_LARGE,
                "sr_newell_normal: the points are so far apart that the normal overflows");

    sr_shadow_info info;
    float vis[4];
    CHECK_FAILS(sr_query_shadow_map(NULL, &info), SR_INVALID_ARG,
                "sr_query_shadow_map: sm is NULL");
    CHECK_FAILS(sr_shadow_visibility(NULL, pos, NULL, vis), SR_INVALID_ARG,
                "sr_shadow_visibility: sm is NULL");
    CHECK_FAILS(sr_shadow_visibility4(NULL, pos, NULL, vis), SR_INVALID_ARG,
                "sr_shadow_visibility4: sm is NULL");

    CHECK_FAILS(sr_path_move_to(NULL, 0, 0), SR_INVALID_ARG, "sr_path_move_to: path is NULL");
    CHECK_FAILS(sr_path_line_to(NULL, 0, 0), SR_INVALID_ARG, "sr_path_line_to: path is NULL");
    CHECK_FAILS(sr_path_quad_to(NULL, 0, 0, 1, 1), SR_INVALID_ARG,
                "sr_path_quad_to: path is NULL");
    CHECK_FAILS(sr_path_cubic_to(NULL, 0, 0, 1, 1, 2, 2), SR_INVALID_ARG,
                "sr_path_cubic_to: path is NULL");
    CHECK_FAILS(sr_path_arc_to(NULL, 1, 1, 0, false, false, 2, 2), SR_INVALID_ARG,
                "sr_path_arc_to: path is NULL");
    CHECK_FAILS(sr_path_close(NULL), SR_INVALID_ARG, "sr_path_close: path is NULL");
    CHECK_FAILS(sr_path_cull_curves(NULL, NULL), SR_INVALID_ARG,
                "sr_path_cull_curves: path is NULL");
}

static void *fail_alloc(size_t size, void *user)
{
    (void)size;
    (void)user;
    return NULL;
}

SR_TEST(make_context_and_null_contexts)
{
    sr_context *ctx = NULL;
    CHECK_FAILS(sr_make_context(NULL, NULL), SR_INVALID_ARG, "sr_make_context: out is NULL");
    CHECK_FAILS(sr_make_context(&(sr_context_desc){ .threads = -1 }, &ctx), SR_INVALID_ARG,
                "sr_context_desc.threads must be in 0..");
    CHECK(ctx == NULL);
    CHECK_FAILS(sr_make_context(&(sr_context_desc){ .allocator = { .alloc = fail_alloc } }, &ctx),
                SR_INVALID_ARG, "sr_context_desc.allocator has alloc but no free");
    CHECK_FAILS(sr_make_context(&(sr_context_desc){ .batch_primitives = 1 }, &ctx),
                SR_INVALID_ARG, "sr_context_desc.batch_primitives must be 0 or in");
    CHECK_FAILS(sr_make_context(&(sr_context_desc){ .arena_size = 4096 }, &ctx), SR_INVALID_ARG,
                "sr_context_desc.arena_size 4096 without an arena");
    char small[64];
    CHECK_FAILS(sr_make_context(&(sr_context_desc){ .arena = small, .arena_size = sizeof small },
                                &ctx),
                SR_OUT_OF_MEMORY, "sr_context_desc.arena_size 64 is too small");

    CHECK_FAILS(sr_draw(NULL, NULL, NULL, NULL), SR_INVALID_ARG, "sr_draw: ctx is NULL");
    sr_framebuffer *fb = NULL;
    CHECK_FAILS(sr_make_framebuffer(NULL, &(sr_framebuffer_desc){ .width = 4, .height = 4 }, &fb),
                SR_INVALID_ARG, "sr_make_framebuffer: ctx is NULL");
    sr_path *path = NULL;
    CHECK_FAILS(sr_make_path(NULL, 0, &path), SR_INVALID_ARG, "sr_make_path: ctx is NULL");
}

/* A context call's message is on the context and on the thread alike. */
SR_TEST(context_calls_set_both)
{
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    sr_framebuffer *fb = NULL;
    CHECK_FAILS(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = 0, .height = 4 }, &fb),
                SR_INVALID_ARG, "sr_framebuffer_desc.width");
    CHECK(strcmp(sr_context_error(ctx), sr_last_error()) == 0);

    /* A path keeps its context: a refused point is reported on both. */
    sr_path *path = NULL;
    REQUIRE(sr_make_path(ctx, 0, &path) == SR_OK);
    CHECK_FAILS(sr_path_line_to(path, NAN, 0), SR_INVALID_ARG,
                "sr_path_line_to: point is not finite");
    CHECK(strcmp(sr_context_error(ctx), sr_last_error()) == 0);
    sr_destroy_path(ctx, path);
    sr_destroy_context(ctx);
}

/* errno-like: a success does not clear or change the message; the
 * context's message, by contrast, is "" after a success on it. */
SR_TEST(success_leaves_the_message)
{
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    CHECK_FAILS(sr_tonemap_rgb((sr_tonemap_op)42, (const float[3]){ 0 }, (float[3]){ 0 }),
                SR_INVALID_ARG, "op 42");
    char before[512];
    snprintf(before, sizeof before, "%s", sr_last_error());

    float x, y, out[3];
    CHECK_EQ(sr_sample_position(4, 1, &x, &y), SR_OK);
    CHECK_EQ(sr_tonemap_rgb(SR_TONEMAP_ACES, (const float[3]){ 1, 1, 1 }, out), SR_OK);
    sr_path *path = NULL;
    CHECK_EQ(sr_make_path(ctx, 0, &path), SR_OK);
    CHECK_EQ(sr_path_move_to(path, 1, 2), SR_OK);
    CHECK_EQ(sr_path_line_to(path, 3, 4), SR_OK);
    CHECK_EQ(sr_path_close(path), SR_OK);
    sr_framebuffer *fb = NULL;
    CHECK_EQ(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = 4, .height = 4 }, &fb),
             SR_OK);
    sr_context *other = NULL;
    CHECK_EQ(sr_make_context(&(sr_context_desc){ .threads = 1 }, &other), SR_OK);
    CHECK(strcmp(sr_last_error(), before) == 0);
    CHECK(strcmp(sr_context_error(ctx), "") == 0);
    sr_destroy_context(other);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_path(ctx, path);
    sr_destroy_context(ctx);
}

SR_TEST(set_and_clear)
{
    sr_set_last_error("a layered library's message");
    CHECK(strcmp(sr_last_error(), "a layered library's message") == 0);
    sr_set_last_error("");
    CHECK(strcmp(sr_last_error(), "") == 0);
    sr_set_last_error("again");
    sr_set_last_error(NULL);
    CHECK(strcmp(sr_last_error(), "") == 0);
    /* A message longer than the buffer is cut, not overrun. */
    char long_message[2000];
    memset(long_message, 'm', sizeof long_message - 1);
    long_message[sizeof long_message - 1] = 0;
    sr_set_last_error(long_message);
    CHECK_EQ(strlen(sr_last_error()), 511);
    CHECK(strncmp(sr_last_error(), long_message, 511) == 0);
}

#ifdef HAVE_THREADS
typedef struct thread_case {
    pthread_barrier_t *failed, *read;
    int op;                   /* the bad operator this thread fails with */
    char seen_first[512];     /* its message before any call */
    char seen_after[512];     /* its message after every thread failed */
} thread_case;

static void *fail_on_thread(void *arg)
{
    thread_case *c = arg;
    snprintf(c->seen_first, sizeof c->seen_first, "%s", sr_last_error());
    float out[3];
    sr_tonemap_rgb((sr_tonemap_op)c->op, (const float[3]){ 0 }, out);
    /* Every thread has failed before any reads: with one shared buffer,
     * all but the last would read another thread's message. */
    pthread_barrier_wait(c->failed);
    snprintf(c->seen_after, sizeof c->seen_after, "%s", sr_last_error());
    pthread_barrier_wait(c->read);
    return NULL;
}

SR_TEST(one_message_per_thread)
{
    sr_set_last_error("the main thread's message");
    enum { N = 2 };
    pthread_barrier_t failed, read;
    REQUIRE(pthread_barrier_init(&failed, NULL, N) == 0);
    REQUIRE(pthread_barrier_init(&read, NULL, N) == 0);
    thread_case cases[N];
    pthread_t threads[N];
    int started = 0;
    for (int i = 0; i < N; i++) {
        cases[i] = (thread_case){ .failed = &failed, .read = &read, .op = 100 + i };
        if (pthread_create(&threads[i], NULL, fail_on_thread, &cases[i]) != 0) {
            break;
        }
        started++;
    }
    REQUIRE(started == N);
    for (int i = 0; i < N; i++) {
        pthread_join(threads[i], NULL);
        char want[64];
        snprintf(want, sizeof want, "sr_tonemap_rgb: op %d is not an operator", cases[i].op);
        CHECK(strcmp(cases[i].seen_first, "") == 0);
        CHECK(strcmp(cases[i].seen_after, want) == 0);
    }
    CHECK(strcmp(sr_last_error(), "the main thread's message") == 0);
    pthread_barrier_destroy(&failed);
    pthread_barrier_destroy(&read);
}
#endif
