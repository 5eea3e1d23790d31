/* jpeg_encode.h - JPEG inputs for the tests that read them (test_jpeg,
 * test_cli), written with libjpeg's own encoder from pixels the test
 * chose.  Only where the build found libjpeg (SR_HAVE_JPEG_TEST). */
#ifndef SR_TEST_JPEG_ENCODE_H
#define SR_TEST_JPEG_ENCODE_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include <jpeglib.h>

typedef struct jpeg_encoding {
    J_COLOR_SPACE space;  /* JCS_RGB, JCS_GRAYSCALE or JCS_CMYK: 3, 1 or 4 bytes a pixel */
    int quality;          /* 1..100 */
    bool progressive;
    bool full_chroma;     /* 4:4:4 rather than libjpeg's default 4:2:0 */
} jpeg_encoding;

/* The w x h pixels (rows packed) as a JPEG in a malloc'd buffer, or NULL. */
static inline uint8_t *jpeg_encode(const uint8_t *pixels, int w, int h, jpeg_encoding e,
                                   size_t *size)
{
    struct jpeg_compress_struct c;
    struct jpeg_error_mgr jerr;
    c.err = jpeg_std_error(&jerr);
    jpeg_create_compress(&c);
    unsigned char *buf = NULL;
    unsigned long len = 0;
    jpeg_mem_dest(&c, &buf, &len);
    c.image_width = (JDIMENSION)w;
    c.image_height = (JDIMENSION)h;
    c.input_components = e.space == JCS_GRAYSCALE ? 1 : e.space == JCS_CMYK ? 4 : 3;
    c.in_color_space = e.space;
    jpeg_set_defaults(&c);
    jpeg_set_quality(&c, e.quality, TRUE);
    if (e.full_chroma) {
        for (int i = 0; i < c.num_components; i++) {
            c.comp_info[i].h_samp_factor = 1;
            c.comp_info[i].v_samp_factor = 1;
        }
    }
    if (e.progressive) {
        jpeg_simple_progression(&c);
    }
    jpeg_start_compress(&c, TRUE);
    size_t stride = (size_t)c.input_components * (size_t)w;
    while (c.next_scanline < c.image_height) {
        JSAMPROW row = (JSAMPROW)(pixels + stride * c.next_scanline);
        jpeg_write_scanlines(&c, &row, 1);
    }
    jpeg_finish_compress(&c);
    jpeg_destroy_compress(&c);
    *size = len;
    return buf;
}

#endif
