/* test_examples.c - the example programs run and draw what the text says:
 * softrast.h's "Use" program (examples/hello.c, the same text in both
 * places) one shaded triangle; docs/shaders.md's toon teapot in a few flat
 * bands with dark ink at its rim, and the procedural checkerboard with
 * crisp squares near the camera that the quad-derivative filter fades to
 * their average far away; docs/draw2d.md's paint example its gradients
 * and pattern.  Also: softrast.h's API map names every function
 * the header declares, and nothing else. */
#include "sr_test.h"
#include "softrast_io.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

/* A whole text file, NUL-terminated; NULL if unreadable. */
static char *read_text(const char *dir, const char *name)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "rb");
    if (!f) {
        return NULL;
    }
    char *text = NULL;
    size_t size = 0, cap = 0, n;
    char buf[8192];
    while ((n = fread(buf, 1, sizeof buf, f)) > 0) {
        if (size + n + 1 > cap) {
            cap = 2 * (size + n + 1);
            char *t = realloc(text, cap);
            if (!t) {
                free(text);
                fclose(f);
                return NULL;
            }
            text = t;
        }
        memcpy(text + size, buf, n);
        size += n;
    }
    fclose(f);
    if (text) {
        text[size] = '\0';
    }
    return text;
}

/* The next line of *p (without its newline) into line; false at the end. */
static bool next_line(const char **p, char *line, size_t cap)
{
    if (!**p) {
        return false;
    }
    const char *e = strchr(*p, '\n');
    size_t n = e ? (size_t)(e - *p) : strlen(*p);
    snprintf(line, cap, "%.*s", (int)(n < cap ? n : cap - 1), *p);
    *p += n + (e != NULL);
    return true;
}

SR_TEST(header_use_example_is_examples_hello)
{
    char *header = read_text(sr_test_src_dir(), "../include/softrast.h");
    char *hello = read_text(sr_test_src_dir(), "../examples/hello.c");
    REQUIRE(header && hello);
    /* The header's block: " *     " + the program's line, " *" for an
     * empty one, from the #include on until the first other line. */
    const char *h = strstr(header, " *     #include <softrast.h>\n");
    const char *x = strstr(hello, "#include <softrast.h>\n");
    REQUIRE(h && x);
    char hl[512], xl[512];
    int line = 0, blank_run = 0;
    bool more_h = true;
    while (more_h) {
        more_h = next_line(&h, hl, sizeof hl) &&
                 (strcmp(hl, " *") == 0 || strncmp(hl, " *     ", 7) == 0);
        if (more_h && strcmp(hl, " *") == 0) {
            blank_run++; /* held back: blank lines may end the block */
            continue;
        }
        if (!more_h) {
            break;
        }
        for (; blank_run > 0; blank_run--, line++) {
            if (!next_line(&x, xl, sizeof xl) || xl[0] != '\0') {
                sr_test_fail(__FILE__, __LINE__, "line %d of the example: header has a blank "
                             "line, hello.c \"%s\"", line + 1, xl);
                goto done;
            }
        }
        line++;
        if (!next_line(&x, xl, sizeof xl) || strcmp(hl + 7, xl) != 0) {
            sr_test_fail(__FILE__, __LINE__, "line %d of the example: header \"%s\", hello.c "
                         "\"%s\"", line, hl + 7, xl);
            goto done;
        }
    }
    while (next_line(&x, xl, sizeof xl)) {
        if (xl[0] != '\0') {
            sr_test_fail(__FILE__, __LINE__, "hello.c goes on after the header's example: "
                         "\"%s\"", xl);
            break;
        }
    }
    CHECK(line > 20);
done:
    free(header);
    free(hello);
}

/* The function a declaration line of the header declares, or false: a
 * line at column 0 that is no comment, preprocessor line, typedef or
 * brace, whose identifier before the first '(' starts with sr_. */
static bool declared_function(const char *l, char *name, size_t cap)
{
    if (strchr(" */#}\t", l[0]) || strncmp(l, "typedef", 7) == 0) {
        return false;
    }
    const char *paren = strchr(l, '(');
    if (!paren) {
        return false;
    }
    const char *b = paren;
    while (b > l && (b[-1] == '_' || (b[-1] >= 'a' && b[-1] <= 'z') ||
                     (b[-1] >= '0' && b[-1] <= '9'))) {
        b--;
    }
    if (paren - b < 4 || strncmp(b, "sr_", 3) != 0) {
        return false;
    }
    snprintf(name, cap, "%.*s", (int)(paren - b), b);
    return true;
}

SR_TEST(api_map_names_every_declared_function)
{
    char *header = read_text(sr_test_src_dir(), "../include/softrast.h");
    REQUIRE(header);
    const char *start = strstr(header, " * API map:");
    REQUIRE(start);
    const char *end = strstr(start, "\n *\n"); /* after the heading */
    REQUIRE(end);
    end = strstr(end + 3, "\n *\n");            /* after the map */
    REQUIRE(end);
    int declared = 0, mapped = 0;
    char l[512], name[128], entry[160];
    for (const char *p = header; next_line(&p, l, sizeof l);) {
        if (declared_function(l, name, sizeof name)) {
            declared++;
            snprintf(entry, sizeof entry, "\n *     %s ", name);
            const char *hit = strstr(start, entry);
            if (!hit || hit > end) {
                sr_test_fail(__FILE__, __LINE__, "%s is declared but not in the API map", name);
            }
        }
    }
    /* And every entry of the map is declared. */
    for (const char *p = start; p < end && next_line(&p, l, sizeof l);) {
        if (strncmp(l, " *     sr_", 10) != 0) {
            continue;
        }
        mapped++;
        snprintf(name, sizeof name, "%.*s", (int)strcspn(l + 7, " "), l + 7);
        snprintf(entry, sizeof entry, "%s(", name);
        bool found = false;
        for (const char *q = header; next_line(&q, l, sizeof l);) {
            char decl[128];
            found |= declared_function(l, decl, sizeof decl) && strcmp(decl, name) == 0;
        }
        if (!found) {
            sr_test_fail(__FILE__, __LINE__, "%s is in the API map but not declared", name);
        }
    }
    CHECK_EQ(mapped, declared);
    CHECK(declared > 90);
    free(header);
}

#if defined(SR_EXAMPLE_TOON) && defined(SR_EXAMPLE_CHECKER) && defined(SR_EXAMPLE_HELLO)

static bool run(const char *exe, const char *out)
{
    pid_t pid = fork();
    if (pid == 0) {
        const char *argv[24];
        if (sr_test_program_argv(exe, (const char *[]){ out, NULL }, argv,
                                 sizeof argv / sizeof argv[0])) {
            execv(argv[0], (char *const *)argv);
        }
        _exit(127);
    }
    int status = 0;
    waitpid(pid, &status, 0);
    return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

/* Run an example writing NAME under the test output directory and read
 * the PNG back (malloc'd RGBA8); NULL when either fails. */
static uint8_t *run_png(const char *exe, const char *name, int *w, int *h)
{
    char out[512];
    snprintf(out, sizeof out, "%s/%s", sr_test_out_dir(), name);
    uint8_t *px = NULL;
    sr_io_error err;
    if (!run(exe, out) || sr_read_png(out, NULL, w, h, &px, &err) != SR_OK) {
        return NULL;
    }
    return px;
}

/* A binary PPM as written by examples/hello.c: RGB, 8 bits. */
static uint8_t *read_ppm(const char *path, int *w, int *h)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        return NULL;
    }
    uint8_t *px = NULL;
    int maxval = 0;
    if (fscanf(f, "P6 %d %d %d", w, h, &maxval) == 3 && maxval == 255 && fgetc(f) == '\n' &&
        *w > 0 && *h > 0 && *w <= 4096 && *h <= 4096) {
        size_t n = (size_t)*w * (size_t)*h * 3;
        px = malloc(n);
        if (px && fread(px, 1, n, f) != n) {
            free(px);
            px = NULL;
        }
    }
    fclose(f);
    return px;
}

SR_TEST(hello_example_draws_the_triangle)
{
    char out[512];
    snprintf(out, sizeof out, "%s/example-hello.ppm", sr_test_out_dir());
    REQUIRE(run(SR_EXAMPLE_HELLO, out));
    int w = 0, h = 0;
    uint8_t *px = read_ppm(out, &w, &h);
    REQUIRE(px);
    CHECK_EQ(w, 64);
    CHECK_EQ(h, 48);
    const uint8_t *corner = px, *centre = px + 3 * (24 * 64 + 32);
    const uint8_t *red = px + 3 * (41 * 64 + 9), *blue = px + 3 * (8 * 64 + 32);
    CHECK(corner[0] == 26 && corner[1] == 26 && corner[2] == 26); /* the clear color, 0.1 */
    CHECK(centre[0] > 40 && centre[1] > 40 && centre[2] > 40);    /* the three colors mixed */
    CHECK(red[0] > 150 && red[0] > 3 * red[1] && red[0] > 3 * red[2]);
    CHECK(blue[2] > 150 && blue[2] > 3 * blue[0] && blue[2] > 3 * blue[1]);
    free(px);
}

SR_TEST(toon_example_draws_bands_and_ink)
{
    int w, h;
    uint8_t *px = run_png(SR_EXAMPLE_TOON, "example-toon.png", &w, &h);
    REQUIRE(px);
    /* Count the pixels of each band color (base x band), exactly. */
    static const float bands[] = { 1.0f, 0.65f, 0.35f, 0.05f };
    int count[4] = { 0, 0, 0, 0 }, background = 0, other = 0;
    for (int i = 0; i < w * h; i++) {
        const uint8_t *p = &px[i * 4];
        int hit = -1;
        for (int b = 0; b < 4; b++) {
            if (p[0] == (uint8_t)(bands[b] * 255.0f + 0.5f) &&
                p[1] == (uint8_t)(0.55f * bands[b] * 255.0f + 0.5f)) {
                hit = b;
            }
        }
        if (hit >= 0) {
            count[hit]++;
        } else if (p[0] == p[1] || (p[0] > 230 && p[1] > 230)) {
            background++;
        } else {
            other++;   /* multisampled edges between bands */
        }
    }
    for (int b = 0; b < 4; b++) {
        CHECK(count[b] > 1000);
    }
    CHECK(background > w * h / 3);
    /* Flat bands: the blended edge pixels are a small minority. */
    CHECK(other < (count[0] + count[1] + count[2] + count[3]) / 4);
    free(px);
}

SR_TEST(checker_example_is_crisp_near_and_filtered_far)
{
    int w, h;
    uint8_t *px = run_png(SR_EXAMPLE_CHECKER, "example-checker.png", &w, &h);
    REQUIRE(px);
    /* The bottom rows (near): mostly the two pure colors.  Just below the
     * horizon (far): mostly in between, no pure light squares. */
    int pure_near = 0, light_far = 0, mid_far = 0, n_near = 0, n_far = 0;
    for (int x = 0; x < w; x++) {
        for (int y = h - 20; y < h; y++) {
            int r = px[(y * w + x) * 4];
            pure_near += r <= 45 || r >= 230;
            n_near++;
        }
    }
    /* Find the horizon: the first row from the top that is not sky. */
    int horizon = 0;
    while (horizon < h && px[(horizon * w + w / 2) * 4 + 2] > 190) {
        horizon++;
    }
    REQUIRE(horizon > 10 && horizon < h - 40);
    for (int x = 0; x < w; x++) {
        for (int y = horizon + 1; y < horizon + 4; y++) {
            int r = px[(y * w + x) * 4];
            light_far += r >= 230;
            mid_far += r > 80 && r < 200;
            n_far++;
        }
    }
    CHECK(pure_near > n_near * 7 / 10);
    CHECK(light_far < n_far / 50);
    CHECK(mid_far > n_far * 8 / 10);
    free(px);
}


#ifdef SR_EXAMPLE_PAINT
/* Whether pixel p is within d codes of r, g, b on each channel. */
static bool near_rgb(const uint8_t *p, int r, int g, int b, int d)
{
    return abs(p[0] - r) <= d && abs(p[1] - g) <= d && abs(p[2] - b) <= d;
}

/* examples/paint.c: the disc's reflected gradient reaches both end
 * colors again and again, the radial gradient is its first stop's color
 * at the focal point, the star shows both checker colors at 80% over
 * white, and the background stays white. */
SR_TEST(paint_example_draws_its_gradients_and_pattern)
{
    int w, h;
    uint8_t *px = run_png(SR_EXAMPLE_PAINT, "example-paint.png", &w, &h);
    REQUIRE(px);
    REQUIRE(w == 400 && h == 140);
    int blue = 0, red = 0, dark = 0, light = 0;
    for (int y = 30; y < 110; y++) {
        for (int x = 20; x < 100; x++) {
            blue += near_rgb(px + (y * w + x) * 4, 26, 77, 204, 6);
            red += near_rgb(px + (y * w + x) * 4, 204, 26, 51, 6);
        }
    }
    for (int y = 65; y < 85; y++) {
        for (int x = 320; x < 340; x++) {
            /* 0.8 of the tile's colors over white */
            dark += near_rgb(px + (y * w + x) * 4, 75, 163, 99, 3);
            light += near_rgb(px + (y * w + x) * 4, 243, 243, 227, 3);
        }
    }
    CHECK(blue >= 40 && red >= 40);
    CHECK(near_rgb(px + (50 * w + 170) * 4, 26, 77, 204, 0));
    CHECK(dark >= 80 && light >= 80);
    CHECK(near_rgb(px + (5 * w + 5) * 4, 255, 255, 255, 0));
    CHECK(near_rgb(px + (130 * w + 300) * 4, 255, 255, 255, 0));
    free(px);
}
#endif

#else

SR_TEST(examples_not_built)
{
    SKIP("built with SR_BUILD_EXAMPLES=OFF");
}

#endif
