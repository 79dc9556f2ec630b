/* Scenes with analytic oracles and failure-mode scenes:
 *   shadow-planes, shadow-planes-stacked — Dong's T1/T2 (research/dong-001.md §9.2): a square
 *     occluder (or two) over a receiver plane under a square area light; the visibility is
 *     V = 1 - overlap / S^2 of the occluder's projection through the point onto the light plane;
 *   furnace — a closed box with uniform albedo a and emission Le: radiance is Le / (1 - a)
 *     everywhere (the energy oracle);
 *   light-leak — two rooms separated by a wall 1/200 of a room thick, a light in one room only:
 *     the other room is black in a correct render. */
#include <math.h>

#include "scene/build_geom.h"

static int finish(gkw_doc *d, const char *dir, gk_err *e)
{
    int rc = gkw_write(d, dir, e);
    gkw_free(d);
    return rc;
}

/* T1/T2 (dong-001.md §9.2): receiver y = 0, 10 x 10, Lambert 0.8; occluders 2 x 2, one-sided
 * black, facing the light; light: square of side S = 1 at y = 4 facing -y with unit radiance
 * (I = L S^2 = 1 cd); camera (0, 6, 6) looking at the origin, 60° field of view. */
#define T_LIGHT_SIZE 1.0
#define T_LIGHT_HEIGHT 4.0
#define T_OCCLUDER_SIZE 2.0
#define T_RECEIVER_SIZE 10.0
#define T_ALBEDO 0.8

static void occluder(gkw_doc *d, const char *name, vec3 c, int material)
{
    float h = (float)T_OCCLUDER_SIZE / 2;
    gkw_geom g = {0};
    gkb_quad(&g, v3(c.x - h, c.y, c.z - h), v3(c.x + h, c.y, c.z - h), v3(c.x + h, c.y, c.z + h),
             v3(c.x - h, c.y, c.z + h), v3(0, 1, 0));
    gkb_object(d, name, &g, material);
}

static int build_shadow(const char *name, bool stacked, const char *dir, gk_err *e)
{
    gkw_doc *d = gkw_new(name);
    gkw_description(d,
                    stacked ? "Dong T2 'stacked blockers': two 2 x 2 black occluders at y = 1 and y = 2 (offset "
                              "(1, 0, 0.5)) over a white receiver under a 1 x 1 area light at y = 4; analytic "
                              "visibility from the union of the projected squares. Tests non-planar blockers and VSM "
                              "light bleeding of the soft-shadow methods (direct light only: method none)."
                            : "Dong T1 'plane-over-plane': a 2 x 2 black occluder at y = 1 over a white receiver "
                              "under a 1 x 1 area light of unit radiance at y = 4; the visibility is analytic "
                              "(params). Tests soft-shadow exactness (VSSM, CSSM, PCSS) with method none.",
                    "none");
    gkw_material recv = {"receiver", {T_ALBEDO, T_ALBEDO, T_ALBEDO, 1}, 0, 1, {0, 0, 0}, 0, 0, 0, false, false, NULL, false, 0, {0, 0, 0}};
    gkw_material black = {"occluder", {0, 0, 0, 1}, 0, 1, {0, 0, 0}, 0, 0, 0, false, false, NULL, false, 0, {0, 0, 0}};
    int mr = gkw_add_material(d, &recv), mb = gkw_add_material(d, &black);
    float h = (float)T_RECEIVER_SIZE / 2;
    gkw_geom g = {0};
    gkb_quad(&g, v3(-h, 0, -h), v3(h, 0, -h), v3(h, 0, h), v3(-h, 0, h), v3(0, 1, 0));
    gkb_object(d, "receiver", &g, mr);
    occluder(d, "occluder", v3(0, 1, 0), mb);
    if (stacked)
        occluder(d, "occluder2", v3(1, 2, 0.5f), mb);
    gkw_light l = {"area-light", "point", {1, 1, 1}, T_LIGHT_SIZE * T_LIGHT_SIZE, 0, 0, 0, {T_LIGHT_SIZE, T_LIGHT_SIZE}};
    gkb_light_node(d, &l, v3(0, (float)T_LIGHT_HEIGHT, 0), v3(0, -1, 0), v3(0, 0, -1));
    gkb_camera_node(d, v3(0, 6, 6), v3(0, 0, 0), 60.0 * M_PI / 180.0, 0.1, 50.0);
    /* Fully lit receiver: E ~ L S^2 / h^2 = 1/16 lux, radiance 0.8/pi E ~ 0.016 nits; +3.5 EV puts it
     * near the display's mid grey. */
    gkw_exposure(d, 3.5);
    double v[3] = {T_LIGHT_SIZE};
    gkw_param(d, "light_size", 1, v);
    v[0] = T_LIGHT_HEIGHT;
    gkw_param(d, "light_height", 1, v);
    v[0] = 1.0;
    gkw_param(d, "light_radiance", 1, v);
    v[0] = T_OCCLUDER_SIZE;
    gkw_param(d, "occluder_size", 1, v);
    v[0] = 0, v[1] = 1, v[2] = 0;
    gkw_param(d, "occluder_center", 3, v);
    if (stacked) {
        v[0] = 1, v[1] = 2, v[2] = 0.5;
        gkw_param(d, "occluder2_center", 3, v);
    }
    v[0] = T_RECEIVER_SIZE;
    gkw_param(d, "receiver_size", 1, v);
    v[0] = T_ALBEDO;
    gkw_param(d, "receiver_albedo", 1, v);
    return finish(d, dir, e);
}

int gk_build_shadow_planes(const char *dir, gk_err *e) { return build_shadow("shadow-planes", false, dir, e); }
int gk_build_shadow_planes_stacked(const char *dir, gk_err *e)
{
    return build_shadow("shadow-planes-stacked", true, dir, e);
}

/* Furnace: the inside of a 2 m cube, each face a 4 x 4 grid (so vertex- and texel-based methods
 * have samples), albedo 0.5 and emission 1 nit everywhere: L = Le / (1 - a) = 2 nits. */
#define F_ALBEDO 0.5
#define F_EMISSION 1.0

int gk_build_furnace(const char *dir, gk_err *e)
{
    gkw_doc *d = gkw_new("furnace");
    gkw_description(d,
                    "White furnace: the closed inside of a 2 m cube, every surface with albedo 0.5 and emission "
                    "1 nit, camera inside. The exact radiance is Le / (1 - a) = 2 nits everywhere: the energy "
                    "conservation oracle of every GI method (none gives 1).",
                    NULL);
    gkw_material m = {"furnace", {F_ALBEDO, F_ALBEDO, F_ALBEDO, 1}, 0, 1, {F_EMISSION, F_EMISSION, F_EMISSION}, 0, 0, 0,
                      false, false, NULL, true, 0, {1, 1, 1}}; /* Lambertian: Le / (1 - a) needs albedo a */
    int mi = gkw_add_material(d, &m);
    gkw_geom g = {0};
    vec3 P[8];
    for (int i = 0; i < 8; i++)
        P[i] = v3(i & 1 ? 1.f : -1.f, i & 2 ? 1.f : -1.f, i & 4 ? 1.f : -1.f);
    static const int faces[6][4] = {{0, 2, 6, 4}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 5, 7, 6}};
    for (int f = 0; f < 6; f++) {
        vec3 a = P[faces[f][0]], b = P[faces[f][1]], c = P[faces[f][2]], dd = P[faces[f][3]];
        vec3 mid = v3_scale(v3_add(v3_add(a, b), v3_add(c, dd)), 0.25f);
        gkb_quad_grid(&g, a, b, c, dd, v3_scale(mid, -1), 4, 4); /* facing the centre */
    }
    gkb_object(d, "box", &g, mi);
    gkb_camera_node(d, v3(0, 0, 0.5f), v3(0, 0, -1), 60.0 * M_PI / 180.0, 0.01, 10.0);
    gkw_exposure(d, log2(0.18 / (F_EMISSION / (1 - F_ALBEDO))));
    double v[1] = {F_ALBEDO};
    gkw_param(d, "albedo", 1, v);
    v[0] = F_EMISSION;
    gkw_param(d, "emission", 1, v);
    v[0] = F_EMISSION / (1 - F_ALBEDO);
    gkw_param(d, "radiance", 1, v);
    return finish(d, dir, e);
}

/* Light leak: rooms x in [-4, -0.01] (lit) and [0.01, 4] (dark), 3 m high, 4 m deep; the wall
 * between them is 0.02 m thick (1/200 of a room's 4 m). */
#define L_WALL 0.01f

int gk_build_light_leak(const char *dir, gk_err *e)
{
    gkw_doc *d = gkw_new("light-leak");
    gkw_description(d,
                    "Two 4 x 3 x 4 m rooms separated by one wall 2 cm thick (1/200 of a room); a light in the "
                    "left room only, camera in the right room looking at the wall. The right room must be black; "
                    "any light there is leakage through the thin wall (voxel cone tracing, light propagation "
                    "grids, VPL clusters).",
                    NULL);
    gkw_material m = {"white", {0.8, 0.8, 0.8, 1}, 0, 1, {0, 0, 0}, 0, 0, 0, false, false, NULL, false, 0, {0, 0, 0}};
    int mi = gkw_add_material(d, &m);
    gkw_geom g = {0};
    gkb_box(&g, v3(-4, 0, -2), v3(4, 3, 2), true);
    gkb_object(d, "rooms", &g, mi);
    gkb_box(&g, v3(-L_WALL, 0, -2), v3(L_WALL, 3, 2), false);
    gkb_object(d, "thin-wall", &g, mi);
    gkw_light l = {"lamp", "point", {1, 0.9, 0.8}, 50.0, 0, 0, 0.1, {0, 0}};
    gkb_light_node(d, &l, v3(-2, 2.2f, 0), v3(0, -1, 0), v3(0, 0, -1));
    gkb_camera_node(d, v3(3.8f, 1.5f, 1.2f), v3(0, 1.2f, -0.6f), 70.0 * M_PI / 180.0, 0.05, 30.0);
    /* The lit room's walls are ~3 nits; -4 EV would show them mid grey, and shows a leak brightly. */
    gkw_exposure(d, -4.0);
    double v[2] = {-L_WALL, L_WALL};
    gkw_param(d, "wall_x", 2, v);
    v[0] = -4, v[1] = -L_WALL;
    gkw_param(d, "lit_room_x", 2, v);
    v[0] = L_WALL, v[1] = 4;
    gkw_param(d, "dark_room_x", 2, v);
    return finish(d, dir, e);
}
