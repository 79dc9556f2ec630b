/* The floor view of the GPU work-model tests (#21; included by tests/gpu/test_*_work.c, not a
 * program itself): a grey floor 6 m square lit by a point light, seen straight down from 2 m over
 * a point 0.6 m inside its edge, so that about a fifth of the view is background and a pass that
 * touches the floor's pixels once can be held to a CPU count of them. */
#ifndef TEST_FLOOR_VIEW_H
#define TEST_FLOOR_VIEW_H

#include <stdio.h>

#include "test_ispm_harness.h"

#define TFV_W 160
#define TFV_H 120

/* Builds the floor scene in t and opens the harness h on it (G-buffer TFV_W x TFV_H); then method
   m on h's programs, `before_scene` (may be NULL) called on it before the scene is set, its knobs
   declared in h's budget with `pins` pinned. The method, or NULL with a message. */
static inline void *tfv_open(ispm_h *h, gkt_scene *t, const char *name, const gk_gi_method *m,
                             void (*before_scene)(void *self), const char *pins)
{
    gkt_scene_init(t, name);
    int grey = gkt_material_lambert(t, v3(0.75f, 0.75f, 0.75f));
    gkt_quad(t, v3(-3, 0, -3), v3(3, 0, -3), v3(3, 0, 3), v3(-3, 0, 3), v3(0, 1, 0), grey);
    gkt_light(t, GK_LIGHT_POINT, GK_SHAPE_POINT, 10.0f, v3(1.0f, 1.5f, 0.0f), v3(1, 1, 0));
    gkt_camera(t, v3(2.4f, 2.0f, 0), v3(2.4f, 0, 0), 40.0f * (float)M_PI / 180.0f);
    gkt_scene_bounds(t);
    if (ih_open_built(h, t, TFV_W, TFV_H))
        return NULL;
    gk_err e = {0};
    gk_gi_context ctx = {.programs = h->programs, .gles_version = h->gl.egl.gles_version};
    void *self = m->create(&ctx, &e);
    if (!self) {
        fprintf(stderr, "%s: %s\n", name, e.msg);
        return NULL;
    }
    if (before_scene)
        before_scene(self);
    gk_budget_init(&h->budget);
    m->declare_knobs(&h->budget);
    if (m->set_scene(self, &t->s, &e) || gk_budget_pin_list(&h->budget, pins, &e)) {
        fprintf(stderr, "%s: %s\n", name, e.msg);
        m->destroy(self);
        return NULL;
    }
    return self;
}

/* The pixels whose G-buffer holds the floor (albedo > 0; the background is cleared to 0). */
static inline long tfv_floor_pixels(const ispm_h *h)
{
    long floor = 0;
    for (int i = 0; i < TFV_W * TFV_H; i++)
        floor += h->albedo[i * 4] > 0.0f;
    return floor;
}

#endif
