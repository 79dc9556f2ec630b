/* The progressive ground truth (see truth.h). */
#include "truth.h"

#include <math.h>
#include <pthread.h>
#include <sched.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include "base/log.h"
#include "ref/caustic_emit.h"
#include "ref/render.h"
#include "ref/trace.h"

#define TILE 16
/* Splats one light path can make: one camera connection per surface hit and one per segment
   through a medium, at most 32 vertices (the reference's max_depth) -- with room to spare. */
#define PATH_SPLATS 72

/* One view: what the workers trace and the sums they add into. Freed by whoever leaves it last
 * once it is retired (the render thread or a worker). */
typedef struct truth_job {
    uint64_t generation;
    gk_ref_scene rs;          /* NULL-free when fixed */
    bool fixed;
    uint64_t seed;
    int sub;                  /* frame pixels per truth pixel along each axis */
    int width, height, tiles_x, n_tiles;
    int items_per_pass;       /* n_tiles eye tiles, then (with a light pass) n_tiles light tiles */
    long next_item;           /* item = pass * items_per_pass + k */
    double *sum, *sum_sq;     /* width * height * 3 each: over complete cycles, of their means */
    int *count;               /* complete cycles per pixel */
    double *cycle_sum;        /* width * height * 3: the passes of the cycle under way */
    int *cycle_n;             /* and how many passes it holds */
    /* The light pass (caustics seen directly, truth.h): items n_tiles .. 2 n_tiles - 1 of a pass
       trace one light path per pixel of their tile. Per truth pixel and channel, the sum and the
       sum of squares of every path's contribution; light_paths paths in all. */
    unsigned light_terms;     /* gk_ref_light_terms; 0: no light pass */
    gk_caustic_emitter emitter;
    double *light_sum, *light_sum_sq;
    uint64_t light_paths;
    long fixed_spp;
    double fixed_noise;
    float *fixed_rgb;
    int users;                /* workers inside one of its tiles */
    bool retired;
} truth_job;

struct gk_truth {
    pthread_mutex_t lock;
    pthread_cond_t wake;
    pthread_t *threads;
    int n_threads;
    bool quit;
    truth_job *job;           /* the current view, or NULL */
    _Atomic uint64_t generation; /* read by workers before every sample */
    uint64_t next_generation;
    int busy;                 /* workers inside a tile */
    uint64_t samples, aborted_tiles, retired_views;
    _Atomic int low_priority_ok;
    _Atomic uint64_t samples_after_stop;
};

int gk_truth_worker_count(int configured)
{
    if (configured > 0)
        return configured;
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n > 1 ? (int)n - 1 : 1;
}

int gk_truth_size(int fw, int fh, int max_w, int max_h, int *w, int *h)
{
    int d = 1;
    while (fw / d > max_w || fh / d > max_h)
        d++;
    *w = fw / d > 0 ? fw / d : 1;
    *h = fh / d > 0 ? fh / d : 1;
    return d;
}

static void job_free(truth_job *j)
{
    if (!j)
        return;
    if (!j->fixed)
        gk_ref_scene_free(&j->rs);
    free(j->sum);
    free(j->sum_sq);
    free(j->count);
    free(j->cycle_sum);
    free(j->cycle_n);
    free(j->fixed_rgb);
    free(j->light_sum);
    free(j->light_sum_sq);
    gk_caustic_emitter_free(&j->emitter);
    free(j);
}

/* Called with the lock held: the job leaves the stage; freed now when no worker is inside it. */
static void retire_locked(gk_truth *t)
{
    truth_job *j = t->job;
    t->job = NULL;
    atomic_store(&t->generation, 0);
    if (!j)
        return;
    t->retired_views++;
    j->retired = true;
    if (j->users == 0)
        job_free(j);
}

/* Lowest priority for the calling thread: SCHED_IDLE runs only when a core has nothing else to do;
 * where it is refused, nice 19 (per thread on Linux). */
static void lower_priority(gk_truth *t)
{
    struct sched_param sp = {.sched_priority = 0};
    if (sched_setscheduler(0, SCHED_IDLE, &sp) == 0 ||
        setpriority(PRIO_PROCESS, (id_t)syscall(SYS_gettid), 19) == 0)
        return;
    atomic_store(&t->low_priority_ok, 0);
}

/* Item -> its pass and its place in the pass (< n_tiles: an eye tile, else a light tile). */
static uint64_t item_pass(const truth_job *j, long item, int *k)
{
    *k = (int)(item % j->items_per_pass);
    return (uint64_t)(item / j->items_per_pass);
}

static bool retired_now(gk_truth *t, const truth_job *j)
{
    return atomic_load_explicit(&t->generation, memory_order_relaxed) != j->generation;
}

/* Traces one pass of one tile into the local buffers; false when the view was retired meanwhile. */
static bool trace_tile(gk_truth *t, truth_job *j, long item, double *acc, uint64_t *traced)
{
    int tile;
    uint64_t pass = item_pass(j, item, &tile);
    int x0 = (tile % j->tiles_x) * TILE, y0 = (tile / j->tiles_x) * TILE;
    const gk_ref_scene *rs = &j->rs;
    gk_trace_stats st = {0};
    int i = 0;
    for (int y = y0; y < y0 + TILE && y < j->height; y++)
        for (int x = x0; x < x0 + TILE && x < j->width; x++, i++) {
            if (retired_now(t, j))
                return false;
            uint64_t pix = (uint64_t)y * (uint64_t)j->width + (uint64_t)x;
            gk_rng rng;
            gk_rng_seed(&rng, j->seed, pix, pass, 2);
            /* pass p goes through the centre of frame pixel k = p mod sub^2 of those this pixel
               stands for: a cycle of sub^2 passes visits each once (see truth.h) */
            int k = (int)(pass % (uint64_t)(j->sub * j->sub));
            float sx = (float)(k % j->sub), sy = (float)(k / j->sub);
            vec3 d = gk_ref_camera_dir(rs, (float)(x * j->sub) + sx + 0.5f, (float)(y * j->sub) + sy + 0.5f);
            vec3 l = gk_trace_eye(rs, rs->eye, d, GK_PATH_ALL, GK_TERM_ALL, GK_BOUNCES_UNLIMITED, 32, 4, &rng, &st);
            (*traced)++;
            if (retired_now(t, j))
                atomic_fetch_add(&t->samples_after_stop, 1); /* finished after its view was retired */
            if (!(isfinite(l.x) && isfinite(l.y) && isfinite(l.z)))
                l = (vec3){0, 0, 0}; /* as the reference renderer: a NaN sample counts as black */
            double v[3] = {l.x, l.y, l.z};
            for (int c = 0; c < 3; c++)
                acc[3 * i + c] = v[c];
        }
    return true;
}

static void add_tile_locked(truth_job *j, long item, const double *acc)
{
    int tile;
    item_pass(j, item, &tile);
    int x0 = (tile % j->tiles_x) * TILE, y0 = (tile / j->tiles_x) * TILE;
    int i = 0;
    for (int y = y0; y < y0 + TILE && y < j->height; y++)
        for (int x = x0; x < x0 + TILE && x < j->width; x++, i++) {
            size_t p = (size_t)y * (size_t)j->width + (size_t)x;
            for (int c = 0; c < 3; c++)
                j->cycle_sum[3 * p + c] += acc[3 * i + c];
            if (++j->cycle_n[p] < j->sub * j->sub)
                continue;
            for (int c = 0; c < 3; c++) { /* a complete cycle: one sample of the box-filtered pixel */
                double m = j->cycle_sum[3 * p + c] / (j->sub * j->sub);
                j->sum[3 * p + c] += m;
                j->sum_sq[3 * p + c] += m * m;
                j->cycle_sum[3 * p + c] = 0;
            }
            j->cycle_n[p] = 0;
            j->count[p]++;
        }
}

/* One light path's contributions, merged per truth pixel (a path may splat twice into one). */
typedef struct path_splats {
    const truth_job *j;
    int n;
    int pix[PATH_SPLATS];
    double v[PATH_SPLATS][3];
} path_splats;

/* A worker's light tile: every path's merged contributions, added under the lock at the end. */
typedef struct light_out {
    size_t n, cap;
    int *pix;
    double (*v)[3];
    bool failed;              /* out of memory: the tile is dropped as if aborted */
} light_out;

/* gk_splat_fn: a splat at frame pixel (px, py) is 1/sub^2 of the box-filtered truth pixel it lies
   in (the frame's last columns and rows beyond w sub, h sub are not compared, truth.h). */
static void splat_truth(void *ctx, int px, int py, vec3 value)
{
    path_splats *ps = ctx;
    const truth_job *j = ps->j;
    int tx = px / j->sub, ty = py / j->sub;
    if (tx >= j->width || ty >= j->height || !(isfinite(value.x) && isfinite(value.y) && isfinite(value.z)))
        return;
    int p = ty * j->width + tx, i = 0;
    while (i < ps->n && ps->pix[i] != p)
        i++;
    if (i == ps->n) {
        if (ps->n == PATH_SPLATS)
            return; /* not reached: PATH_SPLATS bounds what gk_trace_light makes */
        ps->pix[ps->n] = p;
        ps->v[ps->n][0] = ps->v[ps->n][1] = ps->v[ps->n][2] = 0.0;
        ps->n++;
    }
    double w = 1.0 / (double)(j->sub * j->sub);
    ps->v[i][0] += value.x * w;
    ps->v[i][1] += value.y * w;
    ps->v[i][2] += value.z * w;
}

static bool light_out_add(light_out *o, const path_splats *ps)
{
    if (o->n + (size_t)ps->n > o->cap) {
        size_t cap = (o->cap ? 2 * o->cap : 1024) + (size_t)ps->n;
        int *pix = realloc(o->pix, cap * sizeof *pix);
        if (pix)
            o->pix = pix;
        double(*v)[3] = pix ? realloc(o->v, cap * sizeof *v) : NULL;
        if (!v)
            return false;
        o->v = v;
        o->cap = cap;
    }
    for (int i = 0; i < ps->n; i++, o->n++) {
        o->pix[o->n] = ps->pix[i];
        for (int c = 0; c < 3; c++)
            o->v[o->n][c] = ps->v[i][c];
    }
    return true;
}

/* Traces one pass of one light tile: a light path per pixel of the tile (its own random stream),
   as the reference traces one per pixel and sample; false when the view was retired meanwhile. */
static bool trace_light_tile(gk_truth *t, truth_job *j, long item, light_out *out, uint64_t *traced)
{
    int k;
    uint64_t pass = item_pass(j, item, &k);
    int tile = k - j->n_tiles;
    int x0 = (tile % j->tiles_x) * TILE, y0 = (tile / j->tiles_x) * TILE;
    gk_trace_stats st = {0};
    path_splats ps = {.j = j};
    out->n = 0;
    for (int y = y0; y < y0 + TILE && y < j->height; y++)
        for (int x = x0; x < x0 + TILE && x < j->width; x++) {
            if (retired_now(t, j))
                return false;
            gk_rng rng;
            gk_rng_seed(&rng, j->seed, (uint64_t)y * (uint64_t)j->width + (uint64_t)x, pass, 3);
            ps.n = 0;
            gk_trace_light(&j->rs, &j->emitter, j->light_terms, 32, GK_BOUNCES_UNLIMITED, &rng, splat_truth, &ps,
                           &st);
            (*traced)++;
            if (retired_now(t, j))
                atomic_fetch_add(&t->samples_after_stop, 1);
            if (!light_out_add(out, &ps)) {
                out->failed = true;
                return false;
            }
        }
    return true;
}

static void add_light_locked(truth_job *j, const light_out *out, uint64_t paths)
{
    for (size_t i = 0; i < out->n; i++)
        for (int c = 0; c < 3; c++) {
            double v = out->v[i][c];
            j->light_sum[3 * (size_t)out->pix[i] + c] += v;
            j->light_sum_sq[3 * (size_t)out->pix[i] + c] += v * v;
        }
    j->light_paths += paths;
}

static void *worker(void *arg)
{
    gk_truth *t = arg;
    lower_priority(t);
    double acc[TILE * TILE * 3];
    light_out lights = {0};
    pthread_mutex_lock(&t->lock);
    while (!t->quit) {
        truth_job *j = t->job;
        if (!j || j->fixed) {
            pthread_cond_wait(&t->wake, &t->lock);
            continue;
        }
        long item = j->next_item++;
        int k;
        item_pass(j, item, &k);
        bool light = k >= j->n_tiles;
        j->users++;
        t->busy++;
        pthread_mutex_unlock(&t->lock);
        uint64_t traced = 0;
        bool whole = light ? trace_light_tile(t, j, item, &lights, &traced) : trace_tile(t, j, item, acc, &traced);
        pthread_mutex_lock(&t->lock);
        t->busy--;
        j->users--;
        if (whole && !j->retired) {
            if (light)
                add_light_locked(j, &lights, traced);
            else
                add_tile_locked(j, item, acc);
            t->samples += traced;
        } else if (!whole) {
            t->aborted_tiles++; /* left part-way: the retirement was seen between two samples */
        }
        if (j->retired && j->users == 0)
            job_free(j);
        if (lights.failed) {
            lights.failed = false;
            gk_log("truth: out of memory for a light tile: dropped (its paths are not counted)");
        }
    }
    pthread_mutex_unlock(&t->lock);
    free(lights.pix);
    free(lights.v);
    return NULL;
}

gk_truth *gk_truth_create(int workers, gk_err *e)
{
    gk_truth *t = calloc(1, sizeof *t);
    if (!t || !(t->threads = calloc((size_t)(workers > 0 ? workers : 1), sizeof *t->threads))) {
        free(t);
        gk_fail(e, GK_ERUNTIME, "truth: out of memory");
        return NULL;
    }
    pthread_mutex_init(&t->lock, NULL);
    pthread_cond_init(&t->wake, NULL);
    atomic_store(&t->low_priority_ok, 1);
    for (int i = 0; i < workers; i++) {
        if (pthread_create(&t->threads[i], NULL, worker, t) != 0) {
            gk_fail(e, GK_ERUNTIME, "truth: cannot start worker %d of %d", i + 1, workers);
            gk_truth_destroy(t);
            return NULL;
        }
        t->n_threads++;
    }
    return t;
}

void gk_truth_destroy(gk_truth *t)
{
    if (!t)
        return;
    pthread_mutex_lock(&t->lock);
    t->quit = true;
    retire_locked(t);
    pthread_cond_broadcast(&t->wake);
    pthread_mutex_unlock(&t->lock);
    for (int i = 0; i < t->n_threads; i++)
        pthread_join(t->threads[i], NULL);
    pthread_cond_destroy(&t->wake);
    pthread_mutex_destroy(&t->lock);
    free(t->threads);
    free(t);
}

static truth_job *job_alloc(int width, int height, bool fixed)
{
    truth_job *j = calloc(1, sizeof *j);
    size_t n = (size_t)width * (size_t)height;
    if (!j)
        return NULL;
    j->width = width;
    j->height = height;
    j->fixed = fixed;
    j->tiles_x = (width + TILE - 1) / TILE;
    j->n_tiles = j->tiles_x * ((height + TILE - 1) / TILE);
    j->items_per_pass = j->n_tiles;
    if (fixed ? !(j->fixed_rgb = malloc(n * 3 * sizeof(float)))
              : !(j->sum = calloc(n * 3, sizeof(double))) || !(j->sum_sq = calloc(n * 3, sizeof(double))) ||
                    !(j->count = calloc(n, sizeof(int))) || !(j->cycle_sum = calloc(n * 3, sizeof(double))) ||
                    !(j->cycle_n = calloc(n, sizeof(int)))) {
        free(j->sum);
        free(j->sum_sq);
        free(j->count);
        free(j->cycle_sum);
        free(j->cycle_n);
        free(j->fixed_rgb);
        free(j);
        return NULL;
    }
    return j;
}

static uint64_t install(gk_truth *t, truth_job *j)
{
    pthread_mutex_lock(&t->lock);
    retire_locked(t);
    j->generation = ++t->next_generation;
    t->job = j;
    atomic_store(&t->generation, j->generation);
    pthread_cond_broadcast(&t->wake);
    pthread_mutex_unlock(&t->lock);
    return j->generation;
}

uint64_t gk_truth_restart(gk_truth *t, gk_ref_scene *rs, int width, int height, int sub, uint64_t seed)
{
    truth_job *j = job_alloc(width, height, false);
    if (!j) {
        gk_ref_scene_free(rs);
        gk_truth_stop(t);
        gk_log("truth: out of memory; no ground truth for this view");
        return 0;
    }
    j->rs = *rs;
    memset(rs, 0, sizeof *rs);
    j->seed = seed;
    j->sub = sub > 0 ? sub : 1;
    /* Mirrors or glass: the reference's light pass too (caustics seen directly), with its guided
       emission towards the delta surfaces and its split of the paths (gk_ref_light_terms). */
    gk_ref_options ro;
    gk_ref_options_default(&ro);
    j->light_terms = gk_ref_light_terms(&j->rs, &ro);
    if (j->light_terms) {
        size_t n = (size_t)width * (size_t)height * 3;
        gk_err e = {0};
        if (!(j->light_sum = calloc(n, sizeof(double))) || !(j->light_sum_sq = calloc(n, sizeof(double))) ||
            gk_caustic_emitter_build(&j->emitter, &j->rs, ro.caustic_grid, &e) != 0) {
            job_free(j);
            gk_truth_stop(t);
            gk_log("truth: out of memory for the light pass; no ground truth for this view");
            return 0;
        }
        j->items_per_pass = 2 * j->n_tiles;
    }
    return install(t, j);
}

uint64_t gk_truth_use_fixed(gk_truth *t, const float *rgb, int width, int height, long spp, double noise)
{
    truth_job *j = job_alloc(width, height, true);
    if (!j) {
        gk_truth_stop(t);
        return 0;
    }
    memcpy(j->fixed_rgb, rgb, (size_t)width * (size_t)height * 3 * sizeof(float));
    j->fixed_spp = spp;
    j->fixed_noise = noise;
    return install(t, j);
}

void gk_truth_stop(gk_truth *t)
{
    pthread_mutex_lock(&t->lock);
    retire_locked(t);
    pthread_mutex_unlock(&t->lock);
}

void gk_truth_view_free(gk_truth_view *v)
{
    free(v->rgb);
    memset(v, 0, sizeof *v);
}

static bool view_resize(gk_truth_view *v, int width, int height)
{
    if (v->rgb && v->width == width && v->height == height)
        return true;
    float *p = realloc(v->rgb, (size_t)width * (size_t)height * 3 * sizeof(float));
    if (!p)
        return false;
    v->rgb = p;
    v->width = width;
    v->height = height;
    return true;
}

bool gk_truth_snapshot(gk_truth *t, gk_truth_view *v)
{
    pthread_mutex_lock(&t->lock);
    truth_job *j = t->job;
    if (!j || !view_resize(v, j->width, j->height)) {
        pthread_mutex_unlock(&t->lock);
        v->generation = 0;
        v->spp = 0;
        return false;
    }
    size_t n = (size_t)j->width * (size_t)j->height;
    v->generation = j->generation;
    v->fixed = j->fixed;
    if (j->fixed) {
        memcpy(v->rgb, j->fixed_rgb, n * 3 * sizeof(float));
        v->spp = j->fixed_spp;
        v->noise = j->fixed_noise;
        pthread_mutex_unlock(&t->lock);
        return true;
    }
    /* Mean and variance of the mean in one sweep; the sweep is O(pixels) and short (160x90). The
       light pass adds its own mean, and the variance of that mean (its paths are independent of
       the eye samples): per path and pixel x, s^2 / N with s^2 from the sums of x and x^2. */
    long spp = -1;
    double var_sum = 0.0, mean_sum = 0.0;
    double paths = (double)j->light_paths;
    for (size_t p = 0; p < n; p++) {
        int k = j->count[p];
        if (spp < 0 || k < spp)
            spp = k;
        for (int c = 0; c < 3; c++) {
            double s = j->sum[3 * p + c], m = k > 0 ? s / k : 0.0;
            if (k > 1) {
                double var = (j->sum_sq[3 * p + c] - s * m) / (k - 1);
                var_sum += (var > 0 ? var : 0) / k;
            }
            if (j->light_terms && paths > 1) {
                double ls = j->light_sum[3 * p + c], lm = ls / paths;
                double var = (j->light_sum_sq[3 * p + c] - ls * lm) / (paths - 1);
                var_sum += (var > 0 ? var : 0) / paths;
                m += lm;
            }
            v->rgb[3 * p + c] = (float)m;
            mean_sum += m;
        }
    }
    if (j->light_terms) {
        /* in samples per frame pixel, as the eye passes count: a reference's spp traces one light
           path per frame pixel and sample */
        long light_spp = (long)(j->light_paths / ((uint64_t)n * (uint64_t)(j->sub * j->sub)));
        if (light_spp < spp)
            spp = light_spp;
    }
    pthread_mutex_unlock(&t->lock);
    v->spp = spp < 0 ? 0 : spp;
    double mean = mean_sum / (double)(3 * n);
    v->noise = v->spp >= 2 && mean > 0 ? sqrt(var_sum / (double)(3 * n)) / mean : NAN;
    return v->spp > 0;
}

void gk_truth_get_stats(gk_truth *t, gk_truth_stats *s)
{
    pthread_mutex_lock(&t->lock);
    s->samples = t->samples;
    s->aborted_tiles = t->aborted_tiles;
    s->retired_views = t->retired_views;
    s->samples_after_stop = atomic_load(&t->samples_after_stop);
    s->workers = t->n_threads;
    pthread_mutex_unlock(&t->lock);
    s->low_priority = atomic_load(&t->low_priority_ok) != 0;
}

bool gk_truth_busy(gk_truth *t)
{
    pthread_mutex_lock(&t->lock);
    bool busy = t->busy > 0;
    pthread_mutex_unlock(&t->lock);
    return busy;
}
