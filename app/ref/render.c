/* Threaded, deterministic rendering of reference images (see render.h). */
#include "render.h"

#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define TILE 16
#define LIGHT_CHUNKS 16  /* fixed, so the sum order does not depend on the thread count; even, so
                            chunks [0, 8) hold exactly the first half of the samples */

typedef struct job {
    const gk_ref_scene *rs;
    const gk_ref_options *o;
    int n1;                  /* samples in the first half */
    int tiles_x, n_tiles, n_items;
    double *sum_h1, *sum_all; /* eye pass: per pixel RGB sums of the first half and of all samples */
    float **chunk;           /* light pass: one splat image per chunk */
    atomic_int next, done;
    atomic_ullong rays;
    pthread_mutex_t progress_lock;
    int last_percent;
    bool light_pass;
    const gk_caustic_emitter *emitter; /* NULL: the lights' own emission */
    unsigned light_terms;    /* what the light pass connects: GK_TERM_SURFACES (L S+ D E) and/or
                                GK_TERM_VCAUSTICS (L S+ V E) */
    int failed;
} job;

void gk_ref_options_default(gk_ref_options *o)
{
    memset(o, 0, sizeof *o);
    o->spp = 64;
    o->threads = 1;
    o->max_depth = 32;
    o->rr_depth = 4;
    o->seed = 1;
    o->paths = GK_PATH_ALL;
    o->max_diffuse = GK_BOUNCES_UNLIMITED;
    o->caustic_emit = GK_CAUSTIC_EMIT_GUIDED;
    o->caustic_grid = GK_CAUSTIC_GRID_DEFAULT;
    o->caustic_specular = GK_BOUNCES_UNLIMITED;
    o->terms = GK_TERM_ALL;
}

static const struct { const char *name; unsigned bit; } term_names[] = {
    {"airlight", GK_TERM_AIRLIGHT}, {"vcaustics", GK_TERM_VCAUSTICS},
    {"surfaces", GK_TERM_SURFACES}, {"multiple", GK_TERM_MULTIPLE},
};

int gk_ref_terms_parse(const char *s)
{
    if (!strcmp(s, "all"))
        return GK_TERM_ALL;
    unsigned mask = 0;
    const char *p = s;
    while (*p) {
        size_t n = strcspn(p, "+");
        unsigned bit = 0;
        for (size_t i = 0; i < sizeof term_names / sizeof term_names[0]; i++)
            if (strlen(term_names[i].name) == n && !strncmp(p, term_names[i].name, n))
                bit = term_names[i].bit;
        if (!bit)
            return -1;
        mask |= bit;
        p += n;
        if (*p == '+' && *++p == '\0')
            return -1;
    }
    return mask ? (int)mask : -1;
}

const char *gk_ref_terms_name(unsigned terms, char *buf, size_t len)
{
    if (terms == GK_TERM_ALL) {
        snprintf(buf, len, "all");
        return buf;
    }
    size_t at = 0;
    buf[0] = '\0';
    for (size_t i = 0; i < sizeof term_names / sizeof term_names[0]; i++)
        if (terms & term_names[i].bit) {
            int w = snprintf(buf + at, at < len ? len - at : 0, "%s%s", at ? "+" : "", term_names[i].name);
            at += (size_t)w;
            if (at >= len)
                break;
        }
    return buf;
}

int gk_ref_bounces_parse(const char *s)
{
    if (!strcmp(s, "unlimited"))
        return GK_BOUNCES_UNLIMITED;
    char *end;
    long v = strtol(s, &end, 10);
    if (end == s || *end || v < 0 || v > 1000)
        return -2;
    return (int)v;
}

const char *gk_ref_bounces_name(int max_diffuse, char *buf, size_t len)
{
    if (max_diffuse == GK_BOUNCES_UNLIMITED)
        snprintf(buf, len, "unlimited");
    else
        snprintf(buf, len, "%d", max_diffuse);
    return buf;
}

int gk_ref_paths_parse(const char *s)
{
    if (!strcmp(s, "all"))
        return GK_PATH_ALL;
    if (!strcmp(s, "direct"))
        return GK_PATH_DIRECT;
    if (!strcmp(s, "indirect"))
        return GK_PATH_INDIRECT;
    if (!strcmp(s, "caustics"))
        return GK_PATH_CAUSTICS;
    return -1;
}

const char *gk_ref_paths_name(unsigned mask)
{
    switch (mask) {
    case GK_PATH_ALL: return "all";
    case GK_PATH_DIRECT: return "direct";
    case GK_PATH_INDIRECT: return "indirect";
    case GK_PATH_CAUSTICS: return "caustics";
    default: return "mixed";
    }
}

unsigned gk_ref_light_terms(const gk_ref_scene *rs, const gk_ref_options *o)
{
    unsigned terms = 0;
    /* Light-traced caustics L S+ D E have one D vertex: dropped only by a limit of 0 bounces. */
    if ((o->paths & GK_PATH_CAUSTICS) && (o->terms & GK_TERM_SURFACES) && o->max_diffuse != 0)
        terms |= GK_TERM_SURFACES;
    /* Volume caustics L S+ V E have no D vertex: no bounce limit drops them. */
    if (rs->medium.present && (o->terms & GK_TERM_VCAUSTICS))
        terms |= GK_TERM_VCAUSTICS;
    return rs->n_lights > 0 && rs->has_delta_surfaces ? terms : 0;
}

static void render_tile(job *j, int tile, gk_trace_stats *st)
{
    const gk_ref_scene *rs = j->rs;
    int x0 = (tile % j->tiles_x) * TILE, y0 = (tile / j->tiles_x) * TILE;
    for (int y = y0; y < y0 + TILE && y < rs->height; y++)
        for (int x = x0; x < x0 + TILE && x < rs->width; x++) {
            size_t pix = (size_t)y * rs->width + x;
            vec3 d = gk_ref_camera_dir(rs, x + 0.5f, y + 0.5f);
            double acc[3] = {0, 0, 0};
            for (int s = 0; s < j->o->spp; s++) {
                if (s == j->n1)
                    for (int c = 0; c < 3; c++)
                        j->sum_h1[3 * pix + c] = acc[c];
                gk_rng rng;
                gk_rng_seed(&rng, j->o->seed, pix, (uint64_t)s, 0);
                vec3 l = gk_trace_eye(rs, rs->eye, d, j->o->paths, j->o->terms, j->o->max_diffuse,
                                      j->o->max_depth, j->o->rr_depth, &rng, st);
                /* A NaN or Inf sample would poison the pixel: drop it (counted as black). */
                if (isfinite(l.x) && isfinite(l.y) && isfinite(l.z)) {
                    acc[0] += l.x;
                    acc[1] += l.y;
                    acc[2] += l.z;
                }
            }
            if (j->n1 >= j->o->spp)
                for (int c = 0; c < 3; c++)
                    j->sum_h1[3 * pix + c] = acc[c];
            for (int c = 0; c < 3; c++)
                j->sum_all[3 * pix + c] = acc[c];
        }
}

typedef struct splat_ctx { float *img; int width; } splat_ctx;

static void splat_into(void *ctx, int px, int py, vec3 v)
{
    splat_ctx *c = ctx;
    if (!(isfinite(v.x) && isfinite(v.y) && isfinite(v.z)))
        return;
    float *p = &c->img[3 * ((size_t)py * c->width + px)];
    p[0] += v.x;
    p[1] += v.y;
    p[2] += v.z;
}

static int chunk_first_sample(int chunk, int spp) { return (int)((int64_t)chunk * spp / LIGHT_CHUNKS); }

static void render_chunk(job *j, int chunk, gk_trace_stats *st)
{
    const gk_ref_scene *rs = j->rs;
    size_t npix = (size_t)rs->width * rs->height;
    float *img = calloc(npix * 3, sizeof(float));
    if (!img) {
        j->failed = 1;
        return;
    }
    splat_ctx c = {img, rs->width};
    for (int s = chunk_first_sample(chunk, j->o->spp); s < chunk_first_sample(chunk + 1, j->o->spp); s++)
        for (size_t p = 0; p < npix; p++) {
            gk_rng rng;
            gk_rng_seed(&rng, j->o->seed, p, (uint64_t)s, 1);
            gk_trace_light(rs, j->emitter, j->light_terms, j->o->max_depth, j->o->caustic_specular, &rng,
                           splat_into, &c, st);
        }
    j->chunk[chunk] = img;
}

static void show_progress(job *j)
{
    int done = atomic_fetch_add(&j->done, 1) + 1;
    if (!j->o->progress)
        return;
    int percent = (int)(100.0 * done / j->n_items);
    pthread_mutex_lock(&j->progress_lock);
    if (percent != j->last_percent) {
        j->last_percent = percent;
        int bar = percent / 4;
        fprintf(stderr, "\rreference [%.*s%*s] %3d%%", bar, "=========================", 25 - bar, "", percent);
        if (done == j->n_items)
            fputc('\n', stderr);
        fflush(stderr);
    }
    pthread_mutex_unlock(&j->progress_lock);
}

static void *worker(void *arg)
{
    job *j = arg;
    gk_trace_stats st = {0};
    for (;;) {
        int item = atomic_fetch_add(&j->next, 1);
        if (item >= j->n_items)
            break;
        if (item < j->n_tiles)
            render_tile(j, item, &st);
        else
            render_chunk(j, item - j->n_tiles, &st);
        show_progress(j);
    }
    atomic_fetch_add(&j->rays, st.rays);
    return NULL;
}

double gk_ref_rel_rmse(const float *t, const float *r, size_t n)
{
    double se = 0.0, sr = 0.0;
    for (size_t i = 0; i < n; i++) {
        double d = (double)t[i] - (double)r[i];
        se += d * d;
        sr += r[i];
    }
    if (n == 0 || sr == 0.0)
        return NAN;
    return sqrt(se / (double)n) / (sr / (double)n);
}

int gk_ref_render(const gk_ref_scene *rs, const gk_ref_options *o, gk_ref_result *r, gk_err *e)
{
    memset(r, 0, sizeof *r);
    if (rs->width <= 0 || rs->height <= 0 || o->spp <= 0 || o->threads <= 0)
        return gk_fail(e, GK_EINPUT, "reference: size, spp and threads must be positive");
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    size_t npix = (size_t)rs->width * rs->height;
    job j;
    memset(&j, 0, sizeof j);
    j.rs = rs;
    j.o = o;
    j.n1 = o->spp / 2;
    j.tiles_x = (rs->width + TILE - 1) / TILE;
    j.n_tiles = j.tiles_x * ((rs->height + TILE - 1) / TILE);
    j.light_terms = gk_ref_light_terms(rs, o);
    j.light_pass = j.light_terms != 0;
    j.n_items = j.n_tiles + (j.light_pass ? LIGHT_CHUNKS : 0);
    gk_caustic_emitter emitter = {0};
    if (j.light_pass && o->caustic_emit == GK_CAUSTIC_EMIT_GUIDED) {
        if (gk_caustic_emitter_build(&emitter, rs, o->caustic_grid, e))
            return -1;
        j.emitter = &emitter;
    }
    j.last_percent = -1;
    j.sum_h1 = calloc(npix * 3, sizeof(double));
    j.sum_all = calloc(npix * 3, sizeof(double));
    j.chunk = calloc(LIGHT_CHUNKS, sizeof(float *));
    r->rgb = malloc(npix * 3 * sizeof(float));
    float *h1 = malloc(npix * 3 * sizeof(float)), *h2 = malloc(npix * 3 * sizeof(float));
    if (!j.sum_h1 || !j.sum_all || !j.chunk || !r->rgb || !h1 || !h2) {
        gk_fail(e, GK_ERUNTIME, "reference: out of memory for a %dx%d image", rs->width, rs->height);
        goto fail;
    }
    atomic_init(&j.next, 0);
    atomic_init(&j.done, 0);
    atomic_init(&j.rays, 0);
    pthread_mutex_init(&j.progress_lock, NULL);
    pthread_t *th = calloc((size_t)o->threads, sizeof *th);
    int started = 0;
    if (th)
        for (int i = 1; i < o->threads; i++, started++)
            if (pthread_create(&th[i], NULL, worker, &j))
                break;
    worker(&j); /* the calling thread works too */
    for (int i = 1; i <= started; i++)
        pthread_join(th[i], NULL);
    free(th);
    pthread_mutex_destroy(&j.progress_lock);
    if (j.failed) {
        gk_fail(e, GK_ERUNTIME, "reference: out of memory for the light-tracing buffers");
        goto fail;
    }

    /* Eye pass + light pass, each half normalised by its own sample count. Light paths: one per
       pixel per sample, so a sample's light image is divided by (spp * pixels). */
    int n1 = j.n1, n2 = o->spp - j.n1;
    double inv_all = 1.0 / o->spp, inv_light = 1.0 / ((double)o->spp * (double)npix);
    for (size_t i = 0; i < npix * 3; i++) {
        double l1 = 0.0, l2 = 0.0;
        if (j.light_pass)
            for (int c = 0; c < LIGHT_CHUNKS; c++)
                *(c < LIGHT_CHUNKS / 2 ? &l1 : &l2) += j.chunk[c][i];
        double a1 = j.sum_h1[i], a2 = j.sum_all[i] - j.sum_h1[i];
        r->rgb[i] = (float)((j.sum_all[i]) * inv_all + (l1 + l2) * inv_light);
        if (n1 > 0 && n2 > 0) {
            h1[i] = (float)(a1 / n1 + l1 / ((double)n1 * npix));
            h2[i] = (float)(a2 / n2 + l2 / ((double)n2 * npix));
        }
    }
    r->noise_floor = NAN;
    if (n1 > 0 && n2 > 0) {
        double se = 0.0, sum = 0.0;
        for (size_t i = 0; i < npix * 3; i++) {
            double d = (double)h1[i] - (double)h2[i];
            se += d * d;
            sum += r->rgb[i];
        }
        if (sum > 0.0)
            r->noise_floor = sqrt(se / (double)(npix * 3)) / (sum / (double)(npix * 3)) /
                             sqrt((double)o->spp * (1.0 / n1 + 1.0 / n2));
    }
    clock_gettime(CLOCK_MONOTONIC, &t1);
    r->seconds = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
    r->rays = atomic_load(&j.rays);
    r->samples = (uint64_t)npix * (uint64_t)o->spp;
    r->light_paths = j.light_pass ? r->samples : 0;
    for (int c = 0; c < LIGHT_CHUNKS; c++)
        free(j.chunk[c]);
    free(j.chunk);
    free(j.sum_h1);
    free(j.sum_all);
    gk_caustic_emitter_free(&emitter);
    if (n1 > 0 && n2 > 0) {
        r->half[0] = h1, r->half[1] = h2;
        r->n_half[0] = n1, r->n_half[1] = n2;
    } else {
        free(h1);
        free(h2);
    }
    return 0;
fail:
    if (j.chunk)
        for (int c = 0; c < LIGHT_CHUNKS; c++)
            free(j.chunk[c]);
    free(j.chunk);
    free(j.sum_h1);
    free(j.sum_all);
    free(h1);
    free(h2);
    gk_caustic_emitter_free(&emitter);
    gk_ref_result_free(r);
    return -1;
}

void gk_ref_result_free(gk_ref_result *r)
{
    free(r->rgb);
    free(r->half[0]);
    free(r->half[1]);
    r->rgb = r->half[0] = r->half[1] = NULL;
}

double gk_ref_noise_floor_masked(const gk_ref_result *r, int width, int height, const unsigned char *mask,
                                 bool inside)
{
    if (!r->half[0] || !r->half[1])
        return NAN;
    double se = 0.0, sum = 0.0;
    size_t n = 0;
    for (size_t p = 0; p < (size_t)width * height; p++) {
        if ((mask[p] != 0) != inside)
            continue;
        for (int c = 0; c < 3; c++) {
            double d = (double)r->half[0][3 * p + c] - (double)r->half[1][3 * p + c];
            se += d * d;
            sum += r->rgb[3 * p + c];
        }
        n += 3;
    }
    if (n == 0 || !(sum > 0.0))
        return NAN;
    int n1 = r->n_half[0], n2 = r->n_half[1];
    return sqrt(se / (double)n) / (sum / (double)n) / sqrt((double)(n1 + n2) * (1.0 / n1 + 1.0 / n2));
}
