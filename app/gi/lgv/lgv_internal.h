/* State shared by the files of the lgv method (not for other modules). Buffer layouts mirror
 * shaders_gles/lgv/common.glsl, trace.comp and sslgv_*.comp (std430). */
#ifndef GK_LGV_INTERNAL_H
#define GK_LGV_INTERNAL_H

#include <stddef.h>

#include "gl/gl.h"
#include "gl/gl_counters.h"
#include "gl/gl_program.h"
#include "lgv.h"

#define LGV_MAX_MAPS 64          /* lattice maps (4^3 at most) */
#define LGV_MAX_REFRACTORS 4     /* refractor maps: one per transmissive mesh instance, the first four in node order */
#define LGV_MAP_LAYERS_MAX ((LGV_MAX_MAPS + 2 * LGV_MAX_REFRACTORS) * 6)
#define LGV_CAUSTIC_BYTES 48     /* Caustic in trace.comp */
#define LGV_CAUSTIC_HEADER 16
#define LGV_FAR_BITS 0x7149f2caU /* 1e30f: "nothing in this direction" */
/* Stats buffer (trace.comp, sslgv_inject.comp): uints */
enum { LGV_ST_RAYS = 0, LGV_ST_INJECTED = 1, LGV_ST_CAUSTIC = 2, LGV_ST_ESCAPED = 3, LGV_ST_SSLGV = 4, LGV_ST_N = 8 };

/* Named parameters the seed leaves open (research B.1.2), fixed here with their reasons. */
#define LGV_Q 8                  /* angle partition intervals (seed) */
#define LGV_LOOPS 3              /* at most 3 loops (seed) */
#define LGV_ITP_EPS_REL 0.002f   /* stop the partition when the ITP moves < 0.2% of the scene diagonal */
#define LGV_SECANT_STEPS 6       /* secant iterations ([32]: 4-8 typical) */
#define LGV_BOUNCES 6            /* longest photon path (surface events); Russian roulette ends most before */
#define LGV_CENTRE_CLEARANCE_REL 0.05f /* lattice centres keep 5% of the cell spacing from any triangle */
#define LGV_SSLGV_ITERS 12       /* seed: "about twelve" */
#define LGV_C0 1.0f              /* h = C0 sqrt(A / (p N)) with p = 1 (P_min, P_max unspecified) */
/* Eq. (4) with the errata fixed (research B.2.4 warnings i-iii): Phi_p is already Phi / N, so the
 * A C0^2 / (4N) factor is replaced by one constant k chosen so that eq. (7) gives the photon density
 * estimate f_r sum Phi / l^2 on a surface crossing a cell (area l^2): one photon at angle g to the
 * normal contributes 4 k cos g (y0^2 + a^2 cos g) Phi f_r / l^2 = k cos g (0.25 + 0.75 cos g)(4 / pi)
 * Phi f_r / l^2; averaged over cosine-distributed arrivals E[cos g (0.25 + 0.75 cos g)] = 0.5417,
 * so k = pi / (4 x 0.5417). Independent of N and C0 by construction (B.5 item 13 checks it). */
#define LGV_INJECT_SCALE 1.44993f
/* The same with the cosine lobe around -n (gk_lgv_debug.inject_lobe, trace.comp): eq. (7) reads one
 * photon on its own surface as 4 k (pi y0^2 + (2 pi / 3) a^2) Phi f_r / l^2 = 3 k Phi f_r / l^2 at
 * every angle, so k = 1 / 3. */
#define LGV_INJECT_SCALE_LOBE (1.0f / 3.0f)

/* The geometry volume (lgv_geometry.c): fixed-point units per unit of opacity (projected area / l^2;
 * a texel adds at most 10 x its area, a cell's sum stays far below 2^32 / 65536). */
#define LGV_GEO_FIXED 65536.0f

#define LGV_KNOBS 6

/* The passes with a counting variant (lgv_work.c) */
enum { LGV_WORK_TRACE, LGV_WORK_MAPS, LGV_WORK_SSLGV, LGV_WORK_LOOKUP, LGV_WORK_GEOMETRY, LGV_WORK_N };

typedef struct lgv_state {
    gk_gi_context ctx;
    gk_program_cache *own_cache;
    gk_lgv_debug dbg;
    gk_lgv_stats st;
    gk_knob knob[LGV_KNOBS];
    /* budget this frame */
    int photons, n_maps_wanted, map_res, lgv_size, iters, ss_width;
    /* scene */
    const gk_scene *scene;
    vec3 bmin, bmax;
    float diag, area;
    int lattice;                 /* maps per axis */
    int n_maps, n_refractors;
    /* xyz, w = radius (refractors): the lattice maps, the refractor maps, then each refractor's exit
       map (the same centre, its glass left out; lgv_maps.c) */
    float centres[(LGV_MAX_MAPS + 2 * LGV_MAX_REFRACTORS) * 4];
    /* each refractor map's glass: the (node, mesh) of its draw, for the maps' material code
       (cubemap.frag's u_node_mesh) */
    int refractor_draw[LGV_MAX_REFRACTORS * 2];
    bool maps_valid;
    int maps_res, maps_count;    /* what the map textures were made for */
    GLuint dist_tex, nrm_tex, alb_tex, map_depth, map_fbo, centres_ssbo;
    int levels;
    /* photons and grids */
    GLuint lgv_ssbo, caustic_ssbo, stats_ssbo, probe_ssbo;
    GLuint src_ssbo, acc_ssbo, dst_ssbo;
    GLuint out_ssbo;             /* what the volume textures hold: acc_ssbo, or the last iteration's */
    long lgv_cells;
    int dims[3];
    float cell;
    vec3 grid_min;
    GLuint vol[3];
    /* geometry volume (eq. 6's G): on the LGV's corners, built for maps_stamp, geo_dims, geo_cell */
    GLuint geo_ssbo;
    int geo_dims[3];
    float geo_cell;
    unsigned maps_stamp, geo_maps_stamp; /* maps_stamp counts the maps' renderings */
    int vol_dims[3];
    int caustic_cap;
    float fixed_scale;
    /* SSLGV */
    GLuint ss_grid, ss_a, ss_b, ss_img[3];
    int ss_w, ss_h;
    float h;
    GLuint empty_vao;
    unsigned frame_index;
    /* the bench's counting frame (lgv_work.c): the counting variants' counters */
    bool count_work;
    bool maps_ran;               /* this frame rendered the maps */
    gk_counters work[LGV_WORK_N];
} lgv_state;

/* lgv_maps.c: lattice placement (set_scene), rendering of the maps and their min mips. */
int lgv_place_maps(lgv_state *s, const gk_scene *sc, int per_axis, gk_err *e);
int lgv_render_maps(lgv_state *s, const gk_gi_frame *f, gk_err *e);
/* lgv_photons.c: emission + tracing + LGV injection, gathering, the volume textures. */
int lgv_trace_photons(lgv_state *s, const gk_gi_frame *f, gk_err *e);
int lgv_gather(lgv_state *s, const gk_gi_frame *f, gk_err *e);
/* lgv_geometry.c: the geometry volume from the lattice maps (only when the maps or the grid changed). */
int lgv_build_geometry(lgv_state *s, gk_err *e);
/* trace.comp's defines into out: the counting variant's (lgv_work_begin), LGV_GLASS (the refractor
   maps: 0, 1, 2 for several), LGV_SEEING_MAPS (dbg.seeing_maps) and, for gk_lgv_probe, LGV_PROBE. */
void lgv_trace_defines(lgv_state *s, bool probe, char *out, size_t cap);
/* Binds the maps and the tracer's uniforms for a program that includes lgv/tracer.glsl. */
int lgv_bind_tracer(lgv_state *s, GLuint prog, gk_err *e);
/* lgv_sslgv.c: caustic photons into the screen grid, its iterations; lookup into the HDR image. */
int lgv_sslgv(lgv_state *s, const gk_gi_frame *f, gk_err *e);
int lgv_lookup(lgv_state *s, const gk_gi_frame *f, gk_err *e);
void lgv_free_gpu(lgv_state *s);
/* lgv_work.c: the counting variants around the passes, by LGV_WORK_*: begin returns the #defines of
   the pass's shader variant ("" when not counting), end reads the counters back; the work the bench
   reads (gk_gi_method.pass_work). */
const char *lgv_work_begin(lgv_state *s, int pass);
void lgv_work_end(lgv_state *s, int pass);
int lgv_pass_work(void *self, gk_pass_work *out, int max);
void lgv_work_free(lgv_state *s);
/* A shader storage buffer of `bytes` (zeroed when zero is true). */
GLuint lgv_buffer(GLuint old, long bytes, bool zero);

#endif
