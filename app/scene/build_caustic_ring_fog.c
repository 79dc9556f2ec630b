/* caustic-ring-fog: seed 001 ch. 8's ring in fog (research dong-001.md §6.7, "Ring": one-bounce
 * reflection). The caustic-ring room and mirror ring (build_caustic_ring.c: inner radius 0.5 m,
 * height 0.4 m, 32 segments), lit by a spot instead of a point lamp, in a layer of ground fog that
 * fills the room up to 1 m (the camera at 1.6 m looks down into it from above).
 *
 * The spot, 3 m away at 20° elevation, covers the ring (outer cone 14°, the ring subtends 10°): its
 * beam through the fog is the airlight term with the ring's volumetric shadow; the far inner wall
 * reflects it down into the ring, where the reflected rays cross the fog (the volume caustic) and
 * focus into the cardioid on the floor (the surface caustic).
 *
 * The fog layer stops below the camera on purpose: a light-traced volume caustic near the pinhole
 * has a pixel value growing as 1/distance (app/ref/lighttrace.c), so a reference with the camera
 * inside the fog would need far more photons for the same noise floor. Coefficients: sigma_s
 * 0.25 /m, sigma_a 0.02 /m (albedo 0.93, optical depth 0.27 per metre, ~2 across the room), HG
 * g = 0.3 (mild forward scattering, within the seed's -0.7..0.7). */
#include <math.h>

#include "scene/build_geom.h"

#define R_INNER 0.5f
#define R_THICK 0.02f
#define R_HEIGHT 0.4f
#define R_SEGMENTS 32
#define LIGHT_ELEVATION_DEG 20.0
#define LIGHT_DISTANCE 3.0
#define FOG_TOP 1.0

int gk_build_caustic_ring_fog(const char *dir, gk_err *e)
{
    gkw_doc *d = gkw_new("caustic-ring-fog");
    gkw_description(d,
                    "Seed 001's ring in fog: the caustic ring's gold mirror ring lit by a spot through a 1 m layer "
                    "of ground fog (sigma_s 0.25/m, sigma_a 0.02/m, g 0.3). The far inner wall reflects the "
                    "beam down through the fog: a volume caustic above the cardioid on the floor. Tests "
                    "volcaustics and the media of the path tracer.",
                    /* the other methods ignore the medium (README, Participating media): offering them
                       here would show clear air */
                    "volcaustics");
    gkw_material room = {.name = "room", .base = {0.75, 0.75, 0.75, 1}, .metallic = 0, .roughness = 1};
    gkw_material gold = {.name = "mirror-gold", .base = {0.95, 0.9, 0.6, 1}, .metallic = 1, .roughness = 0};
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
    gkw_light l = {.name = "spot",
                   .type = "spot",
                   .color = {1, 1, 1},
                   .intensity = 100.0,
                   .inner_cone = 10.0 * M_PI / 180.0,
                   .outer_cone = 14.0 * M_PI / 180.0};
    /* aimed at the ring's centre, 0.2 m up (the middle of the lit inner wall) */
    gkb_light_node(d, &l, pos, v3_sub(v3(0, 0.2f, 0), pos), v3(0, 1, 0));
    gkb_camera_node(d, v3(0, 1.6f, 1.6f), v3(0, 0.05f, 0), 50.0 * M_PI / 180.0, 0.05, 30.0);
    const double sigma_s[3] = {0.25, 0.25, 0.25}, sigma_a[3] = {0.02, 0.02, 0.02};
    gkw_medium(d, sigma_s, sigma_a, 0.3);
    const double lo[3] = {-X, 0, -X}, hi[3] = {X, FOG_TOP, X};
    gkw_medium_bounds(d, lo, hi);
    double v[4] = {R_INNER, R_HEIGHT, R_THICK, 0};
    gkw_param(d, "ring", 3, v);
    v[0] = pos.x, v[1] = pos.y, v[2] = pos.z;
    gkw_param(d, "light_position", 3, v);
    int rc = gkw_write(d, dir, e);
    gkw_free(d);
    return rc;
}
