#include "gl_timing.h"

#include <EGL/egl.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define RING (GK_TIMER_LAG + 1)

typedef struct frame_slot {
    int n;
    const char *name[GK_MAX_PASSES];
    GLuint query[GK_MAX_PASSES];
    bool pending;
} frame_slot;

struct gk_timer {
    bool gpu;
    /* CPU mode */
    double t0;
    gk_pass_times cur;
    /* GPU mode */
    PFNGLGENQUERIESEXTPROC gen;
    PFNGLDELETEQUERIESEXTPROC del;
    PFNGLBEGINQUERYEXTPROC begin;
    PFNGLENDQUERYEXTPROC end;
    PFNGLGETQUERYOBJECTUIVEXTPROC get_u;
    PFNGLGETQUERYOBJECTUI64VEXTPROC get_u64;
    frame_slot slot[RING];
    int frame;
    gk_pass_times last;
};

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

gk_timer *gk_timer_create(bool use_gpu_queries)
{
    gk_timer *t = calloc(1, sizeof *t);
    if (!t)
        return NULL;
    if (use_gpu_queries && gk_gl_has_extension("GL_EXT_disjoint_timer_query")) {
        t->gen = (PFNGLGENQUERIESEXTPROC)eglGetProcAddress("glGenQueriesEXT");
        t->del = (PFNGLDELETEQUERIESEXTPROC)eglGetProcAddress("glDeleteQueriesEXT");
        t->begin = (PFNGLBEGINQUERYEXTPROC)eglGetProcAddress("glBeginQueryEXT");
        t->end = (PFNGLENDQUERYEXTPROC)eglGetProcAddress("glEndQueryEXT");
        t->get_u = (PFNGLGETQUERYOBJECTUIVEXTPROC)eglGetProcAddress("glGetQueryObjectuivEXT");
        t->get_u64 = (PFNGLGETQUERYOBJECTUI64VEXTPROC)eglGetProcAddress("glGetQueryObjectui64vEXT");
        t->gpu = t->gen && t->del && t->begin && t->end && t->get_u && t->get_u64;
        if (t->gpu)
            for (int i = 0; i < RING; i++)
                t->gen(GK_MAX_PASSES, t->slot[i].query);
    }
    return t;
}

void gk_timer_destroy(gk_timer *t)
{
    if (!t)
        return;
    if (t->gpu)
        for (int i = 0; i < RING; i++)
            t->del(GK_MAX_PASSES, t->slot[i].query);
    free(t);
}

bool gk_timer_uses_gpu(const gk_timer *t) { return t->gpu; }

void gk_timer_frame_begin(gk_timer *t)
{
    memset(&t->cur, 0, sizeof t->cur);
    if (t->gpu)
        t->slot[t->frame % RING].n = 0;
}

void gk_timer_pass_begin(gk_timer *t, const char *name)
{
    if (t->gpu) {
        frame_slot *s = &t->slot[t->frame % RING];
        if (s->n >= GK_MAX_PASSES)
            return;
        s->name[s->n] = name;
        t->begin(GL_TIME_ELAPSED_EXT, s->query[s->n]);
        return;
    }
    if (t->cur.n >= GK_MAX_PASSES)
        return;
    glFinish(); /* the previous pass's work must not be billed to this one */
    t->cur.name[t->cur.n] = name;
    t->t0 = now_ms();
}

void gk_timer_pass_end(gk_timer *t)
{
    if (t->gpu) {
        frame_slot *s = &t->slot[t->frame % RING];
        if (s->n >= GK_MAX_PASSES)
            return;
        t->end(GL_TIME_ELAPSED_EXT);
        s->n++;
        return;
    }
    if (t->cur.n >= GK_MAX_PASSES)
        return;
    glFinish();
    t->cur.ms[t->cur.n++] = now_ms() - t->t0;
}

/* Passes with the same name in one frame (one per light) are summed into one column. */
static void add_pass(gk_pass_times *out, const char *name, double ms)
{
    for (int i = 0; i < out->n; i++)
        if (strcmp(out->name[i], name) == 0) {
            out->ms[i] += ms;
            return;
        }
    if (out->n < GK_MAX_PASSES) {
        out->name[out->n] = name;
        out->ms[out->n++] = ms;
    }
}

void gk_timer_frame_end(gk_timer *t, gk_pass_times *out)
{
    memset(out, 0, sizeof *out);
    if (!t->gpu) {
        for (int i = 0; i < t->cur.n; i++)
            add_pass(out, t->cur.name[i], t->cur.ms[i]);
        return;
    }
    t->slot[t->frame % RING].pending = true;
    t->frame++;
    /* The slot written GK_TIMER_LAG frames ago is read now (and reused next frame). */
    frame_slot *old = &t->slot[t->frame % RING];
    if (old->pending) {
        GLint disjoint = 0;
        glGetIntegerv(GL_GPU_DISJOINT_EXT, &disjoint);
        GLuint avail = 1;
        if (old->n > 0)
            t->get_u(old->query[old->n - 1], GL_QUERY_RESULT_AVAILABLE_EXT, &avail);
        if (!disjoint && avail) {
            gk_pass_times fresh = {0};
            for (int i = 0; i < old->n; i++) {
                GLuint64 ns = 0;
                t->get_u64(old->query[i], GL_QUERY_RESULT_EXT, &ns);
                add_pass(&fresh, old->name[i], (double)ns * 1e-6);
            }
            t->last = fresh;
        }
        old->pending = false;
    }
    *out = t->last;
}
