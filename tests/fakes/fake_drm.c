/* Link-level libdrm fake; see fake_drm.h. */
#include "fake_drm.h"

#include <dlfcn.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

fake_drm_state fake_drm;

#define REAL(name) ((__typeof__(&name))dlsym(RTLD_NEXT, #name))

static const char *const prop_names[] = {"type", "FB_ID", "CRTC_ID", "SRC_X", "SRC_Y", "SRC_W", "SRC_H",
                                         "CRTC_X", "CRTC_Y", "CRTC_W", "CRTC_H", "MODE_ID", "ACTIVE"};
#define N_PROPS (int)(sizeof prop_names / sizeof prop_names[0])
#define PROP_BASE 1000
#define ENCODER_ID 50
#define PRIMARY_PLANE 31
#define OVERLAY_PLANE 32

drmModeModeInfo fake_drm_mode(int w, int h, int hz, bool preferred)
{
    drmModeModeInfo m;
    memset(&m, 0, sizeof m);
    m.hdisplay = (uint16_t)w;
    m.vdisplay = (uint16_t)h;
    m.vrefresh = (uint32_t)hz;
    m.type = DRM_MODE_TYPE_DRIVER | (preferred ? DRM_MODE_TYPE_PREFERRED : 0);
    snprintf(m.name, sizeof m.name, "%dx%d", w, h);
    return m;
}

void fake_drm_disable(void)
{
    if (fake_drm.enabled) {
        close(fake_drm.pipe[0]);
        close(fake_drm.pipe[1]);
    }
    memset(&fake_drm, 0, sizeof fake_drm);
}

void fake_drm_enable(void)
{
    fake_drm_disable();
    fake_drm.enabled = true;
    if (pipe(fake_drm.pipe))
        abort();
    snprintf(fake_drm.device_path, sizeof fake_drm.device_path, "/proc/self/fd/%d", fake_drm.pipe[0]);
    fake_drm.n_connectors = 1;
    fake_drm_connector *c = &fake_drm.conn[0];
    c->id = 40;
    c->type = DRM_MODE_CONNECTOR_HDMIA;
    c->connected = true;
    c->n_modes = 3;
    c->modes[0] = fake_drm_mode(1920, 1080, 60, true);
    c->modes[1] = fake_drm_mode(1280, 720, 60, false);
    c->modes[2] = fake_drm_mode(1920, 1080, 50, false);
    fake_drm.crtc_ids[0] = 20;
    fake_drm.crtc_ids[1] = 21;
    fake_drm.initial_fb = 7;
    fake_drm.next_fb_id = 100;
}

void fake_drm_release_events(void)
{
    for (int i = 0; i < fake_drm.n_events; i++)
        if (write(fake_drm.pipe[1], "e", 1) != 1)
            abort();
}

static void queue_event(void *data)
{
    if (fake_drm.n_events == FAKE_DRM_MAX_EVENTS)
        abort();
    fake_drm.event_data[fake_drm.n_events++] = data;
    if (!fake_drm.hold_events && write(fake_drm.pipe[1], "e", 1) != 1)
        abort();
}

int drmHandleEvent(int fd, drmEventContextPtr ctx)
{
    if (!fake_drm.enabled)
        return REAL(drmHandleEvent)(fd, ctx);
    char byte;
    if (read(fd, &byte, 1) != 1 || fake_drm.n_events == 0)
        return -1;
    void *data = fake_drm.event_data[0];
    memmove(fake_drm.event_data, fake_drm.event_data + 1, sizeof(void *) * (size_t)--fake_drm.n_events);
    fake_drm.flip_events_delivered++;
    if (ctx->page_flip_handler)
        ctx->page_flip_handler(fd, 1, 0, 0, data);
    return 0;
}

int drmSetClientCap(int fd, uint64_t cap, uint64_t value)
{
    if (!fake_drm.enabled)
        return REAL(drmSetClientCap)(fd, cap, value);
    if (cap == DRM_CLIENT_CAP_ATOMIC && fake_drm.atomic_cap_refused) {
        errno = EOPNOTSUPP;
        return -1;
    }
    return 0;
}

drmModeResPtr drmModeGetResources(int fd)
{
    if (!fake_drm.enabled)
        return REAL(drmModeGetResources)(fd);
    if (fake_drm.resources_fail_calls > 0) {
        fake_drm.resources_fail_calls--;
        errno = EOPNOTSUPP;
        return NULL;
    }
    drmModeRes *r = calloc(1, sizeof *r);
    r->count_connectors = fake_drm.n_connectors;
    r->connectors = calloc(4, sizeof(uint32_t));
    for (int i = 0; i < fake_drm.n_connectors; i++)
        r->connectors[i] = fake_drm.conn[i].id;
    r->count_crtcs = 2;
    r->crtcs = calloc(2, sizeof(uint32_t));
    memcpy(r->crtcs, fake_drm.crtc_ids, sizeof fake_drm.crtc_ids);
    r->count_encoders = 1;
    r->encoders = calloc(1, sizeof(uint32_t));
    r->encoders[0] = ENCODER_ID;
    return r;
}

void drmModeFreeResources(drmModeResPtr r)
{
    if (!fake_drm.enabled) {
        REAL(drmModeFreeResources)(r);
        return;
    }
    if (!r)
        return;
    free(r->connectors);
    free(r->crtcs);
    free(r->encoders);
    free(r);
}

static drmModeConnectorPtr get_connector(uint32_t id)
{
    for (int i = 0; i < fake_drm.n_connectors; i++) {
        const fake_drm_connector *f = &fake_drm.conn[i];
        if (f->id != id)
            continue;
        drmModeConnector *c = calloc(1, sizeof *c);
        c->connector_id = f->id;
        c->connector_type = f->type;
        c->connector_type_id = 1;
        c->connection = f->connected ? DRM_MODE_CONNECTED : DRM_MODE_DISCONNECTED;
        c->count_modes = f->connected ? f->n_modes : 0;
        c->modes = calloc(FAKE_DRM_MAX_MODES, sizeof *c->modes);
        memcpy(c->modes, f->modes, sizeof f->modes);
        c->encoder_id = f->current_encoder;
        c->count_encoders = 1;
        c->encoders = calloc(1, sizeof(uint32_t));
        c->encoders[0] = ENCODER_ID;
        return c;
    }
    errno = ENOENT;
    return NULL;
}

drmModeConnectorPtr drmModeGetConnector(int fd, uint32_t id)
{
    return fake_drm.enabled ? get_connector(id) : REAL(drmModeGetConnector)(fd, id);
}

drmModeConnectorPtr drmModeGetConnectorCurrent(int fd, uint32_t id)
{
    return fake_drm.enabled ? get_connector(id) : REAL(drmModeGetConnectorCurrent)(fd, id);
}

void drmModeFreeConnector(drmModeConnectorPtr c)
{
    if (!fake_drm.enabled) {
        REAL(drmModeFreeConnector)(c);
        return;
    }
    if (!c)
        return;
    free(c->modes);
    free(c->encoders);
    free(c);
}

drmModeEncoderPtr drmModeGetEncoder(int fd, uint32_t id)
{
    if (!fake_drm.enabled)
        return REAL(drmModeGetEncoder)(fd, id);
    if (id != ENCODER_ID)
        return NULL;
    drmModeEncoder *enc = calloc(1, sizeof *enc);
    enc->encoder_id = id;
    enc->crtc_id = fake_drm.encoder_crtc;
    enc->possible_crtcs = 0x3;
    return enc;
}

void drmModeFreeEncoder(drmModeEncoderPtr enc)
{
    if (!fake_drm.enabled)
        REAL(drmModeFreeEncoder)(enc);
    else
        free(enc);
}

drmModeCrtcPtr drmModeGetCrtc(int fd, uint32_t id)
{
    if (!fake_drm.enabled)
        return REAL(drmModeGetCrtc)(fd, id);
    drmModeCrtc *c = calloc(1, sizeof *c);
    c->crtc_id = id;
    c->buffer_id = fake_drm.initial_fb;
    c->mode_valid = 1;
    c->mode = fake_drm_mode(1024, 768, 60, false); /* the console's mode, distinct from any we set */
    return c;
}

void drmModeFreeCrtc(drmModeCrtcPtr c)
{
    if (!fake_drm.enabled)
        REAL(drmModeFreeCrtc)(c);
    else
        free(c);
}

int drmModeSetCrtc(int fd, uint32_t crtc, uint32_t fb, uint32_t x, uint32_t y, uint32_t *conns, int count,
                   drmModeModeInfoPtr mode)
{
    if (!fake_drm.enabled)
        return REAL(drmModeSetCrtc)(fd, crtc, fb, x, y, conns, count, mode);
    fake_drm.setcrtc_calls++;
    fake_drm.setcrtc_crtc = crtc;
    fake_drm.setcrtc_fb = fb;
    fake_drm.setcrtc_had_mode = mode != NULL;
    if (mode)
        fake_drm.setcrtc_mode = *mode;
    return 0;
}

int drmModePageFlip(int fd, uint32_t crtc, uint32_t fb, uint32_t flags, void *data)
{
    if (!fake_drm.enabled)
        return REAL(drmModePageFlip)(fd, crtc, fb, flags, data);
    fake_drm.pageflip_calls++;
    if (fake_drm.flip_fails) {
        errno = EINVAL;
        return -1;
    }
    fake_drm.last_flip_fb = fb;
    if (flags & DRM_MODE_PAGE_FLIP_EVENT)
        queue_event(data);
    return 0;
}

int drmModeAddFB2(int fd, uint32_t w, uint32_t h, uint32_t format, const uint32_t handles[4],
                  const uint32_t pitches[4], const uint32_t offsets[4], uint32_t *id, uint32_t flags)
{
    if (!fake_drm.enabled)
        return REAL(drmModeAddFB2)(fd, w, h, format, handles, pitches, offsets, id, flags);
    fake_drm.addfb_calls++;
    *id = fake_drm.next_fb_id++;
    return 0;
}

int drmModeRmFB(int fd, uint32_t id)
{
    if (!fake_drm.enabled)
        return REAL(drmModeRmFB)(fd, id);
    fake_drm.rmfb_calls++;
    return 0;
}

drmModePlaneResPtr drmModeGetPlaneResources(int fd)
{
    if (!fake_drm.enabled)
        return REAL(drmModeGetPlaneResources)(fd);
    drmModePlaneRes *r = calloc(1, sizeof *r);
    r->count_planes = 2;
    r->planes = calloc(2, sizeof(uint32_t));
    r->planes[0] = OVERLAY_PLANE; /* an overlay first: the backend must look at the type */
    r->planes[1] = PRIMARY_PLANE;
    return r;
}

void drmModeFreePlaneResources(drmModePlaneResPtr r)
{
    if (!fake_drm.enabled) {
        REAL(drmModeFreePlaneResources)(r);
        return;
    }
    if (r) {
        free(r->planes);
        free(r);
    }
}

drmModePlanePtr drmModeGetPlane(int fd, uint32_t id)
{
    if (!fake_drm.enabled)
        return REAL(drmModeGetPlane)(fd, id);
    drmModePlane *p = calloc(1, sizeof *p);
    p->plane_id = id;
    p->possible_crtcs = 0x3;
    return p;
}

void drmModeFreePlane(drmModePlanePtr p)
{
    if (!fake_drm.enabled)
        REAL(drmModeFreePlane)(p);
    else
        free(p);
}

drmModeObjectPropertiesPtr drmModeObjectGetProperties(int fd, uint32_t obj, uint32_t type)
{
    if (!fake_drm.enabled)
        return REAL(drmModeObjectGetProperties)(fd, obj, type);
    drmModeObjectProperties *p = calloc(1, sizeof *p);
    p->count_props = N_PROPS;
    p->props = calloc(N_PROPS, sizeof(uint32_t));
    p->prop_values = calloc(N_PROPS, sizeof(uint64_t));
    for (int i = 0; i < N_PROPS; i++)
        p->props[i] = PROP_BASE + (uint32_t)i;
    /* "type": primary (1) for the primary plane, overlay (0) for the other */
    p->prop_values[0] = type == DRM_MODE_OBJECT_PLANE && obj == PRIMARY_PLANE ? DRM_PLANE_TYPE_PRIMARY
                                                                                : DRM_PLANE_TYPE_OVERLAY;
    return p;
}

void drmModeFreeObjectProperties(drmModeObjectPropertiesPtr p)
{
    if (!fake_drm.enabled) {
        REAL(drmModeFreeObjectProperties)(p);
        return;
    }
    if (p) {
        free(p->props);
        free(p->prop_values);
        free(p);
    }
}

drmModePropertyPtr drmModeGetProperty(int fd, uint32_t id)
{
    if (!fake_drm.enabled)
        return REAL(drmModeGetProperty)(fd, id);
    if (id < PROP_BASE || id >= PROP_BASE + N_PROPS)
        return NULL;
    drmModePropertyRes *p = calloc(1, sizeof *p);
    p->prop_id = id;
    snprintf(p->name, sizeof p->name, "%s", prop_names[id - PROP_BASE]);
    return p;
}

void drmModeFreeProperty(drmModePropertyPtr p)
{
    if (!fake_drm.enabled)
        REAL(drmModeFreeProperty)(p);
    else
        free(p);
}

/* The real request type is private to libdrm; the fake's own layout lives only here. */
struct _drmModeAtomicReq {
    int n;
    uint32_t obj[64], prop[64];
    uint64_t value[64];
};

drmModeAtomicReqPtr drmModeAtomicAlloc(void)
{
    if (!fake_drm.enabled)
        return REAL(drmModeAtomicAlloc)();
    return calloc(1, sizeof(struct _drmModeAtomicReq));
}

void drmModeAtomicFree(drmModeAtomicReqPtr req)
{
    if (!fake_drm.enabled)
        REAL(drmModeAtomicFree)(req);
    else
        free(req);
}

int drmModeAtomicAddProperty(drmModeAtomicReqPtr req, uint32_t obj, uint32_t prop, uint64_t value)
{
    if (!fake_drm.enabled)
        return REAL(drmModeAtomicAddProperty)(req, obj, prop, value);
    if (req->n == 64 || prop == 0)
        return -EINVAL;
    req->obj[req->n] = obj;
    req->prop[req->n] = prop;
    req->value[req->n++] = value;
    return req->n;
}

int drmModeAtomicCommit(int fd, const drmModeAtomicReqPtr req, uint32_t flags, void *data)
{
    if (!fake_drm.enabled)
        return REAL(drmModeAtomicCommit)(fd, req, flags, data);
    bool modeset = (flags & DRM_MODE_ATOMIC_ALLOW_MODESET) != 0;
    if ((modeset && fake_drm.atomic_modeset_refused) || (!modeset && fake_drm.flip_fails)) {
        errno = EINVAL;
        return -1;
    }
    fake_drm.atomic_commits++;
    fake_drm.atomic_modesets += modeset;
    for (int i = 0; i < req->n; i++)
        if (req->obj[i] == PRIMARY_PLANE && req->prop[i] == PROP_BASE + 1) /* FB_ID */
            fake_drm.last_flip_fb = (uint32_t)req->value[i];
    if (flags & DRM_MODE_PAGE_FLIP_EVENT)
        queue_event(data);
    return 0;
}

int drmModeCreatePropertyBlob(int fd, const void *data, size_t size, uint32_t *id)
{
    if (!fake_drm.enabled)
        return REAL(drmModeCreatePropertyBlob)(fd, data, size, id);
    *id = 77;
    return 0;
}

int drmModeDestroyPropertyBlob(int fd, uint32_t id)
{
    if (!fake_drm.enabled)
        return REAL(drmModeDestroyPropertyBlob)(fd, id);
    return 0;
}
