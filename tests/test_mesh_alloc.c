/* test_mesh_alloc.c - meshes live on their context's allocator: every
 * array of a mesh made by sr_make_teapot, sr_mesh_compute_normals,
 * sr_parse_obj, sr_load_mesh or sr_make_mesh is a block the context's
 * sr_allocator handed out, and sr_destroy_mesh gives every one back. */
#include "sr_test.h"
#include "softrast.h"
#include "softrast_io.h"

#include <stdlib.h>
#include <string.h>

enum { MAX_BLOCKS = 4096 };

/* A counting allocator that remembers the live blocks. */
typedef struct counter {
    void *live[MAX_BLOCKS];
    int live_count;
    long allocs, frees;
} counter;

static void *count_alloc(size_t size, void *user)
{
    counter *c = user;
    if (c->live_count == MAX_BLOCKS) {
        return NULL;
    }
    void *p = malloc(size);
    if (p) {
        c->live[c->live_count++] = p;
        c->allocs++;
    }
    return p;
}

static void count_free(void *p, void *user)
{
    counter *c = user;
    for (int i = 0; i < c->live_count; i++) {
        if (c->live[i] == p) {
            c->live[i] = c->live[--c->live_count];
            c->frees++;
            free(p);
            return;
        }
    }
    sr_test_fail(__FILE__, __LINE__, "free of a block the allocator never gave: %p", p);
}

static bool is_live(const counter *c, const void *p)
{
    for (int i = 0; i < c->live_count; i++) {
        if (c->live[i] == p) {
            return true;
        }
    }
    return false;
}

/* Every non-NULL array and string of m is a live block of c. */
static void check_owned(const counter *c, const sr_mesh *m, const char *what)
{
    const void *arrays[] = { m->positions, m->normals, m->colors, m->texcoords, m->indices,
                             m->texture_path, m->texture_data, m->parts };
    for (size_t i = 0; i < sizeof arrays / sizeof arrays[0]; i++) {
        if (arrays[i] && !is_live(c, arrays[i])) {
            sr_test_fail(__FILE__, __LINE__, "%s: array %zu is not from the allocator", what, i);
        }
    }
    for (size_t i = 0; i < m->part_count; i++) {
        CHECK(!m->parts[i].texture_path || is_live(c, m->parts[i].texture_path));
    }
}

static sr_context *counted_context(counter *c)
{
    sr_context *ctx = NULL;
    if (sr_make_context(&(sr_context_desc){ .threads = 1,
                                            .allocator = { count_alloc, count_free, c } },
                        &ctx) != SR_OK) {
        fprintf(stderr, "test_mesh_alloc: no context\n");
        exit(1);
    }
    return ctx;
}

SR_TEST(teapot_and_its_normals_come_from_the_allocator)
{
    static counter c;
    sr_context *ctx = counted_context(&c);
    int base = c.live_count;
    sr_mesh m;
    REQUIRE(sr_make_teapot(ctx, 6, &m) == SR_OK);
    check_owned(&c, &m, "teapot");
    CHECK_EQ(c.live_count - base, 4); /* positions, normals, texcoords, indices */
    REQUIRE(sr_mesh_compute_normals(ctx, &m, SR_NORMALS_SMOOTH) == SR_OK);
    check_owned(&c, &m, "smooth normals");
    CHECK_EQ(c.live_count - base, 4); /* the old normals went back */
    REQUIRE(sr_mesh_compute_normals(ctx, &m, SR_NORMALS_FLAT) == SR_OK);
    check_owned(&c, &m, "flat normals");
    CHECK_EQ(c.live_count - base, 4); /* split: every array replaced */
    sr_destroy_mesh(ctx, &m);
    CHECK_EQ(c.live_count, base);
    sr_destroy_context(ctx);
    CHECK_EQ(c.live_count, 0);
    CHECK_EQ(c.allocs, c.frees);
}

SR_TEST(loaded_and_copied_meshes_come_from_the_allocator)
{
    static counter c;
    sr_context *ctx = counted_context(&c);
    int base = c.live_count;
    static const char obj[] = "mtllib none.mtl\n"
                              "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 1 1 0 0 0 1\nv 0 1 0 1 1 1\n"
                              "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\n"
                              "f 1/1/1 2/2/1 3/3/1 4/4/1\n";
    sr_mesh m;
    sr_io_error err;
    REQUIRE(sr_parse_obj(ctx, "quad.obj", obj, sizeof obj - 1, &m, &err) == SR_OK);
    CHECK_EQ(m.triangle_count, 2);
    CHECK(m.positions && m.normals && m.colors && m.texcoords && m.indices);
    check_owned(&c, &m, "parsed OBJ");
    CHECK_EQ(c.live_count - base, 5);

    sr_mesh copy;
    REQUIRE(sr_make_mesh(ctx, &m, &copy) == SR_OK);
    check_owned(&c, &copy, "copy");
    CHECK(copy.positions != m.positions);
    CHECK(memcmp(copy.texcoords, m.texcoords, m.vertex_count * 2 * sizeof(float)) == 0);
    sr_destroy_mesh(ctx, &copy);
    sr_destroy_mesh(ctx, &m);
    CHECK_EQ(c.live_count, base);

    const char *dir = sr_test_models_dir();
    if (dir) {
        char path[4096];
        snprintf(path, sizeof path, "%s/spot.obj", dir);
        REQUIRE(sr_load_mesh(ctx, path, NULL, &m, &err) == SR_OK);
        check_owned(&c, &m, path);
        CHECK(c.live_count > base);
        sr_destroy_mesh(ctx, &m);
        CHECK_EQ(c.live_count, base);
    }
    sr_destroy_context(ctx);
    CHECK_EQ(c.live_count, 0);
    CHECK_EQ(c.allocs, c.frees);
}

SR_TEST(mesh_calls_name_what_is_wrong)
{
    sr_context *ctx = sr_test_ctx();
    sr_mesh m;
    CHECK_EQ(sr_make_teapot(ctx, 0, &m), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "sr_make_bezier_mesh: detail 0");
    CHECK_EQ(sr_mesh_compute_normals(ctx, NULL, SR_NORMALS_SMOOTH), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "sr_mesh_compute_normals");
    CHECK_EQ(sr_make_mesh(ctx, NULL, &m), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "sr_make_mesh");
    sr_io_error err;
    CHECK_EQ(sr_parse_obj(NULL, "x.obj", "v 0 0 0\n", 8, &m, &err), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(err.message, "no context");
    CHECK_EQ(sr_make_teapot(NULL, 4, &m), SR_INVALID_ARG);
}

SR_TEST(make_mesh_refuses_what_its_copy_could_not_hold)
{
    sr_context *ctx = sr_test_ctx();
    float pos[9] = { 0, 0, 0, 1, 0, 0, 0, 1, 0 };
    uint32_t idx[6] = { 0, 1, 2, 2, 1, 0 };
    sr_mesh src = { .vertex_count = 3, .positions = pos, .triangle_count = 2, .indices = idx };
    sr_mesh out;

    /* out == src: the struct keeps the caller's arrays. */
    sr_mesh same = src;
    CHECK_EQ(sr_make_mesh(ctx, &same, &same), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "out is src");
    CHECK(same.positions == pos && same.indices == idx && same.triangle_count == 2);

    /* A triangle count whose indices overflow size_t is refused before
     * any index is read (idx holds 6). */
    sr_mesh huge = src;
    huge.triangle_count = SIZE_MAX / 4;
    CHECK_EQ(sr_make_mesh(ctx, &huge, &out), SR_TOO_LARGE);

    /* Parts must be runs that cover every triangle in order. */
    struct { sr_mesh_part parts[2]; size_t count; const char *needle; } bad[] = {
        { { { .first_triangle = 0, .triangle_count = 5 } }, 1, "src->parts[0]" },
        { { { .first_triangle = SIZE_MAX, .triangle_count = 2 } }, 1, "src->parts[0]" },
        { { { .first_triangle = 1, .triangle_count = 1 } }, 1, "src->parts[0]" },
        { { { .triangle_count = 1 }, { .first_triangle = 0, .triangle_count = 1 } }, 2,
          "src->parts[1]" },
        { { { .triangle_count = 1 } }, 1, "cover triangles 0 .. 1 of 2" },
        { { { .triangle_count = 2, .texture_size = 5 } }, 1, "parts[0].texture_size 5" },
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        sr_mesh m = src;
        m.parts = bad[i].parts;
        m.part_count = bad[i].count;
        CHECK_EQ(sr_make_mesh(ctx, &m, &out), SR_INVALID_ARG);
        CHECK_STR_CONTAINS(sr_context_error(ctx), bad[i].needle);
        CHECK(out.positions == NULL && out.parts == NULL);
    }
    sr_mesh nodata = src;
    nodata.texture_size = 5;
    CHECK_EQ(sr_make_mesh(ctx, &nodata, &out), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "src->texture_size 5");

    /* Runs that cover everything, empty ones included, are copied. */
    sr_mesh_part good[3] = { { .triangle_count = 1 }, { .first_triangle = 1 },
                             { .first_triangle = 1, .triangle_count = 1 } };
    sr_mesh m = src;
    m.parts = good;
    m.part_count = 3;
    REQUIRE(sr_make_mesh(ctx, &m, &out) == SR_OK);
    CHECK_EQ(out.part_count, 3);
    CHECK_EQ(out.parts[2].first_triangle, 1);
    sr_destroy_mesh(ctx, &out);
}
