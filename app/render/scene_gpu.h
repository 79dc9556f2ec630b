/* The scene on the GPU: one VAO (positions, normals, uvs) + index buffer per mesh, one texture per
 * scene texture, and draw helpers that set each node's world matrix and the material uniforms.
 * Attribute locations: 0 position, 1 normal, 2 uv, 3 vertex colour (COLOR_0 RGBA, constant white
 * when the mesh has none), 4 tangent (xyz, handedness w; only normal-mapped meshes have one);
 * shaders use layout(location = N). */
#ifndef GK_SCENE_GPU_H
#define GK_SCENE_GPU_H

#include "base/err.h"
#include "../scene/scene.h"
#include "gl/gl.h"
#include "gl/gl_program.h"

#define GK_MESH_ATTRIBS 6      /* vertex attributes per mesh, locations 0..5 */

typedef struct gk_scene_gpu {
    int n_meshes;
    GLuint *vao, *vbo, *ibo;   /* vbo: GK_MESH_ATTRIBS per mesh (pos, normal, uv, colour, tangent, uv1: TEXCOORD_1, or TEXCOORD_0 again without one) */
    GLsizei *index_count;
    int n_textures;
    GLuint *tex;
    GLuint white_tex;          /* bound where a material has no texture */
} gk_scene_gpu;

int gk_scene_gpu_upload(gk_scene_gpu *g, const gk_scene *s, gk_err *e);
void gk_scene_gpu_free(gk_scene_gpu *g);

enum {
    GK_DRAW_MATERIALS = 1,     /* set u_base_color, u_metallic_roughness, u_emissive, u_mat_flags, u_specular, textures */
    GK_DRAW_SKIP_PROXIES = 2,  /* leave out light_proxy meshes (shadow maps: the light stands in their place) */
    GK_DRAW_SKIP_GLASS = 4,    /* leave out transmissive materials (the G-buffer: render_glass.c draws them) */
    GK_DRAW_ONLY_GLASS = 8,    /* only transmissive materials (render_glass.c) */
    /* The camera's passes (the G-buffer): back faces of single-sided materials (glTF doubleSided
       false) are culled, so a single-sided surface seen from behind shows what lies behind it, as
       the tracer's camera rays pass through it (app/ref/trace.c). The light's passes (shadow maps,
       RSMs, voxelization) keep both faces: a closed mesh must cast its shadow either way. */
    GK_DRAW_CULL_SINGLE_SIDED = 16,
    GK_DRAW_SKIP_BLEND = 32,   /* leave out alphaMode BLEND materials (the G-buffer: render_blend.c draws them) */
};

/* Material flags in u_mat_flags (mirrored in shaders_gles/gbuffer/gbuffer.frag). */
enum {
    GK_MAT_BASE_TEX = 1,
    GK_MAT_MR_TEX = 2,
    GK_MAT_LIGHT_PROXY = 4,
    GK_MAT_DOUBLE_SIDED = 8,
    GK_MAT_SPEC_TEX = 16,       /* KHR_materials_specular specularTexture (A) */
    GK_MAT_SPEC_COLOR_TEX = 32, /* KHR_materials_specular specularColorTexture (RGB) */
    GK_MAT_EMISSIVE_TEX = 64,   /* emissiveTexture (RGB) times u_emissive */
    GK_MAT_NORMAL_TEX = 128,    /* normalTexture, tangent space, XY scaled by u_normal_scale */
    GK_MAT_ALPHA_MASK = 256,    /* alphaMode MASK: discard where base colour alpha < u_alpha_cutoff */
    GK_MAT_OCCLUSION_TEX = 512, /* occlusionTexture (R), 1 + u_occlusion_strength (R - 1) */
};

/* The uniforms gk_scene_gpu_draw sets, by location (-1: the program has no such uniform). A pass
 * embeds this struct in its own uniform struct and lists the fields its shaders declare, e.g.
 * GK_UNIFORM_AS(gbuffer_uniforms, draw.u_model, "u_model"). */
typedef struct gk_draw_uniforms {
    GLint u_model, u_normal_matrix;                                       /* per node */
    GLint u_base_color, u_metallic_roughness, u_emissive, u_mat_flags;    /* per material (GK_DRAW_MATERIALS) */
    GLint u_base_tex, u_mr_tex;                                           /* samplers (GK_DRAW_MATERIALS) */
    /* KHR_materials_specular (brdf_spec.md): u_specular = (((ior-1)/(ior+1))^2 specularColorFactor,
       specularFactor); the shader multiplies the textures in and clamps c0 to 1. */
    GLint u_specular, u_spec_tex, u_spec_color_tex;
    GLint u_emissive_tex;                                                 /* unit 4 */
    GLint u_normal_tex, u_normal_scale;                                   /* unit 5 */
    GLint u_occlusion_tex, u_occlusion_strength;                          /* unit 6 */
    GLint u_glass;             /* (ior, transmission): KHR_materials_ior / _transmission (render_glass.c) */
    /* Each texture slot's UVs (gk_tex_uv): u_tex_xf vec3[2 * GK_TEX_SLOTS], rows of its 2x3
       KHR_texture_transform matrix (identity without one); u_tex_uv1 int, bit k set when slot k
       reads TEXCOORD_1 (attribute 5). Slots in enum gk_tex_slot's order. */
    GLint u_tex_xf, u_tex_uv1;
    GLint u_alpha_cutoff;      /* alphaMode MASK's alphaCutoff (GK_MAT_ALPHA_MASK) */
    /* ivec2 (node, mesh): which draw this is, set per draw, for a pass that tells mesh instances
       apart (lgv's cube maps name each glass instance's refractor map; a mesh drawn by two nodes is
       two instances) */
    GLint u_node_mesh;
} gk_draw_uniforms;

/* The uniforms a depth-only pass lists so that alpha-masked materials cut their holes in it too
 * (shadow/depth.frag, drawn with GK_DRAW_MATERIALS). */
#define GK_ALPHA_MASK_FIELDS(type, member)                                                                             \
    GK_UNIFORM_AS(type, member.u_mat_flags, "u_mat_flags"), GK_UNIFORM_AS(type, member.u_base_color, "u_base_color"), \
        GK_UNIFORM_AS(type, member.u_base_tex, "u_base_tex"),                                                        \
        GK_UNIFORM_AS(type, member.u_alpha_cutoff, "u_alpha_cutoff"),                                                \
        GK_UNIFORM_AS(type, member.u_tex_xf, "u_tex_xf"), GK_UNIFORM_AS(type, member.u_tex_uv1, "u_tex_uv1")

/* shadow/depth.{vert,frag}'s defines for scene s and the draw flags that go with them: alpha
 * masking (GK_ALPHA_MASK 1, drawn with GK_DRAW_MATERIALS) only when a material of s is masked. */
const char *gk_scene_gpu_depth_defines(const gk_scene *s);
int gk_scene_gpu_depth_flags(const gk_scene *s);

/* Draws every node's meshes (after gk_scene_evaluate) with the bound program: sets u_model and
 * u_normal_matrix per node and u_node_mesh per draw; textures on units 0 (base colour),
 * 1 (metallic-roughness), 2 (specular), 3 (specular colour), 4 (emissive), 5 (normal) and
 * 6 (occlusion). */
void gk_scene_gpu_draw(const gk_scene_gpu *g, const gk_scene *s, const gk_draw_uniforms *u, int flags);
/* Draws mesh k of node n alone (the node's matrices, the material's uniforms with
 * GK_DRAW_MATERIALS, back faces of single-sided materials culled with GK_DRAW_CULL_SINGLE_SIDED). */
void gk_scene_gpu_draw_mesh(const gk_scene_gpu *g, const gk_scene *s, const gk_draw_uniforms *u, int flags, int n, int k);
/* The locations by name, for tests and programs built outside a program cache (never per frame). */
void gk_draw_uniforms_lookup(GLuint prog, gk_draw_uniforms *u);

#endif
