/* The photon worker pool (lm_worker.h). */
#include "lm_worker.h"

#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "lm_aim.h"

typedef void (*job_fn)(lm_worker *w, int item, int thread);

struct lm_worker {
    pthread_mutex_t mu;
    pthread_cond_t cv_work, cv_idle;
    bool pending, busy, quit;
    mat4 *req_worlds;            /* the newest request's node matrices */
    lm_tick_settings req_set;

    /* owned by the coordinator thread during a tick */
    const lm_atlas *atlas;
    gk_scene view;               /* the loaded scene with its own node array */
    gk_node *nodes;
    mat4 *built_worlds;          /* the node matrices rs was built with */
    bool have_rs;
    bool rs_rebuilt;             /* refresh_scene rebuilt rs this tick (nodes moved) */
    gk_ref_scene rs;
    lm_photons ph;
    bool have_ph;
    bool first_publication;
    int publications_since_queue;
    lm_tick_settings set;
    lm_path *scratch;            /* fresh paths, photon-indexed */
    int *scratch_j;              /* per group: the photon retraced (-1: all of them) */
    int *selected;
    lm_kdtree *trees;            /* one per thread */
    float *work_irr, *work_full; /* the coordinator's atlases: indirect and full irradiance */
    float *pub_irr, *pub_full;   /* the published ones (under mu) */
    float *pub_queue;            /* per chart: > 0 queues its texels for the final gather (under mu) */
    lm_worker_stats st;          /* under mu */
    /* caustics: the coordinator's list, the fresh traces of a tick, the published points */
    lm_caustics caus;
    bool have_caus;
    int caus_req_n, caus_req_window; /* the settings caus was made for */
    vec3 *caus_new_pos, *caus_new_pow;
    bool *caus_new_has;
    float *pub_caustic;          /* 6 floats a kept photon (under mu) */
    int pub_caustic_n;

    /* the pool */
    pthread_t *threads;
    int n_threads;
    pthread_mutex_t job_mu;
    pthread_cond_t job_cv, job_done_cv;
    job_fn fn;
    int items, next, done;
    uint64_t gen;
    bool helpers_quit;           /* under job_mu (quit is under mu: one flag per lock) */
};

int lm_default_threads(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n > 1 ? (int)n - 1 : 1;
}

/* ---- parallel for over items, the coordinator taking part as thread 0 ---------------------- */
static void run_items(lm_worker *w, uint64_t gen, int thread)
{
    for (;;) {
        pthread_mutex_lock(&w->job_mu);
        if (w->gen != gen || w->next >= w->items) {
            pthread_mutex_unlock(&w->job_mu);
            return;
        }
        int i = w->next++;
        job_fn fn = w->fn;
        pthread_mutex_unlock(&w->job_mu);
        fn(w, i, thread);
        pthread_mutex_lock(&w->job_mu);
        if (++w->done == w->items)
            pthread_cond_broadcast(&w->job_done_cv);
        pthread_mutex_unlock(&w->job_mu);
    }
}

typedef struct helper_arg { lm_worker *w; int thread; } helper_arg;

static void *helper_main(void *p)
{
    helper_arg a = *(helper_arg *)p;
    free(p);
    uint64_t seen = 0;
    for (;;) {
        pthread_mutex_lock(&a.w->job_mu);
        while (a.w->gen == seen && !a.w->helpers_quit)
            pthread_cond_wait(&a.w->job_cv, &a.w->job_mu);
        if (a.w->helpers_quit) {
            pthread_mutex_unlock(&a.w->job_mu);
            return NULL;
        }
        seen = a.w->gen;
        pthread_mutex_unlock(&a.w->job_mu);
        run_items(a.w, seen, a.thread);
    }
}

static void parallel_for(lm_worker *w, job_fn fn, int items)
{
    if (items <= 0)
        return;
    pthread_mutex_lock(&w->job_mu);
    w->fn = fn, w->items = items, w->next = 0, w->done = 0;
    uint64_t gen = ++w->gen;
    pthread_cond_broadcast(&w->job_cv);
    pthread_mutex_unlock(&w->job_mu);
    run_items(w, gen, 0);
    pthread_mutex_lock(&w->job_mu);
    while (w->done < w->items)
        pthread_cond_wait(&w->job_done_cv, &w->job_mu);
    pthread_mutex_unlock(&w->job_mu);
}

/* ---- one tick ------------------------------------------------------------------------------ */
static void fail_tick(lm_worker *w, const char *msg)
{
    pthread_mutex_lock(&w->mu);
    w->st.failed = true;
    snprintf(w->st.error, sizeof w->st.error, "%s", msg);
    pthread_mutex_unlock(&w->mu);
}

/* The tracer's scene follows the request's node matrices; rebuilt only when one changed. */
static int refresh_scene(lm_worker *w, const mat4 *worlds)
{
    int n = w->view.n_nodes;
    if (w->have_rs && !memcmp(w->built_worlds, worlds, sizeof *worlds * (size_t)n))
        return 0;
    for (int i = 0; i < n; i++)
        w->nodes[i].world = worlds[i];
    if (w->have_rs)
        gk_ref_scene_free(&w->rs);
    w->have_rs = false;
    gk_err e = {0};
    mat4 id = m4_identity();
    if (gk_ref_scene_build(&w->rs, &w->view, id, id, v3(0, 0, 0), 1, 1, &e)) {
        fail_tick(w, e.msg);
        return -1;
    }
    w->have_rs = true;
    w->rs_rebuilt = true;
    memcpy(w->built_worlds, worlds, sizeof *worlds * (size_t)n);
    if (w->rs.n_tris != w->atlas->n_ref) {
        char msg[160];
        snprintf(msg, sizeof msg, "lightmap: the tracer has %u triangles, the atlas %u (a node scaled to nothing?)",
                 w->rs.n_tris, w->atlas->n_ref);
        fail_tick(w, msg);
        return -1;
    }
    return 0;
}

static void trace_group(lm_worker *w, int g, int thread)
{
    (void)thread;
    lm_photons *ph = &w->ph;
    int P = ph->per_group;
    if (ph->groups[g].invalid) {
        w->scratch_j[g] = -1;
        for (int j = 0; j < P; j++)
            lm_trace_photon(ph, &w->rs, w->atlas->ref_chart, g * P + j, &w->scratch[g * P + j]);
    } else {
        int j = ph->groups[g].cursor;
        w->scratch_j[g] = j;
        lm_trace_photon(ph, &w->rs, w->atlas->ref_chart, g * P + j, &w->scratch[g * P + j]);
    }
}

static bool same_path(const lm_path *a, const lm_path *b)
{
    if (a->n != b->n)
        return false;
    for (int i = 0; i < a->n; i++) {
        const lm_path_hit *x = &a->h[i], *y = &b->h[i];
        if (x->surface != y->surface || x->kind != y->kind || x->stored != y->stored ||
            memcmp(&x->pos, &y->pos, sizeof x->pos) || memcmp(&x->power, &y->power, sizeof x->power))
            return false;
    }
    return true;
}

static void aim_chart(lm_worker *w, int item, int thread)
{
    int ci = w->selected[item];
    const lm_chart *c = &w->atlas->charts[ci];
    /* the indirect part (shown without the final gather) and the full illumination (what the
       final gather sees on the surfaces) */
    lm_aim_update_chart(w->atlas, &w->ph, ci, w->nodes[c->node].world, &w->trees[2 * thread], w->work_irr,
                        1u << LM_HIT_INDIRECT);
    lm_aim_update_chart(w->atlas, &w->ph, ci, w->nodes[c->node].world, &w->trees[2 * thread + 1], w->work_full,
                        (1u << LM_HIT_DIRECT) | (1u << LM_HIT_CAUSTIC) | (1u << LM_HIT_INDIRECT));
}

/* Caustic photons are traced in chunks (a lock per item of the pool would cost more than a
   photon's few bounces). */
#define LM_CAUSTIC_CHUNK 64

static void trace_caustic_chunk(lm_worker *w, int item, int thread)
{
    (void)thread;
    int end = (item + 1) * LM_CAUSTIC_CHUNK < w->caus.n ? (item + 1) * LM_CAUSTIC_CHUNK : w->caus.n;
    for (int k = item * LM_CAUSTIC_CHUNK; k < end; k++)
        if (lm_caustics_due(&w->caus, k))
            lm_caustics_trace(&w->caus, &w->rs, k, &w->caus_new_pos[k], &w->caus_new_pow[k], &w->caus_new_has[k]);
}

/* One progressive caustic update (lm_caustics.h) and its publication when a hit changed. */
static void tick_caustics(lm_worker *w)
{
    if (!w->have_caus || w->caus_req_n != w->set.caustic_photons || w->caus_req_window != w->set.caustic_window) {
        if (w->have_caus)
            lm_caustics_free(&w->caus);
        free(w->caus_new_pos), free(w->caus_new_pow), free(w->caus_new_has), free(w->pub_caustic);
        w->caus_new_pos = w->caus_new_pow = NULL, w->caus_new_has = NULL;
        w->have_caus = false;
        gk_err e = {0};
        if (lm_caustics_init(&w->caus, &w->rs, w->set.caustic_photons, w->set.caustic_window, &e)) {
            fail_tick(w, e.msg);
            return;
        }
        size_t n = (size_t)(w->caus.n > 0 ? w->caus.n : 1);
        w->caus_new_pos = calloc(n, sizeof *w->caus_new_pos);
        w->caus_new_pow = calloc(n, sizeof *w->caus_new_pow);
        w->caus_new_has = calloc(n, sizeof *w->caus_new_has);
        float *pub = calloc(n * 6, sizeof(float));
        if (!w->caus_new_pos || !w->caus_new_pow || !w->caus_new_has || !pub) {
            free(pub);
            lm_caustics_free(&w->caus);
            fail_tick(w, "lightmap: out of memory for the caustic photons");
            return;
        }
        pthread_mutex_lock(&w->mu);
        w->pub_caustic = pub;
        w->pub_caustic_n = 0;
        w->st.caustic_seq++; /* the new (empty) list replaces the old one */
        pthread_mutex_unlock(&w->mu);
        w->caus_req_n = w->set.caustic_photons, w->caus_req_window = w->set.caustic_window;
        w->have_caus = true;
    }
    lm_caustics *c = &w->caus;
    if (c->n == 0)
        return;
    if (w->rs_rebuilt)
        lm_caustics_aim(c, &w->rs); /* a generator or light may have moved */
    parallel_for(w, trace_caustic_chunk, (c->n + LM_CAUSTIC_CHUNK - 1) / LM_CAUSTIC_CHUNK);
    bool first = c->ticks == 0;
    bool changed = lm_caustics_apply(c, w->caus_new_pos, w->caus_new_pow, w->caus_new_has);
    pthread_mutex_lock(&w->mu);
    if (changed || first) {
        int m = 0;
        for (int k = 0; k < c->n; k++)
            if (c->has[k]) {
                float *o = &w->pub_caustic[6 * m++];
                o[0] = c->pos[k].x, o[1] = c->pos[k].y, o[2] = c->pos[k].z;
                o[3] = c->power[k].x, o[4] = c->power[k].y, o[5] = c->power[k].z;
            }
        w->pub_caustic_n = m;
        w->st.caustic_seq++;
    }
    w->st.caustic_photons = c->n;
    w->st.caustic_hits = w->pub_caustic_n;
    w->st.caustic_retraced = c->retraced;
    pthread_mutex_unlock(&w->mu);
}

static void tick(lm_worker *w, const mat4 *worlds)
{
    w->rs_rebuilt = false;
    if (refresh_scene(w, worlds))
        return;
    const lm_atlas *a = w->atlas;
    size_t texels = (size_t)a->width * (size_t)a->height;
    if (!w->have_ph || w->ph.n_groups != w->set.groups) {
        if (w->have_ph)
            lm_photons_free(&w->ph);
        free(w->scratch), free(w->scratch_j);
        w->scratch = NULL, w->scratch_j = NULL;
        w->have_ph = false;
        gk_err e = {0};
        /* tau: a quarter texel -- a hit that moved less changes its texel's estimate little */
        if (lm_photons_init(&w->ph, &w->rs, w->set.groups, a->n_charts, 0.25f * a->texel_size, &e)) {
            fail_tick(w, e.msg);
            return;
        }
        w->scratch = calloc((size_t)w->ph.n_photons, sizeof *w->scratch);
        w->scratch_j = calloc((size_t)w->ph.n_groups, sizeof *w->scratch_j);
        if (!w->scratch || !w->scratch_j) {
            fail_tick(w, "lightmap: out of memory for the photon paths");
            return;
        }
        w->have_ph = true;
        memset(w->work_irr, 0, sizeof(float) * 4 * texels);
        memset(w->work_full, 0, sizeof(float) * 4 * texels);
        w->first_publication = true;
    }
    lm_photons *ph = &w->ph;
    int P = ph->per_group;
    parallel_for(w, trace_group, ph->n_groups);
    int traced = 0, invalidated = 0, replaced = 0;
    for (int g = 0; g < ph->n_groups; g++) {
        lm_group *gr = &ph->groups[g];
        int j = w->scratch_j[g];
        if (j < 0) {
            for (int q = 0; q < P; q++)
                if (!same_path(&ph->paths[g * P + q], &w->scratch[g * P + q]))
                    lm_photons_replace(ph, g * P + q, &w->scratch[g * P + q]), replaced++;
            traced += P;
            gr->invalid = false;
            continue;
        }
        int k = g * P + j;
        traced++;
        gr->cursor = (j + 1) % P;
        if (lm_path_diverges(&ph->paths[k], &w->scratch[k], ph->tau)) {
            gr->invalid = true;
            gr->invalidations++;
            invalidated++;
        }
        if (!same_path(&ph->paths[k], &w->scratch[k]))
            lm_photons_replace(ph, k, &w->scratch[k]), replaced++;
    }
    tick_caustics(w);
    int n_sel = lm_aim_select(a, ph, w->set.aim_texels, w->selected);
    parallel_for(w, aim_chart, n_sel);
    int texels_updated = 0;
    for (int i = 0; i < n_sel; i++) {
        lm_store *s = &ph->stores[w->selected[i]];
        s->delta_f = s->delta_i = 0.0;
        texels_updated += a->charts[w->selected[i]].w * a->charts[w->selected[i]].h;
    }
    int pending = 0;
    for (int i = 0; i < a->n_charts; i++)
        pending += ph->stores[i].delta_f > 0.0 && ph->stores[i].delta_f > LM_DELTA_REL * ph->stores[i].energy;
    pthread_mutex_lock(&w->mu);
    if (n_sel > 0) {
        memcpy(w->pub_irr, w->work_irr, sizeof(float) * 4 * texels);
        memcpy(w->pub_full, w->work_full, sizeof(float) * 4 * texels);
        /* The final gather's queue: surfaces whose indirect light changed (Δ_i, the seed's order),
           every surface the first time; merged with what the frame has not taken yet. A texel's
           gather sees the other surfaces' AIMs, so the queue waits until the AIM updates have
           caught up (no surface over the threshold), or for 8 publications while they do not
           (a moving light keeps them busy): a texel gathered from half-updated AIMs would keep
           that state, its own Δ_i being spent. */
        w->publications_since_queue++;
        if (pending == 0 || w->publications_since_queue >= 8) {
            for (int i = 0; i < a->n_charts; i++) {
                lm_store *s = &ph->stores[i];
                bool due = s->delta_g > 0.0 && s->delta_g > LM_DELTA_REL * s->energy;
                if (w->first_publication || due) {
                    float prio = (float)(s->delta_g > 0.0 ? s->delta_g : 1e-30);
                    w->pub_queue[i] = w->pub_queue[i] > prio ? w->pub_queue[i] : prio;
                    s->delta_g = 0.0;
                }
            }
            w->first_publication = false;
            w->publications_since_queue = 0;
        }
        w->st.result_seq++;
    }
    w->st.ticks++;
    w->st.groups = ph->n_groups, w->st.photons = ph->n_photons;
    w->st.traced = traced, w->st.invalidated = invalidated, w->st.replaced = replaced;
    w->st.surfaces_updated = n_sel, w->st.texels_updated = texels_updated;
    w->st.pending_surfaces = pending;
    w->st.traced_total += (uint64_t)traced, w->st.invalidations_total += (uint64_t)invalidated;
    w->st.texels_total += (uint64_t)texels_updated;
    pthread_mutex_unlock(&w->mu);
}

static void *coordinator_main(void *p)
{
    lm_worker *w = p;
    int n = w->view.n_nodes;
    mat4 *worlds = malloc(sizeof *worlds * (size_t)(n > 0 ? n : 1));
    for (;;) {
        pthread_mutex_lock(&w->mu);
        while (!w->pending && !w->quit)
            pthread_cond_wait(&w->cv_work, &w->mu);
        if (w->quit) {
            pthread_mutex_unlock(&w->mu);
            break;
        }
        memcpy(worlds, w->req_worlds, sizeof *worlds * (size_t)n);
        w->set = w->req_set;
        w->pending = false;
        w->busy = true;
        bool failed = w->st.failed;
        pthread_mutex_unlock(&w->mu);
        if (!failed && worlds)
            tick(w, worlds);
        pthread_mutex_lock(&w->mu);
        w->busy = false;
        pthread_cond_broadcast(&w->cv_idle);
        pthread_mutex_unlock(&w->mu);
    }
    free(worlds);
    return NULL;
}

/* ---- the render thread's side -------------------------------------------------------------- */
lm_worker *lm_worker_create(const gk_scene *scene, const lm_atlas *atlas, int threads, gk_err *e)
{
    lm_worker *w = calloc(1, sizeof *w);
    if (!w) {
        gk_fail(e, GK_ERUNTIME, "lightmap: out of memory");
        return NULL;
    }
    w->atlas = atlas;
    w->view = *scene;
    int n = scene->n_nodes > 0 ? scene->n_nodes : 1;
    size_t texels = (size_t)atlas->width * (size_t)atlas->height;
    w->nodes = calloc((size_t)n, sizeof *w->nodes);
    w->built_worlds = calloc((size_t)n, sizeof *w->built_worlds);
    w->req_worlds = calloc((size_t)n, sizeof *w->req_worlds);
    w->selected = calloc((size_t)(atlas->n_charts > 0 ? atlas->n_charts : 1), sizeof *w->selected);
    w->work_irr = calloc(texels * 4 + 4, sizeof(float));
    w->pub_irr = calloc(texels * 4 + 4, sizeof(float));
    w->work_full = calloc(texels * 4 + 4, sizeof(float));
    w->pub_full = calloc(texels * 4 + 4, sizeof(float));
    w->pub_queue = calloc((size_t)(atlas->n_charts > 0 ? atlas->n_charts : 1), sizeof(float));
    w->n_threads = threads < 1 ? 1 : threads;
    w->trees = calloc(2 * (size_t)w->n_threads, sizeof *w->trees);
    w->threads = calloc((size_t)w->n_threads, sizeof *w->threads);
    if (!w->nodes || !w->built_worlds || !w->req_worlds || !w->selected || !w->work_irr || !w->pub_irr ||
        !w->work_full || !w->pub_full || !w->pub_queue || !w->trees || !w->threads) {
        free(w->nodes), free(w->built_worlds), free(w->req_worlds), free(w->selected), free(w->work_irr);
        free(w->pub_irr), free(w->work_full), free(w->pub_full), free(w->pub_queue), free(w->trees), free(w->threads);
        free(w);
        gk_fail(e, GK_ERUNTIME, "lightmap: out of memory");
        return NULL;
    }
    memcpy(w->nodes, scene->nodes, sizeof *w->nodes * (size_t)scene->n_nodes);
    w->view.nodes = w->nodes;
    w->st.threads = w->n_threads;
    pthread_mutex_init(&w->mu, NULL);
    pthread_cond_init(&w->cv_work, NULL);
    pthread_cond_init(&w->cv_idle, NULL);
    pthread_mutex_init(&w->job_mu, NULL);
    pthread_cond_init(&w->job_cv, NULL);
    pthread_cond_init(&w->job_done_cv, NULL);
    int started = 0;
    if (pthread_create(&w->threads[0], NULL, coordinator_main, w) == 0)
        started = 1;
    for (int i = 1; started == i && i < w->n_threads; i++) {
        helper_arg *a = malloc(sizeof *a);
        if (!a)
            break;
        *a = (helper_arg){w, i};
        if (pthread_create(&w->threads[i], NULL, helper_main, a) == 0)
            started++;
        else
            free(a);
    }
    if (started < w->n_threads) {
        w->n_threads = started;
        lm_worker_destroy(w);
        gk_fail(e, GK_ERUNTIME, "lightmap: cannot start %d photon worker threads", threads);
        return NULL;
    }
    return w;
}

void lm_worker_destroy(lm_worker *w)
{
    if (!w)
        return;
    pthread_mutex_lock(&w->mu);
    w->quit = true;
    pthread_cond_broadcast(&w->cv_work);
    pthread_mutex_unlock(&w->mu);
    pthread_mutex_lock(&w->job_mu);
    w->helpers_quit = true;
    pthread_cond_broadcast(&w->job_cv);
    pthread_mutex_unlock(&w->job_mu);
    for (int i = 0; i < w->n_threads; i++)
        pthread_join(w->threads[i], NULL);
    if (w->have_rs)
        gk_ref_scene_free(&w->rs);
    if (w->have_ph)
        lm_photons_free(&w->ph);
    if (w->have_caus)
        lm_caustics_free(&w->caus);
    free(w->caus_new_pos), free(w->caus_new_pow), free(w->caus_new_has), free(w->pub_caustic);
    for (int i = 0; w->trees && i < 2 * w->n_threads; i++)
        lm_kdtree_free(&w->trees[i]);
    free(w->scratch), free(w->scratch_j);
    free(w->nodes), free(w->built_worlds), free(w->req_worlds), free(w->selected), free(w->work_irr);
    free(w->pub_irr), free(w->work_full), free(w->pub_full), free(w->pub_queue), free(w->trees), free(w->threads);
    pthread_mutex_destroy(&w->mu);
    pthread_cond_destroy(&w->cv_work);
    pthread_cond_destroy(&w->cv_idle);
    pthread_mutex_destroy(&w->job_mu);
    pthread_cond_destroy(&w->job_cv);
    pthread_cond_destroy(&w->job_done_cv);
    free(w);
}

void lm_worker_submit(lm_worker *w, const gk_scene *s, const lm_tick_settings *set)
{
    pthread_mutex_lock(&w->mu);
    int n = w->view.n_nodes < s->n_nodes ? w->view.n_nodes : s->n_nodes;
    for (int i = 0; i < n; i++)
        w->req_worlds[i] = s->nodes[i].world;
    w->req_set = *set;
    w->pending = true;
    w->st.submitted++;
    pthread_cond_signal(&w->cv_work);
    pthread_mutex_unlock(&w->mu);
}

void lm_worker_wait(lm_worker *w)
{
    pthread_mutex_lock(&w->mu);
    while (w->pending || w->busy)
        pthread_cond_wait(&w->cv_idle, &w->mu);
    pthread_mutex_unlock(&w->mu);
}

bool lm_worker_take(lm_worker *w, uint64_t *seen, lm_take_fn fn, void *ctx)
{
    bool called = false;
    pthread_mutex_lock(&w->mu);
    if (w->st.result_seq != *seen) {
        fn(ctx, w->pub_irr, w->pub_full, w->pub_queue);
        memset(w->pub_queue, 0, sizeof(float) * (size_t)(w->atlas->n_charts > 0 ? w->atlas->n_charts : 1));
        *seen = w->st.result_seq;
        called = true;
    }
    pthread_mutex_unlock(&w->mu);
    return called;
}

bool lm_worker_take_caustics(lm_worker *w, uint64_t *seen, lm_take_caustics_fn fn, void *ctx)
{
    bool called = false;
    pthread_mutex_lock(&w->mu);
    if (w->st.caustic_seq != *seen) {
        fn(ctx, w->pub_caustic, w->pub_caustic_n);
        *seen = w->st.caustic_seq;
        called = true;
    }
    pthread_mutex_unlock(&w->mu);
    return called;
}

void lm_worker_get_stats(lm_worker *w, lm_worker_stats *out)
{
    pthread_mutex_lock(&w->mu);
    *out = w->st;
    pthread_mutex_unlock(&w->mu);
}

/* Test access: read while the pool is idle (after lm_worker_wait). */
int lm_worker_group_invalidations(lm_worker *w, unsigned *out, int cap)
{
    if (!w->have_ph)
        return 0;
    for (int g = 0; g < w->ph.n_groups && g < cap; g++)
        out[g] = w->ph.groups[g].invalidations;
    return w->ph.n_groups;
}

int lm_worker_group_first_hits(lm_worker *w, float *out, int cap)
{
    if (!w->have_ph)
        return 0;
    for (int g = 0; g < w->ph.n_groups && g < cap; g++) {
        const lm_path *p = &w->ph.paths[g * w->ph.per_group];
        vec3 x = p->n > 0 ? p->h[0].pos : v3(0, 0, 0);
        out[3 * g] = x.x, out[3 * g + 1] = x.y, out[3 * g + 2] = x.z;
    }
    return w->ph.n_groups;
}
