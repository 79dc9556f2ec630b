/* env-studio: a few objects on a floor lit by an environment alone (001 ch. 5 §5.3.2, research
 * dong-001.md §3.5: an environment map split into area lights, each shadowed with CSSM; the thesis
 * shows the Buddha under an environment, Fig. 5.10). The environment is the procedural studio map
 * (environment.h: a sun-less gradient sky over a grey ground, a bright key panel, a bluish fill and a
 * top panel; no download), written next to the scene as env-studio.exr (256 x 128, 1.4 degrees a
 * pixel) and referenced through extras.gikiosk.environment. The scene has no light node: every bit
 * of light comes from the map. Materials are Lambertian (specularFactor 0), so what the
 * rasterizer's error against the reference measures is the environment's split, its shadows and
 * the residual's ambient, not the glossy lobe. Objects: a 6 x 6 m light grey floor, a white
 * sphere (r 0.5 m), a red box and a small blue sphere, each casting shadows of the key panel and
 * contact shadows of the sky. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "io/image_io.h"
#include "scene/build_geom.h"
#include "scene/environment.h"

#define ENV_HEIGHT 128

static gkw_material lambert(const char *name, double r, double g, double b)
{
    return (gkw_material){.name = name, .base = {r, g, b, 1}, .metallic = 0, .roughness = 1, .with_specular = true,
                          .specular = 0, .specular_color = {1, 1, 1}};
}

static int write_environment(const char *dir, gk_err *e)
{
    gk_image img = {0};
    if (gk_image_alloc(&img, 2 * ENV_HEIGHT, ENV_HEIGHT, 3) != 0)
        return gk_fail(e, GK_ERUNTIME, "env-studio: out of memory for the environment map");
    gk_env_studio_pixels(img.pixels, ENV_HEIGHT);
    char path[1024];
    snprintf(path, sizeof path, "%s/env-studio.exr", dir);
    /* a fixed DateTime: OpenImageIO stamps the time of writing otherwise, and `make scenes` must
       write the committed bytes again (tests/e2e/scenes.sh) */
    gk_image_meta meta = {.count = 2,
                          .keys = {"gikiosk:environment", "DateTime"},
                          .values = {"procedural studio (app/scene/environment.c), lat-long, row 0 = +Y",
                                     "2026:01:01 00:00:00"}};
    int rc = gk_image_write_float(path, &img, &meta, e);
    gk_image_free(&img);
    return rc;
}

int gk_build_env_studio(const char *dir, gk_err *e)
{
    if (write_environment(dir, e) != 0)
        return -1;
    gkw_doc *d = gkw_new("env-studio");
    gkw_description(d,
                    "A white sphere, a red box and a blue ball on a floor, lit only by an HDR studio environment "
                    "(procedural, env-studio.exr: gradient sky and three soft panels). Seed 001 ch. 5: the "
                    "environment split into area lights, each shadowed with CSSM.",
                    NULL);
    gkw_environment(d, "env-studio.exr", 1.0);
    gkw_material f = lambert("floor", 0.6, 0.6, 0.6), w = lambert("white", 0.8, 0.8, 0.8),
                 r = lambert("red", 0.7, 0.12, 0.1), b = lambert("blue", 0.12, 0.2, 0.7);
    int mfloor = gkw_add_material(d, &f), mw = gkw_add_material(d, &w), mr = gkw_add_material(d, &r),
        mb = gkw_add_material(d, &b);
    gkw_geom g = {0};
    gkb_quad(&g, v3(-3, 0, -3), v3(3, 0, -3), v3(3, 0, 3), v3(-3, 0, 3), v3(0, 1, 0));
    gkb_object(d, "floor", &g, mfloor);
    gkb_sphere(&g, v3(0, 0.5f, 0.3f), 0.5f, 48, 24);
    gkb_object(d, "white-sphere", &g, mw);
    gkb_box(&g, v3(-1.5f, 0, -0.2f), v3(-0.8f, 0.7f, 0.5f), false);
    gkb_object(d, "red-box", &g, mr);
    gkb_sphere(&g, v3(1.0f, 0.25f, -0.4f), 0.25f, 32, 16);
    gkb_object(d, "blue-ball", &g, mb);
    /* From the -Z side, where the key panel (azimuth 35 degrees from -Z) lights the faces we see. */
    gkb_camera_node(d, v3(0.6f, 1.6f, -4.0f), v3(-0.1f, 0.35f, 0.0f), 45.0 * M_PI / 180.0, 0.05, 50.0);
    int rc = gkw_write(d, dir, e);
    gkw_free(d);
    return rc;
}
