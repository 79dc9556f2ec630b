/* The radiosity worker thread (rad_worker.h). */
#include "rad_worker.h"

#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rad_direct.h"
#include "rad_env.h"
#include "rad_vis.h"

struct rad_worker {
    pthread_t thread;
    pthread_mutex_t mu;
    pthread_cond_t cv_work, cv_idle;
    bool pending, busy, quit;
    bool req_redo;             /* rad_worker_redo: the next tick redoes the per-frame pipeline */
    mat4 *req_worlds;          /* the newest request (under mu) */
    rad_settings req_set;

    /* the worker's own (only its thread touches these during a tick) */
    gk_scene view;             /* the loaded scene with its own node array */
    const gk_wall_regions *regions; /* its walls' cuts (NULL: none) */
    gk_node *nodes;
    mat4 *built_worlds;
    bool have_rs;
    gk_ref_scene rs;
    rad_geometry *geo;
    uint64_t geo_id;
    rad_settings geo_set, direct_set;
    bool direct_valid;
    rad_link_cache cache;      /* the static pairs' bins of geo's tree (rad_links_update) */
    uint64_t links_seq;
    int moved_since_links;     /* ticks that moved meshes since the last link build */
    float *e_direct, *work_b0;
    float *env_bins;           /* the environment's mean radiance per bin at env_bins_n (rad_env.h) */
    float *e_env;              /* 3 per leaf: what the empty bins gather */
    int env_bins_n;

    /* published (under mu) */
    rad_geometry *pub_geo;
    uint64_t pub_geo_id, pub_seq;
    float *pub_b0;
    rad_worker_stats st;
};

static void fail(rad_worker *w, const char *msg)
{
    pthread_mutex_lock(&w->mu);
    w->st.failed = true;
    snprintf(w->st.error, sizeof w->st.error, "%s", msg);
    pthread_mutex_unlock(&w->mu);
}

static bool same_geometry(const rad_settings *a, const rad_settings *b)
{
    return a->edge == b->edge && a->n_face == b->n_face && a->weight == b->weight && a->max_verts == b->max_verts &&
           a->vis_rays == b->vis_rays;
}

/* UpdateElements on a copy of the published geometry (the frame may be reading it), and the links
   at the link update rate; the copy becomes w->geo and the caller frees *old once it published. */
static int refit(rad_worker *w, const mat4 *worlds, const rad_settings *set, bool redo, rad_geometry **old)
{
    rad_geometry *g = calloc(1, sizeof *g);
    if (!g || rad_geometry_clone(g, w->geo)) {
        free(g);
        fail(w, "radiosity: out of memory refitting");
        return -1;
    }
    if (rad_geometry_refit(g, worlds, w->view.n_nodes) == 0 && !redo) {
        rad_geometry_free(g), free(g);
        return 0; /* only lights (or nodes without charts) moved */
    }
    if (redo)
        rad_tree_refit(&g->tree, &g->mesh); /* every node, as the seed's frame does */
    bool relink = redo || ++w->moved_since_links >= (set->link_every > 0 ? set->link_every : 1);
    if (relink) {
        gk_err e = {0};
        if (rad_geometry_relink(g, redo ? NULL : &w->cache, &e)) {
            rad_geometry_free(g), free(g);
            fail(w, e.msg);
            return -1;
        }
        if (set->vis_rays)
            rad_links_cull_occluded(&g->links, &g->tree, &w->rs);
        g->links_id = ++w->links_seq;
        w->moved_since_links = 0;
    }
    *old = w->geo;
    w->geo = g;
    w->geo_id++;
    pthread_mutex_lock(&w->mu);
    w->st.refits++;
    if (relink) {
        w->st.link_updates++;
        w->st.leaf_links = g->links.leaf_links, w->st.links_created = g->links.created;
        w->st.pairs_linked = g->links.pairs_linked, w->st.pairs_cached = g->links.pairs_cached;
    }
    pthread_mutex_unlock(&w->mu);
    return 0;
}

/* w->e_direct: the direct irradiance at the leaves, the environment's through the empty bins
   (RAD_ENV_BINS, the seed; RAD_ENV_REST) or by shadow rays with the other lights (RAD_ENV_RAYS). */
static void direct_light(rad_worker *w, const rad_settings *set)
{
    const rad_geometry *g = w->geo;
    int nl = g->tree.n_leaves;
    bool bins = set->env != RAD_ENV_RAYS && w->rs.env_light >= 0 && w->env_bins_n == g->n_face;
    rad_direct_irradiance_except(&w->rs, &g->tree, set->samples, bins ? w->rs.env_light : -1, 0, nl, w->e_direct);
    if (!bins)
        return;
    rad_env_irradiance(&g->tree, &g->links, w->env_bins, set->env == RAD_ENV_REST, w->e_env);
    for (int i = 0; i < 3 * nl; i++)
        w->e_direct[i] += w->e_env[i];
}

static void tick(rad_worker *w, const mat4 *worlds, const rad_settings *set, bool redo)
{
    int n = w->view.n_nodes;
    bool moved = !w->have_rs || memcmp(w->built_worlds, worlds, sizeof *worlds * (size_t)n);
    if (moved) {
        for (int i = 0; i < n; i++)
            w->nodes[i].world = worlds[i];
        if (w->have_rs)
            gk_ref_scene_free(&w->rs);
        w->have_rs = false;
        gk_err e = {0};
        mat4 id = m4_identity();
        if (gk_ref_scene_build(&w->rs, &w->view, id, id, v3(0, 0, 0), 1, 1, &e)) {
            fail(w, e.msg);
            return;
        }
        w->have_rs = true;
        memcpy(w->built_worlds, worlds, sizeof *worlds * (size_t)n);
    }
    rad_geometry *old = NULL;
    if (!w->geo || !same_geometry(&w->geo_set, set)) {
        /* geometry is built once per setting at the pose of its first request; moving meshes are
           refit from that rest pose (rad_tree.h) */
        rad_geometry *g = calloc(1, sizeof *g);
        gk_err e = {0};
        if (!g || rad_geometry_build_regions(g, &w->view, w->regions, set->edge, set->max_verts, set->n_face, set->weight, &e)) {
            free(g);
            fail(w, g ? e.msg : "radiosity: out of memory");
            return;
        }
        if (set->vis_rays)
            rad_links_cull_occluded(&g->links, &g->tree, &w->rs);
        size_t nn = (size_t)g->tree.n_nodes, nl = (size_t)g->tree.n_leaves;
        float *ed = malloc(sizeof *ed * 3 * nl), *b0 = malloc(sizeof *b0 * 3 * nn);
        if (!ed || !b0) {
            free(ed), free(b0);
            rad_geometry_free(g);
            free(g);
            fail(w, "radiosity: out of memory");
            return;
        }
        float *ee = realloc(w->e_env, sizeof *ee * (3 * nl + 1));
        if (ee)
            w->e_env = ee;
        if (ee && w->env_bins_n != set->n_face) {
            /* the environment's bin means, once per scene and bin resolution */
            float *eb = realloc(w->env_bins, sizeof *eb * 3 * 6 * (size_t)set->n_face * (size_t)set->n_face);
            if (eb) {
                rad_env_bin_radiance(&w->view.environment, set->n_face, RAD_ENV_SUBSAMPLES, eb);
                w->env_bins = eb, w->env_bins_n = set->n_face;
            } else
                ee = NULL; /* w->e_env is freed with the worker */
        }
        if (!ee) {
            free(ed), free(b0);
            rad_geometry_free(g);
            free(g);
            fail(w, "radiosity: out of memory");
            return;
        }
        free(w->e_direct), free(w->work_b0);
        w->e_direct = ed, w->work_b0 = b0;
        old = w->geo;
        w->geo = g;
        w->geo_set = *set;
        w->geo_id++;
        g->links_id = ++w->links_seq;
        rad_link_cache_free(&w->cache);
        w->moved_since_links = 0;
        w->direct_valid = false;
        pthread_mutex_lock(&w->mu);
        w->st.geometry_builds++;
        w->st.vertices = g->mesh.n_verts, w->st.nodes = g->tree.n_nodes, w->st.charts = g->mesh.n_charts;
        w->st.leaf_links = g->links.leaf_links, w->st.links_created = g->links.created;
        w->st.bin_bytes = g->links.bin_bytes;
        w->st.moving_charts = rad_geometry_moving_charts(g);
        w->st.pairs_linked = g->links.pairs_linked, w->st.pairs_cached = g->links.pairs_cached;
        pthread_mutex_unlock(&w->mu);
    } else if (redo || (moved && rad_geometry_moving_charts(w->geo) > 0)) {
        if (refit(w, worlds, set, redo, &old))
            return;
    }
    if (!old && !moved && !redo && w->direct_valid && w->direct_set.samples == set->samples &&
        w->direct_set.env == set->env)
        return; /* nothing new to publish */
    direct_light(w, set);
    rad_initial_radiance(w->geo, w->e_direct, w->work_b0);
    w->direct_valid = true;
    w->direct_set = *set;
    size_t bytes = sizeof(float) * 3 * (size_t)w->geo->tree.n_nodes;
    pthread_mutex_lock(&w->mu);
    float *nb = realloc(w->pub_b0, bytes);
    if (nb) {
        memcpy(nb, w->work_b0, bytes);
        w->pub_b0 = nb;
        w->pub_geo = w->geo;
        w->pub_geo_id = w->geo_id;
        w->pub_seq++;
        w->st.publications++;
    } else {
        w->st.failed = true;
        snprintf(w->st.error, sizeof w->st.error, "radiosity: out of memory publishing");
        if (w->pub_geo == old)
            w->pub_geo = NULL; /* freed below: nothing is taken any more (the frame keeps its upload) */
    }
    w->st.direct_updates++;
    pthread_mutex_unlock(&w->mu);
    /* the previous geometry is no longer published (pub_geo was replaced under the lock): free it */
    if (old)
        rad_geometry_free(old), free(old);
}

static void *worker_main(void *p)
{
    rad_worker *w = p;
    int n = w->view.n_nodes;
    mat4 *worlds = malloc(sizeof *worlds * (size_t)(n > 0 ? n : 1));
    pthread_mutex_lock(&w->mu);
    for (;;) {
        while (!w->pending && !w->quit)
            pthread_cond_wait(&w->cv_work, &w->mu);
        if (w->quit)
            break;
        memcpy(worlds, w->req_worlds, sizeof *worlds * (size_t)n);
        rad_settings set = w->req_set;
        bool redo = w->req_redo;
        w->req_redo = false;
        w->pending = false;
        w->busy = w->st.busy = true;
        bool failed = w->st.failed;
        pthread_mutex_unlock(&w->mu);
        if (!failed && worlds)
            tick(w, worlds, &set, redo);
        pthread_mutex_lock(&w->mu);
        w->busy = w->st.busy = false;
        w->st.ticks++;
        pthread_cond_broadcast(&w->cv_idle);
    }
    pthread_mutex_unlock(&w->mu);
    free(worlds);
    return NULL;
}

rad_worker *rad_worker_create(const gk_scene *scene, const gk_wall_regions *regions, gk_err *e)
{
    rad_worker *w = calloc(1, sizeof *w);
    if (!w) {
        gk_fail(e, GK_ERUNTIME, "radiosity: out of memory");
        return NULL;
    }
    int n = scene->n_nodes;
    w->view = *scene;
    w->regions = regions;
    w->nodes = malloc(sizeof *w->nodes * (size_t)(n > 0 ? n : 1));
    w->req_worlds = calloc((size_t)(n > 0 ? n : 1), sizeof *w->req_worlds);
    w->built_worlds = calloc((size_t)(n > 0 ? n : 1), sizeof *w->built_worlds);
    if (!w->nodes || !w->req_worlds || !w->built_worlds) {
        free(w->nodes), free(w->req_worlds), free(w->built_worlds), free(w);
        gk_fail(e, GK_ERUNTIME, "radiosity: out of memory");
        return NULL;
    }
    memcpy(w->nodes, scene->nodes, sizeof *w->nodes * (size_t)n);
    w->view.nodes = w->nodes;
    pthread_mutex_init(&w->mu, NULL);
    pthread_cond_init(&w->cv_work, NULL);
    pthread_cond_init(&w->cv_idle, NULL);
    if (pthread_create(&w->thread, NULL, worker_main, w)) {
        pthread_mutex_destroy(&w->mu);
        pthread_cond_destroy(&w->cv_work), pthread_cond_destroy(&w->cv_idle);
        free(w->nodes), free(w->req_worlds), free(w->built_worlds), free(w);
        gk_fail(e, GK_ERUNTIME, "radiosity: cannot start the worker thread");
        return NULL;
    }
    return w;
}

void rad_worker_destroy(rad_worker *w)
{
    if (!w)
        return;
    pthread_mutex_lock(&w->mu);
    w->quit = true;
    pthread_cond_broadcast(&w->cv_work);
    pthread_mutex_unlock(&w->mu);
    pthread_join(w->thread, NULL);
    pthread_mutex_destroy(&w->mu);
    pthread_cond_destroy(&w->cv_work), pthread_cond_destroy(&w->cv_idle);
    if (w->have_rs)
        gk_ref_scene_free(&w->rs);
    if (w->geo)
        rad_geometry_free(w->geo), free(w->geo);
    rad_link_cache_free(&w->cache);
    free(w->e_direct), free(w->work_b0), free(w->pub_b0), free(w->env_bins), free(w->e_env);
    free(w->nodes), free(w->req_worlds), free(w->built_worlds);
    free(w);
}

void rad_worker_submit(rad_worker *w, const gk_scene *evaluated, const rad_settings *set)
{
    pthread_mutex_lock(&w->mu);
    int n = w->view.n_nodes < evaluated->n_nodes ? w->view.n_nodes : evaluated->n_nodes;
    for (int i = 0; i < n; i++)
        w->req_worlds[i] = evaluated->nodes[i].world;
    w->req_set = *set;
    w->st.submitted++; /* one waiting request is replaced by the newer one: ticks <= submitted */
    w->pending = true;
    pthread_cond_signal(&w->cv_work);
    pthread_mutex_unlock(&w->mu);
}

void rad_worker_redo(rad_worker *w)
{
    pthread_mutex_lock(&w->mu);
    w->req_redo = true;
    pthread_mutex_unlock(&w->mu);
}

void rad_worker_wait(rad_worker *w)
{
    pthread_mutex_lock(&w->mu);
    while ((w->pending || w->busy) && !w->st.failed)
        pthread_cond_wait(&w->cv_idle, &w->mu);
    pthread_mutex_unlock(&w->mu);
}

bool rad_worker_take(rad_worker *w, uint64_t *seen, rad_take_fn fn, void *ctx)
{
    pthread_mutex_lock(&w->mu);
    bool newer = w->pub_seq > *seen && w->pub_geo && w->pub_b0;
    if (newer) {
        fn(ctx, w->pub_geo, w->pub_geo_id, w->pub_b0);
        *seen = w->pub_seq;
    }
    pthread_mutex_unlock(&w->mu);
    return newer;
}

void rad_worker_get_stats(rad_worker *w, rad_worker_stats *out)
{
    pthread_mutex_lock(&w->mu);
    *out = w->st;
    pthread_mutex_unlock(&w->mu);
}
