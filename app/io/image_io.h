/* Image read/write through OpenImageIO (a C++ shim behind this C header). Images are float RGBA,
 * row 0 at the top. PNG is written display-referred (8 bit, values already tonemapped and in
 * [0, 1]); EXR is written linear (half or float). */
#ifndef GK_IMAGE_IO_H
#define GK_IMAGE_IO_H

#include "../core/err.h"

typedef struct gk_image {
    int width, height, channels; /* channels 1..4 */
    float *pixels;               /* width * height * channels, row-major, top row first */
} gk_image;

typedef struct gk_image_meta {   /* string attributes stored in (EXR) headers */
    int count;
    const char *keys[16];
    const char *values[16];
} gk_image_meta;

int gk_image_alloc(gk_image *img, int width, int height, int channels);
void gk_image_free(gk_image *img);

/* Reads any format OIIO knows; 8-bit files are scaled to [0, 1] without colour conversion. */
int gk_image_read(const char *path, gk_image *img, gk_err *e);
/* Reads one string attribute ("gikiosk:command") into out; returns 0 if found. */
int gk_image_read_attr(const char *path, const char *key, char *out, int out_len, gk_err *e);
/* Writes by extension (.png, .exr, ...). meta may be NULL. */
int gk_image_write(const char *path, const gk_image *img, const gk_image_meta *meta, gk_err *e);

#endif
