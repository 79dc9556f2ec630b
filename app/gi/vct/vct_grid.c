/* The voxel grid: fitted to the scene's bounds (largest extent, cubic voxels, a margin of
 * VCT_MARGIN voxels each side so that wide cones leaving the scene sample empty border texels),
 * and the GPU resources at a budget. */
#include <math.h>
#include <string.h>

#include "base/log.h"
#include "gl/gl_target.h"
#include "vct_internal.h"

#define VCT_MARGIN 2

static int log2i(int x)
{
    int l = 0;
    while ((1 << (l + 1)) <= x)
        l++;
    return l;
}

/* Levels of a chain from `res` down to 2^3 (the thesis never allocates 1^3): log2(res) levels. */
static int chain_levels(int res) { return log2i(res) > 0 ? log2i(res) : 1; }

static long chain_texels(int res, int first_level)
{
    long n = 0;
    for (int l = first_level; l < chain_levels(res); l++) {
        long r = res >> l;
        n += r * r * r;
    }
    return n;
}

int gk_vct_channels(bool emissive) { return emissive ? 13 : 10; }

long gk_vct_memory_formula(int res, bool aniso, bool aniso_level0, int channels, int trace_w, int trace_h,
                           int n_triangles)
{
    long r3 = (long)res * res * res;
    long bytes = (long)channels * 4 * r3;                         /* scratch SSBO */
    bytes += 8 * (aniso ? r3 : chain_texels(res, 0));            /* level 0 RGBA16F (+ iso chain) */
    if (aniso)
        bytes += 6L * 8 * chain_texels(res, aniso_level0 ? 0 : 1); /* six directional chains */
    bytes += 2L * 8 * trace_w * trace_h;                          /* diffuse + specular targets */
    bytes += (long)n_triangles * VCT_TRI_FLOATS * 4;              /* triangle SSBO */
    return bytes;
}

/* The scratch SSBO is bound whole, so res^3 * channels * 4 must fit GL_MAX_SHADER_STORAGE_BLOCK_SIZE
   (128 MiB on llvmpipe and the GLES 3.1 minimum): 128^3 fits, 256^3 does not. */
int vct_max_res_allowed(int channels)
{
    GLint64 max_block = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
    int res = 256;
    while (res > 32 && (long)res * res * res * channels * 4 > (long)max_block)
        res /= 2;
    return res;
}

void vct_grid_fit(gk_vct *v, const gk_scene *s, int res)
{
    vec3 lo = s->bmin, hi = s->bmax;
    vec3 ext = v3_sub(hi, lo);
    float e = v3_maxc(ext);
    if (!(e > 0.0f))
        e = 1.0f;
    v->res = res;
    v->size = e * (float)res / (float)(res - 2 * VCT_MARGIN);
    v->voxel = v->size / (float)res;
    vec3 c = v3_scale(v3_add(lo, hi), 0.5f);
    v->origin[0] = c.x - 0.5f * v->size + v->opt.grid_offset[0] * v->voxel;
    v->origin[1] = c.y - 0.5f * v->size + v->opt.grid_offset[1] * v->voxel;
    v->origin[2] = c.z - 0.5f * v->size + v->opt.grid_offset[2] * v->voxel;
    v->levels = chain_levels(res);
    v->stats.res = res;
    memcpy(v->stats.grid_origin, v->origin, sizeof v->origin);
    v->stats.grid_size = v->size;
    v->stats.voxel_size = v->voxel;
}

/* depth_mul 2: the packed directional chains (two views of one axis stacked along z) */
static GLuint tex3d(int res, int levels, int depth_mul)
{
    GLuint t;
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_3D, t);
    glTexStorage3D(GL_TEXTURE_3D, levels, GL_RGBA16F, res, res, res * depth_mul);
    glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, levels > 1 ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
    glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    glBindTexture(GL_TEXTURE_3D, 0);
    return t;
}

void vct_free_gpu(gk_vct *v)
{
    if (v->scratch_ssbo)
        glDeleteBuffers(1, &v->scratch_ssbo);
    if (v->vox0)
        glDeleteTextures(1, &v->vox0);
    if (v->vox_bounce)
        glDeleteTextures(1, &v->vox_bounce);
    if (v->axis_ssbo)
        glDeleteBuffers(1, &v->axis_ssbo);
    v->axis_ssbo = 0;
    if (v->thin_ssbo)
        glDeleteBuffers(1, &v->thin_ssbo);
    v->thin_ssbo = 0;
    if (v->thin_count_ssbo)
        glDeleteBuffers(1, &v->thin_count_ssbo);
    v->thin_count_ssbo = 0;
    v->thin_voxels = 0;
    v->axis_valid = false;
    for (int i = 0; i < 3; i++)
        if (v->voxp[i])
            glDeleteTextures(1, &v->voxp[i]);
    v->scratch_ssbo = v->vox0 = v->vox_bounce = 0;
    memset(v->voxp, 0, sizeof v->voxp);
    v->allocated = false;
}

int vct_alloc(gk_vct *v, const vct_budget *b, gk_err *e)
{
    vct_free_gpu(v);
    while (glGetError() != GL_NO_ERROR) {
    }
    int channels = gk_vct_channels(v->emissive);
    long r3 = (long)b->res * b->res * b->res;
    glGenBuffers(1, &v->scratch_ssbo);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, v->scratch_ssbo);
    glBufferData(GL_SHADER_STORAGE_BUFFER, (GLsizeiptr)(r3 * channels * 4), NULL, GL_DYNAMIC_COPY);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    v->vox0 = tex3d(b->res, b->aniso ? 1 : chain_levels(b->res), 1);
    if (b->aniso) {
        int first = b->aniso_level0 ? 0 : 1;   /* the map level of the chains' first */
        for (int a = 0; a < 3; a++)
            v->voxp[a] = tex3d(b->res >> first, chain_levels(b->res) - first, 2);
    }
    GLenum err = glGetError();
    if (err != GL_NO_ERROR) {
        vct_free_gpu(v);
        return gk_fail(e, GK_ERUNTIME, "vct: allocating the %d^3 voxel grid failed (GL error 0x%x)", b->res, err);
    }
    v->cur = *b;
    v->allocated = true;
    v->need_voxelize = v->need_inject = true;
    return 0;
}

long gk_vct_bounce_memory(int res, bool aniso)
{
    long r3 = (long)res * res * res;
    return 8 * (aniso ? r3 : chain_texels(res, 0));
}

long gk_vct_axis_clamp_memory(int res) { return 3L * 4 * res * res * res; }
long gk_vct_thin_flag_memory(int res) { return 4L * res * res * res; }

int vct_ensure_bounce_target(gk_vct *v, gk_err *e)
{
    if (v->vox_bounce)
        return 0;
    v->vox_bounce = tex3d(v->res, v->cur.aniso ? 1 : chain_levels(v->res), 1);
    GLenum err = glGetError();
    if (err != GL_NO_ERROR)
        return gk_fail(e, GK_ERUNTIME, "vct: allocating the %d^3 second-bounce grid failed (GL error 0x%x)", v->res, err);
    return 0;
}

int vct_ensure_trace_targets(gk_vct *v, int full_w, int full_h, float scale, gk_err *e)
{
    int block = (int)lroundf(1.0f / scale);
    if (block < 1)
        block = 1;
    int w = (full_w + block - 1) / block, h = (full_h + block - 1) / block;
    if (v->trace_diffuse && w == v->trace_w && h == v->trace_h && full_w == v->full_w && full_h == v->full_h)
        return 0;
    if (v->trace_diffuse)
        glDeleteTextures(1, &v->trace_diffuse);
    if (v->trace_spec)
        glDeleteTextures(1, &v->trace_spec);
    GLuint t[2] = {gk_texture_2d(GL_RGBA16F, w, h, GL_NEAREST), gk_texture_2d(GL_RGBA16F, w, h, GL_NEAREST)};
    glBindTexture(GL_TEXTURE_2D, 0);
    if (glGetError() != GL_NO_ERROR)
        return gk_fail(e, GK_ERUNTIME, "vct: allocating %dx%d trace targets failed", w, h);
    v->trace_diffuse = t[0];
    v->trace_spec = t[1];
    v->trace_w = w;
    v->trace_h = h;
    v->full_w = full_w;
    v->full_h = full_h;
    v->stats.trace_w = w;
    v->stats.trace_h = h;
    return 0;
}
