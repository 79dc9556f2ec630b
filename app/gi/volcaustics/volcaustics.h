/* The `volcaustics` GI method (seed 001 ch. 8, Hu et al. 2010; research dong-001.md §6): light
 * shafts and volume caustics in a homogeneous single-scattering medium (gk_scene.medium), as
 * D = A + B + C:
 *   (A) airlight and volumetric shadows: a shadowed ray march at reduced resolution (vc_terms.c);
 *   (B) volume caustics: every light ray reflected once by a mirror or refracted twice through
 *       glass (light-view passes and a compute pass into a caustic buffer per caustic light,
 *       vc_light.c) drawn as a line with GL_LINES from gl_VertexID (no geometry shader), each
 *       fragment adding the single scattering where the view
 *       ray crosses it, normalised so the image does not depend on the caustic buffer's or the
 *       screen's resolution (research §6.4, vc_lines.c, shaders_gles/volcaustics/lines.frag);
 *   (C) the renderer's surfaces (direct light) attenuated by the medium, T(v, p) T(s, p), plus the
 *       surface caustics: the light rays' ends splatted as photons (vc_surface.c).
 * Not done: multiple scattering (the model's), inhomogeneous media. Its passes nest under `gi`:
 * vc_light, vc_lines, vc_surface, vc_airlight, vc_composite. */
#ifndef GK_VOLCAUSTICS_H
#define GK_VOLCAUSTICS_H

#include "gi/gi.h"

/* The terms shown (knob vc_output: all, airlight, vcaustics, surfaces). */
enum { GK_VC_TERM_AIRLIGHT = 1, GK_VC_TERM_VCAUSTICS = 2, GK_VC_TERM_SURFACES = 4, GK_VC_TERM_ALL = 7 };

typedef struct gk_volcaustics_stats {
    int buffer_res;          /* caustic buffer resolution that ran */
    bool light_ok;           /* a point/spot light lit a specular object this frame */
    int caustic_lights;      /* the lights whose lines were drawn this frame */
    int march_w, march_h;    /* (A)'s resolution */
} gk_volcaustics_stats;

const gk_volcaustics_stats *gk_volcaustics_get_stats(const void *self);

#endif
