/* HUD overlay (see hud.h): one dynamic vertex buffer of quads per frame, one draw call. */
#include "hud.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/log.h"
#include "gl/gl.h"
#include "gl/gl_program.h"
#include "font_atlas.h"
#include "hud_internal.h"

/* hud/hud.{vert,frag} */
typedef struct hud_uniforms {
    GLint u_viewport, u_atlas;
} hud_uniforms;
static const gk_uniform_field hud_fields[] = {GK_UNIFORM(hud_uniforms, u_viewport), GK_UNIFORM(hud_uniforms, u_atlas)};


gk_hud *gk_hud_create(int width, int height, const char *shader_dir, int gles, const char *font_path, gk_err *e)
{
    gk_hud *h = calloc(1, sizeof *h);
    if (!h) {
        gk_fail(e, GK_ERUNTIME, "HUD: out of memory");
        return NULL;
    }
    h->width = width;
    h->height = height;
    gk_err fe = {0};
    const char *path = font_path ? font_path : GK_FONT_DEFAULT_PATH;
    if (gk_font_atlas_build(&h->font, path, gk_font_px_for_height(height), &fe) == 0) {
        h->has_text = 1;
    } else {
        gk_log("HUD without text: %s", fe.msg);
        /* A 4x4 atlas with the solid block keeps the graph working. */
        h->font.width = h->font.height = 4;
        h->font.pixels = calloc(16, 1);
        if (h->font.pixels)
            memset(h->font.pixels, 255, 16);
        h->font.white_x = h->font.white_y = 1;
    }
    h->programs = gk_program_cache_create(shader_dir, gles);
    if (!h->programs || !(h->program = gk_program_get(h->programs, "hud/hud.vert", "hud/hud.frag", NULL, e))) {
        if (h->programs && e && !e->msg[0])
            gk_fail(e, GK_ERUNTIME, "HUD: shader program failed");
        else if (!h->programs)
            gk_fail(e, GK_ERUNTIME, "HUD: cannot create the program cache");
        gk_hud_destroy(h);
        return NULL;
    }
    if (!(h->u = gk_program_uniforms(h->programs, h->program, GK_FIELDS(hud_fields), sizeof *h->u, e))) {
        gk_hud_destroy(h);
        return NULL;
    }
    GLint prev_tex, prev_align;
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &prev_tex);
    glGetIntegerv(GL_UNPACK_ALIGNMENT, &prev_align);
    glGenTextures(1, &h->atlas_tex);
    glBindTexture(GL_TEXTURE_2D, h->atlas_tex);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R8, h->font.width, h->font.height, 0, GL_RED, GL_UNSIGNED_BYTE, h->font.pixels);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glPixelStorei(GL_UNPACK_ALIGNMENT, prev_align);
    glBindTexture(GL_TEXTURE_2D, (GLuint)prev_tex);

    GLint prev_vao, prev_buf;
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &prev_vao);
    glGetIntegerv(GL_ARRAY_BUFFER_BINDING, &prev_buf);
    glGenVertexArrays(1, &h->vao);
    glGenBuffers(1, &h->vbo);
    glBindVertexArray(h->vao);
    glBindBuffer(GL_ARRAY_BUFFER, h->vbo);
    const GLsizei stride = FLOATS_PER_VERT * sizeof(float);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, stride, (void *)0);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, stride, (void *)(2 * sizeof(float)));
    glEnableVertexAttribArray(2);
    glVertexAttribPointer(2, 4, GL_FLOAT, GL_FALSE, stride, (void *)(4 * sizeof(float)));
    glBindVertexArray((GLuint)prev_vao);
    glBindBuffer(GL_ARRAY_BUFFER, (GLuint)prev_buf);
    GLenum err = glGetError();
    if (err != GL_NO_ERROR) {
        gk_fail(e, GK_ERUNTIME, "HUD: GL error 0x%x while creating textures and buffers", err);
        gk_hud_destroy(h);
        return NULL;
    }
    return h;
}

void gk_hud_destroy(gk_hud *h)
{
    if (!h)
        return;
    if (h->vbo)
        glDeleteBuffers(1, &h->vbo);
    if (h->vao)
        glDeleteVertexArrays(1, &h->vao);
    if (h->atlas_tex)
        glDeleteTextures(1, &h->atlas_tex);
    if (h->programs)
        gk_program_cache_destroy(h->programs);
    gk_font_atlas_free(&h->font);
    free(h->verts);
    free(h);
}

int gk_hud_has_text(const gk_hud *h) { return h && h->has_text; }

/* ---- geometry ------------------------------------------------------------------------------- */

void gk_hud_quad(gk_hud *h, float x0, float y0, float x1, float y1, float u0, float v0, float u1, float v1,
                 const float c[4])
{
    if (h->n_verts + 6 > h->cap_verts) {
        int cap = h->cap_verts ? h->cap_verts * 2 : 1536;
        float *v = realloc(h->verts, (size_t)cap * FLOATS_PER_VERT * sizeof *v);
        if (!v)
            return;
        h->verts = v;
        h->cap_verts = cap;
    }
    const float corners[6][4] = {{x0, y0, u0, v0}, {x1, y0, u1, v0}, {x1, y1, u1, v1},
                                 {x0, y0, u0, v0}, {x1, y1, u1, v1}, {x0, y1, u0, v1}};
    for (int i = 0; i < 6; i++) {
        float *o = h->verts + (size_t)(h->n_verts++) * FLOATS_PER_VERT;
        memcpy(o, corners[i], 4 * sizeof(float));
        memcpy(o + 4, c, 4 * sizeof(float));
    }
}

void gk_hud_rect(gk_hud *h, float x0, float y0, float x1, float y1, const float c[4])
{
    float u = (h->font.white_x + 1.0f) / (float)h->font.width, v = (h->font.white_y + 1.0f) / (float)h->font.height;
    gk_hud_quad(h, x0, y0, x1, y1, u, v, u, v, c);
}

/* Draws s with its baseline at y; returns the pen position after it. */
float gk_hud_text(gk_hud *h, float x, float y, const char *s, const float c[4])
{
    if (!h->has_text)
        return x;
    float iw = 1.0f / (float)h->font.width, ih = 1.0f / (float)h->font.height;
    for (; *s; s++) {
        int ch = (unsigned char)*s;
        if (ch < GK_FONT_FIRST || ch >= GK_FONT_FIRST + GK_FONT_COUNT)
            ch = '?';
        const gk_glyph *g = &h->font.glyphs[ch - GK_FONT_FIRST];
        float gx = (float)(int)(x + g->xoff + 0.5f), gy = (float)(int)(y + g->yoff + 0.5f);
        if (g->x1 > g->x0)
            gk_hud_quad(h, gx, gy, gx + (g->x1 - g->x0), gy + (g->y1 - g->y0), g->x0 * iw, g->y0 * ih, g->x1 * iw,
                 g->y1 * ih, c);
        x += g->xadvance;
    }
    return x;
}

int gk_hud_wrap(gk_hud *h, const char *text, float max_w, char (*out)[256], int max_lines)
{
    int n = 0;
    if (max_lines <= 0)
        return 0;
    out[0][0] = '\0';
    const char *p = text;
    while (*p) {
        const char *sep = strstr(p, "   ");
        size_t len = sep ? (size_t)(sep - p) : strlen(p);
        char trial[520];
        snprintf(trial, sizeof trial, "%s%s%.*s", out[n], out[n][0] ? "   " : "", (int)len, p);
        if (out[n][0] && gk_font_text_width(&h->font, trial) > max_w) {
            if (n + 1 == max_lines)
                return n + 1; /* the rest is left out */
            n++;
            snprintf(out[n], sizeof out[n], "%.*s", (int)len, p);
        } else {
            snprintf(out[n], sizeof out[n], "%.255s", trial);
        }
        p += len;
        while (*p == ' ')
            p++;
    }
    return out[n][0] ? n + 1 : n;
}

void gk_hud_draw(gk_hud *h, unsigned fbo, const gk_hud_info *in)
{
    static const float white[4] = {1, 1, 1, 1}, grey[4] = {0.75f, 0.75f, 0.75f, 1},
                       panel[4] = {0, 0, 0, 0.55f}, bar_ok[4] = {0.3f, 0.85f, 0.4f, 0.9f},
                       bar_over[4] = {0.95f, 0.35f, 0.25f, 0.9f}, target_line[4] = {1, 0.85f, 0.2f, 1};
    h->n_verts = 0;
    float px = gk_font_px_for_height(h->height);
    if (in->split)
        gk_hud_split_view(h, in, px); /* under the panels */
    if (in->panels_hidden)
        goto draw;
    /* Layout by panel size: corners only, never over the image centre (the middle third in both
       directions, GK_HUD_CENTRE_*): top-left the scene, frame times, error and the frame-time graph,
       within the left third; bottom-left the knob levels, within the left third and the bottom
       third; bottom-right the speed-vs-error plot (hud_truth.c). */
    float pad = px * 0.5f, line = px * 1.25f;
    float x0 = pad, y0 = pad;
    float graph_h = 3 * line;
    /* The top-left panel stays inside the left third (so the top middle, where a ceiling light
       usually is, stays clear): its lines are wrapped there, between items 3 spaces apart. */
    float panel_w = (float)h->width * (float)GK_HUD_CENTRE_LO - pad - 1;
    char groups[3][256], lines[GK_HUD_MAX_TOP_LINES][256];
    int n_lines = 0, first_grey = -1;
    snprintf(groups[0], sizeof groups[0], "%.63s   method %s%s%s%s", in->scene ? in->scene : "-",
             in->method ? in->method : "-", in->method_mode ? " (" : "", in->method_mode ? in->method_mode : "",
             in->method_mode ? ")" : "");
    snprintf(groups[1], sizeof groups[1], "frame %.1f ms   median %.1f   p95 %.1f   target %.1f", in->frame_ms,
             in->median_ms, in->p95_ms, in->target_ms);
    gk_hud_error_line(in, groups[2], sizeof groups[2]);
    for (int g = 0; g < 3 && h->has_text; g++) {
        if (!groups[g][0])
            continue;
        n_lines += gk_hud_wrap(h, groups[g], panel_w - 2 * pad, lines + n_lines, GK_HUD_MAX_TOP_LINES - n_lines);
        if (g == 0)
            first_grey = n_lines; /* the scene's own line is white, the rest of its group grey */
    }
    float limit = (float)h->height * (float)GK_HUD_CENTRE_HI - pad; /* above the knob panel's third */
    if (y0 + 2 * pad + n_lines * line + graph_h > limit)
        graph_h = limit - y0 - 2 * pad - n_lines * line;
    if (graph_h < line)
        graph_h = line;
    float panel_h = pad + n_lines * line + graph_h + pad;
    gk_hud_rect(h, x0, y0, x0 + panel_w, y0 + panel_h, panel);

    float y = y0 + pad + px; /* first baseline */
    for (int i = 0; i < n_lines; i++, y += line)
        gk_hud_text(h, x0 + pad, y, lines[i], i == 0 || i >= first_grey ? white : grey);
    if (n_lines > 0)
        y -= line * 0.5f; /* the graph starts half a line under the last baseline */
    /* Graph: the recent frame times as bars; full height = 2 x target, the target line across. */
    float gx0 = x0 + pad, gx1 = x0 + panel_w - pad, gy0 = y, gy1 = y + graph_h - line * 0.25f;
    float scale = in->target_ms > 0 ? (gy1 - gy0) / (float)(2 * in->target_ms) : 0;
    if (in->recent && in->recent->count > 0) {
        float bw = (gx1 - gx0) / GK_RECENT_FRAMES;
        for (int i = 0; i < in->recent->count; i++) {
            float ms = gk_recent_at(in->recent, i);
            float hgt = ms * scale;
            if (hgt > gy1 - gy0)
                hgt = gy1 - gy0;
            float bx = gx0 + (float)(GK_RECENT_FRAMES - in->recent->count + i) * bw;
            gk_hud_rect(h, bx, gy1 - hgt, bx + (bw > 2 ? bw - 1 : bw), gy1, ms > in->target_ms ? bar_over : bar_ok);
        }
    }
    float ty = gy1 - (float)in->target_ms * scale;
    gk_hud_rect(h, gx0, ty - 1, gx1, ty + 1, target_line);

    /* Knob levels, bottom-left: wrapped at the left third, as many lines as the bottom third holds
       (the rest are left out: the stats CSV has every knob). */
    float bw_max = (float)h->width / 3.0f - 2 * pad;
    int max_lines = (int)(((float)h->height / 3.0f - 3 * pad) / line);
    if (max_lines > GK_HUD_MAX_BUDGET_LINES)
        max_lines = GK_HUD_MAX_BUDGET_LINES;
    char budget_lines[GK_HUD_MAX_BUDGET_LINES][256];
    int n_budget_lines = 0;
    budget_lines[0][0] = '\0';
    if (h->has_text && in->budget && max_lines > 0) {
        for (int k = 0; k < in->budget->n; k++) {
            if (!gk_budget_knob_active(in->budget, k, in->method))
                continue; /* knobs of methods not on screen say nothing to a visitor */
            char item[96];
            snprintf(item, sizeof item, "%s%s=%s", budget_lines[n_budget_lines][0] ? "  " : "",
                     in->budget->def[k]->name, in->budget->def[k]->values[in->budget->level[k]]);
            char trial[352];
            snprintf(trial, sizeof trial, "%s%s", budget_lines[n_budget_lines], item);
            if (budget_lines[n_budget_lines][0] && gk_font_text_width(&h->font, trial) > bw_max - 2 * pad) {
                if (n_budget_lines == max_lines - 1)
                    break;
                n_budget_lines++;
                snprintf(budget_lines[n_budget_lines], sizeof budget_lines[0], "%s", item + 2);
            } else {
                snprintf(budget_lines[n_budget_lines], sizeof budget_lines[0], "%.255s", trial);
            }
        }
        if (budget_lines[n_budget_lines][0])
            n_budget_lines++;
    }
    if (n_budget_lines > 0) {
        float bw = 0;
        for (int i = 0; i < n_budget_lines; i++) {
            float w = gk_font_text_width(&h->font, budget_lines[i]);
            bw = w > bw ? w : bw;
        }
        float by1 = (float)h->height - pad, by0 = by1 - (2 * pad + (float)n_budget_lines * line);
        gk_hud_rect(h, x0, by0, x0 + bw + 2 * pad, by1, panel);
        y = by0 + pad + px;
        for (int i = 0; i < n_budget_lines; i++, y += line)
            gk_hud_text(h, x0 + pad, y, budget_lines[i], grey);
    }
    if (in->truth_note)
        gk_hud_error_plot(h, in, px);

draw:;

    /* Draw, saving and restoring the state we touch. */
    GLint prev_fbo, prev_prog, prev_vao, prev_buf, prev_tex, prev_active, vp[4];
    GLint bsrc_rgb, bdst_rgb, bsrc_a, bdst_a, beq_rgb, beq_a;
    GLboolean blend = glIsEnabled(GL_BLEND), depth = glIsEnabled(GL_DEPTH_TEST), cull = glIsEnabled(GL_CULL_FACE),
              scissor = glIsEnabled(GL_SCISSOR_TEST), stencil = glIsEnabled(GL_STENCIL_TEST);
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &prev_fbo);
    glGetIntegerv(GL_CURRENT_PROGRAM, &prev_prog);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &prev_vao);
    glGetIntegerv(GL_ARRAY_BUFFER_BINDING, &prev_buf);
    glGetIntegerv(GL_ACTIVE_TEXTURE, &prev_active);
    glActiveTexture(GL_TEXTURE0);
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &prev_tex);
    glGetIntegerv(GL_VIEWPORT, vp);
    glGetIntegerv(GL_BLEND_SRC_RGB, &bsrc_rgb);
    glGetIntegerv(GL_BLEND_DST_RGB, &bdst_rgb);
    glGetIntegerv(GL_BLEND_SRC_ALPHA, &bsrc_a);
    glGetIntegerv(GL_BLEND_DST_ALPHA, &bdst_a);
    glGetIntegerv(GL_BLEND_EQUATION_RGB, &beq_rgb);
    glGetIntegerv(GL_BLEND_EQUATION_ALPHA, &beq_a);

    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
    glViewport(0, 0, h->width, h->height);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_STENCIL_TEST);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    /* Colour blends over the image; the destination alpha (opaque panel) is kept. */
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
    glUseProgram(h->program);
    glUniform2f(h->u->u_viewport, (float)h->width, (float)h->height);
    glUniform1i(h->u->u_atlas, 0);
    glBindTexture(GL_TEXTURE_2D, h->atlas_tex);
    glBindVertexArray(h->vao);
    glBindBuffer(GL_ARRAY_BUFFER, h->vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)((size_t)h->n_verts * FLOATS_PER_VERT * sizeof(float)), h->verts,
                 GL_STREAM_DRAW);
    glDrawArrays(GL_TRIANGLES, 0, h->n_verts);

    glBindBuffer(GL_ARRAY_BUFFER, (GLuint)prev_buf);
    glBindVertexArray((GLuint)prev_vao);
    glBindTexture(GL_TEXTURE_2D, (GLuint)prev_tex);
    glActiveTexture((GLenum)prev_active);
    glUseProgram((GLuint)prev_prog);
    glBlendEquationSeparate((GLenum)beq_rgb, (GLenum)beq_a);
    glBlendFuncSeparate((GLenum)bsrc_rgb, (GLenum)bdst_rgb, (GLenum)bsrc_a, (GLenum)bdst_a);
    if (!blend)
        glDisable(GL_BLEND);
    if (depth)
        glEnable(GL_DEPTH_TEST);
    if (cull)
        glEnable(GL_CULL_FACE);
    if (scissor)
        glEnable(GL_SCISSOR_TEST);
    if (stencil)
        glEnable(GL_STENCIL_TEST);
    glViewport(vp[0], vp[1], vp[2], vp[3]);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)prev_fbo);
}
