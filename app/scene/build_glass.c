/* glass: seed 002's Fig. 1d stand-in ("caustics, refractions"; vct-003-grid-photon-002.md B.4.1): a
 * Cornell-like box (0.555 m, white floor, ceiling and back wall, red left and green right wall, all
 * Lambertian, the Cornell box's albedos) with a clear glass sphere (KHR_materials_transmission 1,
 * KHR_materials_ior 1.5, radius 0.1 m, 64 x 32 smooth-normal UV sphere: 3,968 triangles; the seed's
 * scene has 33.0k, a count that only matters for rasterising cost) on the floor and one small point
 * lamp under the ceiling, off to the back left, so the refraction caustic (light -> glass -> glass ->
 * floor) lands on the floor right of and in front of the sphere's contact point, where the camera
 * (raised, looking down at the sphere) sees it. The lamp is a true point, as in caustic-ring: the
 * reference's light tracer then finds the caustic paths (a sphere lamp seen through glass would be
 * eye-path fireflies). */
#include <math.h>

#include "scene/build_geom.h"

#define BOX 0.555f
#define SPHERE_R 0.1f
#define SPHERE_X 0.30f
#define SPHERE_Z 0.30f
#define LAMP_CD 2.0 /* cd: about 8 lux on the floor 0.5 m below, Cornell-box brightness */

static gkw_material lambert(const char *name, double r, double g, double b)
{
    return (gkw_material){.name = name, .base = {r, g, b, 1}, .metallic = 0, .roughness = 1, .with_specular = true,
                          .specular = 0, .specular_color = {1, 1, 1}};
}

int gk_build_glass(const char *dir, gk_err *e)
{
    gkw_doc *d = gkw_new("glass");
    gkw_description(d,
                    "Seed 002's Fig. 1d: a Cornell-like box with a clear glass sphere (transmission 1, ior 1.5) "
                    "on the floor, lit by one point lamp under the ceiling; the sphere focuses a refraction "
                    "caustic onto the floor. Tests glass in the path tracer and caustic methods (lgv, ispm).",
                    NULL);
    gkw_material white = lambert("white", 0.725, 0.71, 0.68), red = lambert("red", 0.63, 0.065, 0.05),
                 green = lambert("green", 0.14, 0.45, 0.091);
    gkw_material glass = {.name = "glass", .base = {1, 1, 1, 1}, .metallic = 0, .roughness = 0, .transmission = 1,
                          .ior = 1.5};
    int mw = gkw_add_material(d, &white), mr = gkw_add_material(d, &red), mg = gkw_add_material(d, &green);
    int mglass = gkw_add_material(d, &glass);
    const float B = BOX;
    gkw_geom g = {0};
    gkb_quad(&g, v3(0, 0, 0), v3(B, 0, 0), v3(B, 0, B), v3(0, 0, B), v3(0, 1, 0));
    gkb_object(d, "floor", &g, mw);
    gkb_quad(&g, v3(0, B, 0), v3(B, B, 0), v3(B, B, B), v3(0, B, B), v3(0, -1, 0));
    gkb_object(d, "ceiling", &g, mw);
    gkb_quad(&g, v3(0, 0, B), v3(B, 0, B), v3(B, B, B), v3(0, B, B), v3(0, 0, -1));
    gkb_object(d, "back", &g, mw);
    gkb_quad(&g, v3(B, 0, 0), v3(B, 0, B), v3(B, B, B), v3(B, B, 0), v3(-1, 0, 0));
    gkb_object(d, "left-red", &g, mr);
    gkb_quad(&g, v3(0, 0, 0), v3(0, 0, B), v3(0, B, B), v3(0, B, 0), v3(1, 0, 0));
    gkb_object(d, "right-green", &g, mg);
    vec3 centre = v3(SPHERE_X, SPHERE_R, SPHERE_Z);
    gkb_sphere(&g, centre, SPHERE_R, 64, 32);
    gkb_object(d, "glass-sphere", &g, mglass);
    vec3 lamp = v3(0.45f, 0.50f, 0.44f);
    gkw_light l = {.name = "lamp", .type = "point", .color = {1, 1, 1}, .intensity = LAMP_CD};
    gkb_light_node(d, &l, lamp, v3(0, -1, 0), v3(0, 0, 1));
    /* The camera stands in the open front, raised, looking down at the sphere. */
    gkb_camera_node(d, v3(0.278f, 0.42f, -0.55f), v3(0.278f, 0.08f, 0.30f), 40.0 * M_PI / 180.0, 0.02, 10.0);
    double v[4] = {centre.x, centre.y, centre.z, SPHERE_R};
    gkw_param(d, "sphere", 4, v);
    v[0] = lamp.x, v[1] = lamp.y, v[2] = lamp.z;
    gkw_param(d, "light_position", 3, v);
    int rc = gkw_write(d, dir, e);
    gkw_free(d);
    return rc;
}
