/* glass-fog: seed 001 ch. 8's refractive object in fog (research dong-001.md §6.7, "Buddha": two
 * refractions), with two caustic lights (§6.6, "# lights"). A clear glass ball (KHR_materials_
 * transmission 1, ior 1.5, radius 0.25 m, 64 x 32 UV sphere) hangs 1.9 m above the floor of a
 * 8 x 3 x 8 m grey room, above a block of fog (4 x 1.6 x 4 m, the caustic-ring-fog medium:
 * sigma_s 0.25 /m, sigma_a 0.02 /m, HG g 0.3). Two spots 1 m from the ball's centre light it:
 *   spot-a straight from above; the ball (a lens of focal length n R / 2 (n - 1) = 0.375 m from its
 *     centre) images the spot 0.6 m below the centre (1/v = 1/f - 1/u, u = 1 m), at y = 1.3, inside
 *     the fog: a bright cone converging from the ball's lower face and diverging to the floor;
 *   spot-b 30 degrees off the vertical, the same intensity: a second, slanted cone;
 * each spot's outer cone (18 degrees) covers the ball (it subtends 14.5 degrees), so a ring of
 * direct light around the ball's shadow crosses the fog too (airlight with a volumetric shadow).
 * The ball stays above the fog on purpose: the real-time method and the reference then agree that
 * no fog lies inside the glass, and the volume caustic is only where the seed puts it, after the
 * second refraction. The camera stands outside the fog block (a light-traced volume caustic near
 * the pinhole is noisy, see build_caustic_ring_fog.c), looking at both cones side on. */
#include <math.h>

#include "scene/build_geom.h"

#define ROOM_X 4.0f
#define ROOM_Y 3.0f
#define BALL_R 0.25f
#define BALL_Y 1.9f
#define FOG_X 2.0
#define FOG_TOP 1.6
#define SPOT_DISTANCE 1.0
#define SPOT_B_TILT_DEG 30.0
#define SPOT_CD 30.0

int gk_build_glass_fog(const char *dir, gk_err *e)
{
    gkw_doc *d = gkw_new("glass-fog");
    gkw_description(d,
                    "Seed 001's refractive object in fog: a clear glass ball (ior 1.5) hanging above a block of "
                    "fog (sigma_s 0.25/m, sigma_a 0.02/m, g 0.3), lit by two spots; it focuses each into a bright "
                    "volumetric cone through the fog (two refractions). Tests volcaustics with glass and several "
                    "caustic lights.",
                    /* the other methods ignore the medium (README, Participating media) */
                    "volcaustics");
    gkw_material room = {.name = "room", .base = {0.75, 0.75, 0.75, 1}, .metallic = 0, .roughness = 1};
    gkw_material glass = {.name = "glass", .base = {1, 1, 1, 1}, .metallic = 0, .roughness = 0, .transmission = 1,
                          .ior = 1.5};
    int mroom = gkw_add_material(d, &room), mglass = gkw_add_material(d, &glass);
    gkw_geom g = {0};
    const float X = ROOM_X, Y = ROOM_Y;
    gkb_box(&g, v3(-X, 0, -X), v3(X, Y, X), true);
    gkb_object(d, "room", &g, mroom);
    vec3 centre = v3(0, BALL_Y, 0);
    gkb_sphere(&g, centre, BALL_R, 64, 32);
    gkb_object(d, "glass-ball", &g, mglass);
    gkw_light l = {.name = "spot-a",
                   .type = "spot",
                   .color = {1, 1, 1},
                   .intensity = SPOT_CD,
                   .inner_cone = 15.0 * M_PI / 180.0,
                   .outer_cone = 18.0 * M_PI / 180.0};
    vec3 pa = v3_add(centre, v3(0, (float)SPOT_DISTANCE, 0));
    gkb_light_node(d, &l, pa, v3(0, -1, 0), v3(0, 0, 1));
    double tilt = SPOT_B_TILT_DEG * M_PI / 180.0;
    vec3 pb = v3_add(centre, v3((float)(-SPOT_DISTANCE * sin(tilt)), (float)(SPOT_DISTANCE * cos(tilt)), 0));
    l.name = "spot-b";
    gkb_light_node(d, &l, pb, v3_sub(centre, pb), v3(0, 1, 0));
    gkb_camera_node(d, v3(0.3f, 1.1f, 3.4f), v3(0.3f, 1.0f, 0), 50.0 * M_PI / 180.0, 0.05, 30.0);
    const double sigma_s[3] = {0.25, 0.25, 0.25}, sigma_a[3] = {0.02, 0.02, 0.02};
    gkw_medium(d, sigma_s, sigma_a, 0.3);
    const double lo[3] = {-FOG_X, 0, -FOG_X}, hi[3] = {FOG_X, FOG_TOP, FOG_X};
    gkw_medium_bounds(d, lo, hi);
    double v[4] = {centre.x, centre.y, centre.z, BALL_R};
    gkw_param(d, "sphere", 4, v);
    v[0] = pa.x, v[1] = pa.y, v[2] = pa.z;
    gkw_param(d, "light_position", 3, v);
    int rc = gkw_write(d, dir, e);
    gkw_free(d);
    return rc;
}
