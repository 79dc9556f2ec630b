/* The catalogue of GI method names (see gi_catalogue.h). A new method is one row here (and, once
 * implemented, its vtable in gi_registry.c with implemented = true). */
#include "gi_catalogue.h"

#include <stdio.h>
#include <string.h>

static const gk_gi_entry catalogue[] = {
    {"none", true, 0, "direct light only (with soft shadows)"},
    {"vct", true, GK_GI_NEEDS_INTERREFLECTION, "voxel cone tracing"},
    {"vpl", true, GK_GI_NEEDS_INTERREFLECTION, "virtual point lights clustered into virtual area lights"},
    {"ispm", true, GK_GI_NEEDS_CAUSTICS, "image-space photon mapping (caustics)"},
    {"lgv", true, GK_GI_NEEDS_CAUSTICS, "photon tracing against cube maps, grid gathering"},
    {"lightmap", true, GK_GI_NEEDS_INTERREFLECTION, "CPU photon maps with selective updates, GPU final gather into light maps"},
    /* line-based volume caustics: a medium, and a specular caster lit by a local light */
    {"volcaustics", true, GK_GI_NEEDS_MEDIA | GK_GI_NEEDS_CAUSTICS, "volume caustics in single-scattering media"},
    {"radiosity", true, GK_GI_NEEDS_INTERREFLECTION, "hierarchical radiosity with implicit visibility"},
};

const gk_gi_entry *gk_gi_catalogue(int *count)
{
    *count = (int)(sizeof catalogue / sizeof catalogue[0]);
    return catalogue;
}

const gk_gi_entry *gk_gi_catalogue_find(const char *name)
{
    for (size_t i = 0; name && i < sizeof catalogue / sizeof catalogue[0]; i++)
        if (!strcmp(catalogue[i].name, name))
            return &catalogue[i];
    return NULL;
}

bool gk_gi_is_method(const char *name)
{
    return gk_gi_catalogue_find(name) != NULL;
}

int gk_gi_method_names(char *out, size_t cap, const char *sep)
{
    size_t len = 0;
    if (cap)
        out[0] = '\0';
    for (size_t i = 0; i < sizeof catalogue / sizeof catalogue[0]; i++) {
        int w = snprintf(len < cap ? out + len : NULL, len < cap ? cap - len : 0, "%s%s", i ? sep : "",
                         catalogue[i].name);
        len += (size_t)w;
    }
    return (int)len;
}
