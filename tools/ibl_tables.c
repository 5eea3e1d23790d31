/* ibl_tables.c - the build's generator of image-based light's tables
 * (docs/ibl.md): the split-sum BRDF table, the sheen's albedo table
 * (docs/pbr.md) and the built-in studio prefiltered at intensity 1,
 * computed with the library's own functions (brdf_integrate.c,
 * sheen_integrate.c, environment_studio.c, environment_prefilter.c) in the
 * order sr_make_environment runs them for an image, and written as a C
 * source of exact hexadecimal floats that the library compiles in.  Run by
 * CMake (under the cross build's emulator, or built by the host's
 * compiler), never at run time.
 *
 *   ibl_tables OUT.c
 */
#include "fragment/environment.h"
#include "fragment/sheen.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static sr__equirect make_image(int w, int h)
{
    sr__equirect e = { w, h, calloc((size_t)w * h * 3, sizeof(float)) };
    if (!e.rgb) {
        fprintf(stderr, "ibl_tables: out of memory\n");
        exit(1);
    }
    return e;
}

/* One channel of n grey texels (3 floats each) as a C array's body;
 * false if a texel is not grey. */
static bool write_grey(FILE *f, const float *rgb, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        if (rgb[3 * i] != rgb[3 * i + 1] || rgb[3 * i] != rgb[3 * i + 2]) {
            return false;
        }
        fprintf(f, "%a,%c", (double)rgb[3 * i], i % 6 == 5 ? '\n' : ' ');
    }
    return true;
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: ibl_tables OUT.c\n");
        return 2;
    }
    /* The studio's source image and its mips, as from_image's prefilter
     * makes them (environment.c); it is the first mip's size already. */
    sr__equirect mip[SR__ENV_MAX_MIPS];
    int mips = sr__mip_count(SR__STUDIO_WIDTH);
    mip[0] = make_image(SR__STUDIO_WIDTH, SR__STUDIO_HEIGHT);
    sr__studio_rows(&mip[0], 0, mip[0].h);
    for (int m = 1; m < mips; m++) {
        mip[m] = make_image(mip[m - 1].w / 2, mip[m - 1].h / 2);
        sr__equirect_halve(&mip[m - 1], &mip[m], 0, mip[m].h);
    }
    float sh[9][3];
    sr__irradiance_sh(&mip[sr__sh_mip(mip[0].w, mips)], sh);
    sr__equirect level[SR_ENVIRONMENT_LEVELS];
    for (int k = 1; k < SR_ENVIRONMENT_LEVELS; k++) {
        int lw = sr__level_width(mip[0].w, k);
        level[k] = make_image(lw, lw / 2);
        sr__spec_plan plan;
        sr__specular_plan((float)k / (SR_ENVIRONMENT_LEVELS - 1), mip, mips, &plan);
        sr__prefilter_rows(mip, &plan, &level[k], 0, level[k].h);
    }

    char tmp[4096];
    if (snprintf(tmp, sizeof tmp, "%s.tmp", argv[1]) >= (int)sizeof tmp) {
        fprintf(stderr, "ibl_tables: %s: path too long\n", argv[1]);
        return 1;
    }
    FILE *f = fopen(tmp, "w");
    if (!f) {
        perror(tmp);
        return 1;
    }
    bool grey = true;
    fprintf(f, "/* Written by tools/ibl_tables.c at build time: do not edit. */\n"
               "#include \"fragment/environment.h\"\n#include \"fragment/sheen.h\"\n\n");
    fprintf(f, "const float sr__brdf_builtin[%d][%d][2] = {\n", SR__BRDF_TABLE_SIZE,
            SR__BRDF_TABLE_SIZE);
    for (int row = 0; row < SR__BRDF_TABLE_SIZE; row++) {
        float t[SR__BRDF_TABLE_SIZE][2];
        sr__brdf_table_row(row, t);
        fprintf(f, "{\n");
        for (int col = 0; col < SR__BRDF_TABLE_SIZE; col++) {
            fprintf(f, "{ %a, %a },%c", (double)t[col][0], (double)t[col][1],
                    col % 3 == 2 ? '\n' : ' ');
        }
        fprintf(f, "},\n");
    }
    fprintf(f, "};\n\n");
    fprintf(f, "const float sr__sheen_builtin[%d][%d] = {\n", SR__SHEEN_TABLE_SIZE,
            SR__SHEEN_TABLE_SIZE);
    for (int row = 0; row < SR__SHEEN_TABLE_SIZE; row++) {
        float t[SR__SHEEN_TABLE_SIZE];
        sr__sheen_table_row(row, t);
        fprintf(f, "{\n");
        for (int col = 0; col < SR__SHEEN_TABLE_SIZE; col++) {
            fprintf(f, "%a,%c", (double)t[col], col % 6 == 5 ? '\n' : ' ');
        }
        fprintf(f, "},\n");
    }
    fprintf(f, "};\n\n");
    for (int k = 1; k < SR_ENVIRONMENT_LEVELS; k++) {
        fprintf(f, "static const float level%d[%d * %d] = {\n", k, level[k].w, level[k].h);
        grey &= write_grey(f, level[k].rgb, (size_t)level[k].w * level[k].h);
        fprintf(f, "};\n\n");
    }
    fprintf(f, "const float *const sr__studio_builtin_levels[%d] = { NULL", SR_ENVIRONMENT_LEVELS);
    for (int k = 1; k < SR_ENVIRONMENT_LEVELS; k++) {
        fprintf(f, ", level%d", k);
    }
    fprintf(f, " };\n\nconst float sr__studio_builtin_sh[9] = {\n");
    grey &= write_grey(f, &sh[0][0], 9);
    fprintf(f, "};\n");
    if (ferror(f) | (fclose(f) != 0) || !grey) {
        fprintf(stderr, "ibl_tables: %s: %s\n", tmp, grey ? "write error" : "studio not grey");
        remove(tmp);
        return 1;
    }
    if (rename(tmp, argv[1]) != 0) {
        perror(argv[1]);
        remove(tmp);
        return 1;
    }
    for (int m = 0; m < mips; m++) {
        free(mip[m].rgb);
    }
    for (int k = 1; k < SR_ENVIRONMENT_LEVELS; k++) {
        free(level[k].rgb);
    }
    return 0;
}
