/* The scene geometry the paraboloid maps are drawn from. A paraboloid projection bends straight
 * edges, so it is only correct on finely tessellated meshes (dong-001.md §4.4: "meshes must be
 * reasonably tessellated"); the Cornell walls are two triangles each. The method therefore keeps its
 * own copy of every drawn mesh, uniformly subdivided until no edge is longer than a fraction of the
 * scene diameter, positions only, light proxies left out (the path tracer does not see them). */
#ifndef GK_VPL_PROXY_H
#define GK_VPL_PROXY_H

#include "base/err.h"
#include "gl/gl.h"
#include "../../scene/scene.h"

typedef struct vpl_proxy_draw {
    int node;
    GLuint vao, vbo;
    GLsizei vertices;
} vpl_proxy_draw;

typedef struct vpl_proxy {
    vpl_proxy_draw *draws;
    int n_draws;
    long triangles;
    long bytes;
} vpl_proxy;

/* max_edge: world-space edge bound (m); the total is capped at max_triangles by raising the bound. */
int vpl_proxy_build(vpl_proxy *p, const gk_scene *s, float max_edge, long max_triangles, gk_err *e);
void vpl_proxy_free(vpl_proxy *p);
/* Draws every proxy with the bound program, setting the mat4 uniform at location u_model to the
 * node's world matrix. */
void vpl_proxy_draw_all(const vpl_proxy *p, const gk_scene *s, GLint u_model);

#endif
