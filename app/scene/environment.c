/* The scene environment: lat-long mapping, lookups, loading, the procedural studio map
 * (environment.h). */
#include "environment.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "base/confine.h"
#include "io/image_io.h"

vec3 gk_env_dir(float u, float v)
{
    float theta = (float)M_PI * v, phi = 2.0f * (float)M_PI * u;
    float st = sinf(theta);
    return v3(st * sinf(phi), cosf(theta), -st * cosf(phi));
}

void gk_env_uv(vec3 d, float *u, float *v)
{
    float phi = atan2f(d.x, -d.z);
    if (phi < 0.0f)
        phi += 2.0f * (float)M_PI;
    float y = d.y < -1.0f ? -1.0f : (d.y > 1.0f ? 1.0f : d.y);
    *u = phi / (2.0f * (float)M_PI);
    if (*u >= 1.0f)
        *u = 0.0f;
    *v = acosf(y) / (float)M_PI;
}

void gk_env_pixel(const gk_environment *env, vec3 d, int *i, int *j)
{
    float u, v;
    gk_env_uv(d, &u, &v);
    int x = (int)(u * (float)env->width), y = (int)(v * (float)env->height);
    *i = x < 0 ? 0 : (x >= env->width ? env->width - 1 : x);
    *j = y < 0 ? 0 : (y >= env->height ? env->height - 1 : y);
}

vec3 gk_env_radiance(const gk_environment *env, vec3 d)
{
    if (!env->present || !env->rgb)
        return v3(0, 0, 0);
    int i, j;
    gk_env_pixel(env, d, &i, &j);
    const float *p = env->rgb + 3 * ((size_t)j * (size_t)env->width + (size_t)i);
    return v3(p[0], p[1], p[2]);
}

float gk_env_pixel_solid_angle(const gk_environment *env, int j)
{
    /* exact: the band between theta_j and theta_j+1, divided into W pixels */
    double t0 = M_PI * j / env->height, t1 = M_PI * (j + 1) / env->height;
    return (float)(2.0 * M_PI * (cos(t0) - cos(t1)) / env->width);
}

int gk_env_load(gk_environment *env, const char *scene_path, const char *base_dir, gk_err *e)
{
    const char *key = "scene extras gikiosk.environment.uri";
    if (!base_dir)
        return gk_fail(e, GK_EINPUT, "%s: %s '%s' cannot be read (no base directory)", scene_path, key, env->uri);
    if (env->uri[0] == '/' || strstr(env->uri, ".."))
        return gk_fail(e, GK_EINPUT, "%s: %s '%s' must be relative, inside the scene's folder", scene_path, key,
                       env->uri);
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", base_dir, env->uri);
    struct stat st;
    if (stat(path, &st) == 0 && !gk_path_inside_dir(path, base_dir))
        return gk_fail(e, GK_EINPUT, "%s: %s '%s' lies outside the scene's folder (a symlink out of it)", scene_path,
                       key, env->uri);
    gk_image img = {0};
    gk_err ie = {0};
    if (gk_image_read(path, &img, &ie) != 0)
        return gk_fail(e, GK_EINPUT, "%s: %s '%s' is missing or unreadable (%s)", scene_path, key, env->uri, ie.msg);
    if (img.width > GK_ENV_MAX_WIDTH) {
        gk_fail(e, GK_EINPUT, "%s: %s '%s' is %dx%d; at most %dx%d (a distant light needs no more: downsample it)",
                scene_path, key, env->uri, img.width, img.height, GK_ENV_MAX_WIDTH, GK_ENV_MAX_WIDTH / 2);
        gk_image_free(&img);
        return -1;
    }
    if (img.width != 2 * img.height || img.height < 4 || img.channels < 3) {
        gk_fail(e, GK_EINPUT,
                "%s: %s '%s' is %dx%d with %d channels; an environment is a lat-long RGB map, width = 2 x height, "
                "at least 8x4", scene_path, key, env->uri, img.width, img.height, img.channels);
        gk_image_free(&img);
        return -1;
    }
    size_t n = (size_t)img.width * (size_t)img.height;
    env->rgb = malloc(n * 3 * sizeof *env->rgb);
    if (!env->rgb) {
        gk_image_free(&img);
        return gk_fail(e, GK_ERUNTIME, "%s: out of memory reading the environment '%s'", scene_path, env->uri);
    }
    for (size_t p = 0; p < n; p++)
        for (int c = 0; c < 3; c++) {
            float x = img.pixels[p * (size_t)img.channels + (size_t)c];
            if (!isfinite(x) || x < 0.0f) {
                int px = (int)(p % (size_t)img.width), py = (int)(p / (size_t)img.width);
                gk_fail(e, GK_EINPUT, "%s: %s '%s': pixel (%d, %d) channel %d is %g; radiance must be finite and >= 0",
                        scene_path, key, env->uri, px, py, c, x);
                gk_image_free(&img);
                free(env->rgb);
                env->rgb = NULL;
                return -1;
            }
            env->rgb[3 * p + (size_t)c] = x * env->intensity;
        }
    env->width = img.width;
    env->height = img.height;
    gk_image_free(&img);
    return 0;
}

/* One soft panel (a studio softbox): centre at elevation/azimuth (degrees), half extents along
   azimuth and elevation (degrees), radiance; edges fall off over the outer 30% of each extent. */
typedef struct studio_panel {
    float elevation, azimuth, half_a, half_b;
    float rgb[3];
} studio_panel;

static const studio_panel kPanels[] = {
    {.elevation = 40, .azimuth = 35, .half_a = 14, .half_b = 10, .rgb = {14.0f, 13.4f, 12.6f}},  /* key */
    {.elevation = 20, .azimuth = 250, .half_a = 18, .half_b = 10, .rgb = {4.0f, 4.2f, 4.6f}},     /* fill */
    {.elevation = 75, .azimuth = 160, .half_a = 12, .half_b = 12, .rgb = {7.0f, 7.0f, 7.0f}},     /* top */
};

static float falloff(float t) /* 1 inside 0.7, 0 past 1, smooth between */
{
    t = fabsf(t);
    if (t <= 0.7f)
        return 1.0f;
    if (t >= 1.0f)
        return 0.0f;
    float x = (t - 0.7f) / 0.3f;
    return 1.0f - x * x * (3.0f - 2.0f * x);
}

static float panel_mask(const studio_panel *p, vec3 d)
{
    const float deg = (float)M_PI / 180.0f;
    vec3 c = gk_env_dir(p->azimuth / 360.0f, 0.5f - p->elevation / 180.0f);
    float phi = p->azimuth * deg;
    vec3 ta = v3(cosf(phi), 0.0f, sinf(phi));  /* d(dir)/d(phi), horizontal */
    vec3 tb = v3_norm(v3_cross(ta, c));        /* towards the zenith */
    float dc = v3_dot(d, c);
    if (dc <= 0.0f)
        return 0.0f;
    float a = atan2f(v3_dot(d, ta), dc), b = atan2f(v3_dot(d, tb), dc);
    return falloff(a / (p->half_a * deg)) * falloff(b / (p->half_b * deg));
}

void gk_env_studio_pixels(float *rgb, int height)
{
    int width = 2 * height;
    /* A sun-less sky: blue-grey at the zenith, brighter and warmer at the horizon; a grey ground
       below (a studio floor seen far off). */
    const float zenith[3] = {0.30f, 0.38f, 0.52f}, horizon[3] = {0.90f, 0.88f, 0.84f}, ground[3] = {0.20f, 0.19f, 0.18f};
    for (int j = 0; j < height; j++)
        for (int i = 0; i < width; i++) {
            vec3 d = gk_env_dir((i + 0.5f) / (float)width, (j + 0.5f) / (float)height);
            float *p = rgb + 3 * ((size_t)j * (size_t)width + (size_t)i);
            float up = d.y > 0.0f ? sqrtf(d.y) : 0.0f;
            for (int c = 0; c < 3; c++)
                p[c] = d.y > 0.0f ? horizon[c] + (zenith[c] - horizon[c]) * up : ground[c];
            for (size_t k = 0; k < sizeof kPanels / sizeof kPanels[0]; k++) {
                float m = panel_mask(&kPanels[k], d);
                for (int c = 0; c < 3; c++)
                    p[c] += m * kPanels[k].rgb[c];
            }
        }
}

int gk_env_make_studio(gk_environment *env, int height, float intensity, gk_err *e)
{
    size_t n = (size_t)height * 2 * (size_t)height * 3;
    float *rgb = malloc(n * sizeof *rgb);
    if (!rgb)
        return gk_fail(e, GK_ERUNTIME, "out of memory making the studio environment");
    gk_env_studio_pixels(rgb, height);
    for (size_t k = 0; k < n; k++)
        rgb[k] *= intensity;
    free(env->rgb);
    env->rgb = rgb;
    env->present = true;
    env->uri[0] = '\0';
    env->intensity = intensity;
    env->width = 2 * height;
    env->height = height;
    return 0;
}

void gk_env_free(gk_environment *env)
{
    free(env->rgb);
    free(env->ambient_sh);
    env->rgb = NULL;
    env->ambient_sh = NULL;
}
