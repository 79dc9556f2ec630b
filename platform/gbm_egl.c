/* GBM + EGL for the KMS backend, with a DRM framebuffer cached per GBM buffer; see gbm_egl.h. */
#include "gbm_egl.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include <xf86drm.h>
#include <xf86drmMode.h>

#include "base/log.h"

/* ---- the real GBM / EGL calls ---- */

static void real_bo_describe(struct gbm_bo *bo, gk_bo_desc *out)
{
    out->width = gbm_bo_get_width(bo);
    out->height = gbm_bo_get_height(bo);
    out->format = gbm_bo_get_format(bo);
    out->handle = gbm_bo_get_handle(bo).u32;
    out->stride = gbm_bo_get_stride(bo);
}

static void *real_bo_get_user_data(struct gbm_bo *bo) { return gbm_bo_get_user_data(bo); }

static int real_egl_setup(gk_gbm_egl *g, bool debug, gk_err *e)
{
    EGLDisplay dpy = eglGetPlatformDisplay(EGL_PLATFORM_GBM_KHR, g->dev, NULL);
    if (gk_egl_init_display(&g->egl, dpy, e))
        return -1;
    EGLint attr[] = {EGL_SURFACE_TYPE, EGL_WINDOW_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_ES3_BIT,
                     EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_NONE};
    EGLint n = 0;
    if (!eglChooseConfig(g->egl.dpy, attr, NULL, 0, &n) || n < 1)
        return gk_fail(e, GK_ERUNTIME, "EGL: no ES3 window config on the GBM display");
    EGLConfig *configs = calloc((size_t)n, sizeof *configs);
    if (!configs)
        return gk_fail(e, GK_ERUNTIME, "out of memory");
    eglChooseConfig(g->egl.dpy, attr, configs, n, &n);
    EGLConfig chosen = NULL;
    for (int i = 0; i < n && !chosen; i++) {
        EGLint id = 0;
        /* The scanout format must match the config exactly, or the flip shows garbage. */
        if (eglGetConfigAttrib(g->egl.dpy, configs[i], EGL_NATIVE_VISUAL_ID, &id) && (uint32_t)id == g->format)
            chosen = configs[i];
    }
    free(configs);
    if (!chosen)
        return gk_fail(e, GK_ERUNTIME, "EGL: no config with native visual XRGB8888 on the GBM display");
    if (gk_egl_create_context(&g->egl, chosen, debug, e))
        return -1;
    g->egl_surface = eglCreateWindowSurface(g->egl.dpy, chosen, (EGLNativeWindowType)g->surface, NULL);
    if (g->egl_surface == EGL_NO_SURFACE)
        return gk_fail(e, GK_ERUNTIME, "EGL: cannot create the window surface on the GBM surface (%s)",
                       gk_egl_error_string(eglGetError()));
    if (gk_egl_make_current(&g->egl, g->egl_surface, e))
        return -1;
    g->gles_version = g->egl.gles_version;
    return 0;
}

static int real_swap_buffers(gk_gbm_egl *g) { return eglSwapBuffers(g->egl.dpy, g->egl_surface) ? 0 : -1; }

static void real_egl_teardown(gk_gbm_egl *g)
{
    if (g->egl.dpy != EGL_NO_DISPLAY && g->egl_surface != EGL_NO_SURFACE) {
        eglMakeCurrent(g->egl.dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroySurface(g->egl.dpy, g->egl_surface);
    }
    g->egl_surface = EGL_NO_SURFACE;
    gk_egl_terminate(&g->egl);
}

const struct gk_gbm_egl_ops gk_gbm_egl_real_ops = {
    .create_device = gbm_create_device,
    .destroy_device = gbm_device_destroy,
    .surface_create = gbm_surface_create,
    .surface_destroy = gbm_surface_destroy,
    .lock_front_buffer = gbm_surface_lock_front_buffer,
    .release_buffer = gbm_surface_release_buffer,
    .bo_get_user_data = real_bo_get_user_data,
    .bo_set_user_data = gbm_bo_set_user_data,
    .bo_describe = real_bo_describe,
    .egl_setup = real_egl_setup,
    .swap_buffers = real_swap_buffers,
    .egl_teardown = real_egl_teardown,
};

/* ---- framebuffer cache ---- */

typedef struct fb_entry {
    int fd;
    uint32_t fb_id;
} fb_entry;

/* Called by GBM when the buffer is destroyed (surface destroyed): the framebuffer goes with it. */
static void destroy_fb(struct gbm_bo *bo, void *data)
{
    (void)bo;
    fb_entry *fb = data;
    if (fb->fb_id)
        drmModeRmFB(fb->fd, fb->fb_id);
    free(fb);
}

static int fb_for_bo(gk_gbm_egl *g, struct gbm_bo *bo, uint32_t *fb_id, gk_err *e)
{
    fb_entry *fb = g->ops->bo_get_user_data(bo);
    if (fb) {
        *fb_id = fb->fb_id;
        return 0;
    }
    gk_bo_desc d;
    g->ops->bo_describe(bo, &d);
    uint32_t handles[4] = {d.handle}, pitches[4] = {d.stride}, offsets[4] = {0};
    uint32_t id = 0;
    if (drmModeAddFB2(g->fd, d.width, d.height, d.format, handles, pitches, offsets, &id, 0))
        return gk_fail(e, GK_ERUNTIME, "kms: drmModeAddFB2 %ux%u failed: %s", d.width, d.height, strerror(errno));
    fb = calloc(1, sizeof *fb);
    if (!fb) {
        drmModeRmFB(g->fd, id);
        return gk_fail(e, GK_ERUNTIME, "out of memory");
    }
    fb->fd = g->fd;
    fb->fb_id = id;
    g->ops->bo_set_user_data(bo, fb, destroy_fb);
    *fb_id = id;
    return 0;
}

/* ---- lifecycle ---- */

int gk_gbm_egl_init(gk_gbm_egl *g, const struct gk_gbm_egl_ops *ops, int fd, uint32_t w, uint32_t h, bool debug,
                    gk_err *e)
{
    memset(g, 0, sizeof *g);
    g->ops = ops;
    g->fd = fd;
    g->width = w;
    g->height = h;
    g->format = GBM_FORMAT_XRGB8888;
    g->egl.dpy = EGL_NO_DISPLAY;
    g->egl.ctx = EGL_NO_CONTEXT;
    g->egl_surface = EGL_NO_SURFACE;
    g->dev = ops->create_device(fd);
    if (!g->dev)
        return gk_fail(e, GK_ERUNTIME, "kms: gbm_create_device failed");
    g->surface = ops->surface_create(g->dev, w, h, g->format, GBM_BO_USE_SCANOUT | GBM_BO_USE_RENDERING);
    if (!g->surface)
        return gk_fail(e, GK_ERUNTIME, "kms: gbm_surface_create %ux%u XRGB8888 failed", w, h);
    return ops->egl_setup(g, debug, e);
}

int gk_gbm_egl_swap_and_lock(gk_gbm_egl *g, struct gbm_bo **bo, uint32_t *fb_id, gk_err *e)
{
    if (g->ops->swap_buffers(g))
        return gk_fail(e, GK_ERUNTIME, "EGL: eglSwapBuffers failed (%s)", gk_egl_error_string(eglGetError()));
    *bo = g->ops->lock_front_buffer(g->surface);
    if (!*bo)
        return gk_fail(e, GK_ERUNTIME, "kms: gbm_surface_lock_front_buffer failed");
    if (fb_for_bo(g, *bo, fb_id, e)) {
        g->ops->release_buffer(g->surface, *bo);
        *bo = NULL;
        return -1;
    }
    return 0;
}

void gk_gbm_egl_release(gk_gbm_egl *g, struct gbm_bo *bo)
{
    if (bo && g->surface)
        g->ops->release_buffer(g->surface, bo);
}

void gk_gbm_egl_fini(gk_gbm_egl *g)
{
    if (!g->ops)
        return;
    g->ops->egl_teardown(g);
    if (g->surface)
        g->ops->surface_destroy(g->surface);
    if (g->dev)
        g->ops->destroy_device(g->dev);
    g->surface = NULL;
    g->dev = NULL;
}
