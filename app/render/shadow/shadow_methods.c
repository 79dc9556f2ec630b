/* The registry of shadow methods (knob `shadow`). */
#include <string.h>

#include "shadow.h"

extern const gk_shadow_method gk_shadow_hard;
extern const gk_shadow_method gk_shadow_pcss;

const gk_shadow_method *const gk_shadow_methods[] = {&gk_shadow_hard, &gk_shadow_pcss, NULL};

const gk_shadow_method *gk_shadow_method_find(const char *name)
{
    for (int i = 0; gk_shadow_methods[i]; i++)
        if (name && strcmp(gk_shadow_methods[i]->name, name) == 0)
            return gk_shadow_methods[i];
    return NULL;
}
