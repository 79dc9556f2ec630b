/* The Cornell box scenes: `cornell` (the measured box with its ceiling light), `cornell-spot` (the
 * box lit by a spotlight aimed at a corner, so most light is indirect: Dong's D6-1 / T5) and
 * `cornell-spot-anim` (the spot sweeping the room on an 8 s loop: T5m).
 *
 * Geometry and camera are the Cornell University Program of Computer Graphics' measured data
 * (www.graphics.cornell.edu/online/box/data.html), given there in millimetres and converted to
 * metres here: camera at (278, 273, -800) looking +z, 35 mm focal length and 25 mm film, so
 * yfov = 2 atan(12.5 / 35) = 39.31 degrees.
 *
 * Albedos: the box's measured reflectance spectra (400-700 nm) integrated against the CIE 1931 2°
 * colour matching functions under an equal-energy illuminant give XYZ, normalised so that a
 * perfect reflector has Y = 1, then converted with the XYZ -> linear sRGB (D65) matrix. The values
 * are the ones commonly used in renderers that reproduce the box: white (0.725, 0.71, 0.68),
 * red (0.63, 0.065, 0.05), green (0.14, 0.45, 0.091). */
#include <math.h>

#include "scene/build_geom.h"

#define MM(x) ((float)(x) * 0.001f)
static vec3 P(double x, double y, double z) { return v3(MM(x), MM(y), MM(z)); }

static const vec3 room_centre_mm = {278.0f, 274.4f, 279.6f};

/* A quad of the measured data facing the inside of the room. */
static void wall(gkw_geom *g, vec3 a, vec3 b, vec3 c, vec3 d)
{
    vec3 mid = v3_scale(v3_add(v3_add(a, b), v3_add(c, d)), 0.25f);
    gkb_quad(g, a, b, c, d, v3_sub(v3_scale(room_centre_mm, 0.001f), mid));
}

/* A block of the measured data: top quad plus four sides, all facing away from its centre. */
static void block(gkw_geom *g, const float top[4][3], float height_mm)
{
    vec3 t[4], b[4], centre = v3(0, 0, 0);
    for (int i = 0; i < 4; i++) {
        t[i] = P(top[i][0], height_mm, top[i][2]);
        b[i] = P(top[i][0], 0, top[i][2]);
        centre = v3_add(centre, v3_scale(v3_add(t[i], b[i]), 0.125f));
    }
    gkb_quad(g, t[0], t[1], t[2], t[3], v3(0, 1, 0));
    for (int i = 0; i < 4; i++) {
        int j = (i + 1) % 4;
        vec3 mid = v3_scale(v3_add(t[i], b[j]), 0.5f);
        gkb_quad(g, b[i], b[j], t[j], t[i], v3_sub(mid, centre));
    }
}

/* Lambertian (KHR_materials_specular specularFactor 0): the measured box is a set of diffuse
   reflectance spectra, with no specular lobe. */
static const gkw_material white = {"white", {0.725, 0.71, 0.68, 1}, 0, 1, {0, 0, 0}, 0, 0, 0, false, false, NULL,
                                    true, 0, {1, 1, 1}};
static const gkw_material red = {"red", {0.63, 0.065, 0.05, 1}, 0, 1, {0, 0, 0}, 0, 0, 0, false, false, NULL,
                                  true, 0, {1, 1, 1}};
static const gkw_material green = {"green", {0.14, 0.45, 0.091, 1}, 0, 1, {0, 0, 0}, 0, 0, 0, false, false, NULL,
                                    true, 0, {1, 1, 1}};

/* The room (walls, floor, ceiling) and optionally the two blocks, as in the measured data. */
static void add_box(gkw_doc *d, bool blocks)
{
    int mw = gkw_add_material(d, &white), mr = gkw_add_material(d, &red), mg = gkw_add_material(d, &green);
    gkw_geom g = {0};
    wall(&g, P(552.8, 0, 0), P(0, 0, 0), P(0, 0, 559.2), P(549.6, 0, 559.2));
    gkb_object(d, "floor", &g, mw);
    wall(&g, P(556.0, 548.8, 0), P(556.0, 548.8, 559.2), P(0, 548.8, 559.2), P(0, 548.8, 0));
    gkb_object(d, "ceiling", &g, mw);
    wall(&g, P(549.6, 0, 559.2), P(0, 0, 559.2), P(0, 548.8, 559.2), P(556.0, 548.8, 559.2));
    gkb_object(d, "back", &g, mw);
    wall(&g, P(0, 0, 559.2), P(0, 0, 0), P(0, 548.8, 0), P(0, 548.8, 559.2));
    gkb_object(d, "right-green", &g, mg);
    wall(&g, P(552.8, 0, 0), P(549.6, 0, 559.2), P(556.0, 548.8, 559.2), P(556.0, 548.8, 0));
    gkb_object(d, "left-red", &g, mr);
    if (!blocks)
        return;
    static const float short_top[4][3] = {{130, 165, 65}, {82, 165, 225}, {240, 165, 272}, {290, 165, 114}};
    static const float tall_top[4][3] = {{423, 330, 247}, {265, 330, 296}, {314, 330, 456}, {472, 330, 406}};
    block(&g, short_top, 165);
    gkb_object(d, "short-block", &g, mw);
    block(&g, tall_top, 330);
    gkb_object(d, "tall-block", &g, mw);
}

static void add_camera(gkw_doc *d)
{
    double yfov = 2.0 * atan(12.5 / 35.0);
    gkb_camera_node(d, P(278, 273, -800), P(278, 273, 0), yfov, 0.05, 20.0);
}

/* Radiance of the ceiling light (nits). The measured light is warm; the usual RGB rendition of
 * its emission is about (17, 12, 4); we keep it white at the same 17 nits so that colour bleeding
 * comes only from the walls. */
#define CEILING_RADIANCE 17.0
#define LIGHT_W 0.130 /* x from 213 to 343 mm */
#define LIGHT_H 0.105 /* z from 227 to 332 mm */

int gk_build_cornell(const char *dir, gk_err *e)
{
    gkw_doc *d = gkw_new("cornell");
    gkw_description(d,
                    "The Cornell box (measured geometry and camera, albedos from the measured spectra) lit by its "
                    "0.13 x 0.105 m ceiling light as a rectangular area light of 17 nits. Tests diffuse "
                    "interreflection and colour bleeding (vct, vpl, lightmap) and soft shadows against the path "
                    "tracer.",
                    NULL);
    add_box(d, true);
    add_camera(d);
    /* The emitter sits 0.1 mm under the ceiling so its face never fights the ceiling's depth. */
    const float y = 0.5487f;
    gkw_light l = {"ceiling-light", "point", {1, 1, 1}, CEILING_RADIANCE * LIGHT_W * LIGHT_H, 0, 0, 0,
                   {LIGHT_W, LIGHT_H}};
    gkb_light_node(d, &l, v3(0.278f, y, 0.2795f), v3(0, -1, 0), v3(0, 0, 1));
    gkw_material proxy = {"light", {0, 0, 0, 1}, 0, 1, {1, 1, 1}, CEILING_RADIANCE, 0, 0, false, true, NULL, false, 0, {0, 0, 0}};
    gkw_geom g = {0};
    gkb_quad(&g, v3(0.213f, y, 0.227f), v3(0.343f, y, 0.227f), v3(0.343f, y, 0.332f), v3(0.213f, y, 0.332f),
             v3(0, -1, 0));
    gkb_object(d, "light-proxy", &g, gkw_add_material(d, &proxy));
    double params[2] = {LIGHT_W, LIGHT_H};
    gkw_param(d, "light_size", 2, params);
    params[0] = CEILING_RADIANCE;
    gkw_param(d, "light_radiance", 1, params);
    int rc = gkw_write(d, dir, e);
    gkw_free(d);
    return rc;
}

/* The spot of D6-1 / T5: near the top front of the box, aimed at the bottom back corner of the
 * red wall, 30° cone (outer half-angle 15°): almost all of the light that reaches the camera has
 * bounced at least once. 20 cd gives ~35 lux where the spot lands. */
static const vec3 spot_pos = {0.278f, 0.52f, 0.056f};
static const vec3 corner = {0.5528f, 0.0f, 0.5592f};
static const gkw_light spot = {"spot", "spot", {1, 1, 1}, 20.0, 12.0 * M_PI / 180.0, 15.0 * M_PI / 180.0, 0, {0, 0}};

static int build_spot(const char *name, bool animated, const char *dir, gk_err *e)
{
    gkw_doc *d = gkw_new(name);
    gkw_description(d,
                    animated ? "The Cornell box lit only by a spotlight near the ceiling that sweeps corner -> red "
                               "wall -> back wall -> corner on an 8 s loop (Dong T5m): mostly indirect light that "
                               "moves; tests VPL/VAL temporal stability (vpl, vct)."
                             : "The Cornell box lit only by a spotlight aimed at the bottom back corner of the red "
                               "wall (Dong D6-1/T5): most of the light is indirect; tests one-bounce GI (vpl, vct, "
                               "lightmap).",
                    NULL);
    add_box(d, true);
    add_camera(d);
    int node = gkb_light_node(d, &spot, spot_pos, v3_sub(corner, spot_pos), v3(0, 1, 0));
    if (animated) {
        const vec3 targets[4] = {corner, v3(0.556f, 0.274f, 0.28f), v3(0.278f, 0.30f, 0.5592f), corner};
        float times[4] = {0.0f, 8.0f / 3.0f, 16.0f / 3.0f, 8.0f}, rot[16];
        for (int k = 0; k < 4; k++) {
            quat q = gkb_look_rotation(v3_sub(targets[k], spot_pos), v3(0, 1, 0));
            rot[4 * k] = q.x, rot[4 * k + 1] = q.y, rot[4 * k + 2] = q.z, rot[4 * k + 3] = q.w;
        }
        gkw_add_channel(d, node, "rotation", "LINEAR", 4, times, rot);
    }
    int rc = gkw_write(d, dir, e);
    gkw_free(d);
    return rc;
}

int gk_build_cornell_spot(const char *dir, gk_err *e) { return build_spot("cornell-spot", false, dir, e); }
int gk_build_cornell_spot_anim(const char *dir, gk_err *e) { return build_spot("cornell-spot-anim", true, dir, e); }
