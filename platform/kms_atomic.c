/* Atomic KMS: the primary plane of our CRTC, property ids looked up by name, one commit per frame
 * (ALLOW_MODESET the first time, then NONBLOCK + PAGE_FLIP_EVENT). A refused atomic modeset falls
 * back to legacy once, for good. */
#include "kms.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "base/log.h"

static uint32_t find_prop(int fd, uint32_t obj, uint32_t type, const char *name, uint64_t *value)
{
    drmModeObjectProperties *props = drmModeObjectGetProperties(fd, obj, type);
    if (!props)
        return 0;
    uint32_t id = 0;
    for (uint32_t i = 0; i < props->count_props && !id; i++) {
        drmModePropertyRes *p = drmModeGetProperty(fd, props->props[i]);
        if (p && strcmp(p->name, name) == 0) {
            id = p->prop_id;
            if (value)
                *value = props->prop_values[i];
        }
        drmModeFreeProperty(p);
    }
    drmModeFreeObjectProperties(props);
    return id;
}

static uint32_t find_primary_plane(gk_kms *k)
{
    drmModePlaneRes *res = drmModeGetPlaneResources(k->fd);
    if (!res)
        return 0;
    uint32_t found = 0;
    for (uint32_t i = 0; i < res->count_planes && !found; i++) {
        drmModePlane *plane = drmModeGetPlane(k->fd, res->planes[i]);
        if (!plane)
            continue;
        uint64_t type = 0;
        if ((plane->possible_crtcs & (1u << k->crtc_index)) &&
            find_prop(k->fd, plane->plane_id, DRM_MODE_OBJECT_PLANE, "type", &type) &&
            type == DRM_PLANE_TYPE_PRIMARY)
            found = plane->plane_id;
        drmModeFreePlane(plane);
    }
    drmModeFreePlaneResources(res);
    return found;
}

static int use_legacy(gk_kms *k, const char *why)
{
    gk_log("kms: atomic modesetting not available (%s): using legacy SetCrtc/PageFlip", why);
    k->commit = gk_kms_legacy_commit;
    return 0;
}

int gk_kms_atomic_init(gk_kms *k, gk_err *e)
{
    (void)e;
    drmSetClientCap(k->fd, DRM_CLIENT_CAP_UNIVERSAL_PLANES, 1);
    if (drmSetClientCap(k->fd, DRM_CLIENT_CAP_ATOMIC, 1))
        return use_legacy(k, "client cap refused");
    k->plane_id = find_primary_plane(k);
    if (!k->plane_id)
        return use_legacy(k, "no primary plane for the CRTC");
    struct gk_kms_atomic_props *p = &k->prop;
    int fd = k->fd;
    p->conn_crtc_id = find_prop(fd, k->connector_id, DRM_MODE_OBJECT_CONNECTOR, "CRTC_ID", NULL);
    p->crtc_mode_id = find_prop(fd, k->crtc_id, DRM_MODE_OBJECT_CRTC, "MODE_ID", NULL);
    p->crtc_active = find_prop(fd, k->crtc_id, DRM_MODE_OBJECT_CRTC, "ACTIVE", NULL);
    const char *plane_names[] = {"FB_ID", "CRTC_ID", "SRC_X", "SRC_Y", "SRC_W", "SRC_H",
                                 "CRTC_X", "CRTC_Y", "CRTC_W", "CRTC_H"};
    uint32_t *plane_ids[] = {&p->plane_fb_id, &p->plane_crtc_id, &p->src_x, &p->src_y, &p->src_w, &p->src_h,
                             &p->crtc_x, &p->crtc_y, &p->crtc_w, &p->crtc_h};
    bool all = p->conn_crtc_id && p->crtc_mode_id && p->crtc_active;
    for (int i = 0; i < 10; i++) {
        *plane_ids[i] = find_prop(fd, k->plane_id, DRM_MODE_OBJECT_PLANE, plane_names[i], NULL);
        all = all && *plane_ids[i];
    }
    if (!all)
        return use_legacy(k, "missing KMS properties");
    k->commit = gk_kms_atomic_commit;
    return 0;
}

int gk_kms_atomic_commit(gk_kms *k, uint32_t fb_id, bool modeset, gk_err *e)
{
    drmModeAtomicReq *req = drmModeAtomicAlloc();
    if (!req)
        return gk_fail(e, GK_ERUNTIME, "out of memory");
    const struct gk_kms_atomic_props *p = &k->prop;
    uint32_t flags = DRM_MODE_PAGE_FLIP_EVENT;
    if (modeset) {
        if (!k->mode_blob && drmModeCreatePropertyBlob(k->fd, &k->mode, sizeof k->mode, &k->mode_blob)) {
            drmModeAtomicFree(req);
            return gk_fail(e, GK_ERUNTIME, "kms: cannot create the mode blob: %s", strerror(errno));
        }
        drmModeAtomicAddProperty(req, k->connector_id, p->conn_crtc_id, k->crtc_id);
        drmModeAtomicAddProperty(req, k->crtc_id, p->crtc_mode_id, k->mode_blob);
        drmModeAtomicAddProperty(req, k->crtc_id, p->crtc_active, 1);
        flags |= DRM_MODE_ATOMIC_ALLOW_MODESET;
    } else {
        flags |= DRM_MODE_ATOMIC_NONBLOCK;
    }
    uint32_t w = k->mode.hdisplay, h = k->mode.vdisplay;
    drmModeAtomicAddProperty(req, k->plane_id, p->plane_fb_id, fb_id);
    drmModeAtomicAddProperty(req, k->plane_id, p->plane_crtc_id, k->crtc_id);
    drmModeAtomicAddProperty(req, k->plane_id, p->src_x, 0);
    drmModeAtomicAddProperty(req, k->plane_id, p->src_y, 0);
    drmModeAtomicAddProperty(req, k->plane_id, p->src_w, (uint64_t)w << 16); /* 16.16 fixed point */
    drmModeAtomicAddProperty(req, k->plane_id, p->src_h, (uint64_t)h << 16);
    drmModeAtomicAddProperty(req, k->plane_id, p->crtc_x, 0);
    drmModeAtomicAddProperty(req, k->plane_id, p->crtc_y, 0);
    drmModeAtomicAddProperty(req, k->plane_id, p->crtc_w, w);
    drmModeAtomicAddProperty(req, k->plane_id, p->crtc_h, h);
    int rc = drmModeAtomicCommit(k->fd, req, flags, k);
    int err = errno;
    drmModeAtomicFree(req);
    if (rc == 0) {
        k->flip_pending = true;
        return 0;
    }
    if (modeset) {
        /* Some drivers advertise atomic but refuse the modeset (e.g. the plane setup): legacy can
         * still drive them. The switch is for good: one function pointer. */
        char why[96];
        snprintf(why, sizeof why, "modeset refused: %s", strerror(err));
        use_legacy(k, why);
        return k->commit(k, fb_id, true, e);
    }
    return gk_fail(e, GK_ERUNTIME, "kms: atomic page flip failed: %s", strerror(err));
}
