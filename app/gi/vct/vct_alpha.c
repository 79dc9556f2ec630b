/* alphaMode MASK in the compute voxelizer (vct/voxelize.comp): the alpha channel of every masked
 * material's base-colour texture, one layer each of an R8 2D array texture, which the voxelizer
 * samples (textureLod, GLES 3.1 compute) at the voxel's point on the triangle. One array has one
 * size and one sampler: layers are the largest masked texture's size (a smaller texture is
 * resampled nearest to it), sampled bilinearly with REPEAT whatever the glTF sampler says (both
 * approximations; a texture of the largest size, as in a scene with one mask, is copied exactly). */
#include <stdlib.h>

#include "vct_internal.h"

int vct_alpha_layers(const gk_scene *s, int *layer)
{
    int n = 0;
    for (int i = 0; i < s->n_materials; i++) {
        const gk_material *m = &s->materials[i];
        bool textured = m->base_color_tex >= 0 && m->base_color_tex < s->n_textures &&
                        s->textures[m->base_color_tex].rgba;
        layer[i] = m->alpha_mask && textured ? n++ : -1;
    }
    return n;
}

/* texel (x, y) of a w x h layer: texture t's alpha at the same place, nearest */
static unsigned char layer_texel(const gk_texture *t, int x, int y, int w, int h)
{
    int tx = (int)(((long)x * t->width) / w), ty = (int)(((long)y * t->height) / h);
    float a = t->rgba[((size_t)ty * (size_t)t->width + (size_t)tx) * 4 + 3];
    a = a < 0.0f ? 0.0f : (a > 1.0f ? 1.0f : a);
    return (unsigned char)(a * 255.0f + 0.5f);
}

int vct_alpha_upload(gk_vct *v, const gk_scene *s, gk_err *e)
{
    if (v->alpha_tex)
        glDeleteTextures(1, &v->alpha_tex);
    v->alpha_tex = 0;
    int *layer = malloc(sizeof(int) * (size_t)(s->n_materials ? s->n_materials : 1));
    if (!layer)
        return gk_fail(e, GK_ERUNTIME, "vct: out of memory for the alpha-mask layers");
    int n = vct_alpha_layers(s, layer), w = 1, h = 1;
    for (int i = 0; i < s->n_materials; i++)
        if (layer[i] >= 0) {
            const gk_texture *t = &s->textures[s->materials[i].base_color_tex];
            w = t->width > w ? t->width : w;
            h = t->height > h ? t->height : h;
        }
    /* no masked texture: one opaque texel, so the sampler is complete (the voxelizer never reads it) */
    size_t texels = (size_t)w * (size_t)h;
    unsigned char *data = malloc(texels * (size_t)(n ? n : 1));
    if (!data) {
        free(layer);
        return gk_fail(e, GK_ERUNTIME, "vct: out of memory for %d alpha-mask layers of %dx%d", n, w, h);
    }
    data[0] = 255;
    for (int i = 0; i < s->n_materials; i++)
        if (layer[i] >= 0) {
            const gk_texture *t = &s->textures[s->materials[i].base_color_tex];
            for (int y = 0; y < h; y++)
                for (int x = 0; x < w; x++)
                    data[(size_t)layer[i] * texels + (size_t)y * (size_t)w + (size_t)x] = layer_texel(t, x, y, w, h);
        }
    glGenTextures(1, &v->alpha_tex);
    glBindTexture(GL_TEXTURE_2D_ARRAY, v->alpha_tex);
    glTexStorage3D(GL_TEXTURE_2D_ARRAY, 1, GL_R8, w, h, n ? n : 1);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, 0, w, h, n ? n : 1, GL_RED, GL_UNSIGNED_BYTE, data);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_REPEAT);
    glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
    free(data);
    free(layer);
    return 0;
}
