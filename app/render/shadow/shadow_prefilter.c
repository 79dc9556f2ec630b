/* Compute passes that derive prefiltered shadow data from the shared depth maps (see
 * shadow_prefilter.h and shaders_gles/shadow/vssm_{linearize,hsm,sat}.comp). */
#include "shadow_prefilter.h"

#include "gl/gl_target.h"

#include <math.h>
#include <stdio.h>

static GLuint groups(int n, int local) { return (GLuint)((n + local - 1) / local); }

int gk_sat_bits(int size)
{
    double w = ceil(GK_SOFT_MAX_KERNEL * size) + 2.0; /* widest box, plus the interpolated box's extra texel */
    int need = (int)ceil(log2(w * w));
    int bits = 32 - need;
    return bits > 24 ? 24 : bits; /* beyond 24 bits the fp32 values being quantised have no more */
}

int gk_pf_levels(int size)
{
    int l = 1;
    while ((size >> l) > 0)
        l++;
    return l;
}

GLuint gk_pf_array_create(GLenum format, int size, int layers, int levels, bool linear, gk_err *e)
{
    while (glGetError() != GL_NO_ERROR) {
    }
    if (levels <= 0)
        levels = gk_pf_levels(size);
    GLuint t = 0;
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D_ARRAY, t);
    glTexStorage3D(GL_TEXTURE_2D_ARRAY, levels, format, size, size, layers);
    GLenum min = linear ? (levels > 1 ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR)
                        : (levels > 1 ? GL_NEAREST_MIPMAP_NEAREST : GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, (GLint)min);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, linear ? GL_LINEAR : GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
    GLenum err = glGetError();
    if (err != GL_NO_ERROR) {
        glDeleteTextures(1, &t);
        gk_fail(e, GK_ERUNTIME, "soft-shadow texture %dx%dx%d (format 0x%04x, %d levels): %s", size, size, layers,
                (unsigned)format, levels, gk_gl_error_name(err));
        return 0;
    }
    return t;
}

void gk_pf_bind(GLint loc, GLuint tex, int unit)
{
    glActiveTexture(GL_TEXTURE0 + (GLenum)unit);
    glBindTexture(GL_TEXTURE_2D_ARRAY, tex);
    glUniform1i(loc, unit);
}

/* shadow/vssm_linearize.comp */
typedef struct linearize_uniforms {
    GLint u_depth, u_proj, u_size;
} linearize_uniforms;
static const gk_uniform_field linearize_fields[] = {GK_UNIFORM(linearize_uniforms, u_depth),
                                                    GK_UNIFORM(linearize_uniforms, u_proj),
                                                    GK_UNIFORM(linearize_uniforms, u_size)};

/* shadow/vssm_hsm.comp */
typedef struct hsm_uniforms {
    GLint u_src_size, u_dst_size;
} hsm_uniforms;
static const gk_uniform_field hsm_fields[] = {GK_UNIFORM(hsm_uniforms, u_src_size), GK_UNIFORM(hsm_uniforms, u_dst_size)};

/* shadow/vssm_sat.comp, rows and columns passes */
typedef struct sat_uniforms {
    GLint u_z, u_size, u_q, u_range;
} sat_uniforms;
static const gk_uniform_field sat_fields[] = {GK_UNIFORM(sat_uniforms, u_z), GK_UNIFORM(sat_uniforms, u_size),
                                              GK_UNIFORM(sat_uniforms, u_q), GK_UNIFORM(sat_uniforms, u_range)};

int gk_pf_linearize(gk_program_cache *progs, GLuint depth, const gk_shadow_view *v, GLuint zmin, GLuint zmax,
                    gk_err *e)
{
    GLuint p = gk_program_get_compute(progs, "shadow/vssm_linearize.comp", zmax ? "#define WITH_MAX 1\n" : NULL, e);
    const linearize_uniforms *u = p ? gk_program_uniforms(progs, p, GK_FIELDS(linearize_fields), sizeof *u, e) : NULL;
    if (!u)
        return -1;
    glUseProgram(p);
    gk_pf_bind(u->u_depth, depth, 0);
    glUniform3f(u->u_proj, v->znear, v->zfar, v->ortho ? 1.0f : 0.0f);
    glUniform1i(u->u_size, v->map_size);
    glBindImageTexture(0, zmin, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32F);
    if (zmax)
        glBindImageTexture(1, zmax, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32F);
    glDispatchCompute(groups(v->map_size, 8), groups(v->map_size, 8), (GLuint)v->n_faces);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    return 0;
}

int gk_pf_hsm(gk_program_cache *progs, GLuint zmin, GLuint zmax, int size, int layers, gk_err *e)
{
    GLuint p = gk_program_get_compute(progs, "shadow/vssm_hsm.comp", NULL, e);
    const hsm_uniforms *u = p ? gk_program_uniforms(progs, p, GK_FIELDS(hsm_fields), sizeof *u, e) : NULL;
    if (!u)
        return -1;
    glUseProgram(p);
    int levels = gk_pf_levels(size);
    for (int l = 1; l < levels; l++) {
        int src = size >> (l - 1), dst = size >> l;
        glUniform1i(u->u_src_size, src);
        glUniform1i(u->u_dst_size, dst);
        glBindImageTexture(0, zmin, l - 1, GL_TRUE, 0, GL_READ_ONLY, GL_R32F);
        glBindImageTexture(1, zmax, l - 1, GL_TRUE, 0, GL_READ_ONLY, GL_R32F);
        glBindImageTexture(2, zmin, l, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32F);
        glBindImageTexture(3, zmax, l, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32F);
        glDispatchCompute(groups(dst, 8), groups(dst, 8), (GLuint)layers);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    }
    return 0;
}

int gk_pf_sat(gk_program_cache *progs, int basis, GLuint z, int size, int layers, float q, float range, GLuint out0,
              GLuint out1, GLuint tmp0, GLuint tmp1, gk_err *e)
{
    char defs[96];
    snprintf(defs, sizeof defs, "#define SAT_ROWS 1\n#define SAT_BASIS %d\n", basis);
    GLuint rows = gk_program_get_compute(progs, "shadow/vssm_sat.comp", defs, e);
    snprintf(defs, sizeof defs, "#define SAT_COLS 1\n#define SAT_BASIS %d\n", basis);
    GLuint cols = rows ? gk_program_get_compute(progs, "shadow/vssm_sat.comp", defs, e) : 0;
    const sat_uniforms *ur = cols ? gk_program_uniforms(progs, rows, GK_FIELDS(sat_fields), sizeof *ur, e) : NULL;
    const sat_uniforms *uc = ur ? gk_program_uniforms(progs, cols, GK_FIELDS(sat_fields), sizeof *uc, e) : NULL;
    if (!uc)
        return -1;
    GLenum fmt = basis == 0 ? GL_R32UI : GL_RGBA32UI;
    GLuint r0 = basis == 0 ? out0 : tmp0, r1 = basis == 0 ? out1 : tmp1;
    glUseProgram(rows);
    gk_pf_bind(ur->u_z, z, 0);
    glUniform1i(ur->u_size, size);
    glUniform1f(ur->u_q, q);
    glUniform1f(ur->u_range, range);
    glBindImageTexture(0, r0, 0, GL_TRUE, 0, GL_WRITE_ONLY, fmt);
    glBindImageTexture(1, r1, 0, GL_TRUE, 0, GL_WRITE_ONLY, fmt);
    glDispatchCompute(groups(size, 64), (GLuint)layers, 1);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    glUseProgram(cols);
    glUniform1i(uc->u_size, size);
    if (basis == 0) {
        glBindImageTexture(0, out0, 0, GL_TRUE, 0, GL_READ_WRITE, fmt);
        glBindImageTexture(1, out1, 0, GL_TRUE, 0, GL_READ_WRITE, fmt);
    } else {
        glBindImageTexture(0, tmp0, 0, GL_TRUE, 0, GL_READ_ONLY, fmt);
        glBindImageTexture(1, tmp1, 0, GL_TRUE, 0, GL_READ_ONLY, fmt);
        glBindImageTexture(2, out0, 0, GL_TRUE, 0, GL_WRITE_ONLY, fmt);
        glBindImageTexture(3, out1, 0, GL_TRUE, 0, GL_WRITE_ONLY, fmt);
    }
    glDispatchCompute(groups(size, 64), (GLuint)layers, 1);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    return 0;
}
