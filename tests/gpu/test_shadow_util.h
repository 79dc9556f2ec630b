/* Shared by tests/gpu/test_shadow*.c (header-only): the analytic soft-shadow scenes of
 * dong-001.md §9.2 built in memory on test_render_fixture.h (the shared gkt_scene builders), one renderer driven through the real
 * pipeline with the shadow method pinned per frame, visibility measured as
 *     V = L(scene) / L(scene without blockers, hard shadows)
 * on a white diffuse receiver (the lighting multiplies the unshadowed radiance by
 * shadow_visibility(), so the ratio is exactly the method's V), and the exact V in C as the light
 * the receiver actually gets, irradiance with occlusion over irradiance without:
 *     V = E(L minus B) / E(L) = 1 - E(B) / E(L),   E(X) = integral over X of cos_r cos_l / r^2 dA
 * (B the blocked part of the light), each E in closed form by the polygon contour integral
 * (Lambert's formula, as fx_polygon_irradiance, in double; exact for a uniform Lambertian polygon):
 *   rectangles (T1, T2): B = (P1 u P2) n L, P_i the occluder squares projected through the
 *   receiver point onto the light plane (scale H / h_i), L the light square; E(P1 u P2) =
 *   E(P1) + E(P2) - E(P1 n P2), all axis-aligned rectangles;
 *   box (T3): the convex hull of the projected box corners clipped to L.
 * Until #11 the truth was the visible AREA fraction 1 - area(B) / S^2, which ignores that the
 * parts of the light nearer the receiver's normal and nearer the receiver count more (on T1 it
 * differs by up to 0.05 in the penumbra). sx_area_v keeps that quantity for the test that shows
 * the difference. */
#ifndef TEST_SHADOW_UTIL_H
#define TEST_SHADOW_UTIL_H

#include "gpu/test_render_fixture.h"
#include "metrics/metrics.h"

#define SX_LIGHT_Y 4.0f

/* Every method name the tests pin, diagnostic variants included (gk_shadow_methods[]): the test's
   own "shadow" knob is added before the renderer's (gk_budget_add keeps the first by name). */
static const gk_knob_def sx_knob_shadow = {
    .name = "shadow", .owner = "test", .n_values = 8,
    .values = {"hard", "pcss", "vssm", "cssm", "cssm_sat", "savsm", "vssm_nocontact", "cssm_raw"},
    .cost = {1, 1, 1, 1, 1, 1, 1, 1}, .default_level = 0,
};

typedef struct sx_rect { float x0, x1, z0, z1, y; } sx_rect;

typedef struct sx_setup {
    float S;                    /* light side (m) */
    vec3 light;                 /* light centre */
    int n_rects;
    sx_rect rect[2];            /* horizontal occluders */
    bool box;                   /* T3: unit cube [-0.5, 0.5] x [0, 1] x [-0.5, 0.5], yawed */
    float box_yaw;
    vec3 eye, target;
    float yfov;
    bool point;                 /* a point light with a rect emitter (6 cube-face maps), as the
                                   shadow-planes scene has; else a rect spot (1 perspective map) */
} sx_setup;

static inline vec3 sx_box_corner(const sx_setup *st, int i)
{
    float x = (i & 1) ? 0.5f : -0.5f, y = (i & 2) ? 1.0f : 0.0f, z = (i & 4) ? 0.5f : -0.5f;
    float c = cosf(st->box_yaw), s = sinf(st->box_yaw);
    return v3(c * x + s * z, y, -s * x + c * z);
}

/* The scene: receiver 10x10 (rho 0.8), blockers (when `blockers`), a rect spot light of side S
   facing down (cone 0.95 rad: one perspective map, dong-001.md's "map from the light centre"), or
   with `point` a rect point light (cube maps; the receiver's rim lies on the side faces). */
static inline void sx_build(fx_scene *f, const sx_setup *st, bool blockers)
{
    fx_init(f, st->eye, st->target, st->yfov);
    f->s.bmin = v3(-5, 0, -5);
    f->s.bmax = v3(5, 2.5f, 5);
    int white = fx_material(f, 0.8f, 0, 0.9f);
    fx_quad(f, -5, 5, -5, 5, 0, white);
    int black = fx_material(f, 0.0f, 0, 0.9f);
    if (blockers) {
        for (int i = 0; i < st->n_rects; i++)
            fx_quad(f, st->rect[i].x0, st->rect[i].x1, st->rect[i].z0, st->rect[i].z1, st->rect[i].y, black);
        if (st->box) {
            static const int faces[5][4] = {{2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}, {0, 4, 6, 2}, {1, 3, 7, 5}};
            for (int k = 0; k < 5; k++) {
                vec3 a = sx_box_corner(st, faces[k][0]), b = sx_box_corner(st, faces[k][1]),
                     c = sx_box_corner(st, faces[k][2]), d = sx_box_corner(st, faces[k][3]);
                gkt_quad(f, a, b, c, d, v3_cross(v3_sub(b, a), v3_sub(c, a)), white);
            }
        }
    }
    gk_light *l = gkt_light(f, st->point ? GK_LIGHT_POINT : GK_LIGHT_SPOT, GK_SHAPE_RECT, 20, st->light, v3(0, -1, 0));
    l->size[0] = l->size[1] = st->S;
    if (!st->point) {
        l->outer_cone = 0.95f;
        l->inner_cone = 0.9f;
    }
}

/* --- exact visibility ------------------------------------------------------------------------ */
/* A convex polygon clipped to [x0,x1]x[z0,z1] (Sutherland-Hodgman) into ax, az (40 entries);
   returns the vertex count. */
static inline int sx_clip(const double *px, const double *pz, int n, double x0, double x1, double z0, double z1,
                          double *ax, double *az)
{
    double bx[40], bz[40];
    int na = n;
    for (int i = 0; i < n; i++)
        ax[i] = px[i], az[i] = pz[i];
    for (int e = 0; e < 4 && na > 0; e++) {
        int nb = 0;
        for (int i = 0; i < na; i++) {
            int j = (i + 1) % na;
            double vi = e == 0 ? ax[i] - x0 : e == 1 ? x1 - ax[i] : e == 2 ? az[i] - z0 : z1 - az[i];
            double vj = e == 0 ? ax[j] - x0 : e == 1 ? x1 - ax[j] : e == 2 ? az[j] - z0 : z1 - az[j];
            if (vi >= 0)
                bx[nb] = ax[i], bz[nb] = az[i], nb++;
            if ((vi >= 0) != (vj >= 0)) {
                double t = vi / (vi - vj);
                bx[nb] = ax[i] + t * (ax[j] - ax[i]), bz[nb] = az[i] + t * (az[j] - az[i]), nb++;
            }
        }
        na = nb;
        for (int i = 0; i < na; i++)
            ax[i] = bx[i], az[i] = bz[i];
    }
    return na;
}

/* Light-plane measure of a polygon (vertices x, z on the light plane y = ly) as seen from the
   receiver point p (normal +y): its area when `area`, else E = integral of cos_r cos_l / r^2 dA. */
static inline double sx_measure(const double *x, const double *z, int n, double ly, vec3 p, bool area)
{
    if (n < 3)
        return 0;
    if (!area) { /* fx_polygon_irradiance in double: a penumbra's slivers need more than float's 7 digits */
        double sum = 0;
        for (int i = 0; i < n; i++) {
            int j = (i + 1) % n;
            double a[3] = {x[i] - p.x, ly - p.y, z[i] - p.z}, b[3] = {x[j] - p.x, ly - p.y, z[j] - p.z};
            double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
            double len = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
            if (len < 1e-300)
                continue;
            sum += atan2(len, a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) * c[1] / len; /* n = +y */
        }
        return 0.5 * fabs(sum);
    }
    double a = 0;
    for (int i = 0; i < n; i++) {
        int j = (i + 1) % n;
        a += x[i] * z[j] - x[j] * z[i];
    }
    return 0.5 * fabs(a);
}

/* The measure of the axis-aligned rectangle [x0,x1]x[z0,z1] on the light plane (0 when empty). */
static inline double sx_rect_measure(double x0, double x1, double z0, double z1, double ly, vec3 p, bool area)
{
    if (x1 <= x0 || z1 <= z0)
        return 0;
    const double x[4] = {x0, x1, x1, x0}, z[4] = {z0, z0, z1, z1};
    return sx_measure(x, z, 4, ly, p, area);
}

/* V at receiver point p: 1 - measure(blocked) / measure(light), the measure E (received light,
   `area` false: the truth) or the area (`area` true: the quantity the tests used before #11). */
static inline double sx_visibility(const sx_setup *st, vec3 p, bool area)
{
    double H = st->light.y - p.y, S = st->S, lx0 = st->light.x - S / 2, lx1 = lx0 + S, lz0 = st->light.z - S / 2,
           lz1 = lz0 + S, ly = st->light.y;
    double blocked = 0;
    if (st->n_rects > 0) {
        double r[2][4];
        for (int i = 0; i < st->n_rects; i++) {
            double k = H / (st->rect[i].y - p.y);
            r[i][0] = p.x + (st->rect[i].x0 - p.x) * k, r[i][1] = p.x + (st->rect[i].x1 - p.x) * k;
            r[i][2] = p.z + (st->rect[i].z0 - p.z) * k, r[i][3] = p.z + (st->rect[i].z1 - p.z) * k;
            blocked += sx_rect_measure(fmax(r[i][0], lx0), fmin(r[i][1], lx1), fmax(r[i][2], lz0), fmin(r[i][3], lz1),
                                       ly, p, area);
        }
        if (st->n_rects == 2) {
            double ix0 = fmax(fmax(r[0][0], r[1][0]), lx0), ix1 = fmin(fmin(r[0][1], r[1][1]), lx1);
            double iz0 = fmax(fmax(r[0][2], r[1][2]), lz0), iz1 = fmin(fmin(r[0][3], r[1][3]), lz1);
            blocked -= sx_rect_measure(ix0, ix1, iz0, iz1, ly, p, area);
        }
    }
    if (st->box) {
        /* corners projected through p onto the light plane (bottom raised by 1e-4 m: the box's
           silhouette seen from a point on its own ground plane reaches the horizon), hull, clip */
        double hx[8], hz[8], ox[16], oz[16];
        for (int i = 0; i < 8; i++) {
            vec3 c = sx_box_corner(st, i);
            double cy = fmax(c.y, 1e-4);
            double k = H / (cy - p.y);
            hx[i] = p.x + (c.x - p.x) * k, hz[i] = p.z + (c.z - p.z) * k;
        }
        /* monotone chain hull */
        int idx[8];
        for (int i = 0; i < 8; i++)
            idx[i] = i;
        for (int i = 1; i < 8; i++)
            for (int j = i; j > 0 && (hx[idx[j]] < hx[idx[j - 1]] || (hx[idx[j]] == hx[idx[j - 1]] && hz[idx[j]] < hz[idx[j - 1]])); j--) {
                int t = idx[j]; idx[j] = idx[j - 1]; idx[j - 1] = t;
            }
        int n = 0;
        for (int pass = 0; pass < 2; pass++) {
            int start = n;
            for (int a = 0; a < 8; a++) {
                int i = pass ? idx[7 - a] : idx[a];
                while (n >= start + 2 && (ox[n - 1] - ox[n - 2]) * (hz[i] - oz[n - 2]) - (oz[n - 1] - oz[n - 2]) * (hx[i] - ox[n - 2]) <= 0)
                    n--;
                ox[n] = hx[i], oz[n] = hz[i], n++;
            }
            n--;
        }
        double cx[40], cz[40];
        int nc = sx_clip(ox, oz, n, lx0, lx1, lz0, lz1, cx, cz);
        blocked += sx_measure(cx, cz, nc, ly, p, area);
    }
    double full = sx_rect_measure(lx0, lx1, lz0, lz1, ly, p, area);
    return fmin(fmax(1.0 - blocked / full, 0.0), 1.0);
}

/* The truth: the received light with occlusion over without. */
static inline double sx_exact_v(const sx_setup *st, vec3 p) { return sx_visibility(st, p, false); }
/* The visible area fraction of the light (not what a receiver gets; kept to show the difference). */
static inline double sx_area_v(const sx_setup *st, vec3 p) { return sx_visibility(st, p, true); }

/* --- rendering -------------------------------------------------------------------------------- */
typedef struct sx_session {
    fx_gl gl;
    gk_renderer *r;
    gk_budget b;
} sx_session;

/* Opens a session whose knob `shadow` is `knob` (a test needing other variants than
   sx_knob_shadow's, which is full at GK_MAX_KNOB_VALUES, passes its own). */
static inline int sx_open_knob(sx_session *x, int w, int h, const gk_knob_def *knob)
{
    memset(x, 0, sizeof *x);
    if (fx_gl_open(&x->gl, w, h) != 0)
        return -1;
    gk_err e = {0};
    gk_render_opts o = {.width = w, .height = h, .gles_version = 32, .shader_dir = getenv("GK_SHADER_DIR")};
    x->r = gk_renderer_create(&o, &e);
    if (!x->r) {
        fprintf(stderr, "renderer: %s\n", e.msg);
        return -1;
    }
    gk_budget_init(&x->b);
    gk_budget_add(&x->b, knob);
    gk_renderer_declare_knobs(x->r, &x->b);
    return 0;
}

static inline int sx_open(sx_session *x, int w, int h) { return sx_open_knob(x, w, h, &sx_knob_shadow); }

static inline void sx_close(sx_session *x)
{
    gk_renderer_destroy(x->r);
    fx_gl_close(&x->gl);
}

/* Draws the scene (already set) with GI method `method` and the given pins and reads the green
   channel into out. */
static inline int sx_draw_method(sx_session *x, const char *method, const char *pins, float *out)
{
    gk_err e = {0};
    if (gk_budget_pin_list(&x->b, pins, &e) != 0) {
        fprintf(stderr, "pins %s: %s\n", pins, e.msg);
        return -1;
    }
    gk_frame_params fp = {.time_s = 0, .method = method, .budget = &x->b};
    gk_frame_report t;
    gk_image img = {0};
    if (gk_renderer_draw(x->r, &fp, x->gl.fb.fbo, &t, &e) != 0 || gk_renderer_read_linear(x->r, &img, &e) != 0) {
        fprintf(stderr, "draw %s: %s\n", pins, e.msg);
        return -1;
    }
    for (int i = 0; i < img.width * img.height; i++)
        out[i] = img.pixels[(size_t)i * img.channels + 1];
    gk_image_free(&img);
    return gk_renderer_gi_failed(x->r, method) ? -1 : 0;
}

/* sx_draw_method without GI. */
static inline int sx_draw(sx_session *x, const char *pins, float *out) { return sx_draw_method(x, "none", pins, out); }

/* T1 "plane-over-plane" (dong-001.md §9.2): light square of side S at y = 4 facing down, blocker 2x2
   at y = 1 centred at the origin; camera (0, 6, 6) looking at the origin, 60 degree FOV. */
static inline sx_setup sx_t1(float S)
{
    sx_setup st = {.S = S, .light = v3(0, SX_LIGHT_Y, 0), .n_rects = 1, .eye = v3(0, 6, 6), .target = v3(0, 0, 0),
                   .yfov = 1.0471976f};
    st.rect[0] = (sx_rect){-1, 1, -1, 1, 1};
    return st;
}

/* Per pixel: the receiver point (valid when the camera ray reaches the receiver plane y = 0
   unobstructed by a blocker) and its exact V. */
typedef struct sx_truth {
    int w, h;
    unsigned char *valid;
    float *v;
    vec3 *p;
} sx_truth;

static inline bool sx_ray_blocked(const sx_setup *st, vec3 eye, vec3 p)
{
    for (int i = 0; i < st->n_rects; i++) {
        const sx_rect *r = &st->rect[i];
        if ((eye.y - r->y) * (p.y - r->y) >= 0)
            continue;
        float t = (r->y - eye.y) / (p.y - eye.y);
        float x = eye.x + t * (p.x - eye.x), z = eye.z + t * (p.z - eye.z);
        if (x >= r->x0 - 0.02f && x <= r->x1 + 0.02f && z >= r->z0 - 0.02f && z <= r->z1 + 0.02f)
            return true;
    }
    if (st->box) { /* slab test in the box's frame, 2 cm margin */
        float c = cosf(st->box_yaw), s = sinf(st->box_yaw);
        vec3 o = v3(c * eye.x - s * eye.z, eye.y, s * eye.x + c * eye.z);
        vec3 q = v3(c * p.x - s * p.z, p.y, s * p.x + c * p.z);
        vec3 d = v3_sub(q, o);
        float lo[3] = {-0.52f, -1.0f, -0.52f}, hi[3] = {0.52f, 1.02f, 0.52f};
        float oo[3] = {o.x, o.y, o.z}, dd[3] = {d.x, d.y, d.z}, t0 = 0, t1 = 1;
        for (int k = 0; k < 3; k++) {
            if (fabsf(dd[k]) < 1e-9f) {
                if (oo[k] < lo[k] || oo[k] > hi[k])
                    return false;
                continue;
            }
            float a = (lo[k] - oo[k]) / dd[k], b = (hi[k] - oo[k]) / dd[k];
            if (a > b) { float t = a; a = b; b = t; }
            t0 = fmaxf(t0, a);
            t1 = fminf(t1, b);
        }
        if (t0 <= t1)
            return true;
    }
    return false;
}

static inline void sx_truth_build(sx_truth *t, fx_scene *f, const sx_setup *st, int w, int h)
{
    t->w = w, t->h = h;
    t->valid = calloc((size_t)w * h, 1);
    t->v = calloc((size_t)w * h, sizeof(float));
    t->p = calloc((size_t)w * h, sizeof(vec3));
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            vec3 p, eye;
            int i = y * w + x;
            if (fx_pixel_on_plane(f, w, h, x, y, 0, &p, &eye) != 0 || sx_ray_blocked(st, eye, p))
                continue;
            t->valid[i] = 1;
            t->p[i] = p;
            t->v[i] = (float)sx_exact_v(st, p);
        }
}

static inline void sx_truth_free(sx_truth *t)
{
    free(t->valid);
    free(t->v);
    free(t->p);
}

/* V of a method = L / L_unblocked where the unblocked radiance is meaningful; NaN elsewhere. */
static inline void sx_ratio(const float *with, const float *without, const sx_truth *t, float *v)
{
    for (int i = 0; i < t->w * t->h; i++)
        v[i] = (t->valid[i] && without[i] > 1e-4f) ? with[i] / without[i] : NAN;
}

/* Error statistics of V against the truth in the umbra (V = 0), penumbra and lit (V = 1) masks. */
typedef struct sx_stats {
    double mean[3], max[3], bias[3];
    int n[3];
} sx_stats;

enum { SX_UMBRA, SX_PENUMBRA, SX_LIT };

static inline int sx_class(float v) { return v <= 1e-6f ? SX_UMBRA : v >= 1 - 1e-6f ? SX_LIT : SX_PENUMBRA; }

static inline sx_stats sx_compare(const float *v, const sx_truth *t)
{
    sx_stats s = {0};
    for (int i = 0; i < t->w * t->h; i++) {
        if (!t->valid[i] || isnan(v[i]))
            continue;
        int c = sx_class(t->v[i]);
        double d = (double)v[i] - t->v[i];
        s.mean[c] += fabs(d);
        s.bias[c] += d;
        s.max[c] = fmax(s.max[c], fabs(d));
        s.n[c]++;
    }
    for (int c = 0; c < 3; c++)
        if (s.n[c]) {
            s.mean[c] /= s.n[c];
            s.bias[c] /= s.n[c];
        }
    return s;
}

static inline void sx_print(const char *what, const char *method, const sx_stats *s)
{
    printf("# %-10s %-15s umbra mean %.4f max %.4f (n %4d) | penumbra mean %.4f max %.4f bias %+.4f (n %4d) | lit mean %.4f max %.4f (n %4d)\n",
           what, method, s->mean[0], s->max[0], s->n[0], s->mean[1], s->max[1], s->bias[1], s->n[1], s->mean[2], s->max[2], s->n[2]);
}

/* The fixture the shadow tests share: one session `ses` of SIZE x SIZE pixels (W and H) opened once for
 * the group (cmocka_run_group_tests(tests, setup, teardown)). */
#define SX_SESSION_GROUP(SIZE)                                                                                   \
    enum { W = SIZE, H = SIZE };                                                                                 \
    static sx_session ses;                                                                                       \
    static int setup(void **state)                                                                               \
    {                                                                                                            \
        (void)state;                                                                                             \
        return sx_open(&ses, W, H);                                                                              \
    }                                                                                                            \
    static int teardown(void **state)                                                                            \
    {                                                                                                            \
        (void)state;                                                                                             \
        sx_close(&ses);                                                                                          \
        return 0;                                                                                                \
    }

#endif
