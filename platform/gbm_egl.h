/* GBM surface + EGL on the GBM platform for the KMS backend, and the cache of DRM framebuffers per
 * GBM buffer. The GBM and EGL calls go through a small struct of function pointers so unit tests
 * can replace them (libdrm itself is faked at link level); gk_gbm_egl_real_ops are the real ones. */
#ifndef GK_PLATFORM_GBM_EGL_H
#define GK_PLATFORM_GBM_EGL_H

#include <stdbool.h>
#include <stdint.h>

#include <gbm.h>

#include "egl.h"

typedef struct gk_gbm_egl gk_gbm_egl;

typedef struct gk_bo_desc {
    uint32_t width, height, format, handle, stride;
} gk_bo_desc;

struct gk_gbm_egl_ops {
    struct gbm_device *(*create_device)(int fd);
    void (*destroy_device)(struct gbm_device *dev);
    struct gbm_surface *(*surface_create)(struct gbm_device *dev, uint32_t w, uint32_t h, uint32_t format,
                                          uint32_t flags);
    void (*surface_destroy)(struct gbm_surface *s);
    struct gbm_bo *(*lock_front_buffer)(struct gbm_surface *s);
    void (*release_buffer)(struct gbm_surface *s, struct gbm_bo *bo);
    void *(*bo_get_user_data)(struct gbm_bo *bo);
    void (*bo_set_user_data)(struct gbm_bo *bo, void *data, void (*destroy)(struct gbm_bo *, void *));
    void (*bo_describe)(struct gbm_bo *bo, gk_bo_desc *out);
    /* EGL display on g->dev, a config matching g->format, window surface on g->surface, context
     * current. */
    int (*egl_setup)(gk_gbm_egl *g, bool debug, gk_err *e);
    int (*swap_buffers)(gk_gbm_egl *g);
    void (*egl_teardown)(gk_gbm_egl *g);
};

extern const struct gk_gbm_egl_ops gk_gbm_egl_real_ops;

struct gk_gbm_egl {
    const struct gk_gbm_egl_ops *ops;
    int fd;
    struct gbm_device *dev;
    struct gbm_surface *surface;
    uint32_t width, height, format;
    gk_egl egl;
    EGLSurface egl_surface;
    int gles_version;
};

int gk_gbm_egl_init(gk_gbm_egl *g, const struct gk_gbm_egl_ops *ops, int fd, uint32_t w, uint32_t h, bool debug,
                    gk_err *e);
/* Swaps, locks the new front buffer and returns it with its DRM framebuffer id (drmModeAddFB2 the
 * first time a buffer is seen, then from the cache kept in the buffer's user data). */
int gk_gbm_egl_swap_and_lock(gk_gbm_egl *g, struct gbm_bo **bo, uint32_t *fb_id, gk_err *e);
void gk_gbm_egl_release(gk_gbm_egl *g, struct gbm_bo *bo);
void gk_gbm_egl_fini(gk_gbm_egl *g);

#endif
