/* State shared by the files of the volcaustics method (not for other modules). */
#ifndef GK_VC_INTERNAL_H
#define GK_VC_INTERNAL_H

#include "gl/gl.h"
#include "gl/gl_counters.h"
#include "gl/gl_program.h"
#include "gl/gl_target.h"
#include "volcaustics.h"

#define VC_KNOBS 7
#define VC_MAX_LIGHTS 4     /* shaders_gles/volcaustics/airlight.frag; the caustic lights (knob vc_lights) */
#define VC_P2_STEPS 64      /* march steps of a reflected ray through the light-view depth (raygen.comp) */
/* March steps of a refracted ray through the back faces' depth, over the specular objects' bounding
   diameter, before 10 bisections (raygen.comp): a chord of glass-fog's ball is at least a few steps
   long even near its rim. */
#define VC_GLASS_STEPS 32

/* The passes with a counting variant (vc_work.c) */
enum { VC_WORK_RAYGEN, VC_WORK_LINES, VC_WORK_SURFACE, VC_WORK_AIRLIGHT, VC_WORK_COMPOSITE, VC_WORK_LIGHTVIEW,
       VC_WORK_N };

/* A light whose reflections or refractions make a volume caustic this frame (vc_light.c). */
typedef struct vc_light {
    bool ok;                 /* a point/spot light with specular geometry in front of it */
    vec3 pos, axis;          /* position, spot axis */
    vec3 radiant;            /* colour * intensity (cd) */
    bool spot;
    float cos_outer, cos_inner;
    vec3 fwd;                /* the light view's axis */
    mat4 vp, inv_vp;
    float texel_omega0;      /* solid angle of a light-view texel on the axis */
    float spec_extent;       /* the specular objects' bounding diameter (m) */
} vc_light;

/* One caustic light's light rays (pass 2's output, the lines pass's input): rgba32f textures. */
typedef struct vc_caustic_buffer {
    GLuint p1, p2, flux;
} vc_caustic_buffer;

typedef struct vc_state {
    gk_gi_context ctx;
    gk_program_cache *own_cache;
    gk_knob knob[VC_KNOBS];
    gk_volcaustics_stats st;
    /* budget this frame */
    int buffer_res;          /* caustic buffer = light view resolution */
    float dx, rf;            /* the regular step and the filter support (m) */
    float march_scale;       /* (A)'s resolution relative to the screen */
    unsigned terms;          /* GK_VC_TERM_* shown */
    int max_lights;          /* caustic lights at most (vc_lights) */
    bool surface_on;         /* surface caustics under (C) (vc_surface) */
    /* scene */
    bool have_specular;
    vec3 spec_min, spec_max; /* bounds of the specular objects (world, at the scene's time) */
    vec3 scene_min, scene_max;
    vc_light light[VC_MAX_LIGHTS];   /* the caustic lights framed this frame */
    /* light views (passes 1a, 1b front and back; shared by the lights) and the caustic buffers
       (pass 2), one per caustic light */
    gk_target lv, lv_nospec, lv_back;
    vc_caustic_buffer cb[VC_MAX_LIGHTS];
    int n_cb;                /* caustic buffers allocated */
    int cb_res;
    /* (A) and (B) images */
    gk_target air, caustic, surface;   /* surface: the surface caustics' irradiance (vc_surface.c) */
    GLenum caustic_fmt;      /* RGBA32F where it can be blended, else RGBA16F (vc_method.c) */
    GLuint empty_vao;
    /* the bench's counting frame (vc_work.c): the counting variants' counters */
    bool count_work;
    gk_counters work[VC_WORK_N];
} vc_state;

/* vc_light.c: frames each caustic light onto the specular objects and renders passes 1a, 1b and 2
   (light rays into its caustic buffer). *n_lines: the caustic buffers filled (0: no light ray can
   reach the medium this frame). */
int vc_light_rays(vc_state *s, const gk_gi_frame *f, int *n_lines, gk_err *e);
void vc_free_light_buffers(vc_state *s);
/* The specular objects' bounds at the frame's time (vc_light.c). */
void vc_specular_bounds(vc_state *s, const gk_scene *sc);
/* vc_lines.c: passes 3-5, the lines of caustic buffers 0..n-1 into the (B) image at screen resolution. */
int vc_lines(vc_state *s, const gk_gi_frame *f, int n, gk_err *e);
/* vc_surface.c: the rays' ends p2 of caustic buffers 0..n-1 splatted as photons into the surface
   caustics' irradiance image (part of (C)). */
int vc_surface_caustics(vc_state *s, const gk_gi_frame *f, int n, gk_err *e);
/* vc_terms.c: (A) by the shadowed ray march, and the composite D = A + B + C into the HDR image. */
int vc_airlight(vc_state *s, const gk_gi_frame *f, gk_err *e);
int vc_composite(vc_state *s, const gk_gi_frame *f, bool have_lines, bool have_surface, gk_err *e);
/* 1 / integral over [-r_f, r_f] of the seed's Gaussian filter (lines.frag), for r_f = 1. */
double vc_filter_integral_unit(void);
void vc_free_gpu(vc_state *s);
/* vc_work.c: the counting variants around the passes, by VC_WORK_*: begin returns the #defines of
   the pass's shader variant ("" when not counting), end reads the counter back; the work the bench
   reads (gk_gi_method.pass_work). */
void vc_work_frame(vc_state *s, const gk_gi_frame *f);
const char *vc_work_begin(vc_state *s, int pass);
void vc_work_end(vc_state *s, int pass);
int vc_pass_work(void *self, gk_pass_work *out, int max);
void vc_work_free(vc_state *s);

#endif
