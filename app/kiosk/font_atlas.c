/* HUD glyph atlas (see font_atlas.h). Debian's libstb (-lstb) carries stb_truetype's
 * implementation, so only the declarations are included here. */
#include "font_atlas.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <stb_truetype.h>

float gk_font_px_for_height(int panel_height)
{
    float px = 28.0f * (float)panel_height / 1080.0f;
    return px < GK_FONT_MIN_PX ? GK_FONT_MIN_PX : px;
}

static unsigned char *read_file(const char *path, long *len, gk_err *e)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        gk_fail(e, GK_EINPUT, "%s: cannot open font: %s", path, strerror(errno));
        return NULL;
    }
    unsigned char *data = NULL;
    if (fseek(f, 0, SEEK_END) == 0 && (*len = ftell(f)) > 0 && fseek(f, 0, SEEK_SET) == 0 &&
        (data = malloc((size_t)*len)) && fread(data, 1, (size_t)*len, f) != (size_t)*len) {
        free(data);
        data = NULL;
    }
    fclose(f);
    if (!data)
        gk_fail(e, GK_EINPUT, "%s: cannot read font", path);
    return data;
}

int gk_font_atlas_build(gk_font_atlas *a, const char *ttf_path, float px, gk_err *e)
{
    memset(a, 0, sizeof *a);
    long len = 0;
    unsigned char *ttf = read_file(ttf_path, &len, e);
    if (!ttf)
        return -1;
    stbtt_fontinfo info;
    if (len < 12 || stbtt_GetFontOffsetForIndex(ttf, 0) < 0 || !stbtt_InitFont(&info, ttf, stbtt_GetFontOffsetForIndex(ttf, 0))) {
        free(ttf);
        return gk_fail(e, GK_EINPUT, "%s: not a TrueType font", ttf_path);
    }
    stbtt_bakedchar baked[GK_FONT_COUNT];
    /* Grow the atlas until every glyph fits with two rows to spare for the solid block. */
    for (int w = 256; w <= 4096; w *= 2) {
        int h = w / 2;
        unsigned char *pix = calloc((size_t)w * (size_t)h, 1);
        if (!pix)
            break;
        int rows = stbtt_BakeFontBitmap(ttf, 0, px, pix, w, h, GK_FONT_FIRST, GK_FONT_COUNT, baked);
        if (rows > 0 && rows + 3 <= h) {
            a->width = w;
            a->height = h;
            a->pixels = pix;
            a->px = px;
            a->white_x = 1;
            a->white_y = h - 3;
            for (int y = a->white_y; y < a->white_y + 2; y++)
                memset(pix + (size_t)y * (size_t)w + a->white_x, 255, 2);
            for (int i = 0; i < GK_FONT_COUNT; i++)
                a->glyphs[i] = (gk_glyph){baked[i].x0, baked[i].y0, baked[i].x1, baked[i].y1,
                                          baked[i].xoff, baked[i].yoff, baked[i].xadvance};
            free(ttf);
            return 0;
        }
        free(pix);
    }
    free(ttf);
    return gk_fail(e, GK_ERUNTIME, "%s: glyphs at %.0f px do not fit a 4096x2048 atlas", ttf_path, px);
}

void gk_font_atlas_free(gk_font_atlas *a)
{
    free(a->pixels);
    memset(a, 0, sizeof *a);
}

float gk_font_text_width(const gk_font_atlas *a, const char *s)
{
    float w = 0;
    for (; *s; s++) {
        int c = (unsigned char)*s;
        if (c < GK_FONT_FIRST || c >= GK_FONT_FIRST + GK_FONT_COUNT)
            c = '?';
        w += a->glyphs[c - GK_FONT_FIRST].xadvance;
    }
    return w;
}
