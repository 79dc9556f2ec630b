/* The shader loader and program cache (app/gl/shader_source.c, gl_program.c): #include
 * expansion with the once-per-program guard, cycle and missing-file errors naming file:line,
 * GL compile errors mapped back to the shader file and line, and uniform locations resolved once
 * per program (a misspelt name fails, an optimised-away one is -1, the block is cached). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "common/gl_fixture.h"
#include "gl/gbuffer_bind.h"
#include "gl/gl_program.h"
#include "gl/shader_source.h"

static gkt_gl gl;
static char dir[256];

static void write_file(const char *rel, const char *text)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", dir, rel);
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

static int setup(void **state)
{
    (void)state;
    snprintf(dir, sizeof dir, "/tmp/gk-shaders-XXXXXX");
    if (!mkdtemp(dir))
        return -1;
    char sub[300];
    snprintf(sub, sizeof sub, "%s/lib", dir);
    mkdir(sub, 0700);
    return gkt_gl_open(&gl);
}

static int teardown(void **state)
{
    (void)state;
    gkt_gl_close(&gl);
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    return system(cmd) == 0 ? 0 : -1;
}

static int count(const char *hay, const char *needle)
{
    int n = 0;
    for (const char *p = hay; (p = strstr(p, needle)); p++)
        n++;
    return n;
}

static void includes_expand_once_with_line_directives(void **state)
{
    (void)state;
    write_file("lib/b.glsl", "float b_value() { return 2.0; }\n");
    write_file("lib/a.glsl", "#include \"lib/b.glsl\"\nfloat a_value() { return b_value(); }\n");
    write_file("main.frag", "precision highp float;\n#include \"lib/a.glsl\"\n  #include \"lib/b.glsl\"\nout vec4 o;\n"
                            "void main() { o = vec4(a_value()); }\n");
    gk_shader_text t;
    gk_err e = {0};
    assert_int_equal(gk_shader_expand(dir, "main.frag", 31, "#define X 1", &t, &e), 0);
    assert_true(strncmp(t.text, "#version 310 es\n#define GK_GLES 31\n#define X 1\n", 46) == 0);
    assert_int_equal(count(t.text, "float b_value()"), 1); /* included twice, expanded once */
    assert_int_equal(t.n_files, 3);
    assert_string_equal(t.files[2], "lib/b.glsl");
    assert_non_null(strstr(t.text, "#line 2 1\n")); /* back in lib/a.glsl after its include */
    assert_non_null(strstr(t.text, "#line 4 0\n")); /* back in main.frag after line 3 */
    gk_shader_text_free(&t);
}

static void include_cycle_and_missing_file_are_errors(void **state)
{
    (void)state;
    write_file("lib/c1.glsl", "#include \"lib/c2.glsl\"\n");
    write_file("lib/c2.glsl", "\n#include \"lib/c1.glsl\"\n");
    write_file("cycle.frag", "#include \"lib/c1.glsl\"\n");
    write_file("missing.frag", "precision highp float;\n\n#include \"lib/nope.glsl\"\n");
    gk_shader_text t;
    gk_err e = {0};
    assert_int_equal(gk_shader_expand(dir, "cycle.frag", 31, NULL, &t, &e), -1);
    assert_int_equal(e.code, GK_ERUNTIME);
    assert_non_null(strstr(e.msg, "lib/c2.glsl:2"));
    assert_non_null(strstr(e.msg, "cycle"));
    assert_int_equal(gk_shader_expand(dir, "missing.frag", 31, NULL, &t, &e), -1);
    assert_non_null(strstr(e.msg, "missing.frag:3"));
    assert_non_null(strstr(e.msg, "lib/nope.glsl"));
}

static void compile_errors_name_file_and_line(void **state)
{
    (void)state;
    write_file("lib/broken.glsl", "float ok_fn() { return 1.0; }\nfloat bad_fn() { return undeclared_x; }\n");
    write_file("uses_broken.frag", "precision highp float;\n#include \"lib/broken.glsl\"\nout vec4 o;\n"
                                   "void main() { o = vec4(bad_fn()); }\n");
    gk_program_cache *c = gk_program_cache_create(dir, 31);
    gk_err e = {0};
    GLuint p = gk_program_get(c, "uses_broken.frag", "uses_broken.frag", NULL, &e);
    (void)p;
    /* The vertex stage is compiled first from the same (fragment) file and fails on the same
       line: either way the message must name the included file and its line 2. */
    printf("# %s\n", e.msg);
    assert_int_equal(e.code, GK_ERUNTIME);
    assert_non_null(strstr(e.msg, "shaders_gles/lib/broken.glsl:2"));
    gk_program_cache_destroy(c);
}

static void embedded_shaders_all_present(void **state)
{
    (void)state;
    /* The program's own shaders come from the embedded table (no --shader-dir). */
    gk_program_cache *c = gk_program_cache_create(NULL, 31);
    gk_err e = {0};
    GLuint p = gk_program_get(c, "common/fullscreen.vert", "direct/light.frag",
                              "#define GK_LIGHT_KIND 5\n#define SHADOW_PCSS 1\n", &e);
    if (!p)
        fail_msg("%s", e.msg);
    assert_true(gk_program_get(c, "common/fullscreen.vert", "direct/light.frag",
                               "#define GK_LIGHT_KIND 5\n#define SHADOW_PCSS 1\n", &e) == p); /* cached */
    gk_program_cache_destroy(c);
}

/* A program with one used uniform (u_tint) and one the compiler drops (u_unused). */
typedef struct tint_uniforms {
    GLint u_tint, u_unused, u_not_listed;
} tint_uniforms;
static const gk_uniform_field tint_fields[] = {GK_UNIFORM(tint_uniforms, u_tint),
                                               GK_UNIFORM(tint_uniforms, u_unused)};
static const gk_uniform_field misspelt_fields[] = {GK_UNIFORM(tint_uniforms, u_tint),
                                                   GK_UNIFORM_AS(tint_uniforms, u_unused, "u_tnit")};

static GLuint tint_program(gk_program_cache *c)
{
    write_file("tint.vert", "layout(location = 0) in vec4 a_pos;\nvoid main() { gl_Position = a_pos; }\n");
    write_file("tint.frag", "precision highp float;\nuniform vec4 u_tint;\nuniform float u_unused;\nout vec4 o;\n"
                            "void main() { o = u_tint; }\n");
    gk_err e = {0};
    GLuint p = gk_program_get(c, "tint.vert", "tint.frag", NULL, &e);
    if (!p)
        fail_msg("%s", e.msg);
    return p;
}

static void misspelt_uniform_fails_naming_it(void **state)
{
    (void)state;
    gk_program_cache *c = gk_program_cache_create(dir, 31);
    GLuint p = tint_program(c);
    gk_err e = {0};
    const tint_uniforms *u = gk_program_uniforms(c, p, GK_FIELDS(misspelt_fields), sizeof *u, &e);
    printf("# %s\n", e.msg);
    assert_null(u);
    assert_int_equal(e.code, GK_ERUNTIME);
    assert_non_null(strstr(e.msg, "'u_tnit'"));
    assert_non_null(strstr(e.msg, "tint.frag")); /* and the program it was looked up in */
    /* A failed table is not cached: it fails again, and the correct table still resolves. */
    gk_err e2 = {0};
    assert_null(gk_program_uniforms(c, p, GK_FIELDS(misspelt_fields), sizeof(tint_uniforms), &e2));
    assert_int_equal(e2.code, GK_ERUNTIME);
    gk_err e3 = {0};
    assert_non_null(gk_program_uniforms(c, p, GK_FIELDS(tint_fields), sizeof(tint_uniforms), &e3));
    assert_int_equal(e3.code, 0);
    gk_program_cache_destroy(c);
}

static void optimised_away_uniform_is_minus_one(void **state)
{
    (void)state;
    gk_program_cache *c = gk_program_cache_create(dir, 31);
    GLuint p = tint_program(c);
    gk_err e = {0};
    const tint_uniforms *u = gk_program_uniforms(c, p, GK_FIELDS(tint_fields), sizeof *u, &e);
    if (!u)
        fail_msg("%s", e.msg);
    assert_int_equal(e.code, 0);
    assert_int_equal(u->u_tint, glGetUniformLocation(p, "u_tint"));
    assert_true(u->u_tint >= 0);
    assert_int_equal(u->u_unused, -1); /* declared, unused: dropped by the compiler, not an error */
    assert_int_equal(u->u_not_listed, -1); /* not in the table */
    gk_program_cache_destroy(c);
}

static void uniform_block_is_cached(void **state)
{
    (void)state;
    gk_program_cache *c = gk_program_cache_create(dir, 31);
    GLuint p = tint_program(c);
    gk_err e = {0};
    const tint_uniforms *a = gk_program_uniforms(c, p, GK_FIELDS(tint_fields), sizeof *a, &e);
    const tint_uniforms *b = gk_program_uniforms(c, p, GK_FIELDS(tint_fields), sizeof *b, &e);
    assert_non_null(a);
    assert_ptr_equal(a, b);
    /* Another program has its own block. */
    GLuint q = gk_program_get(c, "tint.vert", "tint.frag", "#define OTHER 1\n", &e);
    assert_true(q != 0 && q != p);
    const tint_uniforms *d = gk_program_uniforms(c, q, GK_FIELDS(tint_fields), sizeof *d, &e);
    assert_non_null(d);
    assert_ptr_not_equal(a, d);
    gk_program_cache_destroy(c);
}

/* The cache has no fixed cap: 200 variants (more than the 96, then 192, programs a fixed array once
   held; a program past such a cap had no uniforms) are each compiled once, keep their uniforms, and
   are found again, the first ones included after the array has grown. */
static void cache_grows_past_any_fixed_cap(void **state)
{
    (void)state;
    enum { VARIANTS = 200 };
    gk_program_cache *c = gk_program_cache_create(dir, 31);
    (void)tint_program(c); /* writes the shader files */
    GLuint progs[VARIANTS];
    const tint_uniforms *blocks[VARIANTS];
    for (int i = 0; i < VARIANTS; i++) {
        char defines[48];
        snprintf(defines, sizeof defines, "#define VARIANT %d\n", i);
        gk_err e = {0};
        progs[i] = gk_program_get(c, "tint.vert", "tint.frag", defines, &e);
        if (!progs[i])
            fail_msg("variant %d: %s", i, e.msg);
        blocks[i] = gk_program_uniforms(c, progs[i], GK_FIELDS(tint_fields), sizeof *blocks[i], &e);
        if (!blocks[i])
            fail_msg("variant %d: %s", i, e.msg);
        assert_true(blocks[i]->u_tint >= 0);
    }
    for (int i = 0; i < VARIANTS; i++) {
        char defines[48];
        snprintf(defines, sizeof defines, "#define VARIANT %d\n", i);
        gk_err e = {0};
        assert_int_equal(gk_program_get(c, "tint.vert", "tint.frag", defines, &e), progs[i]); /* not recompiled */
        assert_ptr_equal(gk_program_uniforms(c, progs[i], GK_FIELDS(tint_fields), sizeof *blocks[i], &e), blocks[i]);
    }
    gk_program_cache_destroy(c);
}

/* The G-buffer contract (common/gbuffer.glsl) resolves in every program that includes it: the
   emission pass uses only u_gb_emission, the rest is -1, nothing is misspelt. */
typedef struct gb_only_uniforms {
    gk_gbuffer_uniforms gb;
} gb_only_uniforms;
static const gk_uniform_field gb_only_fields[] = {GK_GBUFFER_FIELDS(gb_only_uniforms, gb)};

static void gbuffer_contract_resolves(void **state)
{
    (void)state;
    gk_program_cache *c = gk_program_cache_create(NULL, 31);
    gk_err e = {0};
    GLuint p = gk_program_get(c, "common/fullscreen.vert", "direct/emission.frag", NULL, &e);
    const gb_only_uniforms *u = p ? gk_program_uniforms(c, p, GK_FIELDS(gb_only_fields), sizeof *u, &e) : NULL;
    if (!u)
        fail_msg("%s", e.msg);
    assert_true(u->gb.u_gb_emission >= 0);
    assert_int_equal(u->gb.u_inv_viewproj, -1);
    assert_int_equal(u->gb.u_gb_depth, -1);
    GLuint l = gk_program_get(c, "common/fullscreen.vert", "direct/light.frag", "#define GK_LIGHT_KIND 0\n", &e);
    const gb_only_uniforms *ul = l ? gk_program_uniforms(c, l, GK_FIELDS(gb_only_fields), sizeof *ul, &e) : NULL;
    if (!ul)
        fail_msg("%s", e.msg);
    assert_true(ul->gb.u_gb_depth >= 0 && ul->gb.u_inv_viewproj >= 0 && ul->gb.u_viewport >= 0);
    gk_program_cache_destroy(c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(includes_expand_once_with_line_directives),
        cmocka_unit_test(include_cycle_and_missing_file_are_errors),
        cmocka_unit_test(compile_errors_name_file_and_line),
        cmocka_unit_test(embedded_shaders_all_present),
        cmocka_unit_test(misspelt_uniform_fails_naming_it),
        cmocka_unit_test(optimised_away_uniform_is_minus_one),
        cmocka_unit_test(uniform_block_is_cached),
        cmocka_unit_test(cache_grows_past_any_fixed_cap),
        cmocka_unit_test(gbuffer_contract_resolves),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
