/* State shared by the files of the vpl method (not for other modules). */
#ifndef GK_VPL_INTERNAL_H
#define GK_VPL_INTERNAL_H

#include "gl/gl_counters.h"
#include "gl/gl.h"
#include "gl/gl_program.h"
#include "vpl.h"
#include "vpl_proxy.h"

#define VPL_RSM_RES 128      /* per RSM face; the thesis gives none (dong-001.md §14.3) */
#define VPL_EXACT_RES 64     /* per-VPL hard shadow maps of the exact-visibility reference */
#define VPL_MR_MAX_LEVELS 6  /* 000: coarsest regions 32×32 pixels (16×16 of them at 512²) */

#define VPL_KNOBS 10              /* knobs declared by vpl_method.c */
enum { VPL_UMBRA_OFF, VPL_UMBRA_ON, VPL_UMBRA_PLANE, VPL_UMBRA_HORIZON };   /* vpl_umbra's levels */

typedef struct vpl_state {
    gk_gi_context ctx;
    gk_program_cache *own_cache;   /* when the renderer lent none */
    gk_vpl_debug dbg;
    gk_vpl_stats st;
    gk_knob knob[VPL_KNOBS];     /* handles of vpl_method.c's knobs (no names in the frame loop) */
    /* budget this frame */
    int n, m_knob, val_res, block, blur_radius, vis;
    float res_scale;
    bool clamp;
    int umbra;    /* vpl_umbra: the deep-umbra test on each map's chain of maxima (gather.frag):
                     VPL_UMBRA_OFF, _ON (a depth margin), _PLANE (the blocker's plane) or _HORIZON
                     (the planes, and the map's horizon read for the band below its plane) */
    /* scene */
    float diam;
    float origin[3];   /* bounds centre: positions in render targets are stored relative to it */
    /* Render-target format, chosen once at create (vpl_method.c choose_targets): RGBA32F with
       EXT_color_buffer_float, else RGBA16F (EXT_color_buffer_half_float or 3.2 core); the
       encodings (vpl_rsm.c, gather.frag) keep every stored value within fp16's range. */
    GLenum tgt_fmt;
    bool tgt_half;
    vpl_proxy proxy;
    bool have_proxy;
    /* RSM atlas and VPL generation */
    GLuint rsm_fbo, rsm_tex[3], rsm_depth;
    int rsm_w, rsm_h;
    GLuint gen_fbo, gen_tex[3];
    int gen_n;
    GLuint vpl_tex, val_tex;
    int val_tex_w;
    /* clustering across frames */
    gk_val prev_vals[GK_VPL_MAX_M];
    int prev_m;
    unsigned frame_index;
    /* VAL maps (texture arrays) */
    GLuint map_fbo, basis_fbo, map_depth;
    GLuint z_arr, bcos, bsin, bzcos, bzsin, bmom;
    GLuint zmax;   /* chain of maxima, RG16F: depth, slope (level 0) or gap (vpl_umbra on, plane, horizon) */
    GLuint zplane; /* the surface's plane per texel, target format, one level (vpl_umbra plane, horizon) */
    int map_res, map_layers, map_vis;
    int map_umbra;
    /* indirect buffers */
    GLuint ind_fbo, ind_tex, pos_tex, nrm_tex;
    GLuint blur_fbo, blur_tex, out_fbo[2], out_tex[2];
    int iw, ih, cur;
    bool have_hist;
    GLuint empty_vao;
    /* multi-resolution splatting (seed 000 §3.2), vpl_gather=multires */
    bool multires;
    int mr_levels, mr_w, mr_h;
    GLuint mr_t[VPL_MR_MAX_LEVELS][4], mr_rend[VPL_MR_MAX_LEVELS], mr_sint[VPL_MR_MAX_LEVELS];
    GLuint mr_fbo[VPL_MR_MAX_LEVELS], mr_rend_fbo[VPL_MR_MAX_LEVELS], mr_sint_fbo[VPL_MR_MAX_LEVELS];
    /* the bench's counts (vpl_work.c): the gather's fetches, the VAL maps' fragments */
    gk_counters gather_fetches; /* unfiltered RGBA32F, filtered RGBA8, filtered 16-bit float, R16F */
    gk_counters map_fragments;  /* fragments vpl/val_depth.frag shaded */
    gk_counters blur_fetches;   /* texels the geometry-aware blur's two passes read (vpl/blur.frag) */
    gk_counters compose_fetches; /* texels the compose's upsample reads (vpl/compose.frag) */
    gk_counters rsm_fragments;  /* fragments the RSMs' draws shaded (vpl/rsm.frag) */
    double rsm_gen_reads;       /* the VPL generation's RSM texels: 3 a VPL (from the parameters) */
    long map_basis_fragments;   /* the basis pass's, res² per map (not counted: a full-screen pass) */
    double map_mip_lookups[2];  /* the maps' mip chains' bilinear lookups: RGBA8, 16-bit (from the parameters) */
    double map_zmax_reads;      /* the deep-umbra chain's reduction reads (vpl_umbra on, plane; from the parameters) */
    gk_counters zmax_fetches;   /* the same as vpl/val_zmax.frag's counting variant read them (a check) */
} vpl_state;

/* vpl_rsm.c: RSM of every light + VPL generation + readback into st.vpl; returns VPL count. */
int vpl_generate(vpl_state *s, const gk_gi_frame *f, gk_err *e);
/* vpl_valmap.c: paraboloid maps (+ CSSM/VSM bases and mips) for `count` emitters in val data. */
int vpl_build_maps(vpl_state *s, const gk_gi_frame *f, const gk_val *emitters, int count, gk_err *e);
void vpl_free_maps(vpl_state *s);
/* Uploads VPLs (with labels) and the emitter table the gather reads. */
void vpl_upload(vpl_state *s, const gk_val *emitters, int count);
/* vpl_gather.c: gather + blur + compose into f->hdr_fbo, the passes vpl_gather, vpl_blur, vpl_compose. */
int vpl_gather(vpl_state *s, const gk_gi_frame *f, float fade, gk_err *e);
void vpl_free_gpu(vpl_state *s);
/* vpl_multires.c: min–max mips, per-level gather of valid regions, interpolation into s->ind_tex
   (plus pos_tex/nrm_tex for the blur), replacing the interleaved gather. */
int vpl_gather_multires(vpl_state *s, const gk_gi_frame *f, gk_err *e);
void vpl_free_multires(vpl_state *s);
/* vpl_work.c (#21): around the gather (interleaved, or all the multires levels) of a counting frame
   (f->count_work), zero and bind the counters (returns the define the gather adds, "" when not
   counting) and read them back;
   gk_gi_method.pass_work; the counters' buffer freed. */
const char *vpl_work_begin(vpl_state *s, const gk_gi_frame *f);
void vpl_work_end(vpl_state *s);
/* The same around the VAL maps' depth draws (vpl_valmap.c; the define val_depth.frag adds). */
const char *vpl_work_maps_begin(vpl_state *s, const gk_gi_frame *f);
void vpl_work_maps_end(vpl_state *s, long basis_fragments);
/* After the maps' glGenerateMipmap: `rgba8` and `f16` chains (RG32F moments counted with the 16-bit
   ones) of res² for `layers` maps. */
void vpl_work_maps_mips(vpl_state *s, int res, int layers, int rgba8, int f16);
/* The deep-umbra chain's reads for one res² map (vpl/val_zmax.frag): at level 1 the 4x4 level-0
   texels around each texel's children that lie inside the paraboloid's disc, at each coarser level
   4 a texel. */
double vpl_zmax_reads(int res);
/* Around the chain's reduction draws (vpl_valmap.c build_zmax): the define val_zmax.frag adds when
   counting (NULL when not); _end adds the model's reads of `layers` res² maps. */
const char *vpl_work_zmax_begin(vpl_state *s, bool counting);
void vpl_work_zmax_end(vpl_state *s, int res, int layers);
/* The same around the blur's two passes and the compose (vpl_gather.c): the define blur.frag or
   compose.frag adds, NULL when not counting. */
const char *vpl_work_blur_begin(vpl_state *s, const gk_gi_frame *f);
void vpl_work_blur_end(vpl_state *s);
const char *vpl_work_compose_begin(vpl_state *s, const gk_gi_frame *f);
void vpl_work_compose_end(vpl_state *s);
/* The same around the RSMs' draws and the VPL generation (vpl_rsm.c): the define rsm.frag adds,
   NULL when not counting; _gen adds one light's generation pass of `count` VPLs. */
const char *vpl_work_rsm_begin(vpl_state *s, const gk_gi_frame *f);
void vpl_work_rsm_gen(vpl_state *s, int count);
void vpl_work_rsm_end(vpl_state *s);
int vpl_pass_work(void *self, gk_pass_work *out, int max);
void vpl_work_free(vpl_state *s);
/* Largest value an indirect target stores (fp16 saturates at 65504; fp32: no cap). */
float vpl_target_max(const vpl_state *s);
/* vpl/gather.frag in every variant (visibility defines, dense and MULTIRES): its uniform locations,
   resolved once per program (vpl_gather.c). */
/* Units of the dense gather: G-buffer 10..13, position 2, visibility 3..9 and 14. */
#define VPL_GATHER_GBUFFER_UNIT 10
typedef struct vpl_gather_uniforms {
    gk_gbuffer_uniforms gb;
    GLint u_ind_size, u_vpl, u_val, u_n, u_block, u_dmin2, u_origin, u_out_max;
    GLint u_bcos, u_bsin, u_bzcos, u_bzsin, u_bz, u_bmom, u_bzmax, u_bplane, u_umbra, u_lift, u_n_val;
    GLint u_mr_t[4], u_mr_p[3], u_mr_level, u_mr_top, u_tau_z, u_tau_n;
} vpl_gather_uniforms;
const vpl_gather_uniforms *vpl_gather_uniforms_of(vpl_state *s, GLuint prog, gk_err *e);
/* Binding helpers shared by the gather files. */
void vpl_bind_tex(int unit, GLenum target, GLuint tex, GLint loc);
void vpl_bind_visibility(vpl_state *s, const vpl_gather_uniforms *u);
const char *vpl_vis_define(int vis);
/* gather.frag's VIS_PER_VAL define (each VAL's visibility once per receiver, looked up per VPL) where
   that is cheaper: CSSM or VSM visibility with fewer VALs than the VPLs a receiver takes (n / B²
   interleaved, all n with `multires`); "" otherwise (the per-VPL call) and with dbg.vis_per_vpl. */
const char *vpl_per_val_define(vpl_state *s, bool multires);   /* also sets st.vis_per_val */

/* Emitter geometry shared by the map pass and the gather (centre offset, near radius, far). */
void vpl_emitter_params(const vpl_state *s, const gk_val *v, bool exact, float out_c[3], float *rnear,
                        float *far);
/* How far each map's centre is lifted off its VAL along the normal (m): the band below the map's
   plane where the VAL's own VPLs still light receivers (gather.frag, vpl_umbra=horizon). */
float vpl_lift(const vpl_state *s);

#endif
