/* See image_layout.h. Reads only headers: PNG chunk headers by seeking from one to the next, the
 * EXR header attribute by attribute; no pixel data. */
#include "image_layout.h"

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

static const unsigned char png_signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
static const unsigned char exr_magic[4] = {0x76, 0x2f, 0x31, 0x01};

/* PNG (ISO 15948 §5.3): length (4 bytes, big-endian, at most 2^31-1), type, data, CRC. */
static int check_png(FILE *f, const char *path, long long size, gk_err *e)
{
    long long at = 8;
    while (at + 8 <= size) {
        unsigned char h[8];
        if (fseeko(f, (off_t)at, SEEK_SET) != 0 || fread(h, 1, 8, f) != 8)
            return gk_fail(e, GK_EINPUT, "%s: cannot read the PNG chunk header at byte %lld", path, at);
        uint32_t len = (uint32_t)h[0] << 24 | (uint32_t)h[1] << 16 | (uint32_t)h[2] << 8 | h[3];
        char type[5] = {(char)h[4], (char)h[5], (char)h[6], (char)h[7], 0};
        for (int i = 0; i < 4; i++)
            if (!((type[i] >= 'A' && type[i] <= 'Z') || (type[i] >= 'a' && type[i] <= 'z')))
                type[i] = '?';
        if (at + 12 + (long long)len > size)
            return gk_fail(e, GK_EINPUT, "%s: corrupt PNG: chunk %s at byte %lld claims %u bytes, the file has %lld left",
                           path, type, at, len, size - at - 12 > 0 ? size - at - 12 : 0);
        if (memcmp(type, "IEND", 4) == 0)
            return 0;
        at += 12 + (long long)len;
    }
    return 0; /* ends without IEND: libpng says what is missing */
}

/* Scan lines per chunk of each OpenEXR compression (NONE, RLE, ZIPS, ZIP, PIZ, PXR24, B44, B44A,
 * DWAA, DWAB); an unknown one OpenEXR refuses itself. */
static int exr_lines_per_chunk(int compression)
{
    static const int lines[] = {1, 1, 1, 16, 32, 16, 32, 32, 32, 256};
    return compression >= 0 && compression < (int)(sizeof lines / sizeof lines[0]) ? lines[compression] : 256;
}

/* The part's dataWindow, checked before OpenEXR sizes anything by it: OpenEXR allocates a scan-line
 * image's line-offset table (8 bytes a chunk) from the window as it opens the file, so a 400-byte file
 * claiming 1.7e9 lines made the reader use 2 GB before it failed (tests/fuzz/fuzz_image.c). The window
 * must be non-empty, within the readers' pixel cap (gk_image_alloc's 2^28), and a single-part scan-line
 * file must hold its offset table. */
static int check_exr_window(const char *path, const int32_t box[4], int compression, bool offsets_follow,
                            long long left, gk_err *e)
{
    long long w = (long long)box[2] - box[0] + 1, h = (long long)box[3] - box[1] + 1;
    if (w <= 0 || h <= 0)
        return gk_fail(e, GK_EINPUT, "%s: corrupt OpenEXR: its dataWindow (%d,%d)-(%d,%d) is empty", path, box[0],
                       box[1], box[2], box[3]);
    if (w * h > (1LL << 28))
        return gk_fail(e, GK_EINPUT, "%s: image too large (%lldx%lld in its OpenEXR dataWindow)", path, w, h);
    long long lpc = exr_lines_per_chunk(compression), table = (h + lpc - 1) / lpc * 8;
    if (offsets_follow && table > left)
        return gk_fail(e, GK_EINPUT, "%s: corrupt OpenEXR: its dataWindow (%lldx%lld) needs a %lld-byte line-offset "
                       "table, the file has %lld bytes left", path, w, h, table, left);
    return 0;
}

/* The size of an OpenEXR attribute type OpenEXR reads by its type, not by the size the file gives
 * (ImfStandardAttributes' fixed-size types), or -1 for the others (strings, channel lists, opaque
 * types: read by the size). A file whose size disagrees desynchronises OpenEXR's reading of the header
 * from ours: the fuzzer's 502-byte EXR gave `screenWindowWidth` (float) 3 bytes, so OpenEXR read the
 * following bytes as another attribute, of an unknown type claiming ~2 GB, and allocated it. */
static int exr_fixed_size(const char *type)
{
    static const struct { const char *type; int size; } fixed[] = {
        {"float", 4}, {"double", 8}, {"int", 4}, {"box2i", 16}, {"box2f", 16}, {"v2i", 8}, {"v2f", 8},
        {"v2d", 16}, {"v3i", 12}, {"v3f", 12}, {"v3d", 24}, {"m33f", 36}, {"m33d", 72}, {"m44f", 64},
        {"m44d", 128}, {"compression", 1}, {"lineOrder", 1}, {"envmap", 1}, {"deepImageState", 1},
        {"chromaticities", 32}, {"keycode", 28}, {"timecode", 8}, {"rational", 8}, {"tiledesc", 9},
    };
    for (size_t i = 0; i < sizeof fixed / sizeof fixed[0]; i++)
        if (strcmp(type, fixed[i].type) == 0)
            return fixed[i].size;
    return -1;
}

/* OpenEXR (file layout, "Header"): magic, version (flags in bytes 5..7), then attributes
 * `name\0 type\0 size(int32 LE) value[size]` up to an empty name; a multi-part file has one such
 * header per part and an empty header after the last. */
static int check_exr(FILE *f, const char *path, long long size, gk_err *e)
{
    unsigned char version[4];
    if (fseeko(f, 4, SEEK_SET) != 0 || fread(version, 1, 4, f) != 4)
        return gk_fail(e, GK_EINPUT, "%s: corrupt OpenEXR: the file ends in its version field", path);
    bool multipart = (version[1] & 0x10) != 0; /* flag bit 12 */
    bool tiled = (version[1] & 0x02) != 0;     /* flag bit 9: a single tiled part */
    int32_t box[4] = {0, 0, 0, 0};
    bool have_window = false;
    int compression = 0;
    long long at = 8;
    for (;;) {
        int c = fgetc(f);
        if (c == EOF)
            return gk_fail(e, GK_EINPUT, "%s: corrupt OpenEXR: the file ends inside its header", path);
        at++;
        if (c == 0) { /* an empty name: the end of a header (in a multi-part file, of one part's) */
            /* a multi-part file's offset tables follow all the headers: only the window's size is checked */
            if (have_window && check_exr_window(path, box, compression, !multipart && !tiled, size - at, e))
                return -1;
            have_window = false;
            if (!multipart)
                return 0;
            int next = fgetc(f);
            if (next == 0 || next == EOF)
                return 0; /* the empty header after the last part */
            ungetc(next, f);
            continue;
        }
        char name[256], type[256];
        int n = 0;
        name[n++] = (char)c;
        while ((c = fgetc(f)) != EOF && c != 0 && n < 255)
            name[n++] = (char)c, at++;
        name[n] = 0;
        at++;
        if (c != 0)
            return gk_fail(e, GK_EINPUT, "%s: corrupt OpenEXR: a header attribute name is unterminated", path);
        n = 0;
        while ((c = fgetc(f)) != EOF && c != 0 && n < 255)
            type[n++] = (char)c, at++;
        type[n] = 0;
        at++;
        unsigned char s[4];
        if (c != 0 || fread(s, 1, 4, f) != 4)
            return gk_fail(e, GK_EINPUT, "%s: corrupt OpenEXR: header attribute '%s' is cut short", path, name);
        at += 4;
        int32_t len = (int32_t)((uint32_t)s[0] | (uint32_t)s[1] << 8 | (uint32_t)s[2] << 16 | (uint32_t)s[3] << 24);
        if (len < 0 || at + len > size)
            return gk_fail(e, GK_EINPUT, "%s: corrupt OpenEXR: header attribute '%s' (%s) claims %d bytes, the file has "
                           "%lld left", path, name, type, len, size - at);
        int fixed = exr_fixed_size(type);
        if (fixed >= 0 && len != fixed)
            return gk_fail(e, GK_EINPUT, "%s: corrupt OpenEXR: header attribute '%s' (%s) has %d bytes, not %d", path,
                           name, type, len, fixed);
        unsigned char v[16];
        if (strcmp(name, "dataWindow") == 0 && strcmp(type, "box2i") == 0 && len == 16 && fread(v, 1, 16, f) == 16) {
            for (int i = 0; i < 4; i++)
                box[i] = (int32_t)((uint32_t)v[4 * i] | (uint32_t)v[4 * i + 1] << 8 | (uint32_t)v[4 * i + 2] << 16 |
                                   (uint32_t)v[4 * i + 3] << 24);
            have_window = true;
        } else if (strcmp(name, "compression") == 0 && strcmp(type, "compression") == 0 && len == 1 &&
                   fread(v, 1, 1, f) == 1) {
            compression = v[0];
        }
        if (fseeko(f, (off_t)(at + len), SEEK_SET) != 0)
            return gk_fail(e, GK_EINPUT, "%s: cannot read the OpenEXR header", path);
        at += len;
    }
}

static int check_stream(FILE *f, const char *path, long long size, gk_err *e)
{
    unsigned char head[8];
    size_t got = fread(head, 1, sizeof head, f);
    if (got == 8 && memcmp(head, png_signature, 8) == 0)
        return check_png(f, path, size, e);
    if (got >= 4 && memcmp(head, exr_magic, 4) == 0)
        return check_exr(f, path, size, e);
    return 0;
}

int gk_image_check_layout(const char *path, gk_err *e)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return 0; /* the reader reports what stops it opening the file */
    struct stat st;
    int rc = fstat(fileno(f), &st) == 0 ? check_stream(f, path, (long long)st.st_size, e) : 0;
    fclose(f);
    return rc;
}

int gk_image_check_layout_memory(const void *data, size_t size, const char *name, gk_err *e)
{
    if (!data || size == 0)
        return 0;
    FILE *f = fmemopen((void *)data, size, "rb");
    if (!f)
        return 0;
    int rc = check_stream(f, name, (long long)size, e);
    fclose(f);
    return rc;
}
