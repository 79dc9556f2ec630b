/* Internal to app/scene: the steps of loading that the C++ tinygltf shim (gltf_load.cpp) hands to
 * the C files. The shim only translates glTF into the gk_scene structs and checks the structure it
 * must read (accessor ranges, component types, primitive modes); everything numeric (NaN/Inf,
 * index values, degenerate triangles, normals, textures, features, bounds) is done in C. */
#ifndef GK_SCENE_INTERNAL_H
#define GK_SCENE_INTERNAL_H

#include "scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Texture usage flags set by the shim, so texture.c knows which ones to decode from sRGB. */
enum { GK_TEX_USED_AS_COLOR = 1, GK_TEX_USED_AS_DATA = 2 };

/* After the shim filled the raw data: validates numbers and indices, drops degenerate triangles,
 * generates missing normals, sorts nodes parents first, loads textures (relative to base_dir; NULL:
 * none may be loaded), derives features and bounds. tex_usage: n_textures flags (may be NULL).
 * Returns 0, or -1 with e set (GK_EINPUT, message starting with s->path). */
int gk_scene_finish(gk_scene *s, const char *base_dir, const int *tex_usage, gk_err *e);

/* validate.c */
int gk_scene_validate_meshes(gk_scene *s, gk_err *e);    /* indices, NaN, degenerates, normals */
int gk_scene_validate_nodes(gk_scene *s, gk_err *e);     /* TRS, hierarchy, order parents first */
int gk_scene_validate_lights(gk_scene *s, gk_err *e);
int gk_scene_validate_cameras(gk_scene *s, gk_err *e);
int gk_scene_validate_animations(gk_scene *s, gk_err *e);
int gk_scene_validate_methods(const gk_scene *s, gk_err *e);

/* texture.c */
int gk_scene_load_textures(gk_scene *s, const char *base_dir, const int *tex_usage, gk_err *e);

/* features.c */
void gk_scene_derive_features(gk_scene *s);
/* When the file has no light, no emitter and no environment, adds the default studio (the built-in
 * studio environment and a key light placed around the view camera; default_studio.c) and sets
 * s->default_lighting; else does nothing. */
int gk_scene_add_default_studio(gk_scene *s, gk_err *e);
/* Generates m->tangents (tangents.c) when the mesh has UVs and none; 0, or -1 out of memory. */
/* Tangents from the UV set the normal map reads (uvs: the mesh's TEXCOORD_0 or _1). */
int gk_mesh_generate_tangents(gk_mesh *m, const float *uvs);

#ifdef __cplusplus
}
#endif

#endif
