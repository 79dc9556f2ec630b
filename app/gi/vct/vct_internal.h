/* Internal state of the vct method, shared by its files (not a contract). */
#ifndef GK_VCT_INTERNAL_H
#define GK_VCT_INTERNAL_H

#include "gl/gl_counters.h"
#include "gl/gl.h"
#include "gl/gl_program.h"
#include "vct.h"

#define VCT_MAX_LIGHTS 4
#define VCT_MAX_CONES 9
/* p0, p1, p2 (w: the vertex's alpha, base colour factor x COLOR_0), albedo, emission, uv01 (the
   base-colour UVs of vertices 0 and 1, KHR_texture_transform applied), uv2_mask (vertex 2's UVs,
   the material's alpha-mask layer or -1, its alphaCutoff or -1 when not masked): 7 vec4 */
#define VCT_TRI_FLOATS 28

typedef struct vct_budget {
    int res;            /* vct_res */
    int cones;          /* vct_cones */
    float step;         /* vct_step */
    float trace_scale;  /* vct_trace_scale */
    bool aniso;         /* vct_mips */
    bool aniso_level0;  /* vct_level0=aniso (with aniso only): the directional chains start at level 0 */
    bool thesis;        /* vct_variant=thesis */
    int bounces;        /* vct_bounces: 1 (thesis) or 2 (vct/bounce.comp) */
    int shadow;         /* vct_shadow level: VCT_SHADOW_MAP, or a cone (vct_shadow.c) */
    bool skip;          /* vct_skip: Algorithm 1's empty-space skipping for narrow cones */
    float thick;        /* vct_thick: voxels marked solid behind each fragment (vct/voxelize.comp), 0 off */
    int axis_clamp;     /* vct_axis_clamp: 0 off; 1, 2: no cone sample reads past the first occupied voxel
                           along an axis, or as far as the second (vct/cone_lib.glsl); VCT_AXIS_THIN:
                           1 with only thin walls' voxels occupied (vct/thin_flag.comp) */
} vct_budget;
#define VCT_AXIS_THIN 3
/* vct_axis_clamp=thin: how far behind a thin wall's fragments, in voxels, the clamp also stops
   (voxelize.comp THIN_MARKS). Light-leak at 64^3, RMSE: 0.0021 with no marks, 0.00014 / 8.8e-6 /
   9e-9 / 0 with 3 / 6 / 12 / 16 voxels; res / 4 instead: 9e-7 / 0 / 0.0018 at 32^3 / 64^3 / 128^3
   (16: 0 / 0 / 0.0010). README "The axis clamp at thin walls". */
#define VCT_THIN_DEPTH 16.0f

/* Levels of vct_shadow (vct.c): the renderer's shadow maps, the thesis's fixed apertures, the light's. */
enum { VCT_SHADOW_MAP, VCT_SHADOW_CONE9, VCT_SHADOW_CONE6, VCT_SHADOW_CONE3, VCT_SHADOW_CONE0, VCT_SHADOW_CONE_LIGHT };

typedef struct vct_tris {
    float *data;                 /* n * VCT_TRI_FLOATS, world space */
    int n, n_static;             /* triangles [n_static, n) belong to animated nodes */
    int *dyn_node;               /* per dynamic triangle: node index */
    int *dyn_mesh;               /* per dynamic triangle: mesh index */
    int *dyn_tri;                /* per dynamic triangle: triangle index in the mesh */
    float max_emission;          /* largest emission component (nits), 0 if none */
    vec3 dyn_bmin, dyn_bmax;     /* world bounds of the dynamic triangles at their last upload */
    float *dyn_world;            /* last world matrices of animated nodes (16 per node, n_nodes) */
    int *mask_layer;             /* per material: its layer of gk_vct.alpha_tex, -1 (vct_alpha_layers) */
} vct_tris;

typedef struct gk_vct {
    gk_gi_context ctx;
    gk_vct_options opt;          /* in use: user_opt, or the thesis's with vct_variant=thesis */
    gk_vct_options user_opt;     /* gk_vct_set_options (defaults unless a test sets them) */
    bool thesis;                 /* vct_variant=thesis in effect */
    const gk_scene *scene;
    vct_budget cur;              /* budget the GPU resources were made for */
    gk_knob k_res, k_cones, k_step, k_scale, k_mips, k_variant; /* knob handles (vct.c) */
    gk_knob k_bounces, k_shadow, k_skip, k_level0, k_thick, k_axis_clamp;
    bool allocated;
    bool need_voxelize, need_inject;
    bool emissive, specular;
    /* grid */
    float origin[3], size, voxel;
    int res, levels;
    bool mips_ran;               /* this frame rebuilt the mips (vct_work.c counts their fetches) */
    bool inject_ran;             /* and injected the light (vct_work.c) */
    bool voxelize_ran;           /* and voxelized (all or a moved object's region) */
    bool count_work;             /* this frame is the bench's counting frame (gk_gi_frame.count_work) */
    gk_counters inject_fetches;  /* the bench's counts (vct_work.c): the injection's shadow fetches, */
    gk_counters voxelize_atomics; /* the voxelizer's scratch-buffer atomics */
    gk_counters compose_fetches; /* the compose's low-resolution texels and G-buffer depth reads */
    gk_counters bounce_steps;    /* the second bounce's cone samples (fine, coarse) and gathering voxels */
    bool bounce_ran;             /* this frame ran vct_bounce (its mips are rebuilt in it) */
    /* GL objects */
    GLuint tri_ssbo, scratch_ssbo, counter_ssbo;
    GLuint alpha_tex;            /* R8 2D array: masked materials' base-colour alpha (vct_alpha.c) */
    GLuint vox0;                 /* level-0 radiance (iso: with its mip chain) */
    /* The six directional chains from level 1 (aniso), packed per axis: voxp[a] is (res/2, res/2, res)
       at its level 0, view 2a (+axis, sampled by cones with d_a < 0) in z < 1/2 of every level, view
       2a+1 (-axis) in z >= 1/2, so a cone sample reads one texture per axis whatever the signs of its
       direction (vct/cone_lib.glsl); each view's levels stay within its half (vct/mip_aniso.comp).
       With vct_level0=aniso the chains start at level 0: (res, res, 2 res), one level more. */
    GLuint voxp[3];
    GLuint axis_ssbo;            /* vct_axis_clamp: per voxel the distances to the first occupied voxel
                                    along -x|+x, -y|+y, -z|+z (vct/axis_dist.comp), 3 uints */
    bool axis_valid;             /* axis_ssbo holds the current voxels' distances */
    int axis_nth;                /* to their first (1) or second (2) occupied voxel, or VCT_AXIS_THIN */
    GLuint thin_ssbo;            /* vct_axis_clamp=thin: per voxel its fragments' FACE_BITs and THIN_BIT
                                    (vct/common.glsl), one uint, made with the voxels */
    GLuint thin_count_ssbo;      /* thin_flag.comp's count of flagged voxels (one uint) */
    long thin_voxels;            /* that count, read back after each voxelization: with none the trace
                                    runs without the clamp (vct_pass_trace), bit for bit as `off` */
    GLuint vox_bounce;           /* vct_bounces=2: level 0 of direct + first bounce, written by the bounce
                                    pass while it samples vox0, then swapped with it (same storage) */
    GLuint trace_diffuse, trace_spec;
    GLuint shadow_mask[VCT_MAX_LIGHTS]; /* R32F visibility per G-buffer pixel (vct_shadow.c), mask_w x mask_h */
    int mask_w, mask_h;
    int trace_w, trace_h, full_w, full_h;
    GLuint nearest_sampler, level0_sampler, vao;
    vct_tris tris;
    unsigned long light_hash;
    gk_vct_stats stats;
} gk_vct;

/* vct.c */
void vct_read_budget(gk_vct *v, const gk_budget *b, vct_budget *out);
/* Brings the voxel map up to date for frame f (voxelize, inject, mips, bounce: each only when it
   has work); b: the frame's budget, its resolution clamped to what the GPU allows on return. */
int vct_update(gk_vct *v, const gk_gi_frame *f, vct_budget *b, gk_err *e);

/* vct_shadow.c: gk_gi_method.shadow_mask (the soft-shadow cone) and its textures. */
int vct_shadow_mask(void *self, const gk_gi_frame *f, int light, unsigned *tex, gk_err *e);
void vct_shadow_free(gk_vct *v);

/* vct_grid.c */
void vct_grid_fit(gk_vct *v, const gk_scene *s, int res);
int vct_alloc(gk_vct *v, const vct_budget *b, gk_err *e);
void vct_free_gpu(gk_vct *v);
int vct_ensure_trace_targets(gk_vct *v, int full_w, int full_h, float scale, gk_err *e);
int vct_max_res_allowed(int channels);
/* The second-bounce level 0 (vox_bounce), made on first use at the grid's storage. */
int vct_ensure_bounce_target(gk_vct *v, gk_err *e);

/* vct_alpha.c: each material's layer of the alpha-mask array (-1: not masked, or masked by its
   factor and COLOR_0 alone) into layer[n_materials]; returns the number of layers. */
int vct_alpha_layers(const gk_scene *s, int *layer);
/* (Re)makes v->alpha_tex for scene s. */
int vct_alpha_upload(gk_vct *v, const gk_scene *s, gk_err *e);

/* vct_tris.c */
int vct_tris_build(vct_tris *t, const gk_scene *s, gk_err *e);
void vct_tris_free(vct_tris *t);
/* Re-transforms dynamic triangles whose node moved; returns true and the world bounds of the
   region that changed (old and new positions) if anything moved. */
bool vct_tris_update(vct_tris *t, const gk_scene *s, vec3 *bmin, vec3 *bmax);

/* vct_passes.c */
int vct_pass_voxelize(gk_vct *v, const int lo[3], const int hi[3], gk_err *e);
/* vct_axis_clamp: the distances along the axes to the nth (1, 2) occupied voxel (vct/axis_dist.comp)
   from the scratch buffer into axis_ssbo, made on first use; all rows, after any voxelization. */
int vct_pass_axis_dist(gk_vct *v, int nth, gk_err *e);
/* The trace's AXIS_CLAMP (vct/cone_lib.glsl) for vct_axis_clamp level `level`: 0 off, 1 first (and thin),
   2 second; thin on voxels without a thin wall (thin_voxels 0): 0, nothing to clamp at. */
int vct_axis_clamp_in_use(const gk_vct *v, int level);
int vct_pass_inject(gk_vct *v, const gk_gi_frame *f, gk_err *e);
/* directional: DIRECTIONAL_INJECTION in the level-1 views (the option, or off for the map the second
   bounce gathers from) */
int vct_pass_mips(gk_vct *v, bool directional, gk_err *e);
/* vct_bounces=2: gathers the first bounce into every voxel (vct/bounce.comp) with the budget's cone
   set; vox0 then holds direct + bounce, and the mips must be rebuilt. */
int vct_pass_bounce(gk_vct *v, const vct_budget *b, gk_err *e);
int vct_pass_trace(gk_vct *v, const gk_gi_frame *f, const vct_budget *b, gk_err *e);
int vct_pass_compose(gk_vct *v, const gk_gi_frame *f, gk_err *e);
/* Where Algorithm 1's top-down search starts: map level log2(res) - 3 (thesis code), within the map. */
int vct_skip_top(const gk_vct *v);
/* The cone-tracing programs' defines of the map's layout (ISO_MIPS, ANISO_LEVEL0) into out. */
void vct_map_defines(const gk_vct *v, char *out, size_t n);
/* Binds the voxel map's textures (units 0..6) for a cone-tracing program. */
void vct_bind_map(const gk_vct *v, GLint vox0, const GLint voxp[3], const GLint voxp_l0[3], GLint dir_levels);

/* The uniform-table entries every cone-tracing program shares (trace, bounce, shadow cone): the voxel
   map vct_bind_map binds and cone_lib.glsl's march parameters. The program's uniform struct declares
   members of these names; its field table lists VCT_CONE_FIELDS(its type) beside its own. */
#define VCT_CONE_FIELDS(type)                                                                                  \
    GK_UNIFORM(type, u_vox0), GK_UNIFORM_AS(type, u_voxp[0], "u_voxp0"), GK_UNIFORM_AS(type, u_voxp[1], "u_voxp1"), \
        GK_UNIFORM_AS(type, u_voxp[2], "u_voxp2"), GK_UNIFORM_AS(type, u_voxp_l0[0], "u_voxp0_l0"),           \
        GK_UNIFORM_AS(type, u_voxp_l0[1], "u_voxp1_l0"), GK_UNIFORM_AS(type, u_voxp_l0[2], "u_voxp2_l0"),     \
        GK_UNIFORM(type, u_dir_levels), GK_UNIFORM(type, u_res), GK_UNIFORM(type, u_res_f),                   \
        GK_UNIFORM(type, u_step_mul), GK_UNIFORM(type, u_ao_lambda), GK_UNIFORM(type, u_max_dist),            \
        GK_UNIFORM(type, u_apex_offset), GK_UNIFORM(type, u_footprint_clamp)
/* The cone set for n cones (4, 6 or 9) in the tangent frame (t, n, b); weights calibrated or the
   thesis code's. Returns the number of cones. */
int vct_cone_set(int n, bool faithful, float dir[][3], float aperture[], float weight[]);
/* gk_gi_method.pass_work (vct_work.c): the last trace's counted samples as fetches. */
int vct_pass_work(void *self, gk_pass_work *out, int max);
/* vct_work.c: around the injection of a counting frame (count_work), zero and bind its counter
   (returns the define inject.comp adds, "" when not counting), read it back; free it. */
const char *vct_work_inject_begin(gk_vct *v, bool count_work);
/* The same around the compose (vct/compose.frag VCT_COMPOSE_COUNT_FETCHES: the define, "" when not
   counting). */
const char *vct_work_compose_begin(gk_vct *v, bool count_work);
/* The same around the second bounce's gather (vct/bounce.comp BOUNCE_COUNT_STEPS, v->count_work). */
const char *vct_work_bounce_begin(gk_vct *v);
void vct_work_bounce_end(gk_vct *v);
void vct_work_compose_end(gk_vct *v);
void vct_work_inject_end(gk_vct *v);
/* The same around the voxelizer's dispatches (the define voxelize.comp adds). */
const char *vct_work_voxelize_begin(gk_vct *v);
void vct_work_voxelize_end(gk_vct *v);
void vct_work_free(gk_vct *v);

#endif
