/* libFuzzer target for the image readers `gikiosk compare` uses (gk_image_read and
 * gk_image_read_attr, app/io/image_io.cpp, OpenImageIO underneath): the input is written to a file
 * named .exr when it starts with OpenEXR's magic number and .png otherwise, as compare is handed
 * a reference EXR and a capture PNG. Any input must read, or fail with GK_EINPUT naming the file;
 * no crash, leak, hang, runaway allocation (the harness runs with -rss_limit_mb/-malloc_limit_mb)
 * or undefined behaviour. An image that reads must have the shape the header promised: 1 to 4
 * channels, a positive size. OpenImageIO and the codecs are not instrumented for coverage, so the
 * fuzzer steers by our shim's branches and the seed corpus' variety; this target looks for what
 * reaches gikiosk from a hostile file, not for codec bugs. */
#include <stdbool.h>
#include <stdint.h>

#include "base/log.h"
#include "fuzz_files.h"
#include "io/image_io.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    gk_log_set_quiet(1);
    static const uint8_t exr_magic[4] = {0x76, 0x2f, 0x31, 0x01};
    bool exr = size >= 4 && memcmp(data, exr_magic, 4) == 0;
    char path[300];
    snprintf(path, sizeof path, "%s/image.%s", fuzz_dir(), exr ? "exr" : "png");
    fuzz_write_file(path, data, size);
    gk_image img = {0};
    gk_err e = {0};
    if (gk_image_read(path, &img, &e) != 0) {
        if (e.code != GK_EINPUT || img.pixels)
            abort();
        fuzz_require_named(e.msg, path);
    } else {
        if (!img.pixels || img.width <= 0 || img.height <= 0 || img.channels < 1 || img.channels > 4)
            abort();
        gk_image_free(&img);
    }
    char value[256];
    gk_err ae = {0};
    if (gk_image_read_attr(path, "gikiosk:command", value, sizeof value, &ae) < 0) {
        if (ae.code != GK_EINPUT)
            abort();
        fuzz_require_named(ae.msg, path);
    }
    return 0;
}
