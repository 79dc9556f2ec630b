/* KMS backend: device discovery, connector / CRTC / mode choice, frame pacing by DRM flip events
 * read from the same poll() as the buttons, connector loss and return, CRTC restore on close. */
#include "kms.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/log.h"

#define FLIP_TIMEOUT_MS 1000  /* a flip event later than this means the display is gone */
#define PROBE_INTERVAL_S 1.0

double gk_kms_now(const gk_kms *k) { return gk_monotonic_s() - k->t0; }

int gk_kms_parse_mode(const char *s, int *w, int *h, int *hz, gk_err *e)
{
    char tail = 0;
    *hz = 0;
    int n = sscanf(s, "%dx%d@%d%c", w, h, hz, &tail);
    if (n == 2 || n == 3) {
        /* sscanf stops at a non-matching char: make sure nothing but the parsed parts is there */
        char check[48];
        if (n == 2)
            snprintf(check, sizeof check, "%dx%d", *w, *h);
        else
            snprintf(check, sizeof check, "%dx%d@%d", *w, *h, *hz);
        if (strcmp(check, s) == 0 && *w > 0 && *h > 0 && *hz >= 0)
            return 0;
    }
    return gk_fail(e, GK_EINPUT, "display mode '%s' is not WxH or WxH@HZ (e.g. 1920x1080@60)", s);
}

int gk_kms_choose_mode(const drmModeConnector *c, const char *mode, int want_w, int want_h,
                       drmModeModeInfo *out, gk_err *e)
{
    if (c->count_modes <= 0)
        return gk_fail(e, GK_ERUNTIME, "kms: the connector offers no modes");
    int w = want_w, h = want_h, hz = 0;
    bool strict = mode && mode[0];
    if (strict && gk_kms_parse_mode(mode, &w, &h, &hz, e))
        return -1;
    int best = -1;
    if (w > 0 && h > 0) {
        for (int i = 0; i < c->count_modes; i++) {
            const drmModeModeInfo *m = &c->modes[i];
            if (m->hdisplay != w || m->vdisplay != h || (hz && (int)m->vrefresh != hz))
                continue;
            /* among equal sizes: the preferred one, else the highest refresh */
            if (best < 0 || (m->type & DRM_MODE_TYPE_PREFERRED) ||
                (!(c->modes[best].type & DRM_MODE_TYPE_PREFERRED) && m->vrefresh > c->modes[best].vrefresh))
                best = i;
        }
        if (best < 0 && strict) {
            char offers[512] = "";
            for (int i = 0; i < c->count_modes && strlen(offers) < sizeof offers - 24; i++) {
                char one[24];
                snprintf(one, sizeof one, "%s%dx%d@%u", i ? ", " : "", c->modes[i].hdisplay, c->modes[i].vdisplay,
                         c->modes[i].vrefresh);
                strcat(offers, one);
            }
            return gk_fail(e, GK_ERUNTIME, "kms: mode %s not offered by the display (offers: %s)", mode, offers);
        }
    }
    if (best < 0) {
        best = 0;
        for (int i = 0; i < c->count_modes; i++)
            if (c->modes[i].type & DRM_MODE_TYPE_PREFERRED) {
                best = i;
                break;
            }
    }
    *out = c->modes[best];
    return 0;
}

static int crtc_index_of(const drmModeRes *res, uint32_t crtc_id)
{
    for (int i = 0; i < res->count_crtcs; i++)
        if (res->crtcs[i] == crtc_id)
            return i;
    return -1;
}

/* The CRTC already driving the connector, else the first one one of its encoders can use. */
static int choose_crtc(gk_kms *k, const drmModeRes *res, const drmModeConnector *c)
{
    if (c->encoder_id) {
        drmModeEncoder *enc = drmModeGetEncoder(k->fd, c->encoder_id);
        if (enc) {
            int idx = enc->crtc_id ? crtc_index_of(res, enc->crtc_id) : -1;
            drmModeFreeEncoder(enc);
            if (idx >= 0) {
                k->crtc_index = idx;
                k->crtc_id = res->crtcs[idx];
                return 0;
            }
        }
    }
    for (int i = 0; i < c->count_encoders; i++) {
        drmModeEncoder *enc = drmModeGetEncoder(k->fd, c->encoders[i]);
        if (!enc)
            continue;
        uint32_t possible = enc->possible_crtcs;
        drmModeFreeEncoder(enc);
        for (int j = 0; j < res->count_crtcs; j++)
            if (possible & (1u << j)) {
                k->crtc_index = j;
                k->crtc_id = res->crtcs[j];
                return 0;
            }
    }
    return -1;
}

static void connector_label(const drmModeConnector *c, char *out, size_t size)
{
    const char *type = drmModeGetConnectorTypeName(c->connector_type);
    snprintf(out, size, "%s-%u", type ? type : "connector", c->connector_type_id);
}

/* Fills k from an opened fd: connector, mode, CRTC. Returns 1 when nothing is connected. */
static int probe_card(gk_kms *k, const gk_platform_desc *d, gk_err *e)
{
    drmModeRes *res = drmModeGetResources(k->fd);
    if (!res)
        return 1; /* not a KMS device (render node, or not DRM at all) */
    int rc = 1;
    for (int i = 0; i < res->count_connectors && rc == 1; i++) {
        drmModeConnector *c = drmModeGetConnector(k->fd, res->connectors[i]);
        if (!c)
            continue;
        if (c->connection == DRM_MODE_CONNECTED && c->count_modes > 0) {
            connector_label(c, k->connector_name, sizeof k->connector_name);
            k->connector_id = c->connector_id;
            if (gk_kms_choose_mode(c, d->mode, d->width, d->height, &k->mode, e))
                rc = -1;
            else if (choose_crtc(k, res, c))
                rc = gk_fail(e, GK_ERUNTIME, "kms: %s: %s: no CRTC can drive it", k->device, k->connector_name);
            else
                rc = 0;
        }
        drmModeFreeConnector(c);
    }
    drmModeFreeResources(res);
    return rc;
}

static int try_card(gk_kms *k, const char *path, const gk_platform_desc *d, gk_err *e)
{
    snprintf(k->device, sizeof k->device, "%s", path);
    k->fd = open(path, O_RDWR | O_CLOEXEC);
    if (k->fd < 0)
        return gk_fail(e, GK_ERUNTIME, "kms: cannot open %s: %s", path, strerror(errno));
    int rc = probe_card(k, d, e);
    if (rc != 0) {
        close(k->fd);
        k->fd = -1;
    }
    return rc;
}

int gk_kms_open_display(gk_kms *k, const gk_platform_desc *d, const char *scan_dir, bool *no_display, gk_err *e)
{
    *no_display = false;
    if (d->device[0]) {
        int rc = try_card(k, d->device, d, e);
        if (rc == 1)
            gk_fail(e, GK_ERUNTIME, "kms: %s: no connected display", d->device);
        /* missing device or nothing connected: "no display"; a display we cannot drive: not */
        *no_display = rc != 0 && !k->connector_id;
        return rc ? -1 : 0;
    }
    DIR *dir = opendir(scan_dir);
    char names[16][32];
    int n = 0;
    for (struct dirent *de; dir && (de = readdir(dir)) != NULL && n < 16;)
        if (strncmp(de->d_name, "card", 4) == 0 && strlen(de->d_name) < sizeof names[0])
            strcpy(names[n++], de->d_name);
    if (dir)
        closedir(dir);
    /* card0 before card1 ... card10: by length, then by name */
    for (int i = 1; i < n; i++)
        for (int j = i; j > 0 && (strlen(names[j]) < strlen(names[j - 1]) ||
                                  (strlen(names[j]) == strlen(names[j - 1]) && strcmp(names[j], names[j - 1]) < 0));
             j--) {
            char t[32];
            strcpy(t, names[j]);
            strcpy(names[j], names[j - 1]);
            strcpy(names[j - 1], t);
        }
    for (int i = 0; i < n; i++) {
        char path[600];
        snprintf(path, sizeof path, "%s/%s", scan_dir, names[i]);
        gk_err card_err = {0};
        int rc = try_card(k, path, d, &card_err);
        if (rc == 0)
            return 0;
        if (rc < 0 && k->connector_id) { /* a display is there but cannot be driven as asked */
            if (e)
                *e = card_err;
            return -1;
        }
    }
    *no_display = true;
    return gk_fail(e, GK_ERUNTIME, n ? "kms: no connected display on %s/card*" : "kms: no DRM device in %s",
                   scan_dir);
}

static void page_flip_handler(int fd, unsigned seq, unsigned sec, unsigned usec, void *data)
{
    (void)fd; (void)seq; (void)sec; (void)usec;
    gk_kms *k = data;
    k->flip_pending = false;
    k->flips_completed++;
    /* the previous buffer left the screen: GBM may render into it again */
    if (k->bo_pending) {
        gk_gbm_egl_release(&k->gbm, k->bo_on_screen);
        k->bo_on_screen = k->bo_pending;
        k->bo_pending = NULL;
    }
}

int gk_kms_wait(gk_kms *k, int timeout_ms)
{
    struct pollfd pfd[1 + GK_BUTTONS_MAX_FDS];
    pfd[0] = (struct pollfd){.fd = k->fd, .events = POLLIN};
    int nb = gk_buttons_fds(k->buttons, pfd + 1, GK_BUTTONS_MAX_FDS);
    int rc = poll(pfd, (nfds_t)(1 + nb), gk_buttons_timeout_ms(k->buttons, timeout_ms));
    if (rc < 0)
        return errno == EINTR ? 0 : -1;
    if (pfd[0].revents & POLLIN) {
        drmEventContext ev = {.version = 2, .page_flip_handler = page_flip_handler};
        drmHandleEvent(k->fd, &ev);
    }
    if (k->queue) {
        gk_buttons_dispatch(k->buttons, pfd + 1, nb, k->queue);
        gk_buttons_tick(k->buttons, k->queue);
    }
    return 0;
}

void gk_kms_probe_connector(gk_kms *k, bool force)
{
    double now = gk_kms_now(k);
    if (!force && now < k->next_probe_s)
        return;
    k->next_probe_s = now + PROBE_INTERVAL_S;
    /* while connected, the cheap current state; while lost, a real probe so a plug-in is seen */
    drmModeConnector *c = k->connected ? drmModeGetConnectorCurrent(k->fd, k->connector_id)
                                       : drmModeGetConnector(k->fd, k->connector_id);
    bool connected = c && c->connection == DRM_MODE_CONNECTED;
    drmModeFreeConnector(c);
    if (connected == k->connected)
        return;
    k->connected = connected;
    if (!connected) {
        gk_log("kms: display %s disconnected; rendering continues, probing every second", k->connector_name);
    } else {
        gk_log("kms: display %s connected again; setting the mode", k->connector_name);
        k->modeset_done = false;
    }
}

int gk_kms_present(gk_kms *k, gk_err *e)
{
    /* Wait for the previous flip, keeping buttons alive; a flip that never completes means the
     * display went away under us: stop waiting and probe. */
    double start = gk_kms_now(k);
    while (k->flip_pending) {
        if (gk_kms_wait(k, FLIP_TIMEOUT_MS) < 0)
            return gk_fail(e, GK_ERUNTIME, "kms: poll failed: %s", strerror(errno));
        if (gk_platform_signal_pending())
            return 0;
        if (k->flip_pending && gk_kms_now(k) - start > FLIP_TIMEOUT_MS / 1000.0) {
            gk_log("kms: page flip did not complete within %d ms", FLIP_TIMEOUT_MS);
            k->flip_pending = false;
            gk_kms_probe_connector(k, true);
        }
    }
    gk_kms_probe_connector(k, false);
    struct gbm_bo *bo = NULL;
    uint32_t fb = 0;
    if (gk_gbm_egl_swap_and_lock(&k->gbm, &bo, &fb, e))
        return -1;
    if (!k->connected) {
        /* nothing to show it on: give the buffer back and pace at the mode's rate */
        gk_gbm_egl_release(&k->gbm, bo);
        int period_ms = k->mode.vrefresh ? (int)(1000 / k->mode.vrefresh) : 16;
        return gk_kms_wait(k, period_ms) < 0 ? gk_fail(e, GK_ERUNTIME, "kms: poll failed") : 0;
    }
    bool modeset = !k->modeset_done;
    gk_err commit_err = {0};
    if (k->commit(k, fb, modeset, &commit_err)) {
        gk_gbm_egl_release(&k->gbm, bo);
        gk_kms_probe_connector(k, true);
        if (!k->connected)
            return 0; /* lost: logged by the probe, not an error */
        if (e)
            *e = commit_err;
        return -1;
    }
    k->modeset_done = true;
    if (k->flip_pending) {
        k->bo_pending = bo;
    } else { /* legacy modeset: on screen now */
        gk_gbm_egl_release(&k->gbm, k->bo_on_screen);
        k->bo_on_screen = bo;
    }
    return 0;
}

void gk_kms_teardown(gk_kms *k)
{
    if (k->fd >= 0 && k->flip_pending) {
        double start = gk_kms_now(k);
        while (k->flip_pending && gk_kms_now(k) - start < 0.2) {
            struct pollfd pfd = {.fd = k->fd, .events = POLLIN};
            if (poll(&pfd, 1, 50) > 0) {
                drmEventContext ev = {.version = 2, .page_flip_handler = page_flip_handler};
                drmHandleEvent(k->fd, &ev);
            }
        }
    }
    if (k->fd >= 0 && k->saved_crtc) {
        drmModeCrtc *s = k->saved_crtc;
        /* give the console (or whatever was there) its framebuffer and mode back */
        if (drmModeSetCrtc(k->fd, s->crtc_id, s->buffer_id, s->x, s->y, &k->connector_id, 1,
                           s->mode_valid ? &s->mode : NULL))
            gk_log("kms: could not restore CRTC %u: %s", s->crtc_id, strerror(errno));
    }
    if (k->saved_crtc)
        drmModeFreeCrtc(k->saved_crtc);
    k->saved_crtc = NULL;
    gk_buttons_close(k->buttons);
    k->buttons = NULL;
    gk_gbm_egl_release(&k->gbm, k->bo_pending);
    gk_gbm_egl_release(&k->gbm, k->bo_on_screen);
    k->bo_pending = k->bo_on_screen = NULL;
    gk_gbm_egl_fini(&k->gbm);
    if (k->mode_blob && k->fd >= 0)
        drmModeDestroyPropertyBlob(k->fd, k->mode_blob);
    if (k->fd >= 0)
        close(k->fd);
    k->fd = -1;
}

/* ---- the platform over gk_kms ---- */

static double kms_clock(void *ctx) { return gk_kms_now(ctx); }

static int kms_platform_present(gk_platform *p, gk_err *e) { return gk_kms_present(p->impl, e); }

static int kms_platform_poll(gk_platform *p, int timeout_ms)
{
    gk_kms *k = p->impl;
    gk_kms_probe_connector(k, false);
    if (timeout_ms < 0 || timeout_ms > 1000)
        timeout_ms = 1000; /* wake at least once a second for probing and reconnecting */
    return gk_kms_wait(k, timeout_ms);
}

static double kms_platform_now(const gk_platform *p) { return gk_kms_now(p->impl); }

static void kms_platform_close(gk_platform *p)
{
    gk_kms_teardown(p->impl);
    free(p->impl);
    free(p);
}

static const struct gk_platform_ops kms_ops = {
    .name = "kms", .present = kms_platform_present, .poll = kms_platform_poll, .now = kms_platform_now,
    .close = kms_platform_close,
};

gk_platform *gk_kms_open_with(const gk_platform_desc *desc, const struct gk_gbm_egl_ops *ops,
                              const char *scan_dir, bool *no_display, gk_err *e)
{
    gk_platform *p = calloc(1, sizeof *p);
    gk_kms *k = calloc(1, sizeof *k);
    if (!p || !k) {
        free(p);
        free(k);
        *no_display = false;
        gk_fail(e, GK_ERUNTIME, "out of memory");
        return NULL;
    }
    k->fd = -1;
    k->t0 = gk_monotonic_s();
    k->queue = &p->queue;
    p->ops = &kms_ops;
    p->impl = k;
    if (gk_kms_open_display(k, desc, scan_dir, no_display, e))
        goto fail;
    k->connected = true;
    k->saved_crtc = drmModeGetCrtc(k->fd, k->crtc_id);
    if (gk_kms_atomic_init(k, e))
        goto fail;
    if (gk_gbm_egl_init(&k->gbm, ops, k->fd, k->mode.hdisplay, k->mode.vdisplay, desc->debug, e)) {
        gk_fail_prefix(e, "%s: ", k->device);
        goto fail;
    }
    if (desc->buttons.backend != GK_BUTTONS_NONE) {
        k->buttons = gk_buttons_open(&desc->buttons, kms_clock, k, k->t0, e);
        if (!k->buttons)
            goto fail;
    }
    gk_log("kms: %s %s %s on CRTC %u (%s)", k->device, k->connector_name, k->mode.name, k->crtc_id,
           k->commit == gk_kms_atomic_commit ? "atomic" : "legacy");
    p->width = k->mode.hdisplay;
    p->height = k->mode.vdisplay;
    p->gles_version = k->gbm.gles_version;
    p->framebuffer = 0;
    return p;
fail:
    kms_platform_close(p);
    return NULL;
}

gk_platform *gk_kms_open(const gk_platform_desc *desc, bool *no_display, gk_err *e)
{
    return gk_kms_open_with(desc, &gk_gbm_egl_real_ops, "/dev/dri", no_display, e);
}
