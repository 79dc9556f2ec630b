/* Shared by tests/gpu/test_render*.c and test_shadow*.c (header-only, no main): on the shared
 * fixture (tests/common/gl_fixture.h: context, framebuffer, scene builders) a renderer drawing
 * hand-built scenes of quads and lights into a small FBO, and an independent C version of the
 * BRDF (app/core/brdf_spec.md) and of the Lambert polygon irradiance. */
#ifndef TEST_RENDER_FIXTURE_H
#define TEST_RENDER_FIXTURE_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/gl_fixture.h"
#include "io/image_io.h"
#include "render/renderer.h"
#include "scene/scene.h"

#define FX_PI 3.14159265358979

/* The shared context and one RGBA8 framebuffer the renderer draws into. */
typedef struct fx_gl {
    gkt_gl gl;
    gk_target fb;
} fx_gl;

static inline int fx_gl_open(fx_gl *g, int w, int h)
{
    const GLenum rgba8[1] = {GL_RGBA8};
    memset(g, 0, sizeof *g);
    if (gkt_gl_open(&g->gl) != 0)
        return -1;
    return gkt_target(&g->fb, "test framebuffer", w, h, 1, rgba8, false);
}

static inline void fx_gl_close(fx_gl *g)
{
    gk_target_destroy(&g->fb);
    gkt_gl_close(&g->gl);
}

/* Scenes: the shared builder (gkt_scene), a camera, and the plane tests' horizontal quads. */
typedef gkt_scene fx_scene;

static inline void fx_init(fx_scene *f, vec3 eye, vec3 target, float yfov)
{
    gkt_scene_init(f, "fixture");
    gkt_camera(f, eye, target, yfov);
    f->s.bmin = v3(-4, -1, -4);
    f->s.bmax = v3(4, 3, 4);
}

static inline int fx_material(fx_scene *f, float rho, float metallic, float roughness)
{
    return gkt_material(f, v3(rho, rho, rho), metallic, roughness);
}

/* A horizontal quad (normal +y) from (x0, y, z0) to (x1, y, z1). */
static inline void fx_quad(fx_scene *f, float x0, float x1, float z0, float z1, float y, int material)
{
    gkt_quad(f, v3(x0, y, z0), v3(x1, y, z0), v3(x1, y, z1), v3(x0, y, z1), v3(0, 1, 0), material);
}

/* Renders one frame with the given knobs (NULL: defaults) and reads the linear image back. */
static inline int fx_render(fx_gl *g, fx_scene *f, int gles, const char *budget, gk_image *out, gk_err *e)
{
    gk_render_opts o = {.width = g->fb.width, .height = g->fb.height, .gles_version = gles, .shader_dir = getenv("GK_SHADER_DIR")};
    gk_renderer *r = gk_renderer_create(&o, e);
    if (!r)
        return -1;
    gk_budget b;
    gk_budget_init(&b);
    gk_renderer_declare_knobs(r, &b);
    int rc = budget ? gk_budget_pin_list(&b, budget, e) : 0;
    gk_frame_params fp = {.time_s = 0, .method = "none", .budget = &b};
    gk_frame_report t;
    if (rc == 0)
        rc = gk_renderer_set_scene(r, &f->s, e);
    if (rc == 0)
        rc = gk_renderer_draw(r, &fp, g->fb.fbo, &t, e);
    if (rc == 0)
        rc = gk_renderer_read_linear(r, out, e);
    gk_renderer_destroy(r);
    return rc;
}

/* The world point on the plane y = plane_y seen through pixel (x, y) (top row first). */
static inline int fx_pixel_on_plane(fx_scene *f, int w, int h, int x, int y, float plane_y, vec3 *p, vec3 *eye_out)
{
    mat4 view, proj;
    vec3 eye;
    gk_scene_evaluate(&f->s, 0);
    gk_scene_camera(&f->s, (float)w / (float)h, &view, &proj, &eye);
    mat4 inv = m4_inverse(m4_mul(proj, view));
    float nx = ((float)x + 0.5f) / (float)w * 2 - 1, ny = 1 - ((float)y + 0.5f) / (float)h * 2;
    vec4 a = m4_vec4(inv, (vec4){nx, ny, -1, 1}), b = m4_vec4(inv, (vec4){nx, ny, 1, 1});
    vec3 pa = v3(a.x / a.w, a.y / a.w, a.z / a.w), pb = v3(b.x / b.w, b.y / b.w, b.z / b.w);
    vec3 d = v3_sub(pb, pa);
    if (fabs(d.y) < 1e-9)
        return -1;
    double t = (plane_y - pa.y) / d.y;
    if (t <= 0)
        return -1;
    *p = v3_add(pa, v3_scale(d, (float)t));
    *eye_out = eye;
    /* Only points well inside the test planes (x, z in [-3.9, 3.9]) count. */
    return fabsf(p->x) < 3.9f && fabsf(p->z) < 3.9f ? 0 : -1;
}

/* brdf_spec.md, written again in double precision: the specular term F D V. */
static inline double fx_spec(vec3 n, vec3 v, vec3 l, double f0, double roughness)
{
    double nl = v3_dot(n, l), nv = v3_dot(n, v);
    if (nl <= 0 || nv <= 0)
        return 0;
    vec3 h = v3_norm(v3_add(v, l));
    double a = fmax(roughness * roughness, 0.0025), a2 = a * a;
    double nh = v3_dot(n, h), vh = v3_dot(v, h);
    double F = f0 + (1 - f0) * pow(1 - vh, 5);
    double dd = nh * nh * (a2 - 1) + 1, D = a2 / (FX_PI * dd * dd);
    double V = 0.5 / (nl * sqrt(nv * nv * (1 - a2) + a2) + nv * sqrt(nl * nl * (1 - a2) + a2));
    return F * D * V;
}

/* fresnel_mix's share for the diffuse lobe of the default dielectric (brdf_spec.md: specular
 * weight 1, c0 = 0.04): 1 - Fd(v.h), Fd = 0.04 + 0.96 (1 - v.h)^5. */
static inline double fx_diffuse_share(vec3 v, vec3 l)
{
    double vh = v3_dot(v, v3_norm(v3_add(v, l)));
    return 1.0 - (0.04 + 0.96 * pow(1 - vh, 5));
}

/* Lambert polygon irradiance / radiance (the edge integral), polygon wholly above p's horizon. */
static inline double fx_polygon_irradiance(vec3 p, vec3 n, const vec3 *verts, int count)
{
    double sum = 0;
    for (int i = 0; i < count; i++) {
        vec3 a = v3_norm(v3_sub(verts[i], p)), b = v3_norm(v3_sub(verts[(i + 1) % count], p));
        vec3 c = v3_cross(a, b);
        double len = v3_len(c);
        if (len < 1e-12)
            continue;
        sum += atan2(len, v3_dot(a, b)) * v3_dot(c, n) / len;
    }
    return 0.5 * fabs(sum);
}

#endif
