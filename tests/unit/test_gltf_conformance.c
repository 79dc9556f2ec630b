/* The glTF conformance set (tests/gltf/, written by tools/gltf_conformance.py): one small file per
 * feature the loader reads, converts or refuses, each checked against values known from how the
 * file was made — the pixels of an embedded checker, the vertex a sparse accessor moves, the
 * triangles a strip makes — plus the default studio that lights files without lights. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/tonemap.h"
#include "ref/materials.h"
#include "ref/ref_scene.h"
#include "ref/trace.h"
#include "scene/scene.h"

static gk_scene *load(const char *name)
{
    char path[256];
    snprintf(path, sizeof path, "tests/gltf/%s", name);
    gk_err e = {0};
    gk_scene *s = gk_scene_load(path, &e);
    if (!s)
        print_error("%s\n", e.msg);
    assert_non_null(s);
    return s;
}

static void expect_refused(const char *name, const char *what)
{
    char path[256];
    snprintf(path, sizeof path, "tests/gltf/%s", name);
    gk_err e = {0};
    gk_scene *s = gk_scene_load(path, &e);
    if (s)
        gk_scene_free(s);
    assert_null(s);
    assert_int_equal(e.code, GK_EINPUT);
    if (strncmp(e.msg, path, strlen(path)) != 0 || !strstr(e.msg, what))
        print_error("message: %s\nwanted the path and '%s'\n", e.msg, what);
    assert_int_equal(strncmp(e.msg, path, strlen(path)), 0);
    assert_non_null(strstr(e.msg, what));
}

/* The 2 x 2 checker (top row red, green; bottom row blue, white), sRGB 8-bit: decoded to linear,
 * a channel of 255 is 1 and of 0 is 0 exactly. */
static void expect_checker(const gk_scene *s)
{
    assert_int_equal(s->n_textures, 1);
    const gk_texture *t = &s->textures[0];
    assert_int_equal(t->width, 2);
    assert_int_equal(t->height, 2);
    assert_null(t->embedded); /* freed once decoded */
    const float want[4][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
    for (int p = 0; p < 4; p++)
        for (int c = 0; c < 3; c++)
            assert_float_equal(t->rgba[4 * p + c], want[p][c], 1e-6f);
    assert_int_equal(s->gltf.embedded_images, 1);
}

static void images_inside_the_file_are_decoded(void **state)
{
    (void)state;
    gk_scene *glb = load("texture-glb.glb");
    expect_checker(glb);
    assert_string_equal(glb->textures[0].mime, "image/png");
    gk_scene_free(glb);
    gk_scene *uri = load("texture-data-uri.gltf");
    expect_checker(uri);
    gk_scene_free(uri);
    expect_refused("texture-ktx2.glb", "KHR_texture_basisu");
}

static void sparse_accessors_substitute_their_values(void **state)
{
    (void)state;
    gk_scene *s = load("sparse.gltf");
    const float *p = s->meshes[0].positions; /* vertex 1 moved from (1,0,0) to (2,0,0) */
    assert_float_equal(p[3], 2.0f, 0.0f);
    assert_float_equal(p[6], 0.0f, 0.0f);
    assert_float_equal(p[7], 1.0f, 0.0f);
    assert_int_equal(s->gltf.sparse_accessors, 1);
    assert_float_equal(s->bmax.x, 2.0f, 1e-6f);
    gk_scene_free(s);
    s = load("sparse-zeros.gltf"); /* no base data: zeros, vertices 1 and 2 set */
    p = s->meshes[0].positions;
    const float want[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    for (int i = 0; i < 9; i++)
        assert_float_equal(p[i], want[i], 0.0f);
    assert_int_equal(s->n_triangles, 1);
    gk_scene_free(s);
}

static void quantized_attributes_are_read_when_declared(void **state)
{
    (void)state;
    gk_scene *s = load("quantized.gltf");
    const gk_mesh *m = &s->meshes[0];
    assert_float_equal(m->positions[3], 1000.0f, 0.0f); /* unnormalized: the integer's value */
    assert_float_equal(m->normals[2], 1.0f, 1e-6f);      /* normalized byte 127 */
    assert_float_equal(m->uvs[1], 1.0f, 1e-6f);          /* normalized ushort 65535 */
    assert_float_equal(s->bmax.x, 1.0f, 1e-5f);          /* the node's 0.001 scale: metres */
    assert_int_equal(s->gltf.quantized_accessors, 3);
    assert_non_null(strstr(s->gltf.extensions_read, "KHR_mesh_quantization"));
    gk_scene_free(s);
    expect_refused("quantized-undeclared.gltf", "KHR_mesh_quantization");
}

/* Each triangle's normal z (all lie in z = 0, so +1 or -1 tells the winding). */
static float winding(const gk_mesh *m, uint32_t t)
{
    const uint32_t *i = &m->indices[3 * t];
    const float *a = &m->positions[3 * i[0]], *b = &m->positions[3 * i[1]], *c = &m->positions[3 * i[2]];
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

/* Corner k of triangle t is the file's vertex `want` (vertices are told apart by position; the
 * loader may un-index a mesh to give it flat normals, so indices are not compared). */
static void expect_corner(const gk_mesh *m, uint32_t t, int k, const float *file_positions, uint32_t want)
{
    const float *p = &m->positions[3 * m->indices[3 * t + (uint32_t)k]];
    for (int c = 0; c < 3; c++)
        assert_float_equal(p[c], file_positions[3 * want + (uint32_t)c], 0.0f);
}

static void strips_and_fans_become_triangle_lists(void **state)
{
    (void)state;
    gk_scene *s = load("strip.gltf");
    const gk_mesh *m = &s->meshes[0];
    assert_int_equal(m->n_triangles, 2);
    const float strip_pos[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
    const uint32_t strip[6] = {0, 1, 2, 2, 1, 3};
    for (int i = 0; i < 6; i++)
        expect_corner(m, (uint32_t)i / 3, i % 3, strip_pos, strip[i]);
    for (uint32_t t = 0; t < 2; t++)
        assert_true(winding(m, t) > 0); /* every triangle keeps the strip's (counter-clockwise) winding */
    assert_int_equal(s->gltf.strips_fans, 1);
    gk_scene_free(s);
    s = load("fan.gltf");
    m = &s->meshes[0];
    assert_int_equal(m->n_triangles, 3);
    const float fan_pos[15] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, -1, 1, 0};
    const uint32_t fan[9] = {0, 1, 2, 0, 2, 3, 0, 3, 4};
    for (int i = 0; i < 9; i++)
        expect_corner(m, (uint32_t)i / 3, i % 3, fan_pos, fan[i]);
    for (uint32_t t = 0; t < 3; t++)
        assert_true(winding(m, t) > 0);
    gk_scene_free(s);
}

static void lines_are_loaded_and_not_drawn(void **state)
{
    (void)state;
    gk_scene *s = load("lines.gltf");
    assert_int_equal(s->n_meshes, 2);
    assert_int_equal(s->meshes[0].n_triangles, 0);
    assert_int_equal(s->meshes[1].n_triangles, 1);
    assert_int_equal(s->n_triangles, 1);
    assert_int_equal(s->gltf.not_drawn, 1);
    gk_scene_free(s);
}

static void orthographic_cameras_load_and_are_passed_over(void **state)
{
    (void)state;
    gk_scene *s = load("cameras.gltf");
    assert_int_equal(s->n_cameras, 2);
    assert_true(s->cameras[0].orthographic);
    assert_int_equal(s->camera_node, 2); /* "persp", after "ortho" */
    assert_string_equal(s->nodes[s->camera_node].name, "persp");
    assert_int_equal(s->gltf.orthographic_cameras, 1);
    /* a file that has a light keeps it: no studio */
    assert_false(s->default_lighting);
    assert_int_equal(s->n_lights, 1);
    /* an optional extension that is not read is named, and the file loads */
    assert_string_equal(s->gltf.extensions_ignored, "KHR_materials_clearcoat");
    gk_scene_free(s);
}

static void required_extensions_not_read_are_refused_by_name(void **state)
{
    (void)state;
    expect_refused("requires-instancing.gltf", "requires extension 'EXT_mesh_gpu_instancing'");
}

/* The studio (default_studio.c): the built-in environment plus one key light from the camera's
 * side: the key's direction (node -Z) must point into the scene, away from the camera (it lights
 * what the visitor sees); the environment is split into area lights for the rasterizer. */
static void a_file_without_lights_gets_the_default_studio(void **state)
{
    (void)state;
    gk_scene *s = load("texture-glb.glb");
    assert_true(s->default_lighting);
    assert_true(s->environment.present);
    assert_string_equal(s->environment.uri, "");
    assert_true(s->environment.n_env_lights > 0);
    assert_int_equal(s->n_lights, 1 + s->environment.n_env_lights);
    mat4 view;
    vec3 eye;
    gk_scene_camera(s, 16.0f / 9.0f, &view, NULL, &eye);
    vec3 centre = v3_scale(v3_add(s->bmin, s->bmax), 0.5f);
    vec3 to_scene = v3_norm(v3_sub(centre, eye));
    int keys = 0, lit_from_front = 0;
    for (int i = 0; i < s->n_nodes; i++) {
        if (s->nodes[i].light < 0 || s->lights[s->nodes[i].light].env_part)
            continue;
        const gk_light *l = &s->lights[s->nodes[i].light];
        assert_int_equal(l->type, GK_LIGHT_DIRECTIONAL);
        vec3 pos, dir, u, v;
        gk_scene_light_frame(s, i, &pos, &dir, &u, &v);
        assert_float_equal(v3_len(dir), 1.0f, 1e-4f);
        keys++;
        if (v3_dot(dir, to_scene) > 0.2f)
            lit_from_front++;
    }
    assert_int_equal(keys, 1);
    assert_int_equal(lit_from_front, 1);
    /* the quad faces +z, the default camera looks from +z: the key reaches its lit face */
    gk_scene_free(s);
}

/* metallicFactor 1 with a metallic-roughness texture whose B is 0: a dielectric over its whole
 * surface, so light bounces off it and the GI methods apply (they did not when the factor alone
 * decided). */
static void metalness_comes_from_the_texture(void **state)
{
    (void)state;
    gk_scene *s = load("metallic-texture.glb");
    const gk_material *m = &s->materials[0];
    assert_float_equal(m->metallic, 1.0f, 0.0f);
    assert_float_equal(m->metallic_mean, 0.0f, 1e-6f);
    assert_float_equal(m->roughness_mean, 1.0f, 1e-6f);
    assert_true(s->features.has_interreflection);
    const char *names[16];
    int n = gk_scene_methods(s, names, 16);
    bool vct = false;
    for (int i = 0; i < n; i++)
        vct = vct || strcmp(names[i], "vct") == 0;
    assert_true(vct);
    gk_scene_free(s);
}

/* A normal-mapped mesh without TANGENT gets generated tangents: on the quad (u along +x, v along
 * -y, the glTF UVs of textured_quad) T = dP/du = +x and B = (N x T) w must follow dP/dv = -y, so
 * w = -1; a mesh without a normal map gets none. */
static void normal_maps_get_tangents(void **state)
{
    (void)state;
    gk_scene *s = load("normal-map.glb");
    const gk_mesh *m = &s->meshes[0];
    assert_int_equal(s->materials[0].normal_tex, 0);
    assert_float_equal(s->materials[0].normal_scale, 1.0f, 0.0f);
    assert_non_null(m->tangents);
    for (uint32_t v = 0; v < m->n_vertices; v++) {
        assert_float_equal(m->tangents[4 * v], 1.0f, 1e-5f);
        assert_float_equal(m->tangents[4 * v + 1], 0.0f, 1e-5f);
        assert_float_equal(m->tangents[4 * v + 2], 0.0f, 1e-5f);
        assert_float_equal(m->tangents[4 * v + 3], -1.0f, 0.0f);
    }
    gk_scene_free(s);
    s = load("texture-glb.glb");
    assert_null(s->meshes[0].tangents);
    gk_scene_free(s);
}

/* glTF samplers (sampler-wrap.glb: wrapS CLAMP_TO_EDGE, wrapT MIRRORED_REPEAT, NEAREST) are read,
 * and the tracer looks texels up as GL's rules say (ES 3.2 8.14.2), at UVs where REPEAT or bilinear
 * filtering would give another texel; the GLES side is compared with the tracer in
 * tests/e2e/gltf_conformance.sh. The checker's rows: v in [0, 0.5) red, green; [0.5, 1) blue, white. */
static void samplers_wrap_and_filter_as_declared(void **state)
{
    (void)state;
    gk_scene *s = load("sampler-wrap.glb");
    gk_texture t = s->textures[0];
    assert_int_equal(t.wrap_s, GK_WRAP_CLAMP);
    assert_int_equal(t.wrap_t, GK_WRAP_MIRROR);
    assert_true(t.nearest);
    assert_int_equal(s->gltf.samplers, 1);
    gk_ref_scene rs = {.textures = &t, .n_textures = 1};
    gk_ref_tri tri = {.uv = {{0, 0}, {1, 0}, {0, 1}}}; /* uv = (b1, b2) */
    const struct { float u, v, rgb[3]; const char *why; } at[] = {
        {0.25f, 0.25f, {1, 0, 0}, "inside: red"},
        {-0.25f, 0.25f, {1, 0, 0}, "clamped to column 0 (REPEAT: column 1, green)"},
        {1.25f, 0.25f, {0, 1, 0}, "clamped to column 1 (REPEAT: column 0, red)"},
        {0.25f, 1.25f, {0, 0, 1}, "mirrored to row 1 (REPEAT: row 0, red)"},
        {0.25f, -0.25f, {1, 0, 0}, "mirrored to row 0 (REPEAT: row 1, blue)"},
        {0.25f, 2.25f, {1, 0, 0}, "two periods on: row 0 again"},
        {0.45f, 0.25f, {1, 0, 0}, "nearest texel (bilinear: 0.6 red + 0.4 green)"},
    };
    for (size_t i = 0; i < sizeof at / sizeof at[0]; i++) {
        vec3 c = gk_tri_texture_rgb(&rs, &tri, 0, NULL, at[i].u, at[i].v);
        if (fabsf(c.x - at[i].rgb[0]) > 1e-6f || fabsf(c.y - at[i].rgb[1]) > 1e-6f || fabsf(c.z - at[i].rgb[2]) > 1e-6f)
            fail_msg("uv (%g, %g): got (%g, %g, %g), wanted %s", at[i].u, at[i].v, c.x, c.y, c.z, at[i].why);
    }
    /* bilinear with the same wraps: texel centres at (i + 0.5) / 2, clamp at the edge */
    t.nearest = false;
    vec3 c = gk_tri_texture_rgb(&rs, &tri, 0, NULL, 0.45f, 0.25f);
    assert_float_equal(c.x, 0.6f, 1e-5f);
    assert_float_equal(c.y, 0.4f, 1e-5f);
    c = gk_tri_texture_rgb(&rs, &tri, 0, NULL, -0.5f, 0.25f);
    assert_float_equal(c.x, 1.0f, 1e-6f);
    assert_float_equal(c.y, 0.0f, 1e-6f);
    gk_scene_free(s);
    expect_refused("sampler-bad-wrap.glb", "sampler 0: wrapS 10241");
}

/* KHR_texture_transform (texture-transform.glb: offset (0.5, 1), rotation pi/2, scale (2, 1) on the
 * base colour) gives the matrix uv' = (v + 0.5, 1 - 2u), and the tracer's base colour follows it; a
 * slot on TEXCOORD_1 (texcoord1.glb, whose TEXCOORD_0 is (0, 0) everywhere, one red texel) reads
 * the second set. Nearest-free points: texel centres, where bilinear filtering gives the texel. */
static void texture_transform_and_second_uv_set(void **state)
{
    (void)state;
    gk_scene *s = load("texture-transform.glb");
    const gk_tex_uv *xf = &s->materials[0].tex_uv[GK_SLOT_BASE];
    assert_true(xf->transformed);
    assert_int_equal(xf->texcoord, 0);
    const float want[6] = {0, 1, 0.5f, -2, 0, 1};
    for (int k = 0; k < 6; k++)
        assert_float_equal(xf->m[k], want[k], 1e-6f);
    assert_false(s->materials[0].tex_uv[GK_SLOT_MR].transformed);
    assert_int_equal(s->gltf.texture_transforms, 1);
    assert_string_equal(s->gltf.extensions_read, "KHR_texture_transform");
    gk_ref_scene rs = {.textures = s->textures, .n_textures = s->n_textures};
    gk_ref_tri tri = {.uv = {{0, 0}, {1, 0}, {0, 1}}}; /* uv = (b1, b2) */
    /* uv (0.125, 0.25) -> (0.75, 0.75): white (untransformed: red); (0.375, 0.25) -> (0.75, 0.25):
       green; (0.125, -0.25) -> (0.25, 0.75): blue; (0.375, -0.25) -> (0.25, 0.25): red. */
    const struct { float u, v, rgb[3]; } at[] = {
        {0.125f, 0.25f, {1, 1, 1}}, {0.375f, 0.25f, {0, 1, 0}}, {0.125f, -0.25f, {0, 0, 1}}, {0.375f, -0.25f, {1, 0, 0}}};
    for (size_t i = 0; i < sizeof at / sizeof at[0]; i++) {
        vec3 c = gk_tri_texture_rgb(&rs, &tri, 0, xf, at[i].u, at[i].v);
        if (fabsf(c.x - at[i].rgb[0]) > 1e-5f || fabsf(c.y - at[i].rgb[1]) > 1e-5f || fabsf(c.z - at[i].rgb[2]) > 1e-5f)
            fail_msg("uv (%g, %g): got (%g, %g, %g)", at[i].u, at[i].v, c.x, c.y, c.z);
    }
    gk_scene_free(s);

    s = load("texcoord1.glb");
    assert_int_equal(s->materials[0].tex_uv[GK_SLOT_BASE].texcoord, 1);
    assert_false(s->materials[0].tex_uv[GK_SLOT_BASE].transformed);
    assert_int_equal(s->gltf.second_uv_slots, 1);
    const gk_mesh *m = &s->meshes[0];
    assert_non_null(m->uvs1);
    assert_float_equal(m->uvs[0], 0.0f, 0.0f);
    /* the quad's vertex 2 is at (1, 1) with UV (1, 0) in set 1 */
    assert_float_equal(m->uvs1[2 * 2], 1.0f, 1e-6f);
    assert_float_equal(m->uvs1[2 * 2 + 1], 0.0f, 1e-6f);
    rs = (gk_ref_scene){.textures = s->textures, .n_textures = s->n_textures};
    gk_ref_tri tri1 = {.uv = {{0, 0}, {0, 0}, {0, 0}}, .uv1 = {{0, 0}, {1, 0}, {0, 1}}};
    vec3 c = gk_tri_texture_rgb(&rs, &tri1, 0, &s->materials[0].tex_uv[GK_SLOT_BASE], 0.75f, 0.75f);
    assert_float_equal(c.x, 1.0f, 1e-5f); /* (0.75, 0.75) of set 1: white; set 0 would give red */
    assert_float_equal(c.y, 1.0f, 1e-5f);
    assert_float_equal(c.z, 1.0f, 1e-5f);
    gk_scene_free(s);
    expect_refused("texcoord2.glb", "material 0: base colour texture reads TEXCOORD_2");
    expect_refused("texture-transform-bad.glb", "material 0: base colour texture: KHR_texture_transform needs");
}

/* alphaMode MASK (alpha-mask.glb: the quad at z = 0.5 opaque at its top-left and bottom-right
 * texels, clear at the other two, cutoff 0.5, in front of a wall at z = 0): rays through the clear
 * texels' centres pass the quad and stop at the wall, rays through the opaque ones stop at the quad,
 * for closest-hit and shadow (any-hit) queries alike. */
static void alpha_mask_lets_rays_through_the_holes(void **state)
{
    (void)state;
    gk_scene *s = load("alpha-mask.glb");
    assert_true(s->materials[0].alpha_mask);
    assert_float_equal(s->materials[0].alpha_cutoff, 0.5f, 0.0f);
    assert_false(s->materials[1].alpha_mask);
    assert_int_equal(s->gltf.alpha_masked, 1);
    gk_scene_evaluate(s, 0.0f);
    gk_ref_scene rs;
    gk_err e = {0};
    mat4 id = m4_identity();
    assert_int_equal(gk_ref_scene_build(&rs, s, id, id, v3(0, 0, 0), 1, 1, &e), 0);
    assert_non_null(rs.bvh.tested);
    /* texel (i, j) of the quad at x = -0.5 + i, y = 0.5 - j (uv (0, 0) at the top left, (-1, 1)) */
    const struct { float x, y; bool opaque; } at[] = {{-0.5f, 0.5f, true}, {0.5f, 0.5f, false},
                                                       {-0.5f, -0.5f, false}, {0.5f, -0.5f, true}};
    for (size_t i = 0; i < sizeof at / sizeof at[0]; i++) {
        gk_bvh_hit h;
        vec3 o = v3(at[i].x, at[i].y, 2.0f), d = v3(0, 0, -1);
        assert_true(gk_bvh_intersect(&rs.bvh, o, d, 0.0f, 10.0f, &h));
        float z = 2.0f - h.t;
        if (fabsf(z - (at[i].opaque ? 0.5f : 0.0f)) > 1e-4f)
            fail_msg("ray at (%g, %g) stopped at z %g, wanted the %s", at[i].x, at[i].y, z, at[i].opaque ? "quad" : "wall");
        /* a shadow ray from between quad and wall up to the light side */
        bool blocked = gk_bvh_occluded(&rs.bvh, v3(at[i].x, at[i].y, 0.25f), v3(0, 0, 1), 0.0f, 10.0f);
        assert_int_equal(blocked, at[i].opaque);
    }
    gk_ref_scene_free(&rs);
    gk_scene_free(s);
    /* BLEND is loaded and counted (blend_is_stochastic_transparency_in_the_tracer); a mode glTF
       does not have is refused */
    s = load("alpha-blend.glb");
    assert_false(s->materials[0].alpha_mask);
    assert_true(s->materials[0].alpha_blend);
    assert_int_equal(s->gltf.alpha_blended, 1);
    gk_scene_free(s);
    expect_refused("alpha-bad-mode.glb", "material 0 ('checker'): alphaMode 'CUTOUT' is not OPAQUE, MASK or BLEND");
}

/* A mirroring node (single-sided-mirrored.glb: the single-sided quad under scale (-1, 1, 1)) reverses
 * its triangles' winding, and glTF makes a mirrored node's front faces clockwise: the quad's front
 * still faces the wall (the mirror of -z in x), so the camera ray passes it as in single-sided.glb.
 * Judged by the world-space winding alone the quad would face the camera (as double-sided.glb). */
static void mirrored_nodes_turn_the_front_face(void **state)
{
    (void)state;
    gk_scene *s = load("single-sided-mirrored.glb");
    assert_false(s->materials[0].double_sided);
    gk_scene_evaluate(s, 0.0f);
    int quad = -1;
    for (int n = 0; n < s->n_nodes; n++)
        if (strcmp(s->nodes[n].name, "quad") == 0)
            quad = n;
    assert_true(quad >= 0);
    assert_true(gk_node_mirrored(&s->nodes[quad]));
    assert_false(gk_node_mirrored(&s->nodes[quad == 0 ? 1 : 0]));
    gk_ref_scene rs;
    gk_err e = {0};
    mat4 id = m4_identity();
    assert_int_equal(gk_ref_scene_build(&rs, s, id, id, v3(0, 0, 3), 1, 1, &e), 0);
    rs.eye = v3(0, 0, 3);
    gk_scene_hit h;
    assert_true(gk_scene_intersect_camera(&rs, v3(0.1f, 0.2f, 3.0f), v3(0, 0, -1), INFINITY, &h));
    assert_float_equal(3.0f - h.t, 0.0f, 1e-4f); /* the wall */
    assert_int_equal(rs.tris[h.tri].material, 1);
    assert_true(gk_scene_intersect(&rs, v3(0.1f, 0.2f, 3.0f), v3(0, 0, -1), INFINITY, &h));
    assert_int_equal(rs.tris[h.tri].material, 0);
    assert_true(rs.tris[h.tri].ng.z < -0.99f); /* the quad's front, towards the wall */
    assert_true(gk_scene_camera_sees(&rs, v3(0.1f, 0.2f, 0.0f))); /* the wall through it */
    gk_ref_scene_free(&rs);
    gk_scene_free(s);
}

/* doubleSided (single-sided.glb, double-sided.glb: a quad at z = 0.5 showing its back face to +z,
 * in front of a wall at z = 0): a camera ray from +z passes the single-sided quad and stops at the
 * wall, and stops at the double-sided one; the light tracer's connection to an eye on +z agrees.
 * Every other ray sees both faces: a bounce ray (closest hit) and a shadow ray stop at the quad in
 * both files, so the quad casts its shadow either way. */
static void single_sided_surfaces_are_seen_from_the_front_only(void **state)
{
    (void)state;
    const char *files[] = {"single-sided.glb", "double-sided.glb"};
    for (int both = 0; both < 2; both++) {
        gk_scene *s = load(files[both]);
        assert_int_equal(s->materials[0].double_sided, both);
        assert_int_equal(s->gltf.double_sided, both);
        gk_scene_evaluate(s, 0.0f);
        gk_ref_scene rs;
        gk_err e = {0};
        mat4 id = m4_identity();
        assert_int_equal(gk_ref_scene_build(&rs, s, id, id, v3(0, 0, 3), 1, 1, &e), 0);
        rs.eye = v3(0, 0, 3);
        vec3 o = v3(0.1f, 0.2f, 3.0f), d = v3(0, 0, -1);
        gk_scene_hit h;
        assert_true(gk_scene_intersect_camera(&rs, o, d, INFINITY, &h));
        float z = 3.0f - h.t;
        if (fabsf(z - (both ? 0.5f : 0.0f)) > 1e-4f)
            fail_msg("%s: the camera ray stopped at z %g, wanted the %s", files[both], z, both ? "quad" : "wall");
        assert_int_equal(rs.tris[h.tri].material, both ? 0 : 1);
        assert_true(gk_scene_intersect(&rs, o, d, INFINITY, &h));
        assert_float_equal(3.0f - h.t, 0.5f, 1e-4f); /* a bounce ray stops at the quad's back face */
        assert_true(gk_scene_occluded(&rs, v3(0.1f, 0.2f, 0.25f), v3(0, 0, 1), 10.0f)); /* its shadow */
        assert_int_equal(gk_scene_camera_sees(&rs, v3(0.1f, 0.2f, 0.0f)), !both);
        assert_true(gk_scene_camera_sees(&rs, v3(0.1f, 0.2f, 0.5f)));
        gk_ref_scene_free(&rs);
        gk_scene_free(s);
    }
}

/* occlusionTexture (occlusion-*.glb): the texture, its strength (1 by default, 0 kept) and its UV
 * slot are read; a file without one has none. The tracer does not read it (scene.h). */
static void occlusion_textures_are_read(void **state)
{
    (void)state;
    const struct { const char *file; int tex; float strength; } want[] = {
        {"occlusion-none.glb", -1, 1.0f}, {"occlusion-half.glb", 0, 1.0f}, {"occlusion-strength0.glb", 0, 0.0f}};
    for (size_t i = 0; i < sizeof want / sizeof want[0]; i++) {
        gk_scene *s = load(want[i].file);
        const gk_material *m = &s->materials[0];
        assert_int_equal(m->occlusion_tex, want[i].tex);
        assert_int_equal(s->gltf.occlusion_textures, want[i].tex >= 0);
        if (want[i].tex >= 0) {
            assert_float_equal(m->occlusion_strength, want[i].strength, 0.0f);
            assert_int_equal(m->tex_uv[GK_SLOT_OCCLUSION].texcoord, 0);
            /* grey 128 as data: 128/255, not sRGB-decoded */
            assert_float_equal(s->textures[m->occlusion_tex].rgba[0], 128.0f / 255.0f, 1e-6f);
        }
        gk_scene_free(s);
    }
}

/* alphaMode BLEND (blend-half.glb: a red quad of alpha 0.5 at z = 0.5 in front of a wall at z = 0):
 * the tracer's rays pass it with probability 1 - alpha, camera and shadow rays alike. 10,000 rays
 * on a grid over the quad: the share stopped by it is 0.5 within 0.02 (4 standard deviations of a
 * binomial share, 0.005; measured below). */
static void blend_is_stochastic_transparency_in_the_tracer(void **state)
{
    (void)state;
    gk_scene *s = load("blend-half.glb");
    assert_true(s->materials[0].alpha_blend);
    assert_false(s->materials[0].alpha_mask);
    gk_scene_evaluate(s, 0.0f);
    gk_ref_scene rs;
    gk_err e = {0};
    mat4 id = m4_identity();
    assert_int_equal(gk_ref_scene_build(&rs, s, id, id, v3(0, 0, 2), 1, 1, &e), 0);
    int quad = 0, shadowed = 0, n = 0;
    for (int i = 0; i < 100; i++)
        for (int j = 0; j < 100; j++, n++) {
            float x = -0.99f + 1.98f * ((float)i + 0.5f) / 100.0f, y = -0.99f + 1.98f * ((float)j + 0.5f) / 100.0f;
            gk_bvh_hit h;
            assert_true(gk_bvh_intersect(&rs.bvh, v3(x, y, 2.0f), v3(0, 0, -1), 0.0f, 10.0f, &h));
            quad += fabsf(2.0f - h.t - 0.5f) < 1e-4f;
            shadowed += gk_bvh_occluded(&rs.bvh, v3(x, y, 0.25f), v3(0, 0, 1), 0.0f, 10.0f);
        }
    print_message("# blend: %d of %d camera rays and %d shadow rays stopped by the alpha-0.5 quad\n", quad, n, shadowed);
    assert_in_range(quad, 4800, 5200);
    assert_in_range(shadowed, 4800, 5200);
    gk_ref_scene_free(&rs);
    gk_scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(images_inside_the_file_are_decoded),
        cmocka_unit_test(sparse_accessors_substitute_their_values),
        cmocka_unit_test(quantized_attributes_are_read_when_declared),
        cmocka_unit_test(strips_and_fans_become_triangle_lists),
        cmocka_unit_test(lines_are_loaded_and_not_drawn),
        cmocka_unit_test(orthographic_cameras_load_and_are_passed_over),
        cmocka_unit_test(required_extensions_not_read_are_refused_by_name),
        cmocka_unit_test(a_file_without_lights_gets_the_default_studio),
        cmocka_unit_test(metalness_comes_from_the_texture),
        cmocka_unit_test(normal_maps_get_tangents),
        cmocka_unit_test(samplers_wrap_and_filter_as_declared),
        cmocka_unit_test(texture_transform_and_second_uv_set),
        cmocka_unit_test(alpha_mask_lets_rays_through_the_holes),
        cmocka_unit_test(single_sided_surfaces_are_seen_from_the_front_only),
        cmocka_unit_test(mirrored_nodes_turn_the_front_face),
        cmocka_unit_test(occlusion_textures_are_read),
        cmocka_unit_test(blend_is_stochastic_transparency_in_the_tracer),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
