/* Captures (DESIGN §4): the display image as shown (compose into an RGBA8 target of the output
 * size, the same shader as the frame) and the linear image before exposure (compose without
 * tonemap into RGBA16F, upscaled like the display when render_scale < 1). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../io/image_io.h"
#include "renderer_internal.h"

/* linear: RGBA (alpha 1) when rgba, else RGB like the references; display: RGB. overlay (display
 * only, may be NULL) is drawn over the composed image before it is read. */
static int read_image_overlay(gk_renderer *r, GLenum format, bool linear, bool rgba, gk_overlay_fn overlay, void *user,
                              gk_image *img, gk_err *e)
{
    int w = r->opts.width, h = r->opts.height;
    gk_target t;
    if (gk_target_create(&t, linear ? "capture (linear)" : "capture (display)", w, h, 1, &format, GL_NEAREST,
                         false, e) != 0)
        return -1;
    int rc = gk_render_compose(r, t.fbo, w, h, linear, NULL, e);
    if (rc == 0 && overlay && !linear)
        overlay(user, NULL, t.fbo);
    float *px = NULL;
    if (rc == 0 && (px = malloc(sizeof(float) * 4 * (size_t)w * (size_t)h)) == NULL)
        rc = gk_fail(e, GK_ERUNTIME, "capture: out of memory");
    if (rc == 0 && gk_image_alloc(img, w, h, linear && rgba ? 4 : 3) != 0)
        rc = gk_fail(e, GK_ERUNTIME, "capture: out of memory");
    if (rc == 0) {
        glBindFramebuffer(GL_FRAMEBUFFER, t.fbo);
        glReadBuffer(GL_COLOR_ATTACHMENT0);
        if (linear) {
            glReadPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, px);
        } else {
            unsigned char *b = (unsigned char *)px;
            glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, b);
            for (long i = (long)w * h - 1; i >= 0; i--) /* back to front: expands in place */
                for (int c = 3; c >= 0; c--)
                    px[4 * i + c] = b[4 * i + c] / 255.0f;
        }
        GLenum err = glGetError();
        if (err != GL_NO_ERROR)
            rc = gk_fail(e, GK_ERUNTIME, "capture: reading the %s image failed: %s", linear ? "linear" : "display",
                         gk_gl_error_name(err));
        /* GL rows start at the bottom; images start at the top. */
        for (int y = 0; rc == 0 && y < h; y++)
            for (int x = 0; x < w; x++)
                for (int c = 0; c < img->channels; c++)
                    img->pixels[((size_t)y * w + x) * img->channels + c] = px[((size_t)(h - 1 - y) * w + x) * 4 + c];
        if (img->channels == 4)
            for (long i = 0; rc == 0 && i < (long)w * h; i++)
                img->pixels[4 * i + 3] = 1.0f;
    }
    free(px);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    gk_target_destroy(&t);
    if (rc != 0)
        gk_image_free(img);
    return rc;
}

static int read_image(gk_renderer *r, GLenum format, bool linear, bool rgba, gk_image *img, gk_err *e)
{
    return read_image_overlay(r, format, linear, rgba, NULL, NULL, img, e);
}

int gk_renderer_capture_overlay(gk_renderer *r, const char *png_path, gk_overlay_fn overlay, void *user, gk_err *e)
{
    if (!r->have_frame)
        return gk_fail(e, GK_ERUNTIME, "capture: no frame rendered yet");
    gk_image img;
    if (read_image_overlay(r, GL_RGBA8, false, false, overlay, user, &img, e) != 0)
        return -1;
    int rc = gk_image_write(png_path, &img, NULL, e);
    gk_image_free(&img);
    return rc;
}

/* For tests and metrics: the linear image (RGBA, top row first, output size). */
int gk_renderer_read_linear(gk_renderer *r, gk_image *img, gk_err *e)
{
    if (!r->have_frame)
        return gk_fail(e, GK_ERUNTIME, "capture: no frame rendered yet");
    return read_image(r, GL_RGBA16F, true, true, img, e);
}

int gk_renderer_capture(gk_renderer *r, const char *png_path, const char *exr_path, gk_err *e)
{
    if (!r->have_frame)
        return gk_fail(e, GK_ERUNTIME, "capture: no frame rendered yet");
    gk_image img;
    if (png_path) {
        if (read_image(r, GL_RGBA8, false, false, &img, e) != 0)
            return -1;
        int rc = gk_image_write(png_path, &img, NULL, e);
        gk_image_free(&img);
        if (rc != 0)
            return -1;
    }
    if (exr_path) {
        if (read_image(r, GL_RGBA16F, true, false, &img, e) != 0)
            return -1;
        char exposure[32];
        snprintf(exposure, sizeof exposure, "%g", (double)r->exposure);
        gk_image_meta meta = {.count = 1, .keys = {"gikiosk:exposure"}, .values = {exposure}};
        int rc = gk_image_write(exr_path, &img, &meta, e);
        gk_image_free(&img);
        if (rc != 0)
            return -1;
    }
    return 0;
}
