/* A scene's distant environment (gk_environment in scene.h): the lat-long mapping both renderers
 * use, lookups, loading the map a scene names, and the procedural studio map (a sun-less gradient
 * sky over a grey ground with a few soft bright panels) that env-studio writes next to itself and
 * the default studio builds in.
 *
 * Lat-long layout (binding; scene.h): width W = 2 H; pixel (i, j) covers
 *   theta in [pi j / H, pi (j + 1) / H]     (polar angle from +Y: row 0 looks straight up)
 *   phi   in [2 pi i / W, 2 pi (i + 1) / W] (azimuth from -Z towards +X)
 * direction d = (sin theta sin phi, cos theta, -sin theta cos phi). Radiance is constant over a
 * pixel (nearest lookup), so the tracer's piecewise-constant importance sampling is exact for it
 * and the rasterizer's split sums the same pixels. */
#ifndef GK_ENVIRONMENT_H
#define GK_ENVIRONMENT_H

#include "scene.h"

/* Height of the built-in procedural map (the default studio): 64 rows x 128 columns, 2.8 degrees a
 * pixel, finer than any feature of the map (the panels are at least 20 degrees wide). */
#define GK_ENV_STUDIO_HEIGHT 64

/* The largest map accepted: 4096 x 2048 (96 MiB as float RGB, 0.09 degrees a pixel). The loader
   splits it on the CPU and the renderer uploads it (halved until GL_MAX_TEXTURE_SIZE admits it). */
#define GK_ENV_MAX_WIDTH 4096

/* Direction through lat-long coordinates u, v in [0, 1] (v = 0 up). */
vec3 gk_env_dir(float u, float v);
/* Lat-long coordinates of a unit direction, u in [0, 1), v in [0, 1]. */
void gk_env_uv(vec3 d, float *u, float *v);
/* Pixel column/row of a direction. */
void gk_env_pixel(const gk_environment *env, vec3 d, int *i, int *j);
/* Radiance (intensity applied) along the escaping direction d; 0 without an environment. */
vec3 gk_env_radiance(const gk_environment *env, vec3 d);
/* Solid angle of a pixel of row j. */
float gk_env_pixel_solid_angle(const gk_environment *env, int j);

/* Reads the map env->uri (relative to base_dir, confined to it) and multiplies it by
 * env->intensity. Refuses, naming scene_path and the key: a missing or unreadable file, a layout
 * that is not lat-long (width != 2 height, fewer than 8 x 4 pixels, fewer than 3 channels), one
 * wider than GK_ENV_MAX_WIDTH, and
 * negative, NaN or infinite radiance. GK_EINPUT on bad input. */
int gk_env_load(gk_environment *env, const char *scene_path, const char *base_dir, gk_err *e);

/* Fills rgb (2h x h x 3 floats) with the procedural studio map, radiance in nits at intensity 1. */
void gk_env_studio_pixels(float *rgb, int height);
/* env becomes the built-in studio map (uri "") at the given intensity. */
int gk_env_make_studio(gk_environment *env, int height, float intensity, gk_err *e);

/* Frees the map and the split's tables (the split's lights live in the scene's light list). */
void gk_env_free(gk_environment *env);

#endif
