/* Inside the HUD (hud.c): its state and the quad builders its parts share (hud_truth.c draws the
 * live error's plot and the split view with them). Coordinates are pixels, y down. */
#ifndef GK_KIOSK_HUD_INTERNAL_H
#define GK_KIOSK_HUD_INTERNAL_H

#include "gl/gl.h"
#include "gl/gl_program.h"
#include "font_atlas.h"
#include "hud.h"

struct gk_hud {
    int width, height;
    gk_program_cache *programs;
    GLuint program, vao, vbo, atlas_tex;
    const struct hud_uniforms *u;         /* resolved with the program, kept by the cache */
    gk_font_atlas font;
    int has_text;
    float *verts;                  /* x y u v r g b a per vertex */
    int n_verts, cap_verts;
};

#define FLOATS_PER_VERT 8
#define GK_HUD_MAX_BUDGET_LINES 8
#define GK_HUD_MAX_TOP_LINES 8

/* Wraps text (items separated by 3 spaces) into lines of at most max_w pixels; returns the count. */
int gk_hud_wrap(gk_hud *h, const char *text, float max_w, char (*out)[256], int max_lines);

void gk_hud_quad(gk_hud *h, float x0, float y0, float x1, float y1, float u0, float v0, float u1, float v1,
                 const float c[4]);
/* A solid rectangle. */
void gk_hud_rect(gk_hud *h, float x0, float y0, float x1, float y1, const float c[4]);
/* Draws s with its baseline at y; returns the pen position after it. */
float gk_hud_text(gk_hud *h, float x, float y, const char *s, const float c[4]);

/* hud_truth.c: the split view (under everything else) and the speed-vs-error plot (a corner). */
void gk_hud_split_view(gk_hud *h, const gk_hud_info *in, float px);
void gk_hud_error_plot(gk_hud *h, const gk_hud_info *in, float px);
/* The line of the live error under the frame time ("" when [truth] is off). */
void gk_hud_error_line(const gk_hud_info *in, char *out, int len);

#endif
