/* A glyph atlas for the HUD: printable ASCII of a TrueType font baked with stb_truetype at a pixel
 * height chosen for the panel (~28 px at 1080 lines). CPU only (no GL), so it is testable. */
#ifndef GK_KIOSK_FONT_ATLAS_H
#define GK_KIOSK_FONT_ATLAS_H

#include "base/err.h"

#define GK_FONT_DEFAULT_PATH "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"
#define GK_FONT_FIRST 32
#define GK_FONT_COUNT 95

typedef struct gk_glyph {
    unsigned short x0, y0, x1, y1; /* atlas rectangle */
    float xoff, yoff, xadvance;    /* placement relative to the pen on the baseline */
} gk_glyph;

typedef struct gk_font_atlas {
    int width, height;
    unsigned char *pixels;         /* width*height coverage, row 0 at the top */
    float px;                      /* pixel height baked */
    gk_glyph glyphs[GK_FONT_COUNT];
    int white_x, white_y;          /* a 2x2 block of full coverage, for solid rectangles */
} gk_font_atlas;

/* The smallest HUD text: 14 px. stb_truetype's pixel height spans ascent to descent, so DejaVu Sans
 * capitals come out at about 0.6 of it: measured (tests/gpu/test_hud.c) 8 px high at 14 px, 7 at
 * 12, 12 at 720 lines (18.7 px), 18 at 1080 (28 px); the old floor of 10 px gave 6. */
#define GK_FONT_MIN_PX 14.0f
/* Pixel height of HUD text for a panel height: 28 px at 1080 lines, proportional, at least
 * GK_FONT_MIN_PX. */
float gk_font_px_for_height(int panel_height);
/* Bakes the font; GK_EINPUT if the file is missing or not a font. */
int gk_font_atlas_build(gk_font_atlas *a, const char *ttf_path, float px, gk_err *e);
void gk_font_atlas_free(gk_font_atlas *a);
/* Advance width of an ASCII string in pixels (other bytes count as '?'). */
float gk_font_text_width(const gk_font_atlas *a, const char *s);

#endif
