/* The shader loader and program cache (app/render/shader_source.c, gl_program.c): #include
 * expansion with the once-per-program guard, cycle and missing-file errors naming file:line, and
 * GL compile errors mapped back to the shader file and line. */
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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(includes_expand_once_with_line_directives),
        cmocka_unit_test(include_cycle_and_missing_file_are_errors),
        cmocka_unit_test(compile_errors_name_file_and_line),
        cmocka_unit_test(embedded_shaders_all_present),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
