/* Playlist and attract mode with synthetic times and events; method choice per scene. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "kiosk/playlist.h"

static const char names[3][GK_NAME_LEN] = {"a", "b", "c"};

static gk_input_event ev(enum gk_input_kind k, enum gk_button b, double t)
{
    return (gk_input_event){.kind = k, .button = b, .time_s = t};
}

static void dwell_advances_and_wraps(void **state)
{
    (void)state;
    gk_playlist pl;
    gk_playlist_init(&pl, names, 3, 10, 30);
    gk_playlist_start(&pl, 0);
    assert_string_equal(gk_playlist_scene(&pl), "a");
    assert_int_equal(gk_playlist_tick(&pl, 9.99), 0);
    assert_int_equal(gk_playlist_tick(&pl, 10.0), GK_PL_SCENE);
    assert_string_equal(gk_playlist_scene(&pl), "b");
    assert_int_equal(gk_playlist_tick(&pl, 15), 0);
    assert_int_equal(gk_playlist_tick(&pl, 20.01), GK_PL_SCENE);
    assert_int_equal(gk_playlist_tick(&pl, 30.02), GK_PL_SCENE);
    assert_string_equal(gk_playlist_scene(&pl), "a"); /* wrapped */
}

static void input_pauses_attract_mode(void **state)
{
    (void)state;
    gk_playlist pl;
    gk_playlist_init(&pl, names, 3, 10, 30);
    gk_playlist_start(&pl, 0);
    gk_input_event e = ev(GK_INPUT_PRESS, GK_BTN_INFO, 5);
    assert_int_equal(gk_playlist_input(&pl, &e), GK_PL_INPUT);
    assert_true(gk_playlist_next_change(&pl) == 35);
    assert_int_equal(gk_playlist_tick(&pl, 20), 0);  /* dwell is over, but the input pause is not */
    assert_int_equal(gk_playlist_tick(&pl, 34.9), 0);
    assert_int_equal(gk_playlist_tick(&pl, 35), GK_PL_SCENE);
    assert_string_equal(gk_playlist_scene(&pl), "b");
    /* later visits use the dwell again once the pause is over */
    assert_true(gk_playlist_next_change(&pl) == 45);
}

static void next_prev_wrap(void **state)
{
    (void)state;
    gk_playlist pl;
    gk_playlist_init(&pl, names, 3, 10, 0);
    gk_playlist_start(&pl, 0);
    gk_input_event e = ev(GK_INPUT_CLICK, GK_BTN_PREV, 1);
    assert_int_equal(gk_playlist_input(&pl, &e), GK_PL_INPUT | GK_PL_SCENE);
    assert_string_equal(gk_playlist_scene(&pl), "c");
    e = ev(GK_INPUT_CLICK, GK_BTN_NEXT, 2);
    gk_playlist_input(&pl, &e);
    assert_string_equal(gk_playlist_scene(&pl), "a");
    /* a click starts a new visit: its dwell runs from the click */
    assert_true(gk_playlist_next_change(&pl) == 12);
    /* a raw press does not change the scene */
    e = ev(GK_INPUT_PRESS, GK_BTN_NEXT, 3);
    assert_int_equal(gk_playlist_input(&pl, &e), GK_PL_INPUT);
    assert_string_equal(gk_playlist_scene(&pl), "a");
}

static void failed_scenes_are_skipped(void **state)
{
    (void)state;
    gk_playlist pl;
    gk_playlist_init(&pl, names, 3, 10, 0);
    assert_int_equal(gk_playlist_mark_failed(&pl, 0), 2);
    gk_playlist_start(&pl, 0);
    assert_string_equal(gk_playlist_scene(&pl), "b");
    assert_int_equal(gk_playlist_step(&pl, +1, 1), GK_PL_SCENE);
    assert_string_equal(gk_playlist_scene(&pl), "c");
    assert_int_equal(gk_playlist_step(&pl, +1, 2), GK_PL_SCENE);
    assert_string_equal(gk_playlist_scene(&pl), "b");
    assert_int_equal(gk_playlist_mark_failed(&pl, 2), 1);
    /* one usable scene: next does nothing, the visit goes on */
    assert_int_equal(gk_playlist_step(&pl, +1, 3), 0);
    assert_string_equal(gk_playlist_scene(&pl), "b");
    assert_int_equal(gk_playlist_tick(&pl, 100), 0);
    assert_int_equal(gk_playlist_mark_failed(&pl, 1), 0);
}

static void mode_cycles_methods_info_toggles_hold_resets(void **state)
{
    (void)state;
    gk_playlist pl;
    gk_playlist_init(&pl, names, 3, 10, 0);
    gk_playlist_start(&pl, 0);
    char m[3][GK_METHOD_LEN] = {"none", "vct", "vpl"};
    gk_playlist_set_methods(&pl, m, 3, 1);
    assert_string_equal(gk_playlist_method(&pl), "vct");
    gk_input_event e = ev(GK_INPUT_CLICK, GK_BTN_MODE, 1);
    assert_int_equal(gk_playlist_input(&pl, &e), GK_PL_INPUT | GK_PL_METHOD);
    assert_string_equal(gk_playlist_method(&pl), "vpl");
    gk_playlist_input(&pl, &e);
    assert_string_equal(gk_playlist_method(&pl), "none");
    e = ev(GK_INPUT_HOLD, GK_BTN_MODE, 2);
    assert_int_equal(gk_playlist_input(&pl, &e), GK_PL_INPUT | GK_PL_METHOD);
    assert_string_equal(gk_playlist_method(&pl), "vct");
    assert_int_equal(gk_playlist_input(&pl, &e), GK_PL_INPUT); /* already the default */
    assert_true(pl.hud_visible);
    e = ev(GK_INPUT_CLICK, GK_BTN_INFO, 3);
    assert_int_equal(gk_playlist_input(&pl, &e), GK_PL_INPUT | GK_PL_HUD);
    assert_false(pl.hud_visible);
    /* holding info toggles the split view (and leaves the HUD and the method alone) */
    assert_false(pl.split_view);
    e = ev(GK_INPUT_HOLD, GK_BTN_INFO, 3.5);
    assert_int_equal(gk_playlist_input(&pl, &e), GK_PL_INPUT | GK_PL_SPLIT);
    assert_true(pl.split_view);
    assert_false(pl.hud_visible);
    assert_string_equal(gk_playlist_method(&pl), "vct");
    assert_int_equal(gk_playlist_input(&pl, &e), GK_PL_INPUT | GK_PL_SPLIT);
    assert_false(pl.split_view);
    /* a single method: mode changes nothing */
    gk_playlist_set_methods(&pl, m, 1, 0);
    e = ev(GK_INPUT_CLICK, GK_BTN_MODE, 4);
    assert_int_equal(gk_playlist_input(&pl, &e), GK_PL_INPUT);
    e = ev(GK_INPUT_QUIT, GK_BTN_NEXT, 5);
    assert_int_equal(gk_playlist_input(&pl, &e), 0);
}

static void methods_for_scene_rules(void **state)
{
    (void)state;
    const char *applicable[] = {"none", "vct", "vpl", "lightmap"};
    char out[GK_PL_MAX_METHODS][GK_METHOD_LEN], note[256];
    int def;
    /* derived: everything that applies, the first GI method by default */
    int n = gk_methods_for_scene(applicable, 4, NULL, NULL, out, &def, note, sizeof note);
    assert_int_equal(n, 4);
    assert_string_equal(out[def], "vct");
    assert_string_equal(note, "");
    /* configured: its order, the first is the default, what does not apply is noted */
    n = gk_methods_for_scene(applicable, 4, "vpl,ispm,none", NULL, out, &def, note, sizeof note);
    assert_int_equal(n, 2);
    assert_string_equal(out[0], "vpl");
    assert_string_equal(out[1], "none");
    assert_int_equal(def, 0);
    assert_string_equal(note, "method 'ispm' does not apply");
    /* forced and applicable: it becomes the default, added if the list lacked it */
    n = gk_methods_for_scene(applicable, 4, "vpl,none", "lightmap", out, &def, note, sizeof note);
    assert_int_equal(n, 3);
    assert_string_equal(out[def], "lightmap");
    /* forced but not applicable: logged, the scene's default stays */
    n = gk_methods_for_scene(applicable, 4, "vpl,none", "ispm", out, &def, note, sizeof note);
    assert_string_equal(out[def], "vpl");
    assert_string_equal(note, "--method ispm does not apply to this scene; using vpl");
    /* nothing applies but none */
    const char *only_none[] = {"none"};
    n = gk_methods_for_scene(only_none, 1, "vct", NULL, out, &def, note, sizeof note);
    assert_int_equal(n, 1);
    assert_string_equal(out[def], "none");
}

/* prev held pauses the animation time and resumes it where it stood; a scene change (here next)
 * starts the new visit at time 0, running; with one scene a step keeps the pause, at time 0. */
static void prev_hold_pauses_animation_time(void **state)
{
    (void)state;
    gk_playlist pl;
    gk_playlist_init(&pl, names, 3, 100, 0);
    gk_playlist_start(&pl, 10);
    assert_true(gk_playlist_anim_time(&pl, 12.5) == 2.5);
    gk_input_event e = ev(GK_INPUT_HOLD, GK_BTN_PREV, 13);
    assert_int_equal(gk_playlist_input(&pl, &e), GK_PL_INPUT | GK_PL_PAUSE);
    assert_true(pl.paused);
    assert_string_equal(gk_playlist_scene(&pl), "a"); /* a hold is no click: the scene stays */
    assert_true(gk_playlist_anim_time(&pl, 13) == 3.0);
    assert_true(gk_playlist_anim_time(&pl, 40) == 3.0); /* frozen */
    e = ev(GK_INPUT_HOLD, GK_BTN_PREV, 20);
    assert_int_equal(gk_playlist_input(&pl, &e), GK_PL_INPUT | GK_PL_PAUSE);
    assert_false(pl.paused);
    assert_true(gk_playlist_anim_time(&pl, 20) == 3.0); /* resumed where it stood */
    assert_true(gk_playlist_anim_time(&pl, 21.5) == 4.5);
    e = ev(GK_INPUT_HOLD, GK_BTN_PREV, 22);               /* paused at 5 s again */
    gk_playlist_input(&pl, &e);
    assert_true(gk_playlist_anim_time(&pl, 30) == 5.0);
    e = ev(GK_INPUT_CLICK, GK_BTN_NEXT, 31);
    assert_int_equal(gk_playlist_input(&pl, &e), GK_PL_INPUT | GK_PL_SCENE);
    assert_false(pl.paused);                               /* the next scene moves from time 0 */
    assert_true(gk_playlist_anim_time(&pl, 31) == 0.0);
    assert_true(gk_playlist_anim_time(&pl, 32) == 1.0);

    gk_playlist_init(&pl, names, 1, 10, 0);                /* one scene: a step restarts its visit */
    gk_playlist_start(&pl, 0);
    e = ev(GK_INPUT_HOLD, GK_BTN_PREV, 4);
    gk_playlist_input(&pl, &e);
    assert_int_equal(gk_playlist_tick(&pl, 10), 0);
    assert_true(pl.paused);
    assert_true(gk_playlist_anim_time(&pl, 12) == 0.0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(dwell_advances_and_wraps),
        cmocka_unit_test(input_pauses_attract_mode),
        cmocka_unit_test(next_prev_wrap),
        cmocka_unit_test(failed_scenes_are_skipped),
        cmocka_unit_test(mode_cycles_methods_info_toggles_hold_resets),
        cmocka_unit_test(methods_for_scene_rules),
        cmocka_unit_test(prev_hold_pauses_animation_time),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
