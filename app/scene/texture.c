/* Textures of a scene, read through OpenImageIO (app/io/image_io.h) into linear float RGBA.
 * Base-colour textures are stored sRGB-encoded (glTF), so they are decoded to linear here once;
 * data textures (metallic-roughness) are used as stored. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "base/confine.h"
#include "core/tonemap.h"
#include "io/image_io.h"
#include "scene_internal.h"

/* glTF uris are URL-encoded ("my%20file.png"). */
static void uri_decode(const char *in, char *out, size_t cap)
{
    size_t o = 0;
    for (size_t i = 0; in[i] && o + 1 < cap; i++) {
        unsigned v;
        if (in[i] == '%' && in[i + 1] && in[i + 2] && sscanf(in + i + 1, "%2x", &v) == 1) {
            out[o++] = (char)v;
            i += 2;
        } else {
            out[o++] = in[i];
        }
    }
    out[o] = '\0';
}

static int to_rgba(gk_texture *t, const gk_image *img, bool srgb)
{
    size_t n = (size_t)img->width * (size_t)img->height;
    t->rgba = malloc((n ? n : 1) * 4 * sizeof(float));
    if (!t->rgba)
        return -1;
    t->width = img->width;
    t->height = img->height;
    for (size_t i = 0; i < n; i++) {
        const float *p = img->pixels + i * (size_t)img->channels;
        float rgba[4] = {p[0], p[0], p[0], 1.0f};
        if (img->channels == 2)
            rgba[3] = p[1];
        if (img->channels >= 3)
            rgba[1] = p[1], rgba[2] = p[2];
        if (img->channels == 4)
            rgba[3] = p[3];
        for (int c = 0; c < 3 && srgb; c++)
            rgba[c] = gk_srgb_to_linear(rgba[c]);
        memcpy(t->rgba + 4 * i, rgba, sizeof rgba);
    }
    return 0;
}

/* metallic_mean and roughness_mean of every material (scene.h), once its textures are decoded. */
static void material_means(gk_scene *s)
{
    for (int m = 0; m < s->n_materials; m++) {
        gk_material *mat = &s->materials[m];
        mat->metallic_mean = mat->metallic;
        mat->roughness_mean = mat->roughness;
        int ti = mat->metallic_roughness_tex;
        if (ti < 0 || ti >= s->n_textures || !s->textures[ti].rgba)
            continue;
        const gk_texture *t = &s->textures[ti];
        size_t n = (size_t)t->width * (size_t)t->height;
        double g = 0, b = 0;
        for (size_t i = 0; i < n; i++)
            g += t->rgba[4 * i + 1], b += t->rgba[4 * i + 2];
        if (n) {
            mat->roughness_mean = mat->roughness * (float)(g / (double)n);
            mat->metallic_mean = mat->metallic * (float)(b / (double)n);
        }
    }
}

int gk_scene_load_textures(gk_scene *s, const char *base_dir, const int *tex_usage, gk_err *e)
{
    for (int i = 0; i < s->n_textures; i++) {
        gk_texture *t = &s->textures[i];
        bool srgb = tex_usage && (tex_usage[i] & GK_TEX_USED_AS_COLOR);
        if (t->embedded) {
            char name[600];
            snprintf(name, sizeof name, "%s: texture %d (embedded %s)", s->path, i, t->mime[0] ? t->mime : "image");
            gk_image img = {0};
            if (gk_image_read_memory(t->embedded, t->embedded_size, name, &img, e) != 0)
                return -1;
            int rc = img.channels >= 1 && img.channels <= 4 ? to_rgba(t, &img, srgb) : -1;
            gk_image_free(&img);
            free(t->embedded);
            t->embedded = NULL;
            if (rc != 0)
                return gk_fail(e, GK_EINPUT, "%s: unusable layout or out of memory", name);
            continue;
        }
        if (!base_dir)
            return gk_fail(e, GK_EINPUT, "%s: texture %d: image '%s' cannot be read (no base directory)", s->path, i,
                           t->uri);
        char rel[256], path[1024];
        uri_decode(t->uri, rel, sizeof rel);
        if (rel[0] == '/' || strstr(rel, ".."))
            return gk_fail(e, GK_EINPUT, "%s: texture %d: image uri '%s' must be relative, inside the scene's folder",
                           s->path, i, t->uri);
        snprintf(path, sizeof path, "%s/%s", base_dir, rel);
        /* the name passed, but a symlink in the folder may still point outside it (found by
           tests/fuzz/fuzz_gltf_files.c): resolved, the file must lie inside, as a buffer's must */
        struct stat st;
        if (stat(path, &st) == 0 && !gk_path_inside_dir(path, base_dir))
            return gk_fail(e, GK_EINPUT, "%s: texture %d: image '%s' lies outside the scene's folder (a symlink out of it)",
                           s->path, i, t->uri);
        gk_image img = {0};
        gk_err ie = {0};
        if (gk_image_read(path, &img, &ie) != 0)
            return gk_fail(e, GK_EINPUT, "%s: texture %d: image '%s' is missing or unreadable (%s)", s->path, i, t->uri,
                           ie.msg);
        int rc = img.channels >= 1 && img.channels <= 4 ? to_rgba(t, &img, srgb) : -1;
        gk_image_free(&img);
        if (rc != 0)
            return gk_fail(e, GK_EINPUT, "%s: texture %d: image '%s' has an unusable layout", s->path, i, t->uri);
    }
    material_means(s);
    return 0;
}
