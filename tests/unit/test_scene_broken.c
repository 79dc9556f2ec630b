/* The loader on small hand-written files: a valid triangle first (so the broken variants fail for
 * the reason they were broken), then each defect gives GK_EINPUT with a message that starts with
 * the file's path and says what is wrong. Also: degenerate triangles dropped and counted,
 * generated normals, a texture decoded from sRGB, the default camera, loading from memory. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/tonemap.h"
#include "io/image_io.h"
#include "scene/scene.h"

static char tmpdir[256];

static void write_file(const char *name, const void *data, size_t len)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", tmpdir, name);
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(data, 1, len, f), len);
    fclose(f);
}

/* t.bin: three positions (0,0,0) (1,0,0) (0,1,0), then u16 indices 0 1 2 (+2 bytes of padding);
 * a second triangle (collinear: degenerate) for the degenerate test: (0,0,0) (1,0,0) (2,0,0). */
static void write_bin(const char *name, float nan_at, unsigned index2)
{
    unsigned char bin[44] = {0};
    float p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    if (nan_at >= 0)
        p[(int)nan_at] = NAN;
    memcpy(bin, p, sizeof p);
    uint16_t idx[3] = {0, 1, (uint16_t)index2};
    memcpy(bin + 36, idx, sizeof idx);
    write_file(name, bin, sizeof bin);
}

/* A one-triangle document; the parts that the cases vary are parameters. */
static void write_gltf(const char *name, const char *bin, int mode, int pos_count, int view_len, const char *material,
                       const char *extra)
{
    char json[4096];
    int n = snprintf(json, sizeof json,
                     "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],"
                     "\"nodes\":[{\"mesh\":0}],"
                     "\"meshes\":[{\"name\":\"tri\",\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,"
                     "\"mode\":%d%s}]}],"
                     "\"buffers\":[{\"uri\":\"%s\",\"byteLength\":44}],"
                     "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":%d},"
                     "{\"buffer\":0,\"byteOffset\":36,\"byteLength\":6}],"
                     "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":%d,\"type\":\"VEC3\"},"
                     "{\"bufferView\":1,\"componentType\":5123,\"count\":3,\"type\":\"SCALAR\"}]%s}",
                     mode, material, bin, view_len, pos_count, extra);
    assert_true(n > 0 && n < (int)sizeof json);
    write_file(name, json, (size_t)n);
}

static char *path_of(const char *name)
{
    static char path[512];
    snprintf(path, sizeof path, "%s/%s", tmpdir, name);
    return path;
}

/* Loads NAME and expects GK_EINPUT, a message starting with the path and containing `what`. */
static void expect_input_error(const char *name, const char *what)
{
    gk_err e = {0};
    char *path = path_of(name);
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

static int setup(void **state)
{
    (void)state;
    snprintf(tmpdir, sizeof tmpdir, "/tmp/gk-scene-test.XXXXXX");
    if (!mkdtemp(tmpdir))
        return -1;
    write_bin("t.bin", -1, 2);
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmpdir);
    return system(cmd) == 0 ? 0 : -1;
}

static void valid_triangle_loads_with_generated_normals(void **state)
{
    (void)state;
    write_gltf("ok.gltf", "t.bin", 4, 3, 36, "", "");
    gk_err e = {0};
    gk_scene *s = gk_scene_load(path_of("ok.gltf"), &e);
    if (!s)
        print_error("%s\n", e.msg);
    assert_non_null(s);
    assert_int_equal(s->n_triangles, 1);
    assert_int_equal(s->n_materials, 1); /* only the default */
    assert_non_null(s->meshes[0].normals);
    assert_float_equal(s->meshes[0].normals[2], 1.0f, 1e-6f); /* flat +z */
    /* no camera in the file: the default one frames the bounds from outside, looking at the centre */
    assert_int_equal(s->camera_node, -1);
    mat4 view, proj;
    vec3 eye;
    gk_scene_camera(s, 1.0f, &view, &proj, &eye);
    assert_true(eye.z > 0.5f);
    vec3 c = m4_point(view, v3(0.5f, 0.5f, 0.0f));
    assert_float_equal(c.x, 0.0f, 1e-4f);
    assert_float_equal(c.y, 0.0f, 1e-4f);
    assert_true(c.z < 0);
    gk_scene_free(s);
}

static void broken_files_name_the_file_and_the_defect(void **state)
{
    (void)state;
    write_bin("badindex.bin", -1, 5);
    write_gltf("badindex.gltf", "badindex.bin", 4, 3, 36, "", "");
    expect_input_error("badindex.gltf", "index 5");

    write_gltf("pastview.gltf", "t.bin", 4, 10, 36, "", "");
    expect_input_error("pastview.gltf", "reads past");

    write_gltf("pastbuffer.gltf", "t.bin", 4, 3, 80, "", "");
    expect_input_error("pastbuffer.gltf", "past buffer");

    write_bin("nan.bin", 4, 2);
    write_gltf("nan.gltf", "nan.bin", 4, 3, 36, "", "");
    expect_input_error("nan.gltf", "NaN");

    /* LINES (mode 1) loads and is not drawn (tests/gltf/lines.gltf); 7 is no glTF mode at all */
    write_gltf("badmode.gltf", "t.bin", 7, 3, 36, "", "");
    expect_input_error("badmode.gltf", "mode 7");

    write_gltf("notex.gltf", "t.bin", 4, 3, 36, ",\"material\":0",
               ",\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}],"
               "\"textures\":[{\"source\":0}],\"images\":[{\"uri\":\"missing.png\"}]");
    expect_input_error("notex.gltf", "missing.png");

    write_gltf("nobin.gltf", "absent.bin", 4, 3, 36, "", "");
    expect_input_error("nobin.gltf", "tinygltf");

    write_gltf("badmat.gltf", "t.bin", 4, 3, 36, ",\"material\":3", "");
    expect_input_error("badmat.gltf", "material 3");

    write_gltf("cycle.gltf", "t.bin", 4, 3, 36, "", ",\"cameras\":[]");
    /* a node hierarchy cycle: 0 -> 1 -> 0 */
    const char *cyc = "{\"asset\":{\"version\":\"2.0\"},\"nodes\":[{\"children\":[1]},{\"children\":[0]}]}";
    write_file("cycle.gltf", cyc, strlen(cyc));
    expect_input_error("cycle.gltf", "cycle");

    const char *notjson = "this is { not json";
    write_file("notjson.gltf", notjson, strlen(notjson));
    expect_input_error("notjson.gltf", "tinygltf");

    const char *methods = "{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"extras\":{\"gikiosk\":{\"methods\":\"vct,rtx\"}}}]}";
    write_file("methods.gltf", methods, strlen(methods));
    expect_input_error("methods.gltf", "unknown method 'rtx'");

    expect_input_error("does-not-exist.gltf", "no such file");

    /* KHR_materials_specular: out-of-range or malformed values are refused, naming the key */
    const char *bad_specular[][2] = {
        {"{\"specularFactor\":1.5}", "specularFactor"},
        {"{\"specularFactor\":\"high\"}", "specularFactor"},
        {"{\"specularColorFactor\":[1,1]}", "specularColorFactor"},
        {"{\"specularColorFactor\":[1,-1,1]}", "specularColorFactor"},
        {"{\"specularTexture\":{\"index\":\"x\"}}", "specularTexture"},
        {"{\"specularColorTexture\":{\"index\":4}}", "specular colour texture 4"},
    };
    for (size_t i = 0; i < sizeof bad_specular / sizeof bad_specular[0]; i++) {
        char materials[256];
        snprintf(materials, sizeof materials, ",\"materials\":[{\"extensions\":{\"KHR_materials_specular\":%s}}]",
                 bad_specular[i][0]);
        write_gltf("badspec.gltf", "t.bin", 4, 3, 36, ",\"material\":0", materials);
        expect_input_error("badspec.gltf", bad_specular[i][1]);
    }

    /* Glass: KHR_materials_transmission / KHR_materials_ior out of range or malformed, refused
       naming the material, the extension's key and the range */
    const char *bad_glass[][2] = {
        {"\"KHR_materials_transmission\":{\"transmissionFactor\":1.2}", "'lens'): KHR_materials_transmission transmissionFactor must be a number in [0, 1]"},
        {"\"KHR_materials_transmission\":{\"transmissionFactor\":-0.1}", "transmissionFactor"},
        {"\"KHR_materials_transmission\":{\"transmissionFactor\":\"clear\"}", "transmissionFactor"},
        {"\"KHR_materials_ior\":{\"ior\":0.5}", "'lens'): KHR_materials_ior ior must be 0 or a finite number >= 1"},
        {"\"KHR_materials_ior\":{\"ior\":-2}", "KHR_materials_ior ior"},
        {"\"KHR_materials_ior\":{\"ior\":[1.5]}", "KHR_materials_ior ior"},
        {"\"KHR_materials_emissive_strength\":{\"emissiveStrength\":-1}", "emissiveStrength"},
    };
    for (size_t i = 0; i < sizeof bad_glass / sizeof bad_glass[0]; i++) {
        char materials[256];
        snprintf(materials, sizeof materials, ",\"materials\":[{\"name\":\"lens\",\"extensions\":{%s}}]", bad_glass[i][0]);
        write_gltf("badglass.gltf", "t.bin", 4, 3, 36, ",\"material\":0", materials);
        expect_input_error("badglass.gltf", bad_glass[i][1]);
    }
}

static void degenerate_triangles_are_dropped_and_counted(void **state)
{
    (void)state;
    /* two triangles over four positions: (0,1,2) is fine, (0,1,3) is collinear */
    unsigned char bin[64] = {0};
    float p[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 2, 0, 0};
    uint16_t idx[6] = {0, 1, 2, 0, 1, 3};
    memcpy(bin, p, sizeof p);
    memcpy(bin + 48, idx, sizeof idx);
    write_file("deg.bin", bin, sizeof bin);
    const char *json =
        "{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}],"
        "\"buffers\":[{\"uri\":\"deg.bin\",\"byteLength\":64}],"
        "\"bufferViews\":[{\"buffer\":0,\"byteLength\":48},{\"buffer\":0,\"byteOffset\":48,\"byteLength\":12}],"
        "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\"},"
        "{\"bufferView\":1,\"componentType\":5123,\"count\":6,\"type\":\"SCALAR\"}]}";
    write_file("deg.gltf", json, strlen(json));
    gk_err e = {0};
    gk_scene *s = gk_scene_load(path_of("deg.gltf"), &e);
    assert_non_null(s);
    assert_int_equal(s->n_triangles, 1);
    assert_int_equal(s->n_degenerate_dropped, 1);
    gk_scene_free(s);
}

static void base_colour_texture_is_decoded_to_linear(void **state)
{
    (void)state;
    gk_image img = {0};
    assert_int_equal(gk_image_alloc(&img, 4, 4, 3), 0);
    for (int i = 0; i < 4 * 4 * 3; i++)
        img.pixels[i] = 0.5f;
    gk_err e = {0};
    char *png = path_of("grey.png");
    assert_int_equal(gk_image_write(png, &img, NULL, &e), 0);
    gk_image_free(&img);
    write_gltf("tex.gltf", "t.bin", 4, 3, 36, ",\"material\":0",
               ",\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}],"
               "\"textures\":[{\"source\":0}],\"images\":[{\"uri\":\"grey.png\"}]");
    gk_scene *s = gk_scene_load(path_of("tex.gltf"), &e);
    if (!s)
        print_error("%s\n", e.msg);
    assert_non_null(s);
    assert_int_equal(s->n_textures, 1);
    assert_int_equal(s->textures[0].width, 4);
    assert_int_equal(s->materials[0].base_color_tex, 0);
    /* 0.5 is stored as 128/255 in 8 bits; its linear value is ~0.216, not 0.5 */
    assert_float_equal(s->textures[0].rgba[0], gk_srgb_to_linear(128.0f / 255.0f), 1e-3f);
    assert_float_equal(s->textures[0].rgba[3], 1.0f, 1e-6f);
    gk_scene_free(s);
}

/* KHR_materials_specular: factors read, textures referenced (colour texture decoded as sRGB, the
 * weight texture as data), defaults where the extension is absent. */
static void specular_extension_is_read(void **state)
{
    (void)state;
    gk_image img = {0};
    assert_int_equal(gk_image_alloc(&img, 2, 2, 4), 0);
    for (int i = 0; i < 2 * 2 * 4; i++)
        img.pixels[i] = 0.5f;
    gk_err e = {0};
    assert_int_equal(gk_image_write(path_of("half.png"), &img, NULL, &e), 0);
    gk_image_free(&img);
    write_gltf("spec.gltf", "t.bin", 4, 3, 36, ",\"material\":0",
               ",\"materials\":[{\"extensions\":{\"KHR_materials_specular\":{\"specularFactor\":0.25,"
               "\"specularColorFactor\":[2,1,0.5],\"specularTexture\":{\"index\":0},"
               "\"specularColorTexture\":{\"index\":1}}}},{\"name\":\"plain\"}],"
               "\"textures\":[{\"source\":0},{\"source\":1}],\"images\":[{\"uri\":\"half.png\"},{\"uri\":\"half.png\"}]");
    gk_scene *s = gk_scene_load(path_of("spec.gltf"), &e);
    if (!s)
        print_error("%s\n", e.msg);
    assert_non_null(s);
    const gk_material *m = &s->materials[0];
    assert_float_equal(m->specular, 0.25f, 1e-7f);
    assert_float_equal(m->specular_color[0], 2.0f, 1e-7f);
    assert_float_equal(m->specular_color[2], 0.5f, 1e-7f);
    assert_int_equal(m->specular_tex, 0);
    assert_int_equal(m->specular_color_tex, 1);
    assert_float_equal(s->textures[0].rgba[3], 128.0f / 255.0f, 1e-3f);                      /* data */
    assert_float_equal(s->textures[1].rgba[0], gk_srgb_to_linear(128.0f / 255.0f), 1e-3f); /* colour */
    const gk_material *plain = &s->materials[1];
    assert_float_equal(plain->specular, 1.0f, 0);
    assert_float_equal(plain->specular_color[1], 1.0f, 0);
    assert_int_equal(plain->specular_tex, -1);
    assert_float_equal(s->materials[s->n_materials - 1].specular, 1.0f, 0); /* the glTF default material */
    gk_scene_free(s);
}

static void glass_extensions_are_read(void **state)
{
    (void)state;
    write_gltf("glass.gltf", "t.bin", 4, 3, 36, ",\"material\":0",
               ",\"materials\":[{\"extensions\":{\"KHR_materials_transmission\":{\"transmissionFactor\":0.75},"
               "\"KHR_materials_ior\":{\"ior\":1.33}}},{\"extensions\":{\"KHR_materials_ior\":{\"ior\":0}}},"
               "{\"name\":\"plain\"}]");
    gk_err e = {0};
    gk_scene *s = gk_scene_load(path_of("glass.gltf"), &e);
    if (!s)
        print_error("%s\n", e.msg);
    assert_non_null(s);
    assert_float_equal(s->materials[0].transmission, 0.75f, 1e-7f);
    assert_float_equal(s->materials[0].ior, 1.33f, 1e-7f);
    assert_float_equal(s->materials[1].ior, 0.0f, 0); /* the extension's special value is allowed */
    assert_float_equal(s->materials[2].transmission, 0.0f, 0); /* defaults */
    assert_float_equal(s->materials[2].ior, 1.5f, 0);
    assert_true(s->features.has_transmission);
    gk_scene_free(s);
}

/* The scene medium (scene.h, gk_medium): read with its defaults, and every malformed value refused
 * with the key named. */
static void scene_medium_is_read_and_validated(void **state)
{
    (void)state;
    char extra[512];
    snprintf(extra, sizeof extra, ",\"extras\":{\"gikiosk\":{\"medium\":{\"sigma_s\":[0.1,0.2,0.3],"
                                  "\"sigma_a\":0.05,\"g\":0.7,\"bounds\":[[-1,0,-1],[1,2,1]]}}}");
    write_gltf("fog.gltf", "t.bin", 4, 3, 36, "", extra);
    gk_err e = {0};
    gk_scene *s = gk_scene_load(path_of("fog.gltf"), &e);
    if (!s)
        print_error("%s\n", e.msg);
    assert_non_null(s);
    assert_true(s->medium.present && s->features.has_medium && s->medium.bounded);
    assert_float_equal(s->medium.sigma_s[2], 0.3f, 1e-7f);
    assert_float_equal(s->medium.sigma_a[1], 0.05f, 1e-7f);
    assert_float_equal(s->medium.g, 0.7f, 1e-7f);
    assert_float_equal(s->medium.box_max.y, 2.0f, 1e-7f);
    gk_scene_free(s);
    /* without the key: no medium */
    write_gltf("clear.gltf", "t.bin", 4, 3, 36, "", "");
    s = gk_scene_load(path_of("clear.gltf"), &e);
    assert_non_null(s);
    assert_false(s->medium.present || s->features.has_medium);
    gk_scene_free(s);

    const char *bad[][2] = {
        {"{\"sigma_s\":-0.1}", "medium.sigma_s"},
        {"{\"sigma_a\":[0.1,-1,0.1]}", "medium.sigma_a"},
        {"{\"sigma_s\":[0.1,0.1]}", "medium.sigma_s"},
        {"{\"sigma_s\":\"thick\"}", "medium.sigma_s"},
        {"{\"sigma_s\":1e999}", "number overflow"}, /* JSON has no NaN/Inf: the parser refuses it */
        {"{\"g\":1.0}", "medium.g"},
        {"{\"g\":-1.5}", "medium.g"},
        {"{\"sigma\":0.1}", "unknown key 'sigma'"},
        {"{\"bounds\":[[0,0,0],[1,-1,1]]}", "medium.bounds"},
        {"{\"bounds\":[[0,0,0]]}", "medium.bounds"},
        {"0.3", "gikiosk.medium must be an object"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        snprintf(extra, sizeof extra, ",\"extras\":{\"gikiosk\":{\"medium\":%s}}", bad[i][0]);
        write_gltf("badfog.gltf", "t.bin", 4, 3, 36, "", extra);
        expect_input_error("badfog.gltf", bad[i][1]);
    }
}

static void memory_loads_read_no_files(void **state)
{
    (void)state;
    /* the same valid document, from memory without a base directory: its .bin may not be read */
    char path[512];
    snprintf(path, sizeof path, "%s/ok.gltf", tmpdir);
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    char buf[4096];
    size_t n = fread(buf, 1, sizeof buf, f);
    fclose(f);
    gk_err e = {0};
    gk_scene *s = gk_scene_load_memory(buf, n, "mem.gltf", NULL, &e);
    assert_null(s);
    assert_int_equal(e.code, GK_EINPUT);
    assert_int_equal(strncmp(e.msg, "mem.gltf: ", 10), 0);
    s = gk_scene_load_memory(buf, n, "mem.gltf", tmpdir, &e);
    assert_non_null(s);
    assert_string_equal(s->name, "mem");
    gk_scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(valid_triangle_loads_with_generated_normals),
        cmocka_unit_test(broken_files_name_the_file_and_the_defect),
        cmocka_unit_test(degenerate_triangles_are_dropped_and_counted),
        cmocka_unit_test(base_colour_texture_is_decoded_to_linear),
        cmocka_unit_test(specular_extension_is_read),
        cmocka_unit_test(glass_extensions_are_read),
        cmocka_unit_test(memory_loads_read_no_files),
        cmocka_unit_test(scene_medium_is_read_and_validated),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
