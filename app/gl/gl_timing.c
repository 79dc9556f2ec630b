#include "gl_timing.h"

#include <EGL/egl.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define RING (GK_TIMER_LAG + 1)
#define FENCE_TIMEOUT_NS 10000000000ull /* 10 s: a hung GPU must not hang the clock forever */

/* One frame's pass tree and, in GPU mode, its query segments. */
typedef struct frame_slot {
    gk_frame_report report;           /* names and parents; ms filled when resolved */
    int n_queries;
    GLuint query[GK_TIMER_MAX_QUERIES];
    int owner[GK_TIMER_MAX_QUERIES];  /* pass index each query segment is billed to */
    bool pending;
} frame_slot;

struct gk_timer {
    bool gpu;
    gk_timer_queries q;
    frame_slot slot[RING];
    int frame;                        /* GPU mode: frames begun */
    int stack[GK_TIMER_MAX_DEPTH];    /* open passes, innermost last */
    double started[GK_TIMER_MAX_DEPTH];
    int depth;
    int overflow;                     /* passes begun past a limit: their ends are ignored */
    bool query_open;
    gk_frame_report last;
};

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

/* CPU mode: everything submitted so far has run when this returns. */
static void wait_gpu_idle(void)
{
    GLsync s = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    if (!s)
        return;
    glClientWaitSync(s, GL_SYNC_FLUSH_COMMANDS_BIT, FENCE_TIMEOUT_NS);
    glDeleteSync(s);
}

static bool ext_disjoint(void)
{
    GLint d = 0;
    glGetIntegerv(GL_GPU_DISJOINT_EXT, &d);
    return d != 0;
}

static gk_timer *create(const gk_timer_queries *q)
{
    gk_timer *t = calloc(1, sizeof *t);
    if (!t)
        return NULL;
    if (q) {
        t->q = *q;
        t->gpu = true;
        for (int i = 0; i < RING; i++)
            t->q.gen(GK_TIMER_MAX_QUERIES, t->slot[i].query);
    }
    return t;
}

gk_timer *gk_timer_create_with_queries(const gk_timer_queries *q) { return create(q); }

gk_timer *gk_timer_create(bool use_gpu_queries)
{
    if (!use_gpu_queries || !gk_gl_has_extension("GL_EXT_disjoint_timer_query"))
        return create(NULL);
    gk_timer_queries q = {
        .gen = (void (*)(GLsizei, GLuint *))eglGetProcAddress("glGenQueriesEXT"),
        .del = (void (*)(GLsizei, const GLuint *))eglGetProcAddress("glDeleteQueriesEXT"),
        .begin = (void (*)(GLenum, GLuint))eglGetProcAddress("glBeginQueryEXT"),
        .end = (void (*)(GLenum))eglGetProcAddress("glEndQueryEXT"),
        .get_u = (void (*)(GLuint, GLenum, GLuint *))eglGetProcAddress("glGetQueryObjectuivEXT"),
        .get_u64 = (void (*)(GLuint, GLenum, GLuint64 *))eglGetProcAddress("glGetQueryObjectui64vEXT"),
        .disjoint = ext_disjoint,
    };
    bool ok = q.gen && q.del && q.begin && q.end && q.get_u && q.get_u64;
    return create(ok ? &q : NULL);
}

void gk_timer_destroy(gk_timer *t)
{
    if (!t)
        return;
    if (t->gpu)
        for (int i = 0; i < RING; i++)
            t->q.del(GK_TIMER_MAX_QUERIES, t->slot[i].query);
    free(t);
}

bool gk_timer_uses_gpu(const gk_timer *t) { return t->gpu; }

static frame_slot *current(gk_timer *t) { return &t->slot[t->gpu ? t->frame % RING : 0]; }

void gk_timer_frame_begin(gk_timer *t)
{
    frame_slot *s = current(t);
    memset(&s->report, 0, sizeof s->report);
    s->n_queries = 0;
    s->pending = false;
    t->depth = 0;
    t->overflow = 0;
    t->query_open = false;
}

/* GPU mode: the open segment ends; a new one, billed to pass `owner`, starts (owner < 0: none). */
static void switch_segment(gk_timer *t, int owner)
{
    frame_slot *s = current(t);
    if (t->query_open) {
        t->q.end(GL_TIME_ELAPSED_EXT);
        t->query_open = false;
    }
    if (owner < 0 || s->n_queries >= GK_TIMER_MAX_QUERIES)
        return;
    s->owner[s->n_queries] = owner;
    t->q.begin(GL_TIME_ELAPSED_EXT, s->query[s->n_queries++]);
    t->query_open = true;
}

/* The entry for name under the innermost open pass: an existing one (a pass per light) or new. */
static int entry_for(gk_frame_report *r, const char *name, int parent)
{
    for (int i = 0; i < r->n; i++)
        if (r->pass[i].parent == parent && strcmp(r->pass[i].name, name) == 0)
            return i;
    if (r->n >= GK_MAX_PASSES)
        return -1;
    r->pass[r->n] = (gk_pass_time){.name = name, .parent = parent, .ms = 0.0};
    return r->n++;
}

void gk_timer_pass_begin(gk_timer *t, const char *name)
{
    frame_slot *s = current(t);
    int parent = t->depth > 0 ? t->stack[t->depth - 1] : -1;
    int k = t->overflow || t->depth >= GK_TIMER_MAX_DEPTH ? -1 : entry_for(&s->report, name, parent);
    if (k < 0) {
        t->overflow++;
        return;
    }
    t->stack[t->depth] = k;
    if (t->gpu) {
        switch_segment(t, k);
    } else {
        wait_gpu_idle(); /* the work before this pass is not billed to it */
        t->started[t->depth] = now_ms();
    }
    t->depth++;
}

void gk_timer_pass_end(gk_timer *t)
{
    if (t->overflow) {
        t->overflow--;
        return;
    }
    if (t->depth == 0)
        return;
    t->depth--;
    int k = t->stack[t->depth];
    if (t->gpu) {
        switch_segment(t, t->depth > 0 ? t->stack[t->depth - 1] : -1);
    } else {
        wait_gpu_idle();
        current(t)->report.pass[k].ms += now_ms() - t->started[t->depth];
    }
}

/* Inclusive times from the segments: a pass's own segments plus its children (children follow
 * their parent in the report, so one backward sweep adds each finished child into its parent). */
static void resolve_segments(gk_timer *t, frame_slot *s, gk_frame_report *out)
{
    *out = s->report;
    for (int i = 0; i < out->n; i++)
        out->pass[i].ms = 0.0;
    for (int q = 0; q < s->n_queries; q++) {
        GLuint64 ns = 0;
        t->q.get_u64(s->query[q], GL_QUERY_RESULT_EXT, &ns);
        out->pass[s->owner[q]].ms += (double)ns * 1e-6;
    }
    for (int i = out->n - 1; i >= 0; i--)
        if (out->pass[i].parent >= 0)
            out->pass[out->pass[i].parent].ms += out->pass[i].ms;
}

void gk_timer_frame_end(gk_timer *t, gk_frame_report *out)
{
    while (t->depth > 0 || t->overflow)
        gk_timer_pass_end(t);
    if (!t->gpu) {
        *out = current(t)->report;
        out->total_ms = gk_frame_report_top_sum(out);
        return;
    }
    current(t)->pending = true;
    t->frame++;
    /* The slot written GK_TIMER_LAG frames ago is read now (and reused next frame). */
    frame_slot *old = current(t);
    if (old->pending) {
        bool disjoint = t->q.disjoint ? t->q.disjoint() : false;
        GLuint avail = 1;
        if (old->n_queries > 0)
            t->q.get_u(old->query[old->n_queries - 1], GL_QUERY_RESULT_AVAILABLE_EXT, &avail);
        if (!disjoint && avail) {
            resolve_segments(t, old, &t->last);
            t->last.total_ms = gk_frame_report_top_sum(&t->last);
        }
        old->pending = false;
    }
    *out = t->last;
}
