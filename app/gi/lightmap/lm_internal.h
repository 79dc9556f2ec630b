/* State shared by the lightmap method's files (not for other modules). */
#ifndef GK_LM_INTERNAL_H
#define GK_LM_INTERNAL_H

#include "gl/gl.h"
#include "gl/gl_counters.h"
#include "gl/gl_program.h"
#include "lightmap.h"
#include "lm_atlas.h"
#include "lm_caustic_gpu.h"
#include "lm_gather.h"

#define LM_KNOBS 10
#define LM_IIM_TAU_S 0.25 /* the IIM blend (research B.2's recommendation; the seed: "fairly fast") */

typedef struct lm_state {
    gk_gi_context ctx;
    gk_program_cache *own_cache;
    gk_knob knob[LM_KNOBS];
    gk_lightmap_stats st;
    int threads_override;
    bool one_worker;             /* lightmap_workers=1 this frame */
    /* the scene: the method's own copy loaded from the scene's file (the worker threads read it
       while the renderer's may be freed), or borrowed when the scene has no file (tests) */
    gk_scene *own_scene;
    const gk_scene *scene;       /* what the atlas and the worker were built from */
    const gk_scene *source;      /* the renderer's scene it stands for */
    lm_atlas atlas;
    bool have_atlas;
    lm_worker *worker;
    uint64_t seen;               /* the worker's last publication uploaded */
    /* GPU */
    GLuint vao, vbo, empty_vao;
    GLuint irr_tex;              /* AIM, indirect irradiance (shown without the final gather) */
    float irr_scale;             /* the texture holds E / irr_scale */
    GLuint full_tex;             /* AIM, full irradiance (what the final gather sees) */
    float full_scale;
    /* final gather: IIMs (the gathered one and the two shown, blended) and the texel queue */
    bool iim_on;                 /* lightmap_iim > 0 this frame */
    GLuint iim_gathered, iim_shown[2];
    int iim_cur;
    bool iim_blend_started;
    double last_time;
    lm_gather gather;
    float *queue_prio;           /* per chart: its Δ_i when queued, 0 when none of its texels waits */
    int *queue_left, *queue_cursor;
    lm_gather_job *jobs;
    int *order;
    GLuint uv_fbo, uv_tex, uv_depth;
    int uv_w, uv_h;
    /* caustics: the points of the worker's newest list on the GPU and their mean flux */
    lm_caustic_gpu caustic;
    uint64_t caustic_seen;
    vec3 caustic_flux;
    bool caustic_cull;           /* filter only the tiles with photons (false: the whole screen) */
    gk_gl_caps caps;             /* R16F counts need color_buffer_half */
    bool warned_count;           /* lightmap_count=float without R16F targets, logged once */
    /* the bench's counting frame (lm_work.c) */
    bool counting;               /* this frame is one (gk_gi_frame.count_work) */
    gk_counters compose_lookups;
    gk_counters uv_fragments;    /* the UV pass's */
    gk_counters blend_fetches;   /* the IIM blend's texel reads */
    gk_counters gather_draws;    /* the final gather's draws: fragments, AIM lookups (gather.frag) */
    double caustic_reads;        /* the caustic filter's count texels in it, -1 when it did not run */
    double caustic_points_drawn; /* the count pass's point fragments in it (-1: not counted) */
    double caustic_cull_fragments; /* the cull's fragments in it (0: no cull) */
} lm_state;

/* lm_display.c */
int lm_display_setup(lm_state *s, gk_err *e);       /* VBO of the atlas vertices, irradiance texture */
void lm_display_upload(void *state, const float *indirect, const float *full, const float *queue);
/* The final gather of up to `texels` queued texels at res² and the IIM blend. */
int lm_display_gather(lm_state *s, const gk_gi_frame *f, int texels, int res, gk_err *e);
int lm_display_draw(lm_state *s, const gk_gi_frame *f, gk_err *e);
void lm_display_free(lm_state *s);
/* Takes the worker's newest caustic photons (lm_worker_take_caustics) and adds the filtered
   caustics to the frame. */
int lm_display_caustics(lm_state *s, const gk_gi_frame *f, gk_err *e);

/* lm_work.c (#21): each frame's start; around the compose draw (the defines of its counting
   variant, or NULL); after the caustic filter; the passes' gk_pass_work entries (the method's
   pass_work); the counters' buffer freed. */
void lm_work_frame(lm_state *s, const gk_gi_frame *f);
const char *lm_work_compose_begin(lm_state *s);
void lm_work_compose_end(lm_state *s);
/* The same around the UV draw and the IIM blend's dispatch. */
const char *lm_work_uv_begin(lm_state *s);
void lm_work_uv_end(lm_state *s);
const char *lm_work_blend_begin(lm_state *s);
void lm_work_blend_end(lm_state *s);
/* ... and around the final gather's draws (lm_display_gather): gather.frag's define, on binding 5
   (the reduction's counter takes 6 across the draws). */
const char *lm_work_gather_begin(lm_state *s);
void lm_work_gather_end(lm_state *s);
void lm_work_caustics(lm_state *s);
int lm_pass_work(void *self, gk_pass_work *out, int max);
void lm_work_free(lm_state *s);

#endif
