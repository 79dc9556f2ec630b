/* The uniforms of shaders_gles/volcaustics/medium.glsl as a block embedded in each program's
 * uniform struct (gk_program_uniforms), and the one function that sets them from the scene. */
#ifndef GK_VC_MEDIUM_UNIFORMS_H
#define GK_VC_MEDIUM_UNIFORMS_H

#include "gl/gl.h"
#include "gl/gl_program.h"
#include "scene/scene.h"

typedef struct vc_medium_uniforms {
    GLint u_sigma_s, u_sigma_t, u_hg_g, u_box_min, u_box_max;
} vc_medium_uniforms;

#define VC_MEDIUM_FIELDS(type, member)                                                                        \
    GK_UNIFORM_AS(type, member.u_sigma_s, "u_sigma_s"), GK_UNIFORM_AS(type, member.u_sigma_t, "u_sigma_t"),  \
        GK_UNIFORM_AS(type, member.u_hg_g, "u_hg_g"), GK_UNIFORM_AS(type, member.u_box_min, "u_box_min"),    \
        GK_UNIFORM_AS(type, member.u_box_max, "u_box_max")

/* An unbounded medium is the box +-VC_UNBOUNDED (m): far beyond any scene, finite for the slab test. */
#define VC_UNBOUNDED 1e6f

void vc_set_medium(const vc_medium_uniforms *u, const gk_scene *sc);

#endif
