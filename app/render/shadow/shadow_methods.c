/* The registry of shadow methods (knob `shadow`). */
#include <string.h>

#include "shadow.h"

extern const gk_shadow_method gk_shadow_hard;
extern const gk_shadow_method gk_shadow_pcss;
/* shadow_vssm.c, shadow_cssm.c: the knob's vssm and cssm, then diagnostic variants used by the
   failure tests (savsm, vssm_nocontact, cssm_sat, cssm_raw, pcss8, vssm_thesis, cssm_thesis), then
   cssm_env (the environment lights' until #11's receiver plane, kept for comparison) and
   cssm_plane, the environment lights' own (render_env.c). The renderer keeps one state per entry
   (GK_MAX_SHADOW_METHODS in renderer_internal.h; checked below). */
extern const gk_shadow_method gk_shadow_vssm, gk_shadow_cssm, gk_shadow_cssm_sat, gk_shadow_savsm,
    gk_shadow_vssm_nocontact, gk_shadow_cssm_raw, gk_shadow_pcss8, gk_shadow_vssm_thesis, gk_shadow_cssm_thesis,
    gk_shadow_cssm_env, gk_shadow_cssm_plane;

const gk_shadow_method *const gk_shadow_methods[] = {&gk_shadow_hard, &gk_shadow_pcss, &gk_shadow_vssm, &gk_shadow_cssm,
                                                     &gk_shadow_cssm_sat, &gk_shadow_savsm, &gk_shadow_vssm_nocontact,
                                                     &gk_shadow_cssm_raw, &gk_shadow_pcss8, &gk_shadow_vssm_thesis,
                                                     &gk_shadow_cssm_thesis, &gk_shadow_cssm_env,
                                                     &gk_shadow_cssm_plane, NULL};
_Static_assert(sizeof gk_shadow_methods / sizeof gk_shadow_methods[0] - 1 <= 16,
               "more shadow methods than GK_MAX_SHADOW_METHODS renderer states");

const gk_shadow_method *gk_shadow_method_find(const char *name)
{
    for (int i = 0; gk_shadow_methods[i]; i++)
        if (name && strcmp(gk_shadow_methods[i]->name, name) == 0)
            return gk_shadow_methods[i];
    return NULL;
}
