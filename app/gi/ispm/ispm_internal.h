/* State shared by the files of the ispm method (not for other modules). */
#ifndef GK_ISPM_INTERNAL_H
#define GK_ISPM_INTERNAL_H

#include "gl/gl.h"
#include "gl/gl_counters.h"
#include "gl/gl_program.h"
#include "ispm.h"

#define ISPM_RSM_RES 256     /* research A.4's llvmpipe size (the seed: 512²) */
#define ISPM_RSM_LEVELS 9    /* 256 .. 1 */
#define ISPM_PEEL_LAYERS 4   /* tier B: the seed's Fig. 4.2b compares against 4 layers */
#define ISPM_NODE_BYTES 20   /* Node in shaders_gles/ispm/common.glsl */
#define ISPM_PHOTON_BYTES 48
#define ISPM_HIT_BYTES 48
#define ISPM_FOOT_BYTES 32   /* ispm_radius=footprint's ellipse per hit: two (axis, semi-axis) vec4s */
/* "Same surface" for a splat and for a footprint's neighbours (research A.1.12): normals within 37° */
#define ISPM_SAME_SURFACE_COS 0.8f
/* Header of the photon buffer (ISPM_PHOTON_HEADER in common.glsl), in uints. */
enum {
    ISPM_PH_COUNT = 0, ISPM_PH_LEVEL = 1, ISPM_PH_OVERFLOW = 2, ISPM_PH_TOP = 3, ISPM_PH_NONZERO = 4,
    ISPM_PH_HITS = 20, ISPM_PH_REFLECTED = 21, ISPM_PH_STEPS = 22, ISPM_PH_HEADER_UINTS = 24
};
#define ISPM_PH_HEADER_BYTES (ISPM_PH_HEADER_UINTS * 4)
enum { ISPM_LL_COUNT = 0, ISPM_LL_CAPACITY = 1, ISPM_LL_OVERFLOW = 2 };

#define ISPM_KNOBS 7

/* ispm_radius's levels: the seed's disk, a disk from the hits' density, an ellipse from the photons'
   neighbours (round where they are missing: the density's disk) */
enum { ISPM_RADIUS_SEED = 0, ISPM_RADIUS_DENSITY = 1, ISPM_RADIUS_FOOTPRINT = 2 };

/* The light as the photon passes see it this frame (ispm_photons.c). */
typedef struct ispm_light {
    bool ok;                 /* a point/spot light and specular geometry in front of it */
    vec3 pos, axis;
    vec3 radiant;
    bool spot;
    float cos_outer, cos_inner;
    mat4 view, proj, vp, inv_vp;
    float tan_half;
    float omega_texel;       /* mean solid angle of an RSM texel (sr) */
} ispm_light;

typedef struct ispm_state {
    gk_gi_context ctx;
    gk_program_cache *own_cache;
    gk_ispm_debug dbg;
    gk_ispm_stats st;
    gk_knob knob[ISPM_KNOBS];
    /* the diffuse indirect part: the vpl method, through its gi.h interface */
    const gk_gi_method *vpl;
    void *vpl_self;
    /* budget this frame */
    int photons, trace_res, tier, bounces;
    int radius;              /* ispm_radius: ISPM_RADIUS_SEED, _DENSITY or _FOOTPRINT */
    float splat_scale;
    long pool_bytes;
    /* scene */
    float diam;
    ispm_light light;
    /* RSM and photons */
    GLuint rsm_fbo, rsm_tex[3], rsm_depth;
    GLuint counts_ssbo, photon_ssbo, hit_buf;
    int capacity;            /* photon slots allocated */
    /* lists */
    GLuint nodes_ssbo, pixels_ssbo, ctr_ssbo, ll_fbo;
    long nodes_cap;          /* nodes the pool holds */
    int ll_res;              /* trace resolution the pixel buffer was made for */
    GLuint peel_fbo, peel_tex[ISPM_PEEL_LAYERS], peel_depth;
    int peel_res;
    bool lists_ok;           /* start-up probe */
    /* splat + upsample */
    GLuint splat_fbo, splat_tex, splat_vao, empty_vao;
    GLuint grid_ssbo;        /* ispm_density.c's photon counts per screen cell */
    long grid_cap;
    GLuint block_ssbo;       /* ispm_footprint.c's RSM block -> photon slot map (RSM_RES² ints) */
    GLuint foot_buf;         /* its ellipses, ISPM_FOOT_BYTES per photon slot */
    int foot_cap;
    GLenum splat_fmt;        /* RGBA32F with EXT_color_buffer_float + EXT_float_blend, else RGBA16F */
    int splat_w, splat_h;
    /* view of the last frame's lists (tests) */
    mat4 view, proj;
    /* counters read back one frame late (double-buffered copies) */
    GLuint readback[2];
    int readback_frame;
    unsigned frame_index;
    bool logged_overflow, logged_tier;
    /* the bench's counting frame (ispm_work.c): its caustic passes' work */
    bool counting;           /* this frame is one (gk_gi_frame.count_work) */
    bool work_counted;       /* the counts below are this counting frame's */
    unsigned work_trace_loads, work_list_fragments, work_list_dropped;
    gk_counters splat_fragments;
    gk_counters upsample_fetches;   /* the upsample's splat texels */
    gk_counters rsm_fragments;      /* the RSM's fragments (ispm/rsm.frag) */
    /* the mask pyramid's and the emission's reads and atomics, modelled from the photon header
       (ispm_work_photons; by kind: RSM texels, RSM depths, storage loads, atomics), and
       the same as mask.comp's and emit.comp's counting variants count them (a check) */
    double photons_work[4];
    bool photons_modelled;
    gk_counters photons_fetches;
} ispm_state;

/* ispm_photons.c: frames the light onto the specular geometry, renders the RSM, builds the mask
   pyramid and emits the reflected photons into photon_ssbo. False in *any when there is nothing to
   emit this frame (no light, no specular geometry). */
int ispm_emit_photons(ispm_state *s, const gk_gi_frame *f, bool *any, gk_err *e);
/* ispm_lists.c: the camera-frustum lists at the trace resolution (tier A or B). */
bool ispm_probe_lists(int gles_version);
int ispm_build_lists(ispm_state *s, const gk_gi_frame *f, gk_err *e);
/* ispm_splat.c: trace, splat and upsample+compose into f->hdr_fbo. */
int ispm_trace(ispm_state *s, const gk_gi_frame *f, gk_err *e);
int ispm_splat(ispm_state *s, const gk_gi_frame *f, gk_err *e);
int ispm_upsample(ispm_state *s, const gk_gi_frame *f, gk_err *e);
/* The splat target's size for this frame (the full frame times ispm_splat, at least 1×1). */
void ispm_splat_size(const ispm_state *s, const gk_gi_frame *f, int *w, int *h);
/* ispm_density.c: the splat radii from the hits' density (between trace and splat). */
int ispm_density_radius(ispm_state *s, const gk_gi_frame *f, gk_err *e);
/* ispm_footprint.c: the splat ellipses from the photons' neighbours (after the density radius). */
int ispm_footprint(ispm_state *s, const gk_gi_frame *f, gk_err *e);
void ispm_free_gpu(ispm_state *s);
/* ispm_work.c (#21): each frame's start (a counting frame or not); around the splat draw (the
   defines of its counting variant, or NULL); the trace's loads and the lists' fragments and drops
   as read back (kept in a counting frame); the caustic passes' gk_pass_work entries. */
void ispm_work_frame(ispm_state *s, const gk_gi_frame *f);
const char *ispm_work_splat_begin(ispm_state *s);
void ispm_work_splat_end(ispm_state *s);
/* The same around the upsample's draw. */
const char *ispm_work_upsample_begin(ispm_state *s);
void ispm_work_upsample_end(ispm_state *s);
const char *ispm_work_rsm_begin(ispm_state *s);
void ispm_work_rsm_end(ispm_state *s);
void ispm_work_counters(ispm_state *s, unsigned trace_loads, unsigned list_fragments, unsigned list_dropped);
/* Around the mask pyramid and the emission (ispm_photons.c): the define both compute shaders add
   (NULL when not counting); and, from the photon header read back in a counting frame (ph: its
   ISPM_PH_HEADER_UINTS uints), the model of their work: per kind RSM texels, depth texels, storage
   loads, atomics (ispm_photons_model, also the test's). */
const char *ispm_work_photons_begin(ispm_state *s);
void ispm_work_photons_end(ispm_state *s);
void ispm_photons_model(const unsigned *ph, int capacity, double out[4]);
void ispm_work_photons(ispm_state *s, const unsigned *ph);
/* ll_build.frag's storage-buffer atomics for `fragments` frustum fragments of which `dropped` found
   the pool full */
double ispm_list_atomics(unsigned fragments, unsigned dropped);
int ispm_caustic_work(const ispm_state *s, gk_pass_work *out, int max);
void ispm_work_free(ispm_state *s);

#endif
