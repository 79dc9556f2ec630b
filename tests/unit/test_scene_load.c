/* The loader on every committed scene (config/scenes): counts, bounds, light semantics, camera,
 * animation evaluation at known times, features and methods. Run from the repository root. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "scene/scene.h"

static gk_scene *load(const char *name)
{
    char path[256];
    snprintf(path, sizeof path, "config/scenes/%s.gltf", name);
    gk_err e = {0};
    gk_scene *s = gk_scene_load(path, &e);
    if (!s)
        print_error("%s\n", e.msg);
    assert_non_null(s);
    return s;
}

static bool has_method(const gk_scene *s, const char *m)
{
    const char *names[8];
    int n = gk_scene_methods(s, names, 8);
    for (int i = 0; i < n; i++)
        if (!strcmp(names[i], m))
            return true;
    return false;
}

/* Triangle counts are those the builders produce (build_*.c); a change to a builder that changes
 * them must be deliberate. */
static void every_scene_loads_with_its_counts(void **state)
{
    (void)state;
    static const struct { const char *name; uint32_t tris; int lights; } expect[] = {
        {"cornell", 32, 1},        {"cornell-spot", 30, 1},       {"cornell-spot-anim", 30, 1},
        {"shadow-planes", 4, 1},   {"shadow-planes-stacked", 6, 1}, {"light-leak", 24, 1},
        {"caustic-ring", 202, 1},  {"atrium", 79808, 3},          {"furnace", 192, 0},
        {"glass", 3978, 1},
    };
    for (size_t i = 0; i < sizeof expect / sizeof expect[0]; i++) {
        gk_scene *s = load(expect[i].name);
        assert_string_equal(s->name, expect[i].name);
        assert_int_equal(s->n_triangles, expect[i].tris);
        assert_int_equal(s->n_lights, expect[i].lights);
        assert_int_equal(s->n_degenerate_dropped, 0);
        assert_true(s->description[0] != '\0');
        assert_true(s->camera_node >= 0);
        const char *names[8];
        assert_true(gk_scene_methods(s, names, 8) >= 1);
        assert_string_equal(names[0], "none");
        gk_scene_free(s);
    }
}

static void cornell_geometry_camera_and_light(void **state)
{
    (void)state;
    gk_scene *s = load("cornell");
    /* measured data in mm: x 0..556, y 0..548.8, z 0..559.2 */
    assert_float_equal(s->bmin.x, 0.0f, 1e-6f);
    assert_float_equal(s->bmax.x, 0.556f, 1e-6f);
    assert_float_equal(s->bmax.y, 0.5488f, 1e-6f);
    assert_float_equal(s->bmax.z, 0.5592f, 1e-6f);
    const gk_camera *c = &s->cameras[s->nodes[s->camera_node].camera];
    assert_float_equal(c->yfov, 2.0 * atan(12.5 / 35.0), 1e-6);
    mat4 view, proj;
    vec3 eye;
    gk_scene_camera(s, 1.0f, &view, &proj, &eye);
    assert_float_equal(eye.x, 0.278f, 1e-6f);
    assert_float_equal(eye.y, 0.273f, 1e-6f);
    assert_float_equal(eye.z, -0.8f, 1e-6f);
    /* looking +z: the back wall's centre is straight ahead, 1.3592 m away (view space -z) */
    vec3 p = m4_point(view, v3(0.278f, 0.273f, 0.5592f));
    assert_float_equal(p.x, 0.0f, 1e-5f);
    assert_float_equal(p.y, 0.0f, 1e-5f);
    assert_float_equal(p.z, -1.3592f, 1e-5f);
    /* the red wall (x = 0.556) is on the left of the image */
    assert_true(m4_point(view, v3(0.55f, 0.27f, 0.3f)).x < 0);
    /* ceiling light: a 0.13 x 0.105 rectangle facing down whose radiance I/(W H) is the proxy's */
    int ln = -1;
    for (int i = 0; i < s->n_nodes; i++)
        if (s->nodes[i].light >= 0)
            ln = i;
    assert_true(ln >= 0);
    const gk_light *l = &s->lights[s->nodes[ln].light];
    assert_int_equal(l->shape, GK_SHAPE_RECT);
    assert_float_equal(l->size[0], 0.13f, 1e-6f);
    assert_float_equal(l->size[1], 0.105f, 1e-6f);
    float radiance = l->intensity / (l->size[0] * l->size[1]);
    assert_float_equal(radiance, 17.0f, 1e-3f);
    vec3 pos, dir, u, v;
    gk_scene_light_frame(s, ln, &pos, &dir, &u, &v);
    assert_float_equal(pos.y, 0.5487f, 1e-6f);
    assert_float_equal(dir.y, -1.0f, 1e-6f);
    assert_float_equal(fabsf(u.x), 1.0f, 1e-6f); /* width along x: 213..343 mm */
    assert_float_equal(fabsf(v.z), 1.0f, 1e-6f); /* height along z: 227..332 mm */
    bool proxy = false;
    for (int m = 0; m < s->n_materials; m++)
        if (s->materials[m].light_proxy) {
            proxy = true;
            assert_float_equal(s->materials[m].emissive[0], radiance, 1e-3f);
        }
    assert_true(proxy);
    assert_true(s->features.has_area_lights);
    assert_false(s->features.has_emissive); /* the proxy is not an emitter of its own */
    assert_false(s->features.is_closed);    /* the front is open */
    assert_true(has_method(s, "vct") && has_method(s, "lightmap") && !has_method(s, "ispm"));
    gk_scene_free(s);
}

static vec3 spot_dir(gk_scene *s, float t)
{
    gk_scene_evaluate(s, t);
    for (int i = 0; i < s->n_nodes; i++)
        if (s->nodes[i].light >= 0) {
            vec3 d;
            gk_scene_light_frame(s, i, NULL, &d, NULL, NULL);
            return d;
        }
    fail();
    return v3(0, 0, 0);
}

/* The spot's targets in build_cornell.c: the red wall's bottom back corner at t = 0 and 8 s, the
 * red wall's centre at 8/3 s; in between the rotation is slerped. */
static void spot_animation_evaluates_at_known_times(void **state)
{
    (void)state;
    gk_scene *s = load("cornell-spot-anim");
    assert_float_equal(s->anim_duration, 8.0f, 1e-6f);
    assert_true(s->features.has_animation);
    /* the seed's dynamic objects drive the light maps' photon invalidation: animation is no bar */
    assert_true(has_method(s, "lightmap"));
    vec3 pos = v3(0.278f, 0.52f, 0.056f);
    vec3 corner = v3_norm(v3_sub(v3(0.5528f, 0, 0.5592f), pos));
    vec3 wall = v3_norm(v3_sub(v3(0.556f, 0.274f, 0.28f), pos));
    vec3 d0 = spot_dir(s, 0.0f), d1 = spot_dir(s, 8.0f / 3.0f), dl = spot_dir(s, 8.0f + 8.0f / 3.0f);
    assert_float_equal(v3_dot(d0, corner), 1.0f, 1e-5f);
    assert_float_equal(v3_dot(d1, wall), 1.0f, 1e-5f);
    assert_float_equal(v3_dot(dl, wall), 1.0f, 1e-5f); /* looped */
    /* halfway in time is halfway in angle (slerp about one axis) */
    vec3 dm = spot_dir(s, 4.0f / 3.0f);
    float total = acosf(fminf(1.0f, v3_dot(corner, wall)));
    assert_float_equal(acosf(fminf(1.0f, v3_dot(dm, corner))), total / 2, 2e-3f);
    assert_float_equal(acosf(fminf(1.0f, v3_dot(dm, wall))), total / 2, 2e-3f);
    gk_scene_free(s);
}

static void analytic_scenes_carry_their_parameters(void **state)
{
    (void)state;
    gk_scene *s = load("shadow-planes");
    float v[4];
    assert_int_equal(gk_scene_param(s, "light_size", v, 4), 1);
    assert_float_equal(v[0], 1.0f, 0);
    assert_int_equal(gk_scene_param(s, "light_height", v, 4), 1);
    assert_float_equal(v[0], 4.0f, 0);
    assert_int_equal(gk_scene_param(s, "occluder_center", v, 4), 3);
    assert_float_equal(v[1], 1.0f, 0);
    assert_int_equal(gk_scene_param(s, "nope", v, 4), -1);
    assert_true(s->has_exposure);
    const char *names[8];
    assert_int_equal(gk_scene_methods(s, names, 8), 1); /* extras methods "none" */
    /* unit radiance: I = L S^2 */
    assert_float_equal(s->lights[0].intensity, 1.0f, 0);
    gk_scene_free(s);

    s = load("furnace");
    assert_true(s->features.is_closed);
    assert_true(s->features.has_emissive);
    assert_int_equal(gk_scene_param(s, "radiance", v, 4), 1);
    assert_float_equal(v[0], 2.0f, 0);
    for (int m = 0; m < s->n_materials - 1; m++)
        assert_float_equal(s->materials[m].base_color[0], 0.5f, 0);
    gk_scene_free(s);

    s = load("caustic-ring");
    assert_true(s->features.has_specular && s->features.has_caustics);
    assert_true(has_method(s, "ispm") && has_method(s, "lgv"));
    gk_scene_free(s);

    s = load("light-leak");
    assert_int_equal(gk_scene_param(s, "wall_x", v, 4), 2);
    assert_float_equal(v[1] - v[0], 0.02f, 1e-6f); /* 1/200 of the 4 m room */
    gk_scene_free(s);
}

static void atrium_is_within_budget(void **state)
{
    (void)state;
    gk_scene *s = load("atrium");
    assert_in_range(s->n_triangles, 50000, 100000);
    bool sun = false;
    for (int i = 0; i < s->n_lights; i++)
        sun = sun || (s->lights[i].type == GK_LIGHT_DIRECTIONAL && s->lights[i].shape == GK_SHAPE_DISC);
    assert_true(sun);
    assert_true(s->bmax.x - s->bmin.x > 27.0f && s->bmax.y > 9.0f);
    gk_scene_free(s);
}

static void find_and_feature_strings(void **state)
{
    (void)state;
    char path[256];
    assert_int_equal(gk_scene_find("config/scenes", "cornell", path, sizeof path), 0);
    assert_string_equal(path, "config/scenes/cornell.gltf");
    assert_int_equal(gk_scene_find("config/scenes", "no-such-scene", path, sizeof path), -1);
    assert_int_equal(gk_scene_find("config/scenes", "../scenes/cornell", path, sizeof path), -1);
    gk_scene *s = load("caustic-ring");
    char f[128];
    gk_scene_features_string(&s->features, f, sizeof f);
    assert_string_equal(f, "specular,caustics");
    gk_scene_free(s);
}

/* Builders wind every triangle so that its geometric normal agrees with its vertex normals
 * (smooth normals of cylinders and cloth lean at most ~30° off the face: cos > 0.8), and the
 * rooms (Cornell walls, furnace) face inwards. */
static void triangles_face_the_way_their_normals_say(void **state)
{
    (void)state;
    static const char *const names[] = {"cornell", "cornell-spot", "shadow-planes", "light-leak",
                                        "caustic-ring", "atrium", "furnace", "glass"};
    for (size_t k = 0; k < sizeof names / sizeof names[0]; k++) {
        gk_scene *s = load(names[k]);
        for (int m = 0; m < s->n_meshes; m++) {
            const gk_mesh *mesh = &s->meshes[m];
            for (uint32_t t = 0; t < mesh->n_triangles; t++) {
                const uint32_t *tri = mesh->indices + 3 * (size_t)t;
                const float *a = mesh->positions + 3 * (size_t)tri[0], *b = mesh->positions + 3 * (size_t)tri[1],
                            *c = mesh->positions + 3 * (size_t)tri[2];
                vec3 g = v3_norm(v3_cross(v3(b[0] - a[0], b[1] - a[1], b[2] - a[2]),
                                          v3(c[0] - a[0], c[1] - a[1], c[2] - a[2])));
                for (int j = 0; j < 3; j++) {
                    const float *n = mesh->normals + 3 * (size_t)tri[j];
                    float d = v3_dot(g, v3(n[0], n[1], n[2]));
                    if (d < 0.8f)
                        print_error("%s mesh %d triangle %u: normal disagrees (%f)\n", names[k], m, t, d);
                    assert_true(d >= 0.8f);
                }
                if (!strcmp(names[k], "furnace"))
                    assert_true(v3_dot(g, v3(-a[0], -a[1], -a[2])) > 0); /* towards the centre */
            }
        }
        gk_scene_free(s);
    }
    /* Cornell: the floor faces up, the ceiling down, the back wall towards the camera (-z) */
    gk_scene *s = load("cornell");
    for (int i = 0; i < s->n_nodes; i++) {
        const gk_node *n = &s->nodes[i];
        if (n->mesh_count != 1)
            continue;
        const float *nr = s->meshes[n->mesh_first].normals;
        if (!strcmp(n->name, "floor"))
            assert_float_equal(nr[1], 1.0f, 1e-3f);
        if (!strcmp(n->name, "ceiling"))
            assert_float_equal(nr[1], -1.0f, 1e-3f);
        if (!strcmp(n->name, "back"))
            assert_float_equal(nr[2], -1.0f, 1e-3f);
        if (!strcmp(n->name, "left-red"))
            assert_true(nr[0] < -0.99f);
    }
    gk_scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(every_scene_loads_with_its_counts),
        cmocka_unit_test(cornell_geometry_camera_and_light),
        cmocka_unit_test(spot_animation_evaluates_at_known_times),
        cmocka_unit_test(analytic_scenes_carry_their_parameters),
        cmocka_unit_test(atrium_is_within_budget),
        cmocka_unit_test(triangles_face_the_way_their_normals_say),
        cmocka_unit_test(find_and_feature_strings),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
