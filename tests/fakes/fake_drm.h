/* Link-level fake of the libdrm calls the KMS backend uses. Inert unless a test calls
 * fake_drm_enable(): until then every function forwards to the real libdrm (dlsym RTLD_NEXT).
 * The "device" is a pipe: the backend opens fake_drm.device_path, and each queued flip event
 * writes one byte so the backend's poll() wakes like on a real DRM fd. */
#ifndef GK_FAKE_DRM_H
#define GK_FAKE_DRM_H

#include <stdbool.h>
#include <stdint.h>

#include <xf86drm.h>
#include <xf86drmMode.h>

#define FAKE_DRM_MAX_MODES 8
#define FAKE_DRM_MAX_EVENTS 16

typedef struct fake_drm_connector {
    uint32_t id;
    uint32_t type;                  /* DRM_MODE_CONNECTOR_HDMIA ... */
    bool connected;
    int n_modes;
    drmModeModeInfo modes[FAKE_DRM_MAX_MODES];
    uint32_t current_encoder;       /* 0 = not driven yet */
} fake_drm_connector;

typedef struct fake_drm_state {
    bool enabled;
    char device_path[64];
    int pipe[2];
    /* the card */
    int n_connectors;
    fake_drm_connector conn[4];
    uint32_t crtc_ids[2];           /* two CRTCs; the encoder can drive both */
    uint32_t encoder_crtc;          /* CRTC the encoder currently drives (0 = none) */
    uint32_t initial_fb;            /* what the saved CRTC shows (the console) */
    int resources_fail_calls;       /* GetResources gives NULL this many times first */
    bool atomic_cap_refused;
    bool atomic_modeset_refused;
    bool flip_fails;
    bool hold_events;               /* queue flip events but do not wake the fd */
    /* what happened */
    int setcrtc_calls, pageflip_calls, atomic_commits, atomic_modesets, addfb_calls, rmfb_calls;
    int flip_events_delivered;
    uint32_t setcrtc_crtc, setcrtc_fb, last_flip_fb;
    drmModeModeInfo setcrtc_mode;
    bool setcrtc_had_mode;
    uint32_t next_fb_id;
    int n_events;
    void *event_data[FAKE_DRM_MAX_EVENTS];
} fake_drm_state;

extern fake_drm_state fake_drm;

drmModeModeInfo fake_drm_mode(int w, int h, int hz, bool preferred);
/* One HDMI connector, connected, offering 1920x1080@60 (preferred), 1280x720@60, 1920x1080@50. */
void fake_drm_enable(void);
void fake_drm_disable(void);
/* Wakes the fd for events queued while hold_events was set. */
void fake_drm_release_events(void);

#endif
