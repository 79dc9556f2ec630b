/* glTF occlusionTexture on the GI methods' indirect light (renderer_internal.h): each method adds its
 * light into the HDR image itself, so the renderer takes the contribution as the difference to the
 * image before the method (the cross-fade's copy, render_gi_blend.c) and scales it by the G-buffer's
 * ao (compose/gi_occlusion.frag). Direct light is never darkened by the texture. Scenes without an
 * occlusion texture skip the pass (and the copy it needs). */
#include "renderer_internal.h"

/* compose/gi_occlusion.frag */
typedef struct occlusion_uniforms {
    gk_gbuffer_uniforms gb;
    GLint u_pre;
} occlusion_uniforms;
static const gk_uniform_field occlusion_fields[] = {GK_GBUFFER_FIELDS(occlusion_uniforms, gb),
                                                    GK_UNIFORM(occlusion_uniforms, u_pre)};

bool gk_gi_occlusion_needed(const gk_renderer *r)
{
    return r->scene && r->scene->gltf.occlusion_textures > 0;
}

int gk_gi_occlusion_apply(gk_renderer *r, const gk_pass_ctx *ctx, gk_err *e)
{
    if (!gk_gi_occlusion_needed(r) || !r->blend.pre_valid)
        return 0;
    gk_pass_begin(ctx, "occlusion");
    GLuint prog = gk_program_get(r->progs, "common/fullscreen.vert", "compose/gi_occlusion.frag", NULL, e);
    const occlusion_uniforms *u =
        prog ? gk_program_uniforms(r->progs, prog, GK_FIELDS(occlusion_fields), sizeof *u, e) : NULL;
    if (u) {
        glBindFramebuffer(GL_FRAMEBUFFER, r->hdr.fbo);
        glViewport(0, 0, r->render_w, r->render_h);
        glDisable(GL_DEPTH_TEST);
        glEnable(GL_BLEND);
        glBlendEquation(GL_FUNC_ADD);
        glBlendFunc(GL_ONE, GL_SRC_ALPHA);
        glUseProgram(prog);
        gk_gbuffer_bind(ctx->gbuffer, &u->gb, UNIT_ALBEDO, 0);
        glActiveTexture(GL_TEXTURE0 + GK_GBUFFER_UNITS);
        glBindTexture(GL_TEXTURE_2D, r->blend.pre.color[0]);
        glUniform1i(u->u_pre, GK_GBUFFER_UNITS);
        gk_render_fullscreen(r);
        glDisable(GL_BLEND);
        glActiveTexture(GL_TEXTURE0);
        if (r->count_work) /* gi_occlusion.frag: the pixel's depth and its pre-GI texel, every pixel */
            r->occlusion_pixels = (double)r->render_w * r->render_h;
    }
    gk_pass_end(ctx);
    return u ? 0 : -1;
}
