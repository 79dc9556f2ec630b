/* EGL context creation shared by the backends (mock: surfaceless display, kms: GBM display).
 * Asks for OpenGL ES 3.2, accepts 3.1, and records the version actually obtained (31 or 32). */
#ifndef GK_PLATFORM_EGL_H
#define GK_PLATFORM_EGL_H

#include <stdbool.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include "base/err.h"

typedef struct gk_egl {
    EGLDisplay dpy;
    EGLContext ctx;
    EGLConfig cfg;          /* EGL_NO_CONFIG_KHR for a configless context */
    int egl_major, egl_minor;
    int gles_version;       /* 31 or 32, filled by gk_egl_make_current */
    bool debug;             /* a KHR_debug callback is installed */
} gk_egl;

/* True when the space-separated extension list ext contains name exactly. */
bool gk_egl_has_ext(const char *ext, const char *name);

/* eglInitialize, with Mesa's never-freed driver start-up state excluded from LeakSanitizer under
 * `make asan` (see egl.c). Every eglInitialize of the project (tests included) goes through it. */
EGLBoolean gk_egl_initialize(EGLDisplay dpy, EGLint *major, EGLint *minor);

/* eglInitialize + eglBindAPI(ES). On failure the display is not left initialized. */
int gk_egl_init_display(gk_egl *g, EGLDisplay dpy, gk_err *e);

/* Creates an ES context on cfg (EGL_NO_CONFIG_KHR allowed when the display supports it): 3.2 asked,
 * 3.1 accepted; robustness where offered; EGL_CONTEXT_OPENGL_DEBUG only on EGL 1.5 and when debug. */
int gk_egl_create_context(gk_egl *g, EGLConfig cfg, bool debug, gk_err *e);

/* Makes the context current with surf (EGL_NO_SURFACE: surfaceless), checks the GL version
 * obtained (>= 3.1), installs the debug callback when asked and logs version and renderer once. */
int gk_egl_make_current(gk_egl *g, EGLSurface surf, gk_err *e);

/* Releases the context and terminates the display (safe on a partly set-up gk_egl). */
void gk_egl_terminate(gk_egl *g);

/* "EGL_BAD_MATCH (0x3009)" for the last EGL error. */
const char *gk_egl_error_string(EGLint err);

#endif
