/* The one catalogue of GI method names (app/gi/gi_catalogue.h): no name twice, it agrees with the
 * registry of implemented methods (gi_registry.c) both ways, the joined list messages use, and the
 * mapping of scene features onto needs. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "gi/gi.h"
#include "gi/gi_catalogue.h"
#include "scene/scene.h"

static void no_name_twice_and_none_first(void **state)
{
    (void)state;
    int n;
    const gk_gi_entry *c = gk_gi_catalogue(&n);
    assert_true(n >= 8); /* DESIGN §5: none and seven methods */
    assert_string_equal(c[0].name, "none");
    assert_true(c[0].implemented);
    assert_int_equal(c[0].needs, 0);
    for (int i = 0; i < n; i++) {
        assert_non_null(c[i].name);
        assert_true(c[i].name[0] != '\0');
        assert_true(c[i].needs != 0 || i == 0); /* only "none" is needed by every scene */
        assert_ptr_equal(gk_gi_catalogue_find(c[i].name), &c[i]);
        for (int j = i + 1; j < n; j++)
            if (!strcmp(c[i].name, c[j].name))
                fail_msg("method '%s' is listed twice (entries %d and %d)", c[i].name, i, j);
    }
}

static void registry_agrees_with_implemented(void **state)
{
    (void)state;
    int n, nr;
    const gk_gi_entry *c = gk_gi_catalogue(&n);
    const gk_gi_method *const *reg = gk_gi_methods(&nr);
    /* Every implemented entry has a vtable ("none" is the renderer's own: none registered). */
    for (int i = 0; i < n; i++) {
        const gk_gi_method *m = gk_gi_find(c[i].name);
        if (i == 0)
            assert_null(m);
        else if (c[i].implemented && !m)
            fail_msg("catalogue: '%s' is implemented but has no vtable in gi_registry.c", c[i].name);
        else if (!c[i].implemented && m)
            fail_msg("gi_registry.c: '%s' is registered but the catalogue says it is not implemented", c[i].name);
    }
    /* Every vtable is an implemented catalogue entry, and registered once. */
    for (int k = 0; k < nr; k++) {
        const gk_gi_entry *e = gk_gi_catalogue_find(reg[k]->name);
        if (!e || !e->implemented)
            fail_msg("gi_registry.c: '%s' is not an implemented method of the catalogue", reg[k]->name);
        for (int j = k + 1; j < nr; j++)
            assert_string_not_equal(reg[k]->name, reg[j]->name);
    }
}

static void names_joined_for_messages(void **state)
{
    (void)state;
    char buf[256];
    int len = gk_gi_method_names(buf, sizeof buf, ", ");
    assert_string_equal(buf, "none, vct, vpl, ispm, lgv, lightmap, volcaustics, radiosity");
    assert_int_equal(len, (int)strlen(buf));
    char small[8];
    assert_int_equal(gk_gi_method_names(small, sizeof small, " "), len - 7); /* ", " -> " " x 7 */
    assert_string_equal(small, "none vc");
    assert_true(gk_gi_is_method("vct"));
    assert_true(gk_gi_is_method("radiosity"));
    assert_false(gk_gi_is_method("rtx"));
    assert_false(gk_gi_is_method(""));
    assert_false(gk_gi_is_method("VCT"));
    assert_false(gk_gi_is_method(NULL));
}

static void scene_features_map_onto_needs(void **state)
{
    (void)state;
    gk_scene_features f = {0};
    assert_int_equal(gk_scene_gi_needs(&f), GK_GI_NEEDS_STATIC);
    f.has_animation = true;
    assert_int_equal(gk_scene_gi_needs(&f), 0);
    f.has_interreflection = true;
    f.has_caustics = true;
    assert_int_equal(gk_scene_gi_needs(&f), GK_GI_NEEDS_INTERREFLECTION | GK_GI_NEEDS_CAUSTICS);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(no_name_twice_and_none_first),
        cmocka_unit_test(registry_agrees_with_implemented),
        cmocka_unit_test(names_joined_for_messages),
        cmocka_unit_test(scene_features_map_onto_needs),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
