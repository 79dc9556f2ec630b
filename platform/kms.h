/* The KMS backend's state and its parts, structured like kmscube: kms.c (device, connector, CRTC and
 * mode choice; the platform ops), kms_atomic.c / kms_legacy.c (how a frame reaches the screen,
 * behind the one `commit` pointer), gbm_egl.c (GBM surface + EGL + framebuffer cache). */
#ifndef GK_PLATFORM_KMS_H
#define GK_PLATFORM_KMS_H

#include <stdbool.h>
#include <stdint.h>

#include <xf86drm.h>
#include <xf86drmMode.h>

#include "buttons.h"
#include "gbm_egl.h"

typedef struct gk_kms gk_kms;

/* Shows fb_id on the CRTC. modeset: the first frame (sets the mode, may block); otherwise a page
 * flip that completes with a DRM event (flip_pending is set). */
typedef int (*gk_kms_commit_fn)(gk_kms *k, uint32_t fb_id, bool modeset, gk_err *e);

struct gk_kms_atomic_props {
    uint32_t conn_crtc_id;
    uint32_t crtc_mode_id, crtc_active;
    uint32_t plane_fb_id, plane_crtc_id;
    uint32_t src_x, src_y, src_w, src_h, crtc_x, crtc_y, crtc_w, crtc_h;
};

struct gk_kms {
    int fd;
    char device[640];
    uint32_t connector_id, crtc_id;
    int crtc_index;
    char connector_name[32];
    drmModeModeInfo mode;
    drmModeCrtc *saved_crtc;        /* restored on close */
    gk_kms_commit_fn commit;        /* gk_kms_atomic_commit or gk_kms_legacy_commit */
    uint32_t plane_id, mode_blob;   /* atomic */
    struct gk_kms_atomic_props prop;
    bool modeset_done;
    bool flip_pending;
    unsigned flips_completed;
    struct gbm_bo *bo_on_screen, *bo_pending;
    gk_gbm_egl gbm;
    bool connected;
    double next_probe_s;
    double t0;                      /* CLOCK_MONOTONIC at open: the platform clock's origin */
    gk_buttons *buttons;
    gk_event_queue *queue;          /* where buttons read while waiting for a flip go */
};

/* "1920x1080" or "1920x1080@60" (hz = 0 when not given). Bad syntax: GK_EINPUT. */
int gk_kms_parse_mode(const char *s, int *w, int *h, int *hz, gk_err *e);
/* Picks the mode: `mode` string when set (must exist: GK_ERUNTIME listing what the connector
 * offers); else want_w x want_h when offered; else the preferred mode (else the first). */
int gk_kms_choose_mode(const drmModeConnector *c, const char *mode, int want_w, int want_h,
                       drmModeModeInfo *out, gk_err *e);

/* Opens `device`, or else the first card<N> in scan_dir with a connected connector; chooses the
 * connector, CRTC and mode and saves the current CRTC. *no_display is set when there is no device or
 * nothing connected. */
int gk_kms_open_display(gk_kms *k, const gk_platform_desc *d, const char *scan_dir, bool *no_display, gk_err *e);
/* Chooses atomic (when the driver accepts the client cap and a primary plane is found) or legacy. */
int gk_kms_atomic_init(gk_kms *k, gk_err *e);
int gk_kms_atomic_commit(gk_kms *k, uint32_t fb_id, bool modeset, gk_err *e);
int gk_kms_legacy_commit(gk_kms *k, uint32_t fb_id, bool modeset, gk_err *e);

/* Presents the rendered frame: waits for the previous flip, swaps, commits. */
int gk_kms_present(gk_kms *k, gk_err *e);
/* One poll() over the DRM fd and the button fds; handles flip events and button edges. */
int gk_kms_wait(gk_kms *k, int timeout_ms);
/* Checks the connector (at most once a second unless force); logs loss and return. */
void gk_kms_probe_connector(gk_kms *k, bool force);
/* Waits for a pending flip, restores the saved CRTC, frees everything. */
void gk_kms_teardown(gk_kms *k);

/* The platform over a gk_kms, with replaceable GBM/EGL ops and card directory (tests). */
gk_platform *gk_kms_open_with(const gk_platform_desc *desc, const struct gk_gbm_egl_ops *ops,
                              const char *scan_dir, bool *no_display, gk_err *e);

double gk_kms_now(const gk_kms *k);

#endif
