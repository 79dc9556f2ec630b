/* atrium: a Sponza-like courtyard built procedurally, the performance scene. A 28 x 14 m stone
 * hall open to the sky, with arcades of columns and round arches on two floors along both long
 * sides, and coloured drapes hanging from the upper gallery; ~80k triangles. Lit by the sun
 * (directional, lux, with the sun's real angular radius) and two warm lamps in the arcades.
 * Columns and arches are instanced (one mesh, many nodes), so the file stays small (~1 MB). */
#include <math.h>
#include <stdio.h>

#include "scene/build_geom.h"

#define HALF_X 14.0f       /* hall: x in [-14, 14], z in [-7, 7] */
#define HALF_Z 7.0f
#define HEIGHT 10.0f
#define ARCADE_Z 3.0f      /* column centres at z = +-3 */
#define BAY 2.4f           /* column spacing along x */
#define N_BAYS 10          /* columns at x = -12 .. 12 */
#define SLAB1 4.6f         /* gallery floor: y 4.6 .. 5.0 */
#define SLAB2 9.0f         /* gallery roof: y 9.0 .. 9.4 */

/* A column: square base, fluted-looking shaft (many facets), square capital. */
static void column(gkw_geom *g, float radius, float y0, float y1, float block)
{
    gkb_box(g, v3(-block, y0, -block), v3(block, y0 + 0.25f, block), false);
    gkb_cylinder(g, v3(0, 0, 0), radius, y0 + 0.25f, y1 - 0.3f, 32, 6, false);
    gkb_box(g, v3(-block, y1 - 0.3f, -block), v3(block, y1, block), false);
}

/* One bay of an arcade wall in its local frame: a slab of thickness t (z in [-t/2, t/2]) spanning
 * x in [-w/2, w/2], y in [y_spring, y_top], with a semicircular opening of radius r centred at
 * (0, y_spring). Each face is a strip of quads between the arc and the bay's outline. */
static void arch_bay(gkw_geom *g, float w, float r, float y_spring, float y_top, float t, int n)
{
    for (int side = -1; side <= 1; side += 2) {
        float z = side * t * 0.5f;
        for (int i = 0; i < n; i++) {
            float a0 = (float)M_PI * (float)i / (float)n, a1 = (float)M_PI * (float)(i + 1) / (float)n;
            vec3 p0 = v3(-r * cosf(a0), y_spring + r * sinf(a0), z), p1 = v3(-r * cosf(a1), y_spring + r * sinf(a1), z);
            /* the outline point in the same direction from the arc's centre, clamped to the bay */
            vec3 q0, q1;
            for (int k = 0; k < 2; k++) {
                float a = k ? a1 : a0, dx = -cosf(a), dy = sinf(a);
                float s = fminf(dx != 0 ? (w * 0.5f) / fabsf(dx) : 1e9f, dy > 0 ? (y_top - y_spring) / dy : 1e9f);
                vec3 q = v3(dx * s, y_spring + dy * s, z);
                if (k)
                    q1 = q;
                else
                    q0 = q;
            }
            gkb_quad(g, p0, p1, q1, q0, v3(0, 0, (float)side));
            /* where the outline turns the bay's top corner, fill the corner triangle */
            bool side0 = fabsf(fabsf(q0.x) - w * 0.5f) < 1e-4f, side1 = fabsf(fabsf(q1.x) - w * 0.5f) < 1e-4f;
            if (side0 != side1) {
                vec3 corner = v3(copysignf(w * 0.5f, side0 ? q0.x : q1.x), y_top, z);
                gkb_triangle(g, q0, corner, q1, v3(0, 0, (float)side));
            }
        }
    }
    for (int i = 0; i < n; i++) { /* intrados, facing the opening */
        float a0 = (float)M_PI * (float)i / (float)n, a1 = (float)M_PI * (float)(i + 1) / (float)n;
        vec3 c0 = v3(-r * cosf(a0), y_spring + r * sinf(a0), 0), c1 = v3(-r * cosf(a1), y_spring + r * sinf(a1), 0);
        vec3 h = v3(0, 0, t * 0.5f), mid = v3_scale(v3_add(c0, c1), 0.5f);
        gkb_quad(g, v3_sub(c0, h), v3_sub(c1, h), v3_add(c1, h), v3_add(c0, h), v3(-mid.x, y_spring - mid.y, 0));
    }
}

/* A drape: a cloth of w x h hanging from y_top, folded by a few sine waves that fade downwards. */
static void drape(gkw_geom *g, float w, float h, float y_top, float phase)
{
    const int nu = 48, nv = 64;
    uint32_t first = g->nv;
    for (int j = 0; j <= nv; j++)
        for (int i = 0; i <= nu; i++) {
            float u = (float)i / nu, v = (float)j / nv;
            float amp = 0.07f * (1.0f - 0.6f * v), k = 2.0f * (float)M_PI * 3.0f;
            float x = (u - 0.5f) * w * (1.0f - 0.15f * v * v), y = y_top - v * h;
            float z = amp * sinf(k * u + phase + 1.5f * v);
            float dzdx = amp * k * cosf(k * u + phase + 1.5f * v) / w;
            gkb_vertex(g, v3(x, y, z), v3(-dzdx, 0, 1), u, v);
        }
    for (int j = 0; j < nv; j++)
        for (int i = 0; i < nu; i++) {
            uint32_t a = first + (uint32_t)(j * (nu + 1) + i), b = a + 1, c = a + (uint32_t)(nu + 1), dd = c + 1;
            gkb_tri(g, a, c, dd); /* +z facing: rows go down (-y), columns go +x */
            gkb_tri(g, a, dd, b);
        }
}

static void instance(gkw_doc *d, const char *name, int mesh, vec3 t, quat r)
{
    gkw_node *n = gkw_node_add(d, name, NULL);
    if (n) {
        n->mesh = mesh;
        n->t = t;
        n->r = r;
    }
}

int gk_build_atrium(const char *dir, gk_err *e)
{
    gkw_doc *d = gkw_new("atrium");
    gkw_description(d,
                    "A Sponza-like courtyard (procedural): two floors of columns and round arches along both sides, "
                    "coloured drapes, open to the sky; ~80k triangles. Sun (directional, 2000 lux) plus two lamps "
                    "in the arcades. The performance scene for the scheduler and the bench (vct, vpl, lightmap).",
                    NULL);
    gkw_material stone = {"stone", {0.58, 0.52, 0.42, 1}, 0, 0.9, {0, 0, 0}, 0, 0, 0, false, false, NULL, false, 0, {0, 0, 0}};
    gkw_material floor_m = {"floor", {0.45, 0.42, 0.38, 1}, 0, 0.8, {0, 0, 0}, 0, 0, 0, false, false, NULL, false, 0, {0, 0, 0}};
    static const double cloth[3][4] = {{0.55, 0.05, 0.04, 1}, {0.05, 0.35, 0.08, 1}, {0.05, 0.09, 0.45, 1}};
    int ms = gkw_add_material(d, &stone), mf = gkw_add_material(d, &floor_m), mc[3];
    for (int k = 0; k < 3; k++) {
        gkw_material m = {k == 0 ? "drape-red" : k == 1 ? "drape-green" : "drape-blue",
                          {cloth[k][0], cloth[k][1], cloth[k][2], 1}, 0, 1, {0, 0, 0}, 0, 0, 0, true, false, NULL, false, 0, {0, 0, 0}};
        mc[k] = gkw_add_material(d, &m);
    }
    gkw_geom g = {0};
    gkb_quad_grid(&g, v3(-HALF_X, 0, -HALF_Z), v3(HALF_X, 0, -HALF_Z), v3(HALF_X, 0, HALF_Z), v3(-HALF_X, 0, HALF_Z),
                  v3(0, 1, 0), 56, 28);
    gkb_object(d, "floor", &g, mf);
    /* outer walls (inside faces), gallery floors and roofs */
    gkb_quad_grid(&g, v3(-HALF_X, 0, -HALF_Z), v3(HALF_X, 0, -HALF_Z), v3(HALF_X, HEIGHT, -HALF_Z),
                  v3(-HALF_X, HEIGHT, -HALF_Z), v3(0, 0, 1), 28, 10);
    gkb_quad_grid(&g, v3(-HALF_X, 0, HALF_Z), v3(HALF_X, 0, HALF_Z), v3(HALF_X, HEIGHT, HALF_Z),
                  v3(-HALF_X, HEIGHT, HALF_Z), v3(0, 0, -1), 28, 10);
    gkb_quad_grid(&g, v3(-HALF_X, 0, -HALF_Z), v3(-HALF_X, 0, HALF_Z), v3(-HALF_X, HEIGHT, HALF_Z),
                  v3(-HALF_X, HEIGHT, -HALF_Z), v3(1, 0, 0), 14, 10);
    gkb_quad_grid(&g, v3(HALF_X, 0, -HALF_Z), v3(HALF_X, 0, HALF_Z), v3(HALF_X, HEIGHT, HALF_Z),
                  v3(HALF_X, HEIGHT, -HALF_Z), v3(-1, 0, 0), 14, 10);
    for (int s = -1; s <= 1; s += 2) {
        float z0 = s < 0 ? -HALF_Z : ARCADE_Z - 0.25f, z1 = s < 0 ? -ARCADE_Z + 0.25f : HALF_Z;
        gkb_box(&g, v3(-HALF_X, SLAB1, z0), v3(HALF_X, SLAB1 + 0.4f, z1), false);
        gkb_box(&g, v3(-HALF_X, SLAB2, z0), v3(HALF_X, SLAB2 + 0.4f, z1), false);
    }
    gkb_object(d, "walls", &g, ms);
    /* instanced pieces: ground and upper columns, ground and upper arch bays */
    column(&g, 0.25f, 0, 3.5f, 0.32f);
    int col1 = gkw_add_mesh(d, "column-ground", &g, ms);
    gkb_free(&g);
    column(&g, 0.2f, SLAB1 + 0.4f, 7.9f, 0.26f);
    int col2 = gkw_add_mesh(d, "column-upper", &g, ms);
    gkb_free(&g);
    arch_bay(&g, BAY, 0.88f, 3.5f, SLAB1, 0.5f, 32);
    int arch1 = gkw_add_mesh(d, "arch-ground", &g, ms);
    gkb_free(&g);
    arch_bay(&g, BAY, 0.94f, 7.9f, SLAB2, 0.4f, 32);
    int arch2 = gkw_add_mesh(d, "arch-upper", &g, ms);
    gkb_free(&g);
    quat id = {0, 0, 0, 1};
    char name[32];
    for (int s = -1; s <= 1; s += 2)
        for (int i = 0; i <= N_BAYS; i++) {
            float x = -0.5f * BAY * N_BAYS + BAY * (float)i;
            snprintf(name, sizeof name, "column-%c%d", s < 0 ? 'n' : 's', i);
            instance(d, name, col1, v3(x, 0, s * ARCADE_Z), id);
            snprintf(name, sizeof name, "column-up-%c%d", s < 0 ? 'n' : 's', i);
            instance(d, name, col2, v3(x, 0, s * ARCADE_Z), id);
            if (i == N_BAYS)
                continue;
            snprintf(name, sizeof name, "arch-%c%d", s < 0 ? 'n' : 's', i);
            instance(d, name, arch1, v3(x + 0.5f * BAY, 0, s * ARCADE_Z), id);
            snprintf(name, sizeof name, "arch-up-%c%d", s < 0 ? 'n' : 's', i);
            instance(d, name, arch2, v3(x + 0.5f * BAY, 0, s * ARCADE_Z), id);
        }
    /* eight drapes hanging in front of the upper arcade, facing the courtyard */
    for (int k = 0; k < 8; k++) {
        int s = k < 4 ? -1 : 1, bay = 1 + 2 * (k % 4) + (s > 0);
        float x = -0.5f * BAY * N_BAYS + BAY * ((float)bay + 0.5f);
        drape(&g, 1.7f, 3.4f, 8.6f, 0.9f * (float)k);
        snprintf(name, sizeof name, "drape-%d", k);
        int mesh = gkw_add_mesh(d, name, &g, mc[k % 3]);
        gkb_free(&g);
        instance(d, name, mesh, v3(x, 0, s * (ARCADE_Z - 0.45f)),
                 s < 0 ? id : gkb_axis_angle(v3(0, 1, 0), (float)M_PI));
    }
    /* sun: 2000 lux, 0.00465 rad angular radius (the real sun's), from high up and to the side */
    gkw_light sun = {"sun", "directional", {1, 0.95, 0.88}, 2000.0, 0, 0, 0.00465, {0, 0}};
    gkb_light_node(d, &sun, v3(0, 20, 0), v3(-0.45f, -1.0f, -0.35f), v3(0, 1, 0));
    gkw_light lamp = {"lamp-north", "point", {1, 0.75, 0.5}, 800.0, 0, 0, 0.05, {0, 0}};
    gkb_light_node(d, &lamp, v3(-6, 3.0f, -5), v3(0, -1, 0), v3(0, 0, -1));
    lamp.name = "lamp-south";
    gkb_light_node(d, &lamp, v3(6, 3.0f, 5), v3(0, -1, 0), v3(0, 0, -1));
    gkb_camera_node(d, v3(-12.5f, 1.7f, 0.8f), v3(4, 3.2f, 0), 60.0 * M_PI / 180.0, 0.1, 100.0);
    int rc = gkw_write(d, dir, e);
    gkw_free(d);
    return rc;
}
