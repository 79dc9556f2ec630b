/* caustic-ring: seed 000's "simple caustic ring" (photon-mapping-000-004.md, scene 1): a mirror
 * ring (inner radius 0.5 m, height 0.4 m, wall 2 cm, 32 segments: inner wall, outer wall and top
 * rim, 192 triangles) standing on the floor of a five-quad room open towards the camera (10
 * triangles): 202 triangles in all, as in the seed. A small light 3 m away at 20° elevation lights
 * the far inner wall (tan 20° < H / 2R = 0.4), whose reflection focuses into the cardioid caustic
 * on the floor inside the ring. */
#include <math.h>

#include "scene/build_geom.h"

#define R_INNER 0.5f
#define R_THICK 0.02f
#define R_HEIGHT 0.4f
#define R_SEGMENTS 32
#define LIGHT_ELEVATION_DEG 20.0
#define LIGHT_DISTANCE 3.0

int gk_build_caustic_ring(const char *dir, gk_err *e)
{
    gkw_doc *d = gkw_new("caustic-ring");
    gkw_description(d,
                    "Seed 000's caustic ring: a gold mirror ring (metallic 1, roughness 0) on a diffuse floor, lit "
                    "by a point light 3 m away at 20° elevation; the far inner wall focuses "
                    "the light into a cardioid caustic inside the ring. Tests caustic methods (ispm, lgv, "
                    "lightmap) and the caustic paths of the path tracer.",
                    NULL);
    gkw_material room = {"room", {0.75, 0.75, 0.75, 1}, 0, 1, {0, 0, 0}, 0, 0, 0, false, false, NULL, false, 0, {0, 0, 0}};
    gkw_material gold = {"mirror-gold", {0.95, 0.9, 0.6, 1}, 1, 0, {0, 0, 0}, 0, 0, 0, false, false, NULL, false, 0, {0, 0, 0}};
    int mroom = gkw_add_material(d, &room), mgold = gkw_add_material(d, &gold);
    gkw_geom g = {0};
    const float X = 4, Y = 3;
    gkb_quad(&g, v3(-X, 0, -X), v3(X, 0, -X), v3(X, 0, X), v3(-X, 0, X), v3(0, 1, 0));   /* floor */
    gkb_quad(&g, v3(-X, Y, -X), v3(X, Y, -X), v3(X, Y, X), v3(-X, Y, X), v3(0, -1, 0));  /* ceiling */
    gkb_quad(&g, v3(-X, 0, -X), v3(X, 0, -X), v3(X, Y, -X), v3(-X, Y, -X), v3(0, 0, 1)); /* back */
    gkb_quad(&g, v3(-X, 0, -X), v3(-X, 0, X), v3(-X, Y, X), v3(-X, Y, -X), v3(1, 0, 0)); /* left */
    gkb_quad(&g, v3(X, 0, -X), v3(X, 0, X), v3(X, Y, X), v3(X, Y, -X), v3(-1, 0, 0));    /* right */
    gkb_object(d, "room", &g, mroom);
    gkb_cylinder(&g, v3(0, 0, 0), R_INNER, 0, R_HEIGHT, R_SEGMENTS, 1, true);
    gkb_cylinder(&g, v3(0, 0, 0), R_INNER + R_THICK, 0, R_HEIGHT, R_SEGMENTS, 1, false);
    gkb_annulus(&g, v3(0, 0, 0), R_HEIGHT, R_INNER, R_INNER + R_THICK, R_SEGMENTS);
    gkb_object(d, "ring", &g, mgold);
    double el = LIGHT_ELEVATION_DEG * M_PI / 180.0;
    vec3 pos = v3((float)(-LIGHT_DISTANCE * cos(el)), (float)(LIGHT_DISTANCE * sin(el)), 0);
    /* A true point lamp, as in the seed: its caustic (light -> mirror -> floor -> eye) is then found by
       the reference's light tracer. A 2 cm sphere looked tidier but made the path-traced reference
       useless: eye paths reaching an 80,000-nit sphere through the mirror are rare fireflies, and
       the references' noise floor was 100% (caustics alone: 2000%). */
    gkw_light l = {"lamp", "point", {1, 1, 1}, 100.0, 0, 0, 0.0, {0, 0}};
    gkb_light_node(d, &l, pos, v3_scale(pos, -1), v3(0, 1, 0));
    gkb_camera_node(d, v3(0, 1.6f, 1.6f), v3(0, 0.05f, 0), 50.0 * M_PI / 180.0, 0.05, 30.0);
    double v[4] = {R_INNER, R_HEIGHT, R_THICK, 0};
    gkw_param(d, "ring", 3, v);
    v[0] = pos.x, v[1] = pos.y, v[2] = pos.z;
    gkw_param(d, "light_position", 3, v);
    int rc = gkw_write(d, dir, e);
    gkw_free(d);
    return rc;
}
