/* EGL context creation shared by the mock and KMS backends; see egl.h. */
#include "egl.h"

#include <stdio.h>
#include <string.h>

#include <GLES3/gl32.h>
#include <GLES2/gl2ext.h>

#include "base/log.h"

/* Under AddressSanitizer (make asan), Mesa's driver start-up inside eglInitialize keeps one-time
   state that is never freed, and unloads the driver before the leak report, so the report cannot
   be suppressed by library name. Allocations made while LeakSanitizer is disabled are not reported:
   only that call is excluded, every allocation of ours is still checked. */
#if defined(__SANITIZE_ADDRESS__)
#define GK_HAVE_LSAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define GK_HAVE_LSAN 1
#endif
#endif
#ifdef GK_HAVE_LSAN
#include <sanitizer/lsan_interface.h>
#define LSAN_OFF() __lsan_disable()
#define LSAN_ON() __lsan_enable()
#else
#define LSAN_OFF() ((void)0)
#define LSAN_ON() ((void)0)
#endif

bool gk_egl_has_ext(const char *ext, const char *name)
{
    if (!ext || !name || !*name)
        return false;
    size_t n = strlen(name);
    for (const char *p = ext; (p = strstr(p, name)) != NULL; p += n) {
        bool starts = p == ext || p[-1] == ' ';
        bool ends = p[n] == ' ' || p[n] == '\0';
        if (starts && ends)
            return true;
    }
    return false;
}

const char *gk_egl_error_string(EGLint err)
{
    static const struct { EGLint code; const char *name; } names[] = {
        {EGL_SUCCESS, "EGL_SUCCESS"}, {EGL_NOT_INITIALIZED, "EGL_NOT_INITIALIZED"},
        {EGL_BAD_ACCESS, "EGL_BAD_ACCESS"}, {EGL_BAD_ALLOC, "EGL_BAD_ALLOC"},
        {EGL_BAD_ATTRIBUTE, "EGL_BAD_ATTRIBUTE"}, {EGL_BAD_CONFIG, "EGL_BAD_CONFIG"},
        {EGL_BAD_CONTEXT, "EGL_BAD_CONTEXT"}, {EGL_BAD_CURRENT_SURFACE, "EGL_BAD_CURRENT_SURFACE"},
        {EGL_BAD_DISPLAY, "EGL_BAD_DISPLAY"}, {EGL_BAD_MATCH, "EGL_BAD_MATCH"},
        {EGL_BAD_NATIVE_PIXMAP, "EGL_BAD_NATIVE_PIXMAP"}, {EGL_BAD_NATIVE_WINDOW, "EGL_BAD_NATIVE_WINDOW"},
        {EGL_BAD_PARAMETER, "EGL_BAD_PARAMETER"}, {EGL_BAD_SURFACE, "EGL_BAD_SURFACE"},
        {EGL_CONTEXT_LOST, "EGL_CONTEXT_LOST"},
    };
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        if (names[i].code == err)
            return names[i].name;
    return "unknown EGL error";
}

EGLBoolean gk_egl_initialize(EGLDisplay dpy, EGLint *major, EGLint *minor)
{
    LSAN_OFF();
    EGLBoolean ok = eglInitialize(dpy, major, minor);
    LSAN_ON();
    return ok;
}

int gk_egl_init_display(gk_egl *g, EGLDisplay dpy, gk_err *e)
{
    memset(g, 0, sizeof *g);
    g->dpy = EGL_NO_DISPLAY;
    g->ctx = EGL_NO_CONTEXT;
    g->cfg = EGL_NO_CONFIG_KHR;
    if (dpy == EGL_NO_DISPLAY)
        return gk_fail(e, GK_ERUNTIME, "EGL: no display (%s)", gk_egl_error_string(eglGetError()));
    EGLint major = 0, minor = 0;
    if (!gk_egl_initialize(dpy, &major, &minor))
        return gk_fail(e, GK_ERUNTIME, "EGL: eglInitialize failed (%s)", gk_egl_error_string(eglGetError()));
    if (!eglBindAPI(EGL_OPENGL_ES_API)) {
        eglTerminate(dpy);
        return gk_fail(e, GK_ERUNTIME, "EGL: OpenGL ES API not available (%s)",
                       gk_egl_error_string(eglGetError()));
    }
    g->dpy = dpy;
    g->egl_major = major;
    g->egl_minor = minor;
    return 0;
}

int gk_egl_create_context(gk_egl *g, EGLConfig cfg, bool debug, gk_err *e)
{
    const char *ext = eglQueryString(g->dpy, EGL_EXTENSIONS);
    bool egl15 = g->egl_major > 1 || (g->egl_major == 1 && g->egl_minor >= 5);
    bool robust_offered = gk_egl_has_ext(ext, "EGL_EXT_create_context_robustness");
    /* EGL_CONTEXT_OPENGL_DEBUG is an EGL 1.5 token: on 1.4 displays (GBM, softpipe) it makes
     * eglCreateContext fail with EGL_BAD_ATTRIBUTE, so it is only asked on 1.5. */
    bool want_debug = debug && egl15;
    EGLint last_error = EGL_SUCCESS;
    for (int minor = 2; minor >= 1; minor--) {
        for (int robust = robust_offered ? 1 : 0; robust >= 0; robust--) {
            EGLint attr[16];
            int n = 0;
            attr[n++] = EGL_CONTEXT_MAJOR_VERSION;
            attr[n++] = 3;
            attr[n++] = EGL_CONTEXT_MINOR_VERSION;
            attr[n++] = minor;
            if (robust) {
                attr[n++] = EGL_CONTEXT_OPENGL_ROBUST_ACCESS_EXT;
                attr[n++] = EGL_TRUE;
                attr[n++] = EGL_CONTEXT_OPENGL_RESET_NOTIFICATION_STRATEGY_EXT;
                attr[n++] = EGL_LOSE_CONTEXT_ON_RESET_EXT;
            }
            if (want_debug) {
                attr[n++] = EGL_CONTEXT_OPENGL_DEBUG;
                attr[n++] = EGL_TRUE;
            }
            attr[n++] = EGL_NONE;
            EGLContext ctx = eglCreateContext(g->dpy, cfg, EGL_NO_CONTEXT, attr);
            if (ctx != EGL_NO_CONTEXT) {
                g->ctx = ctx;
                g->cfg = cfg;
                g->debug = want_debug;
                return 0;
            }
            last_error = eglGetError();
        }
    }
    return gk_fail(e, GK_ERUNTIME, "EGL: cannot create an OpenGL ES 3.1 or 3.2 context (%s)",
                   gk_egl_error_string(last_error));
}

static void GL_APIENTRY log_gl_debug(GLenum source, GLenum type, GLuint id, GLenum severity,
                                     GLsizei length, const GLchar *message, const void *user)
{
    (void)source; (void)id; (void)length; (void)user;
    if (severity == GL_DEBUG_SEVERITY_NOTIFICATION)
        return; /* push/pop group chatter: not worth a line each */
    const char *kind = type == GL_DEBUG_TYPE_ERROR ? "error" :
                       type == GL_DEBUG_TYPE_PERFORMANCE ? "performance" : "debug";
    gk_log("GL %s: %s", kind, message);
}

static void install_debug_callback(int gles_version)
{
    typedef void (GL_APIENTRY *callback_fn)(GLDEBUGPROC, const void *);
    const char *gl_ext = (const char *)glGetString(GL_EXTENSIONS);
    callback_fn set_callback = NULL;
    if (gles_version >= 32)
        set_callback = (callback_fn)eglGetProcAddress("glDebugMessageCallback");
    else if (gk_egl_has_ext(gl_ext, "GL_KHR_debug"))
        set_callback = (callback_fn)eglGetProcAddress("glDebugMessageCallbackKHR");
    if (!set_callback) {
        gk_log("GL debug output asked but KHR_debug is not available");
        return;
    }
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    set_callback(log_gl_debug, NULL);
}

int gk_egl_make_current(gk_egl *g, EGLSurface surf, gk_err *e)
{
    if (!eglMakeCurrent(g->dpy, surf, surf, g->ctx))
        return gk_fail(e, GK_ERUNTIME, "EGL: eglMakeCurrent failed (%s)", gk_egl_error_string(eglGetError()));
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    int version = major * 10 + minor;
    if (version < 31)
        return gk_fail(e, GK_ERUNTIME, "GL: got OpenGL ES %d.%d, need 3.1 or later", major, minor);
    g->gles_version = version >= 32 ? 32 : 31;
    if (g->debug)
        install_debug_callback(g->gles_version);
    gk_log("OpenGL ES %d.%d (EGL %d.%d) on %s%s", major, minor, g->egl_major, g->egl_minor,
           (const char *)glGetString(GL_RENDERER), g->debug ? ", debug output on" : "");
    return 0;
}

void gk_egl_terminate(gk_egl *g)
{
    if (g->dpy == EGL_NO_DISPLAY)
        return;
    eglMakeCurrent(g->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (g->ctx != EGL_NO_CONTEXT)
        eglDestroyContext(g->dpy, g->ctx);
    eglTerminate(g->dpy);
    eglReleaseThread();
    g->ctx = EGL_NO_CONTEXT;
    g->dpy = EGL_NO_DISPLAY;
}
