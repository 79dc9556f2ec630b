/* The implemented GI methods' vtables, in the order the kiosk offers them after "none". A method
 * file defines `const gk_gi_method gk_gi_NAME;` and is listed here, and its catalogue entry
 * (gi_catalogue.c) says implemented; tests/unit/test_gi_catalogue.c checks the two agree. */
#include "gi.h"

#include <string.h>

extern const gk_gi_method gk_gi_vct;
extern const gk_gi_method gk_gi_vpl;
extern const gk_gi_method gk_gi_ispm;
extern const gk_gi_method gk_gi_lightmap;
extern const gk_gi_method gk_gi_radiosity;
extern const gk_gi_method gk_gi_lgv;
extern const gk_gi_method gk_gi_volcaustics;

static const gk_gi_method *const registry[] = {
    &gk_gi_vct,
    &gk_gi_vpl,
    &gk_gi_ispm,
    &gk_gi_lightmap,
    &gk_gi_radiosity,
    &gk_gi_lgv,
    &gk_gi_volcaustics,
    NULL, /* sentinel: keeps the array valid C even with no method registered */
};

const gk_gi_method *const *gk_gi_methods(int *count)
{
    *count = (int)(sizeof registry / sizeof registry[0]) - 1;
    return registry;
}

const gk_gi_method *gk_gi_find(const char *name)
{
    int n;
    const gk_gi_method *const *m = gk_gi_methods(&n);
    for (int i = 0; i < n; i++)
        if (strcmp(m[i]->name, name) == 0)
            return m[i];
    return NULL;
}
