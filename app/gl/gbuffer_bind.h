/* The C side of the one G-buffer contract (shaders_gles/common/gbuffer.glsl): the renderer's
 * direct light and every GI method bind the G-buffer textures and its matrices here, from the
 * locations of the program's uniforms. A pass's uniform struct embeds gk_gbuffer_uniforms and its
 * field table lists GK_GBUFFER_FIELDS:
 *
 *     typedef struct { gk_gbuffer_uniforms gb; GLint u_sigma; } compose_uniforms;
 *     static const gk_uniform_field compose_fields[] = {
 *         GK_GBUFFER_FIELDS(compose_uniforms, gb), GK_UNIFORM(compose_uniforms, u_sigma)};
 *     ...
 *     gk_gbuffer_bind(&gbuffer, &u->gb, first_unit, sampler);
 */
#ifndef GK_GL_GBUFFER_BIND_H
#define GK_GL_GBUFFER_BIND_H

#include "core/vecmath.h"
#include "gl.h"
#include "gl_program.h"

typedef struct gk_gbuffer_uniforms {
    GLint u_gb_albedo, u_gb_normal, u_gb_emission, u_gb_depth, u_gb_specular;
    GLint u_inv_viewproj, u_eye, u_viewport;
} gk_gbuffer_uniforms;

#define GK_GBUFFER_FIELDS(type, member)                                                                                \
    GK_UNIFORM_AS(type, member.u_gb_albedo, "u_gb_albedo"), GK_UNIFORM_AS(type, member.u_gb_normal, "u_gb_normal"),   \
        GK_UNIFORM_AS(type, member.u_gb_emission, "u_gb_emission"),                                                    \
        GK_UNIFORM_AS(type, member.u_gb_depth, "u_gb_depth"),                                                          \
        GK_UNIFORM_AS(type, member.u_gb_specular, "u_gb_specular"),                                                    \
        GK_UNIFORM_AS(type, member.u_inv_viewproj, "u_inv_viewproj"), GK_UNIFORM_AS(type, member.u_eye, "u_eye"),     \
        GK_UNIFORM_AS(type, member.u_viewport, "u_viewport")

/* The frame's G-buffer (written by the renderer's gbuffer pass) and the view it was drawn with;
 * the pass context (pass.h) lends it to every pass. Layout: depth DEPTH_COMPONENT32F window depth
 * of proj (world = inv_view_proj * (uv, depth)*2-1); albedo RGBA8 (rgb base colour, a metallic);
 * normal RGBA16F (xyz world normal, w roughness); emission RGBA16F (emitted radiance, nits);
 * specular RGBA8 (KHR_materials_specular: rgb sqrt(c0), the dielectric F0 colour; a weight);
 * geom_normal RGBA16F (xyz = the surface's unit normal before its normal map, facing the viewer:
 * the same encoding as normal's xyz, so either texture reads the same), 0 when the driver has fewer than 5 draw buffers: then the shading normal stands in. */
typedef struct gk_gbuffer_view {
    GLuint albedo, normal, emission, depth, specular;
    GLuint geom_normal;
    int width, height;                 /* internal render size (after render_scale) */
    mat4 view, proj, view_proj, inv_view_proj;
    vec3 eye;
} gk_gbuffer_view;

/* Texture units the G-buffer takes from first_unit on: albedo, normal, emission, depth, specular. */
#define GK_GBUFFER_UNITS 5

/* Binds the five textures on first_unit.. (with sampler object `sampler` on each, 0 for the
 * textures' own filtering) and sets the sampler, matrix, eye and viewport uniforms of the current
 * program. Leaves GL_TEXTURE0 + first_unit + 4 active. */
void gk_gbuffer_bind(const gk_gbuffer_view *g, const gk_gbuffer_uniforms *u, int first_unit, GLuint sampler);

/* Binds the geometric normal (gbuffer.glsl's u_gb_geom_normal, read by gb_geom_normal) on `unit`
 * for the passes that need the surface's own plane rather than the normal-mapped one (the shadow
 * receiver offset, vct's cone apex): the shading normal when the G-buffer has no 5th target (the
 * two then coincide except on normal-mapped materials). Not part of gk_gbuffer_bind, so the
 * texture units every other pass uses stay where they were. */
void gk_gbuffer_bind_geom_normal(const gk_gbuffer_view *g, GLint location, int unit, GLuint sampler);

#endif
