/* A structural check of PNG and OpenEXR files before OpenImageIO opens them. Both formats carry
 * lengths that their readers allocate before reading: a PNG chunk's length, an EXR header
 * attribute's size. A few hundred bytes claiming a 1.7 GB text chunk made OIIO (libpng, OpenEXR)
 * allocate and touch about 2 GB before failing on the short file (found by
 * tests/fuzz/fuzz_image.c and fuzz_gltf_files.c). Every such length must fit in the file. */
#ifndef GK_IMAGE_LAYOUT_H
#define GK_IMAGE_LAYOUT_H

#include <stddef.h>

#include "base/err.h"

/* Checks the file's layout when it starts with the PNG signature (every chunk up to IEND lies
 * inside the file) or the OpenEXR magic (every header attribute's size does); any other file
 * passes unchecked. Returns 0, or -1 with GK_EINPUT naming path, the chunk or attribute and the
 * sizes. */
int gk_image_check_layout(const char *path, gk_err *e);
/* The same check on an image held in memory (a glTF's embedded image); name is used in messages. */
int gk_image_check_layout_memory(const void *data, size_t size, const char *name, gk_err *e);

#endif
