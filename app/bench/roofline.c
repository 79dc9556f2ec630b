/* The roofline micro-benchmark (roofline.h): one compute dispatch per kind of fetch, timed by the
 * renderer's timer (CPU mode, fence at each pass boundary, as `gikiosk bench` times frames). */
#include "roofline.h"
#include "roofline_internal.h"

#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl/frame_report.h"
#include "gl/gl_timing.h"

typedef enum { KIND_TEX3D, KIND_TEX2D, KIND_IMAGE3D, KIND_SSBO, KIND_RASTER } fetch_kind;

typedef struct roofline_case {
    const char *name;
    const char *format;
    fetch_kind kind;
    GLenum internal_format;
    bool nearest;   /* not filterable in GLES 3.1 (32-bit float, integer, depth): texelFetch */
    int size;       /* level-0 side: vct's default 64³ volume; a 512² shadow map / SAT */
} roofline_case;

/* The single-channel nearest kinds are what the shadow lookups and vpl's exact visibility read
   (app/render/render_work.c, app/gi/vpl/vpl_work.c): a 32-bit depth map, VSSM's min/max mips and
   CSSM's range (R32F), the summed-area tables (R32UI), vpl's paraboloid depths (R16F). The
   storage-buffer kinds are vec4 loads from a buffer of size³ of them, as radiosity's bounces gather
   their links' radiance (app/gi/radiosity/rad_work.c), and atomicAdd to a buffer of size³ uints, as
   vct's voxelizer sums its fragments into the scratch buffer (vct_work.c). The raster kind is
   fragments, not fetches: the rate at which a flat shader fills an R16F target with a depth test,
   as the passes that rasterize (vpl's VAL maps) do; its size is the fill's (roofline_fill.c). */
static const roofline_case cases[] = {
    {.name = "tex3d_rgba8_trilinear", .format = "rgba8", .kind = KIND_TEX3D, .internal_format = GL_RGBA8, .size = 64},
    {.name = "tex3d_rgba16f_trilinear", .format = "rgba16f", .kind = KIND_TEX3D, .internal_format = GL_RGBA16F,
     .size = 64},
    {.name = "tex2d_rgba8_trilinear", .format = "rgba8", .kind = KIND_TEX2D, .internal_format = GL_RGBA8, .size = 512},
    {.name = "tex2d_rgba16f_trilinear", .format = "rgba16f", .kind = KIND_TEX2D, .internal_format = GL_RGBA16F,
     .size = 512},
    {.name = "tex2d_rgba32f_nearest", .format = "rgba32f", .kind = KIND_TEX2D, .internal_format = GL_RGBA32F,
     .nearest = true, .size = 512},
    {.name = "tex2d_depth32f_nearest", .format = "depth32f", .kind = KIND_TEX2D,
     .internal_format = GL_DEPTH_COMPONENT32F, .nearest = true, .size = 512},
    {.name = "tex2d_r32f_nearest", .format = "r32f", .kind = KIND_TEX2D, .internal_format = GL_R32F, .nearest = true,
     .size = 512},
    {.name = "tex2d_r32ui_nearest", .format = "r32ui", .kind = KIND_TEX2D, .internal_format = GL_R32UI,
     .nearest = true, .size = 512},
    {.name = "tex2d_r16f_nearest", .format = "r16f", .kind = KIND_TEX2D, .internal_format = GL_R16F, .nearest = true,
     .size = 512},
    {.name = "image3d_rgba8_load", .format = "rgba8", .kind = KIND_IMAGE3D, .internal_format = GL_RGBA8, .size = 64},
    {.name = "image3d_rgba16f_load", .format = "rgba16f", .kind = KIND_IMAGE3D, .internal_format = GL_RGBA16F,
     .size = 64},
    /* size³ a power of two (roofline.comp wraps its index with a mask); 16³: 64 KB, in cache, as
       radiosity's node radiance is (64³, 4 MB: 23-76 M loads/s in three rounds, against 104-124 at
       16³ in three more, load average 8-9, not interleaved) */
    {.name = "ssbo_rgba32f_load", .format = "rgba32f", .kind = KIND_SSBO, .internal_format = GL_RGBA32F, .size = 16},
    {.name = "ssbo_r32ui_atomic", .format = "r32ui", .kind = KIND_SSBO, .internal_format = GL_R32UI, .size = 16},
    {.name = "raster_r16f_depth_fill", .format = "r16f", .kind = KIND_RASTER, .internal_format = GL_R16F, .size = 64},
};

void gk_roofline_opts_defaults(gk_roofline_opts *o)
{
    /* 64³ invocations x 64 fetches = 16.8 M fetches: ~0.1 s at llvmpipe's ~170 M/s on 2 cores,
     * well above the fence's resolution, a blink on a GPU */
    *o = (gk_roofline_opts){.invocations = 64 * 64 * 64, .fetches = 64, .reps = 5};
}

static int levels_of(int size)
{
    int n = 1;
    while (size > 1) {
        size /= 2;
        n++;
    }
    return n;
}

/* How GLES takes texels of a sized format: RGBA8 as bytes, integers as uints, depth and the float
   formats as floats (R16F accepts GL_FLOAT). */
typedef struct upload_format {
    GLenum format, type;
    int channels;
} upload_format;

static upload_format upload_format_of(GLenum internal_format)
{
    switch (internal_format) {
    case GL_RGBA8: return (upload_format){GL_RGBA, GL_UNSIGNED_BYTE, 4};
    case GL_R32UI: return (upload_format){GL_RED_INTEGER, GL_UNSIGNED_INT, 1};
    case GL_R32F:
    case GL_R16F: return (upload_format){GL_RED, GL_FLOAT, 1};
    case GL_DEPTH_COMPONENT32F: return (upload_format){GL_DEPTH_COMPONENT, GL_FLOAT, 1};
    default: return (upload_format){GL_RGBA, GL_FLOAT, 4};
    }
}

/* A texture of the case's format with every level filled with a non-constant pattern (a constant
 * one would let a clever driver fold the fetches). */
static GLuint make_texture(const roofline_case *c)
{
    GLenum target = c->kind == KIND_TEX2D ? GL_TEXTURE_2D : GL_TEXTURE_3D;
    int levels = c->kind == KIND_IMAGE3D || c->nearest ? 1 : levels_of(c->size);
    GLuint tex;
    glGenTextures(1, &tex);
    glBindTexture(target, tex);
    int depth = c->kind == KIND_TEX2D ? 1 : c->size;
    if (target == GL_TEXTURE_3D)
        glTexStorage3D(target, levels, c->internal_format, c->size, c->size, c->size);
    else
        glTexStorage2D(target, levels, c->internal_format, c->size, c->size);
    size_t texels = (size_t)c->size * c->size * depth;
    upload_format up = upload_format_of(c->internal_format);
    void *data = malloc(texels * (size_t)up.channels * 4);
    if (!data) {
        glDeleteTextures(1, &tex);
        return 0;
    }
    for (size_t i = 0; i < texels * (size_t)up.channels; i++) {
        unsigned v = (unsigned)((i * 2654435761u) >> 24 & 255);
        if (up.type == GL_UNSIGNED_BYTE)
            ((unsigned char *)data)[i] = (unsigned char)v;
        else if (up.type == GL_UNSIGNED_INT)
            ((GLuint *)data)[i] = v;
        else
            ((float *)data)[i] = (float)v / 255.0f;
    }
    for (int l = 0, s = c->size, d = depth; l < levels; l++, s = s > 1 ? s / 2 : 1, d = d > 1 ? d / 2 : 1) {
        if (target == GL_TEXTURE_3D)
            glTexSubImage3D(target, l, 0, 0, 0, s, s, d, up.format, up.type, data);
        else
            glTexSubImage2D(target, l, 0, 0, s, s, up.format, up.type, data);
    }
    free(data);
    GLenum min = c->nearest ? GL_NEAREST : GL_LINEAR_MIPMAP_LINEAR;
    glTexParameteri(target, GL_TEXTURE_MIN_FILTER, (GLint)min);
    glTexParameteri(target, GL_TEXTURE_MAG_FILTER, c->nearest ? GL_NEAREST : GL_LINEAR);
    return tex;
}

/* The storage-buffer case's source: size³ vec4s of the same pattern. */
static GLuint make_buffer(const roofline_case *c)
{
    /* vec4s of the pattern, or size³ uints (the atomic kind) of it */
    size_t n = (size_t)c->size * c->size * c->size * (c->internal_format == GL_R32UI ? 1 : 4);
    float *data = malloc(n * sizeof(float));
    if (!data)
        return 0;
    for (size_t i = 0; i < n; i++) {
        unsigned v = (unsigned)((i * 2654435761u) >> 24 & 255);
        if (c->internal_format == GL_R32UI)
            ((GLuint *)data)[i] = v;
        else
            data[i] = (float)v / 255.0f;
    }
    GLuint buf;
    glGenBuffers(1, &buf);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, buf);
    glBufferData(GL_SHADER_STORAGE_BUFFER, (GLsizeiptr)(n * sizeof(float)), data, GL_DYNAMIC_COPY);
    free(data);
    return buf;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

double gk_roofline_time(const gk_roofline_opts *o, void (*run)(void *ctx), void (*after_warmup)(void *ctx), void *ctx)
{
    gk_timer *timer = gk_timer_create(false);
    double ms[64];
    int reps = o->reps < 64 ? o->reps : 64;
    for (int i = -1; i < reps; i++) {   /* i = -1: untimed, compiles the JIT code */
        if (i == 0 && after_warmup)
            after_warmup(ctx);
        gk_frame_report rep;
        gk_timer_frame_begin(timer);
        gk_timer_pass_begin(timer, "roofline");
        run(ctx);
        gk_timer_pass_end(timer);
        gk_timer_frame_end(timer, &rep);
        if (i >= 0)
            ms[i] = gk_frame_report_ms(&rep, "roofline");
    }
    gk_timer_destroy(timer);
    qsort(ms, (size_t)reps, sizeof ms[0], cmp_double);
    return ms[reps / 2];
}

void gk_roofline_result_set(gk_roofline_result *r, const char *name, const char *format, int size,
                            const gk_roofline_opts *o, double median_ms)
{
    r->name = name;
    r->format = format;
    r->size = size;
    r->fetches = (double)o->invocations * o->fetches;
    r->expected = r->fetches * o->reps;
    r->unit = "fetches";
    r->median_ms = median_ms;
    r->fetches_per_s = median_ms > 0.0 ? r->fetches / (median_ms * 1e-3) : 0.0;
}

struct dispatch {
    const gk_roofline_opts *o;
    GLuint counter;
};

static void dispatch_run(void *ctx)
{
    const struct dispatch *d = ctx;
    glDispatchCompute((GLuint)(d->o->invocations / 64), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

/* the untimed dispatch's count is not the timed ones' */
static void dispatch_zero_counter(void *ctx)
{
    const struct dispatch *d = ctx;
    const GLuint zero = 0;
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, d->counter);
    glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof zero, &zero);
}

static int measure_case(gk_program_cache *programs, const gk_roofline_opts *o, const roofline_case *c,
                        gk_roofline_result *r, gk_err *e)
{
    if (c->kind == KIND_RASTER)
        return gk_roofline_fill(programs, o, c->name, c->format, r, e);
    char defines[160];
    snprintf(defines, sizeof defines, "#define %s 1\n%s%s%s",
             c->kind == KIND_TEX3D   ? "TEX3D"
             : c->kind == KIND_TEX2D ? "TEX2D"
             : c->kind == KIND_SSBO  ? "SSBO"
                                     : "IMAGE3D",
             c->nearest ? "#define NEAREST 1\n" : "",
             c->internal_format == GL_RGBA8 ? "#define FORMAT_RGBA8 1\n" : "",
             c->internal_format == GL_R32UI ? "#define FORMAT_UINT 1\n" : "");
    GLuint prog = gk_program_get_compute(programs, "bench/roofline.comp", defines, e);
    if (!prog)
        return -1;
    GLuint tex = c->kind == KIND_SSBO ? make_buffer(c) : make_texture(c);
    if (!tex)
        return gk_fail(e, GK_ERUNTIME, "roofline: out of memory for the %s texture", c->name);
    GLuint bufs[2];
    glGenBuffers(2, bufs);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, bufs[0]);
    glBufferData(GL_SHADER_STORAGE_BUFFER, sizeof(GLuint), NULL, GL_DYNAMIC_READ);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, bufs[1]);
    glBufferData(GL_SHADER_STORAGE_BUFFER, (GLsizeiptr)o->invocations * 16, NULL, GL_DYNAMIC_COPY);
    glUseProgram(prog);
    gk_uniform_1i(prog, "u_fetches", o->fetches);
    gk_uniform_1i(prog, "u_size", c->size);
    /* between levels 1 and 2: a trilinear blend of two mips, as a cone sample a few voxels wide */
    gk_uniform_1f(prog, "u_lod", c->kind == KIND_IMAGE3D || c->kind == KIND_SSBO || c->nearest ? 0.0f : 1.5f);
    if (c->kind == KIND_SSBO) {
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, tex);
    } else if (c->kind == KIND_IMAGE3D) {
        glBindImageTexture(0, tex, 0, GL_TRUE, 0, GL_READ_ONLY, c->internal_format);
    } else {
        glActiveTexture(GL_TEXTURE0);
        glBindTexture(c->kind == KIND_TEX2D ? GL_TEXTURE_2D : GL_TEXTURE_3D, tex);
        gk_uniform_1i(prog, "u_tex", 0);
    }
    struct dispatch d = {o, bufs[0]};
    double median = gk_roofline_time(o, dispatch_run, dispatch_zero_counter, &d);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, bufs[0]);
    const GLuint *counted = glMapBufferRange(GL_SHADER_STORAGE_BUFFER, 0, sizeof(GLuint), GL_MAP_READ_BIT);
    r->counted = counted ? *counted : 0;
    glUnmapBuffer(GL_SHADER_STORAGE_BUFFER);
    glDeleteBuffers(2, bufs);
    if (c->kind == KIND_SSBO)
        glDeleteBuffers(1, &tex);
    else
        glDeleteTextures(1, &tex);
    GLenum err = glGetError();
    if (err != GL_NO_ERROR)
        return gk_fail(e, GK_ERUNTIME, "roofline: %s: GL error 0x%04x", c->name, err);
    gk_roofline_result_set(r, c->name, c->format, c->size, o, median);
    return 0;
}

int gk_roofline_measure(gk_program_cache *programs, const gk_roofline_opts *o, gk_roofline_result *out,
                        int max, gk_err *e)
{
    if (o->invocations <= 0 || o->invocations % 64 || o->fetches <= 0 || o->reps <= 0)
        return gk_fail(e, GK_EINPUT, "roofline: invocations must be a positive multiple of 64, fetches and reps positive");
    int n = 0;
    for (size_t i = 0; i < sizeof cases / sizeof cases[0] && n < max; i++, n++)
        if (measure_case(programs, o, &cases[i], &out[n], e) < 0)
            return -1;
    return n;
}

int gk_roofline_write_csv(const gk_roofline_result *r, int n, const char *path, gk_err *e)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return gk_fail(e, GK_ERUNTIME, "%s: cannot write", path);
    fprintf(f, "name,format,size,fetches,median_ms,fetches_per_s\n");
    for (int i = 0; i < n; i++)
        fprintf(f, "%s,%s,%d,%.0f,%.4f,%.6g\n", r[i].name, r[i].format, r[i].size, r[i].fetches, r[i].median_ms,
                r[i].fetches_per_s);
    return fclose(f) == 0 ? 0 : gk_fail(e, GK_ERUNTIME, "%s: write failed", path);
}
