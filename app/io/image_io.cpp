// OpenImageIO shim behind app/io/image_io.h: the only C++ in the image path. Every OIIO call is
// wrapped so no C++ exception or object escapes into the C code.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

extern "C" {
#include "base/outfile.h"
#include "base/readfile.h"
#include "io/image_io.h"
#include "io/image_layout.h"
}

namespace {

// The largest image file read (compare, textures): 1 GiB, beyond any capture or reference
// (a 4096x4096 RGBA float EXR is 256 MiB).
const size_t kMaxImageFileBytes = size_t(1) << 30;

// Pixels come back exactly as stored: OIIO would otherwise premultiply PNG/TIFF colour by alpha.
OIIO::ImageSpec read_config()
{
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    return config;
}

std::string lower_extension(const char *path)
{
    std::string p(path);
    size_t slash = p.find_last_of('/');
    size_t dot = p.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
        return "";
    std::string ext = p.substr(dot + 1);
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return (char)std::tolower(c); });
    return ext;
}

// OIIO error strings can span lines; one line reads better after "file: ".
std::string one_line(std::string s)
{
    while (!s.empty() && (s.back() == '\n' || s.back() == ' '))
        s.pop_back();
    std::replace(s.begin(), s.end(), '\n', ' ');
    return s.empty() ? std::string("unknown error") : s;
}

enum class PixelStore { uint8, half, float32 };

PixelStore store_for(const std::string &ext, bool exr_float)
{
    if (ext == "exr")
        return exr_float ? PixelStore::float32 : PixelStore::half;
    if (ext == "hdr" || ext == "tif" || ext == "tiff" || ext == "pfm")
        return PixelStore::float32;
    return PixelStore::uint8;
}

int write_image(const char *path, const gk_image *img, const gk_image_meta *meta, bool exr_float, gk_err *e)
{
    if (!img || !img->pixels || img->width <= 0 || img->height <= 0 || img->channels < 1 || img->channels > 4)
        return gk_fail(e, GK_ERUNTIME, "%s: cannot write an empty or malformed image", path);
    try {
        auto out = OIIO::ImageOutput::create(path);
        if (!out)
            return gk_fail(e, GK_EINPUT, "%s: no image format for this extension (%s)", path,
                           one_line(OIIO::geterror()).c_str());
        std::string ext = lower_extension(path);
        PixelStore store = store_for(ext, exr_float);
        OIIO::TypeDesc type = store == PixelStore::uint8 ? OIIO::TypeDesc::UINT8
                              : store == PixelStore::half ? OIIO::TypeDesc::HALF
                                                          : OIIO::TypeDesc::FLOAT;
        OIIO::ImageSpec spec(img->width, img->height, img->channels, type);
        if (meta)
            for (int i = 0; i < meta->count && i < (int)(sizeof meta->keys / sizeof meta->keys[0]); i++)
                if (meta->keys[i] && meta->values[i])
                    spec.attribute(meta->keys[i], meta->values[i]);
        if (ext == "exr")
            spec.attribute("compression", "zip");
        // Our pixels are stored as given (alpha not premultiplied): tell OIIO not to divide by alpha.
        spec.attribute("oiio:UnassociatedAlpha", 1);

        size_t n = (size_t)img->width * img->height * img->channels;
        const float *src = img->pixels;
        float *clamped = nullptr;
        if (store == PixelStore::uint8) { // display-referred: clamp, no colour conversion
            clamped = (float *)malloc(n * sizeof(float));
            if (!clamped)
                return gk_fail(e, GK_ERUNTIME, "%s: out of memory", path);
            for (size_t i = 0; i < n; i++) {
                float v = src[i];
                clamped[i] = std::isnan(v) ? 0.0f : std::min(1.0f, std::max(0.0f, v));
            }
            src = clamped;
        }
        // Encoded in memory (OIIO's IOProxy), then written to a temporary file beside the target
        // with every write checked and renamed over it once complete (base/outfile.h): a full
        // disk never leaves a truncated image nor destroys the previous one. (OIIO's PNG writer
        // does not notice a failing write; going through memory makes every format's failure
        // ours to see.)
        std::vector<unsigned char> encoded;
        OIIO::Filesystem::IOVecOutput vec_out(encoded);
        bool in_memory = out->supports("ioproxy");
        if (in_memory) {
            void *proxy = &vec_out;
            spec.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
        }
        gk_outfile tmp;
        if (in_memory ? gk_outfile_open(&tmp, path, e) : gk_outfile_reserve(&tmp, path, e)) {
            free(clamped);
            return -1;
        }
        bool ok = out->open(in_memory ? path : tmp.tmp, spec) && out->write_image(OIIO::TypeDesc::FLOAT, src);
        std::string err = ok ? "" : one_line(out->geterror());
        bool closed = out->close();
        if (ok && !closed)
            err = one_line(out->geterror());
        free(clamped);
        if (!ok || !closed) {
            gk_outfile_discard(&tmp);
            return gk_fail(e, GK_ERUNTIME, "%s: cannot write image: %s", path, err.c_str());
        }
        if (in_memory && !encoded.empty())
            fwrite(encoded.data(), 1, encoded.size(), tmp.f); // checked by the commit (ferror)
        return gk_outfile_commit(&tmp, e);
    } catch (const std::exception &ex) {
        return gk_fail(e, GK_ERUNTIME, "%s: cannot write image: %s", path, ex.what());
    }
}

} // namespace

extern "C" int gk_image_alloc(gk_image *img, int width, int height, int channels)
{
    img->width = img->height = img->channels = 0;
    img->pixels = nullptr;
    if (width <= 0 || height <= 0 || channels < 1 || channels > 4 || (size_t)width * height > (size_t)1 << 28)
        return -1;
    img->pixels = (float *)calloc((size_t)width * height * channels, sizeof(float));
    if (!img->pixels)
        return -1;
    img->width = width;
    img->height = height;
    img->channels = channels;
    return 0;
}

extern "C" void gk_image_free(gk_image *img)
{
    if (!img)
        return;
    free(img->pixels);
    img->pixels = nullptr;
    img->width = img->height = img->channels = 0;
}

namespace {

// Reads the first subimage of an opened input into img as float, at most 4 channels.
int read_opened(OIIO::ImageInput *in, const char *path, gk_image *img, gk_err *e)
{
    const OIIO::ImageSpec &spec = in->spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || spec.depth > 1)
        return gk_fail(e, GK_EINPUT, "%s: not a 2D image (%dx%dx%d, %d channels)", path, spec.width, spec.height,
                       spec.depth, spec.nchannels);
    int channels = std::min(spec.nchannels, 4);
    // A side over MAX_SIDE is refused before OpenImageIO reads it: its read_scanlines allocates a
    // buffer of many scan lines, so a one-line EXR 16,777,219 pixels wide (the fuzzer's 679-byte file,
    // tests/fuzz/corpus/image/found-width-16777219.exr; 2^24 pixels, under the pixel cap) made it ask
    // for 34 GB. No texture, environment map or reference is that wide: GLES textures end at
    // GL_MAX_TEXTURE_SIZE (16384 on the boards and llvmpipe).
    const int MAX_SIDE = 32768;
    if (spec.width > MAX_SIDE || spec.height > MAX_SIDE)
        return gk_fail(e, GK_EINPUT, "%s: image too large (%dx%d: a side over %d)", path, spec.width, spec.height,
                       MAX_SIDE);
    if (gk_image_alloc(img, spec.width, spec.height, channels) != 0)
        return gk_fail(e, GK_EINPUT, "%s: image too large (%dx%d)", path, spec.width, spec.height);
    if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, img->pixels)) {
        std::string err = one_line(in->geterror());
        gk_image_free(img);
        return gk_fail(e, GK_EINPUT, "%s: cannot read image: %s", path, err.c_str());
    }
    in->close();
    return 0;
}

// The format of an encoded image from its signature: what glTF images are (PNG, JPEG), plus the
// KTX2 container of KHR_texture_basisu, recognised only to be refused by name.
const char *sniff_extension(const unsigned char *d, size_t n)
{
    static const unsigned char png[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    static const unsigned char ktx2[12] = {0xab, 'K', 'T', 'X', ' ', '2', '0', 0xbb, '\r', '\n', 0x1a, '\n'};
    if (n >= 8 && memcmp(d, png, 8) == 0)
        return "png";
    if (n >= 3 && d[0] == 0xff && d[1] == 0xd8 && d[2] == 0xff)
        return "jpg";
    if (n >= 12 && memcmp(d, ktx2, 12) == 0)
        return "ktx2";
    if (n >= 4 && memcmp(d, "\x76\x2f\x31\x01", 4) == 0)
        return "exr";
    return "";
}

} // namespace

extern "C" int gk_image_read(const char *path, gk_image *img, gk_err *e)
{
    img->width = img->height = img->channels = 0;
    img->pixels = nullptr;
    // A regular file of bounded size, checked before OIIO opens it: `compare REF /dev/zero` would
    // otherwise read forever, and a directory or FIFO would block or read as garbage.
    if (gk_check_regular_file(path, "image", kMaxImageFileBytes, e))
        return -1;
    // Lengths in PNG chunks and EXR headers must fit in the file before OIIO allocates them.
    if (gk_image_check_layout(path, e))
        return -1;
    try {
        OIIO::ImageSpec config = read_config();
        auto in = OIIO::ImageInput::open(path, &config);
        if (!in)
            return gk_fail(e, GK_EINPUT, "%s: cannot read image: %s", path, one_line(OIIO::geterror()).c_str());
        return read_opened(in.get(), path, img, e);
    } catch (const std::exception &ex) {
        gk_image_free(img);
        return gk_fail(e, GK_EINPUT, "%s: cannot read image: %s", path, ex.what());
    }
}

extern "C" int gk_image_read_memory(const void *data, size_t size, const char *name, gk_image *img, gk_err *e)
{
    img->width = img->height = img->channels = 0;
    img->pixels = nullptr;
    if (!data || size == 0)
        return gk_fail(e, GK_EINPUT, "%s: the image holds no bytes", name);
    if (size > kMaxImageFileBytes)
        return gk_fail(e, GK_EINPUT, "%s: image too large (%zu bytes)", name, size);
    if (gk_image_check_layout_memory(data, size, name, e))
        return -1;
    std::string ext = sniff_extension((const unsigned char *)data, size);
    if (ext.empty())
        ext = lower_extension(name);
    if (ext == "ktx2")
        return gk_fail(e, GK_EINPUT, "%s: KTX2 / Basis Universal images (KHR_texture_basisu) are not supported: no "
                       "Debian library decodes them; ship PNG or JPEG", name);
    if (ext.empty())
        return gk_fail(e, GK_EINPUT, "%s: unrecognised image format (PNG and JPEG are what glTF allows)", name);
    try {
        OIIO::ImageSpec config = read_config();
        // OIIO picks the reader by the name's extension and reads through the proxy, handed over
        // as the "oiio:ioproxy" attribute of the open configuration (OIIO 2.x).
        OIIO::Filesystem::IOMemReader reader(const_cast<void *>(data), size);
        void *proxy = &reader;
        config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
        std::string fake = std::string("embedded.") + ext;
        auto in = OIIO::ImageInput::open(fake, &config);
        if (!in)
            return gk_fail(e, GK_EINPUT, "%s: cannot read image: %s", name, one_line(OIIO::geterror()).c_str());
        return read_opened(in.get(), name, img, e);
    } catch (const std::exception &ex) {
        gk_image_free(img);
        return gk_fail(e, GK_EINPUT, "%s: cannot read image: %s", name, ex.what());
    }
}

extern "C" int gk_image_read_attr(const char *path, const char *key, char *out, int out_len, gk_err *e)
{
    if (out && out_len > 0)
        out[0] = '\0';
    if (gk_check_regular_file(path, "image", kMaxImageFileBytes, e) || gk_image_check_layout(path, e))
        return -1;
    try {
        auto in = OIIO::ImageInput::open(path);
        if (!in)
            return gk_fail(e, GK_EINPUT, "%s: cannot read image: %s", path, one_line(OIIO::geterror()).c_str());
        const OIIO::ParamValue *p = in->spec().find_attribute(key, OIIO::TypeDesc::STRING);
        if (!p)
            return 1;
        std::string value = in->spec().get_string_attribute(key);
        if (out && out_len > 0)
            snprintf(out, (size_t)out_len, "%s", value.c_str());
        in->close();
        return 0;
    } catch (const std::exception &ex) {
        return gk_fail(e, GK_EINPUT, "%s: cannot read image: %s", path, ex.what());
    }
}

extern "C" int gk_image_write(const char *path, const gk_image *img, const gk_image_meta *meta, gk_err *e)
{
    return write_image(path, img, meta, false, e);
}

extern "C" int gk_image_write_float(const char *path, const gk_image *img, const gk_image_meta *meta, gk_err *e)
{
    return write_image(path, img, meta, true, e);
}
