/* State shared by the radiosity method's files (not for other modules). */
#ifndef GK_RAD_INTERNAL_H
#define GK_RAD_INTERNAL_H

#include "gl/gl.h"
#include "gl/gl_counters.h"
#include "gl/gl_program.h"
#include "radiosity.h"
#include "scene/wall_split.h"

#define RAD_KNOBS 8
#define RAD_MAX_VERTS 60000     /* ~2x the richest tessellation of our scenes: a dropped-in scene
                                   too large for it shows direct light only, with a log line */
#define RAD_DIRECT_SAMPLES 64   /* per area light and surfel: the direct light's noise (1/8) only
                                   seeds the bounce, which averages it over many surfels */
#define RAD_TEX_WIDTH 1024   /* the irradiance texture's width (the 3.1 floor's size limit is 2048) */

typedef struct rad_gpu {
    GLuint links, leaves, nodes;     /* SSBOs: uvec2 per link, 48-byte leaf records, uvec4 per node */
    GLuint b0, unshot[2];            /* vec4 per node: B0 (from the worker), then ping-pong */
    GLuint vao, vbo, ibo;
    GLuint irr_tex;
    int tex_h;
    int n_leaves, n_nodes, n_levels, n_indices;
    int level_first[RAD_MAX_LEVELS + 1];
    long link_count;
    uint64_t geometry_id;            /* the worker's geometry uploaded (0: none) */
    uint64_t links_id;               /* its link set (rad_geometry.links_id) */
    bool have_b0;
    float *scratch;                  /* vec4 staging */
    size_t scratch_cap;
    bool out_of_memory;
} rad_gpu;

typedef struct rad_state {
    gk_gi_context ctx;
    gk_program_cache *own_cache;
    gk_knob knob[RAD_KNOBS];
    gk_radiosity_stats st;
    gk_scene *own_scene;
    bool rays;                       /* radiosity_vis=rays: own_scene is cut along its walls */
    gk_wall_regions regions;         /* the cuts' labels (n_meshes 0: none made) */
    const gk_scene *scene;           /* what the worker reads */
    const gk_scene *source;          /* the renderer's scene it stands for */
    rad_worker *worker;
    uint64_t seen;
    bool logged_failure;
    rad_gpu gpu;
    gk_counters display_fragments;   /* the bench's count of the display's fragments (rad_work.c) */
} rad_state;

/* rad_method.c: the worker's settings for a scene at knob values (tess: edge = diagonal / tess) */
rad_settings rad_settings_for(const gk_scene *sc, float tess, int n_face, rad_weight weight);

/* rad_gpu.c */
void rad_gpu_take(void *state, const rad_geometry *g, uint64_t geometry_id, const float *b0); /* rad_take_fn */
int rad_gpu_bounce(rad_state *s, const gk_gi_frame *f, int bounces, gk_err *e);
int rad_gpu_display(rad_state *s, const gk_gi_frame *f, gk_err *e);
void rad_gpu_free(rad_gpu *g);
long rad_gpu_memory(const rad_gpu *g);
/* rad_work.c: gk_gi_method.pass_work, the last frame's bounces' link gathers and display fragments */
int rad_pass_work(void *self, gk_pass_work *out, int max);
/* rad_work.c: around the display draw; begin returns the define of its counting variant when
   f->count_work (NULL otherwise), end reads the count back. */
const char *rad_work_display_begin(rad_state *s, const gk_gi_frame *f);
void rad_work_display_end(rad_state *s);

#endif
