/* The one catalogue of GI method names (DESIGN §5): every name the command line, the kiosk config,
 * scene files, CSVs and the bench accept, in the table's order, whether the method is implemented,
 * and what it needs from a scene. Everything that validates, lists or derives method names asks
 * here; nobody keeps a list of their own.
 *
 * A leaf: pure data and small functions, no GL, no includes from the rest of app/. That is what
 * lets app/scene/ (which derives the methods a scene needs) and app/kiosk/ (config, knob owners)
 * use it, and lets the fuzz build (Makefile FUZZ_SRCS: base/, app/scene, app/core, app/io) link it:
 * FUZZ_SRCS names app/gi/gi_catalogue.c explicitly, nothing else of app/gi/.
 *
 * The implemented methods' vtables stay in the registry (gi.h: gk_gi_methods / gk_gi_find,
 * gi_registry.c); tests/unit/test_gi_catalogue.c asserts that the registry and the `implemented`
 * flags agree. */
#ifndef GK_GI_CATALOGUE_H
#define GK_GI_CATALOGUE_H

#include <stdbool.h>
#include <stddef.h>

/* What a method needs from a scene before it is worth running there ("model no more than a scene
 * needs"). A method is needed when the scene has ALL of its needs; 0 = always (none). The scene
 * side (app/scene/features.c, gk_scene_gi_needs) maps its feature flags onto these bits. */
enum {
    GK_GI_NEEDS_INTERREFLECTION = 1u << 0, /* light bounces between diffuse surfaces */
    GK_GI_NEEDS_CAUSTICS = 1u << 1,        /* specular/transmissive surfaces lit by point/spot lights */
    GK_GI_NEEDS_STATIC = 1u << 2,          /* nothing moves (baked light maps) */
    GK_GI_NEEDS_MEDIA = 1u << 3,           /* a participating medium */
};

typedef struct gk_gi_entry {
    const char *name;        /* "none", "vct", ... */
    bool implemented;        /* has a gk_gi_method in the registry ("none" counts: the renderer's own) */
    unsigned needs;          /* GK_GI_NEEDS_* bits, all required */
    const char *what;        /* one line for usage texts */
} gk_gi_entry;

/* Every method of DESIGN §5, "none" first, in the table's order. */
const gk_gi_entry *gk_gi_catalogue(int *count);
/* The entry named `name`, or NULL when it is not a method. */
const gk_gi_entry *gk_gi_catalogue_find(const char *name);
/* Is `name` one of the catalogue's names (implemented or not)? */
bool gk_gi_is_method(const char *name);
/* The names joined by sep ("none, vct, vpl, ..."), for messages and usage texts; always
 * NUL-terminated (truncated to cap). Returns the length it would have had, like snprintf. */
int gk_gi_method_names(char *out, size_t cap, const char *sep);

#endif
