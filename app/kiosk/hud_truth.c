/* The HUD's parts of the live error (issue 19): the error line, the speed-vs-error plot and the
 * split view. Quads only (hud_internal.h): the truth image is drawn as one solid quad per truth
 * pixel, tonemapped here as the compose pass tonemaps the frame, so no shader is added. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/tonemap.h"
#include "hud_internal.h"
#include "live_error.h"

void gk_hud_error_line(const gk_hud_info *in, char *out, int len)
{
    if (!in->truth_note)
        out[0] = '\0';
    else if (in->truth_note[0])
        snprintf(out, (size_t)len, "%s", in->truth_note);
    else if (!isfinite(in->error))
        snprintf(out, (size_t)len, "error: waiting for the truth's first pass");
    else if (isfinite(in->truth_noise))
        snprintf(out, (size_t)len, "error %.3f   truth %ld spp   noise %.3f", in->error, in->truth_spp, in->truth_noise);
    else
        snprintf(out, (size_t)len, "error %.3f   truth %ld spp", in->error, in->truth_spp);
}

/* A colour per method name (a small fixed palette), so one method's points read as one series. */
static void method_colour(const char *m, float c[4])
{
    static const float palette[6][3] = {{0.35f, 0.75f, 1.0f}, {1.0f, 0.55f, 0.3f}, {0.6f, 0.95f, 0.4f},
                                        {0.95f, 0.45f, 0.85f}, {0.95f, 0.95f, 0.4f}, {0.6f, 0.6f, 1.0f}};
    unsigned hsh = 5381;
    for (; *m; m++)
        hsh = hsh * 33u + (unsigned char)*m;
    memcpy(c, palette[hsh % 6], 3 * sizeof(float));
    c[3] = 1;
}

/* Judged frames a point needs before it is plotted: one or two frames at a new level can still
 * carry one-off costs the warm-up rule missed (a 1.5 s mean stretched the axis of the first
 * screenshots); ten is a sixth of a second at 60 Hz. */
#define PLOT_MIN_FRAMES 10

void gk_hud_error_plot(gk_hud *h, const gk_hud_info *in, float px)
{
    static const float panel[4] = {0, 0, 0, 0.55f}, axis[4] = {0.75f, 0.75f, 0.75f, 1},
                       ring[4] = {1, 1, 1, 1}, grey[4] = {0.75f, 0.75f, 0.75f, 1};
    /* bottom-right corner: 16 x 10 text heights, at most the right third wide, so clear of the
       centre (hud.h's layout rule) */
    float pad = px * 0.5f, w = 16 * px, hgt = 10 * px;
    if (w > (float)h->width * (float)(1 - GK_HUD_CENTRE_HI) - 2 * pad)
        w = (float)h->width * (float)(1 - GK_HUD_CENTRE_HI) - 2 * pad;
    float x1 = (float)h->width - pad, y1 = (float)h->height - pad, x0 = x1 - w, y0 = y1 - hgt;
    gk_hud_rect(h, x0, y0, x1, y1, panel);
    gk_hud_text(h, x0 + pad, y0 + pad + px, "error", grey);
    float ax0 = x0 + pad + 0.5f * px, ax1 = x1 - pad, ay0 = y0 + pad + 1.5f * px, ay1 = y1 - pad - 1.5f * px;
    gk_hud_rect(h, ax0, ay1, ax1, ay1 + 1, axis);
    gk_hud_rect(h, ax0, ay0, ax0 + 1, ay1, axis);
    double max_ms = in->target_ms, max_err = 0;
    for (int i = 0; i < in->n_points; i++) {
        const gk_live_point *p = &in->points[i];
        if (p->frames < PLOT_MIN_FRAMES || !isfinite(p->error))
            continue;
        if (p->ms_sum / p->frames > max_ms)
            max_ms = p->ms_sum / p->frames;
        if (isfinite(p->error) && p->error > max_err)
            max_err = p->error;
    }
    max_ms *= 1.1;
    max_err = max_err > 0 ? max_err * 1.1 : 1;
    char buf[64];
    snprintf(buf, sizeof buf, "frame ms (0-%.0f)", max_ms);
    gk_hud_text(h, ax1 - gk_font_text_width(&h->font, buf), y1 - pad, buf, grey);
    snprintf(buf, sizeof buf, "max %.2f", max_err);
    gk_hud_text(h, ax1 - gk_font_text_width(&h->font, buf), y0 + pad + px, buf, grey);
    for (int i = 0; i < in->n_points; i++) {
        const gk_live_point *p = &in->points[i];
        if (p->frames < PLOT_MIN_FRAMES || !isfinite(p->error))
            continue; /* not measured yet: no place on the plot */
        float x = ax0 + (float)(p->ms_sum / p->frames / max_ms) * (ax1 - ax0);
        float y = ay1 - (float)(p->error / max_err) * (ay1 - ay0);
        float c[4], r = px * 0.3f;
        method_colour(p->method, c);
        if (i == in->current_point) { /* the point now shown: larger, ringed */
            r = px * 0.55f;
            gk_hud_rect(h, x - r - 2, y - r - 2, x + r + 2, y + r + 2, ring);
        }
        gk_hud_rect(h, x - r, y - r, x + r, y + r, c);
    }
}

void gk_hud_split_view(gk_hud *h, const gk_hud_info *in, float px)
{
    static const float divider[4] = {1, 1, 1, 1}, panel[4] = {0, 0, 0, 0.55f}, white[4] = {1, 1, 1, 1};
    float mid = (float)(h->width / 2);
    if (in->truth_rgb && in->truth_sub > 0) {
        float s = (float)in->truth_sub;
        for (int y = 0; y < in->truth_h; y++)
            for (int x = 0; x < in->truth_w; x++) {
                float qx0 = (float)x * s, qx1 = qx0 + s;
                if (qx1 <= mid)
                    continue;
                const float *v = &in->truth_rgb[3 * ((size_t)y * in->truth_w + x)];
                float c[4] = {gk_tonemap(v[0], in->exposure), gk_tonemap(v[1], in->exposure),
                              gk_tonemap(v[2], in->exposure), 1};
                gk_hud_rect(h, qx0 < mid ? mid : qx0, (float)y * s, qx1, (float)(y + 1) * s, c);
            }
    }
    gk_hud_rect(h, mid - 1, 0, mid + 1, (float)h->height, divider);
    /* the divider's label, two short lines centred on the divider at the bottom edge, between the
       corner panels (the bottom third's middle is theirs to leave free): both numbers */
    char top[96], bottom[96];
    if (isfinite(in->error))
        snprintf(top, sizeof top, "%s %.1f ms | error %.3f", in->method ? in->method : "-", in->frame_ms, in->error);
    else
        snprintf(top, sizeof top, "%s %.1f ms | error -", in->method ? in->method : "-", in->frame_ms);
    if (in->truth_rgb && isfinite(in->truth_noise))
        snprintf(bottom, sizeof bottom, "truth %ld spp | noise %.3f", in->truth_spp, in->truth_noise);
    else if (in->truth_rgb)
        snprintf(bottom, sizeof bottom, "truth %ld spp", in->truth_spp);
    else
        snprintf(bottom, sizeof bottom, "%s", in->truth_note && in->truth_note[0] ? in->truth_note : "no truth yet");
    float pad = px * 0.5f, line = px * 1.25f;
    float wt = gk_font_text_width(&h->font, top), wb = gk_font_text_width(&h->font, bottom);
    float w = (wt > wb ? wt : wb) + 2 * pad;
    float y1 = (float)h->height - pad, y0 = y1 - 2 * pad - 2 * line;
    gk_hud_rect(h, mid - w / 2, y0, mid + w / 2, y1, panel);
    gk_hud_text(h, mid - wt / 2, y0 + pad + px, top, white);
    gk_hud_text(h, mid - wb / 2, y0 + pad + px + line, bottom, white);
}
