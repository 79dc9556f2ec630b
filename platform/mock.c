/* The mock platform: EGL surfaceless display, a configless ES context, an FBO with an RGBA8 colour
 * texture of the requested size as "the display", a virtual clock (presents x frame period) and
 * input from a button script through the same gesture detector as real buttons. Deterministic. */
#include <stdlib.h>
#include <string.h>

#include <GLES3/gl32.h>

#include "egl.h"
#include "platform_impl.h"
#include "script.h"

typedef struct mock {
    gk_egl egl;
    GLuint fbo, color;
    long presents;
    double period_s;
    gk_script script;
    gk_gesture gesture[GK_BTN_COUNT];
    bool quit_at_script_end, quit_sent;
} mock;

static double mock_now(const gk_platform *p)
{
    const mock *m = p->impl;
    return (double)m->presents * m->period_s;
}

static int mock_present(gk_platform *p, gk_err *e)
{
    (void)e;
    mock *m = p->impl;
    /* Flush so the frame is really rendered "by the display time", as a swap would. */
    glFlush();
    m->presents++;
    return 0;
}

static void push_all(gk_platform *p, const gk_input_event *ev, int n)
{
    for (int i = 0; i < n; i++)
        gk_evq_push(&p->queue, ev[i]);
}

static void tick_all(gk_platform *p, double t)
{
    mock *m = p->impl;
    gk_input_event ev[GK_GESTURE_MAX_EVENTS];
    for (int b = 0; b < GK_BTN_COUNT; b++)
        push_all(p, ev, gk_gesture_tick(&m->gesture[b], (enum gk_button)b, t, ev));
}

/* Virtual time does not pass while polling, so the timeout is not waited: everything due at the
 * current virtual time is delivered at once. */
static int mock_poll(gk_platform *p, int timeout_ms)
{
    (void)timeout_ms;
    mock *m = p->impl;
    double now = mock_now(p);
    gk_input_event ev[GK_GESTURE_MAX_EVENTS];
    /* 1e-9: the virtual clock is a product of doubles; an edge scripted "at" a frame time counts. */
    while (m->script.next < m->script.count && m->script.edges[m->script.next].time_s <= now + 1e-9) {
        const gk_raw_edge *edge = &m->script.edges[m->script.next++];
        tick_all(p, edge->time_s); /* holds of other buttons that fell due earlier come first */
        push_all(p, ev, gk_gesture_edge(&m->gesture[edge->button], edge->button, edge->pressed, edge->time_s, ev));
    }
    tick_all(p, now);
    if (m->quit_at_script_end && !m->quit_sent && m->script.next == m->script.count) {
        bool any_down = false;
        for (int b = 0; b < GK_BTN_COUNT; b++)
            any_down |= m->gesture[b].down;
        if (!any_down) {
            m->quit_sent = true;
            gk_evq_push(&p->queue, (gk_input_event){.kind = GK_INPUT_QUIT, .button = GK_BTN_NEXT, .time_s = now});
        }
    }
    return 0;
}

static void mock_close(gk_platform *p)
{
    mock *m = p->impl;
    if (m->egl.ctx != EGL_NO_CONTEXT && eglGetCurrentContext() == m->egl.ctx) {
        if (m->fbo)
            glDeleteFramebuffers(1, &m->fbo);
        if (m->color)
            glDeleteTextures(1, &m->color);
    }
    gk_egl_terminate(&m->egl);
    gk_script_free(&m->script);
    free(m);
    free(p);
}

static const struct gk_platform_ops mock_ops = {
    .name = "mock", .present = mock_present, .poll = mock_poll, .now = mock_now, .close = mock_close,
};

static int create_framebuffer(mock *m, int w, int h, gk_err *e)
{
    glGenTextures(1, &m->color);
    glBindTexture(GL_TEXTURE_2D, m->color);
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA8, w, h);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindTexture(GL_TEXTURE_2D, 0);
    glGenFramebuffers(1, &m->fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, m->fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, m->color, 0);
    GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        return gk_fail(e, GK_ERUNTIME, "mock platform: %dx%d RGBA8 framebuffer incomplete (0x%x)", w, h, status);
    glViewport(0, 0, w, h);
    return 0;
}

/* The mock's size cap (DCI 4K). On llvmpipe a frame's time grows with its pixels: issue 12 measured
 * 23 s at 4096x4096 with GI, so about 12 s here at most; a stop request is honoured between a
 * frame's passes (app/render/render_frame.c), so this cap bounds how long SIGTERM waits through the
 * longest pass at this size (board/gikiosk.service's TimeoutStopSec). Larger sizes are refused, not
 * left to run for minutes a frame. */
#define GK_MOCK_MAX_SIDE 4096
#define GK_MOCK_MAX_PIXELS (4096 * 2160)

gk_platform *gk_mock_open(const gk_platform_desc *desc, gk_err *e)
{
    if (desc->width <= 0 || desc->height <= 0 || desc->width > GK_MOCK_MAX_SIDE || desc->height > GK_MOCK_MAX_SIDE ||
        (long)desc->width * desc->height > GK_MOCK_MAX_PIXELS) {
        gk_fail(e, GK_EINPUT, "mock platform: size %dx%d is beyond the mock's limit (at most %d on a side and "
                "%d pixels, 4096x2160)", desc->width, desc->height, GK_MOCK_MAX_SIDE, GK_MOCK_MAX_PIXELS);
        return NULL;
    }
    gk_platform *p = calloc(1, sizeof *p);
    mock *m = calloc(1, sizeof *m);
    if (!p || !m) {
        free(p);
        free(m);
        gk_fail(e, GK_ERUNTIME, "out of memory");
        return NULL;
    }
    p->ops = &mock_ops;
    p->impl = m;
    m->egl.dpy = EGL_NO_DISPLAY;
    m->period_s = desc->frame_period_s > 0 ? desc->frame_period_s : 1.0 / 60.0;
    m->quit_at_script_end = desc->quit_at_script_end;
    for (int b = 0; b < GK_BTN_COUNT; b++)
        gk_gesture_init(&m->gesture[b], desc->buttons.hold_ms);
    /* The script first: a bad script is bad input (exit 2) and costs no GPU setup. */
    if (desc->script_path[0] && gk_script_load(desc->script_path, &m->script, e))
        goto fail;
    EGLDisplay dpy = eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
    if (gk_egl_init_display(&m->egl, dpy, e)) {
        gk_fail_prefix(e, "mock platform: ");
        goto fail;
    }
    const char *ext = eglQueryString(m->egl.dpy, EGL_EXTENSIONS);
    EGLConfig cfg = EGL_NO_CONFIG_KHR;
    if (!gk_egl_has_ext(ext, "EGL_KHR_no_config_context") && !gk_egl_has_ext(ext, "EGL_MESA_configless_context")) {
        EGLint attr[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_ES3_BIT, EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8,
                         EGL_BLUE_SIZE, 8, EGL_ALPHA_SIZE, 8, EGL_NONE};
        EGLint n = 0;
        if (!eglChooseConfig(m->egl.dpy, attr, &cfg, 1, &n) || n < 1) {
            gk_fail(e, GK_ERUNTIME, "mock platform: no RGBA8 ES3 EGL config");
            goto fail;
        }
    }
    if (!gk_egl_has_ext(ext, "EGL_KHR_surfaceless_context")) {
        gk_fail(e, GK_ERUNTIME, "mock platform: EGL_KHR_surfaceless_context missing");
        goto fail;
    }
    if (gk_egl_create_context(&m->egl, cfg, desc->debug, e) || gk_egl_make_current(&m->egl, EGL_NO_SURFACE, e)) {
        gk_fail_prefix(e, "mock platform: ");
        goto fail;
    }
    /* What the GPU can render to bounds the size too (a context may offer less than the cap). */
    GLint max_rb = 0;
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_rb);
    if (max_rb > 0 && (desc->width > max_rb || desc->height > max_rb)) {
        gk_fail(e, GK_EINPUT, "mock platform: size %dx%d is beyond the GPU's GL_MAX_RENDERBUFFER_SIZE %d",
                desc->width, desc->height, max_rb);
        goto fail;
    }
    if (create_framebuffer(m, desc->width, desc->height, e))
        goto fail;
    p->width = desc->width;
    p->height = desc->height;
    p->gles_version = m->egl.gles_version;
    p->framebuffer = m->fbo;
    return p;
fail:
    mock_close(p);
    return NULL;
}
