/* Image read/write through OpenImageIO (a C++ shim behind this C header). Images are float,
 * 1 to 4 channels (RGBA order), row 0 at the top. PNG is written display-referred (8 bit, values
 * already tonemapped and in [0, 1]); EXR is written linear (half or float). */
#ifndef GK_IMAGE_IO_H
#define GK_IMAGE_IO_H

#include "base/err.h"

typedef struct gk_image {
    int width, height, channels; /* channels 1..4 */
    float *pixels;               /* width * height * channels, row-major, top row first */
} gk_image;

typedef struct gk_image_meta {   /* string attributes stored in (EXR) headers */
    int count;
    const char *keys[24];
    const char *values[24];
} gk_image_meta;

/* Allocates zeroed pixels; returns 0, or -1 for a bad size or out of memory (img left empty). */
int gk_image_alloc(gk_image *img, int width, int height, int channels);
/* Frees the pixels and zeroes the struct; safe on a zeroed or already freed image. */
void gk_image_free(gk_image *img);

/* Reads any format OIIO knows; 8-bit files are scaled to [0, 1] without colour conversion.
 * img is allocated here (free it with gk_image_free); files with more than 4 channels keep the
 * first 4. Missing, unreadable or corrupt files: GK_EINPUT naming the file and OIIO's error. */
int gk_image_read(const char *path, gk_image *img, gk_err *e);
/* Reads an encoded image held in memory (PNG, JPEG, or any format OIIO reads from memory), as
 * gk_image_read does a file. `name` is used in messages; its extension (".png", ".jpg") names
 * the format when given, else the format is recognised from the data's first bytes. */
int gk_image_read_memory(const void *data, size_t size, const char *name, gk_image *img, gk_err *e);
/* Reads one string attribute ("gikiosk:command") into out; returns 0 if found, 1 if the file has
 * no such attribute (e untouched, out set to ""), -1 when the file cannot be read (GK_EINPUT). */
int gk_image_read_attr(const char *path, const char *key, char *out, int out_len, gk_err *e);
/* Writes by extension (.png, .exr, ...). meta may be NULL. EXR is HALF; .hdr/.tif/.tiff/.pfm are
 * float; every other format (.png, .jpg, ...) is 8 bit, values clamped to [0, 1] (NaN -> 0).
 * An extension OIIO cannot write: GK_EINPUT; a failing write: GK_ERUNTIME naming the file. */
int gk_image_write(const char *path, const gk_image *img, const gk_image_meta *meta, gk_err *e);
/* Same as gk_image_write, but EXR is written as 32-bit FLOAT (exact round trip; twice the size). */
int gk_image_write_float(const char *path, const gk_image *img, const gk_image_meta *meta, gk_err *e);

#endif
