/* Legacy KMS: drmModeSetCrtc for the first frame, drmModePageFlip afterwards. Used when the driver
 * refuses atomic (old drivers, or a refused atomic modeset). */
#include "kms.h"

#include <errno.h>
#include <string.h>

int gk_kms_legacy_commit(gk_kms *k, uint32_t fb_id, bool modeset, gk_err *e)
{
    if (modeset) {
        if (drmModeSetCrtc(k->fd, k->crtc_id, fb_id, 0, 0, &k->connector_id, 1, &k->mode))
            return gk_fail(e, GK_ERUNTIME, "kms: drmModeSetCrtc %s on CRTC %u failed: %s", k->mode.name,
                           k->crtc_id, strerror(errno));
        return 0; /* synchronous: no event follows */
    }
    if (drmModePageFlip(k->fd, k->crtc_id, fb_id, DRM_MODE_PAGE_FLIP_EVENT, k))
        return gk_fail(e, GK_ERUNTIME, "kms: drmModePageFlip failed: %s", strerror(errno));
    k->flip_pending = true;
    return 0;
}
