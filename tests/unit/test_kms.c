/* The KMS backend against the libdrm fake (link level) and fake GBM/EGL ops: mode choice, atomic
 * and legacy paths, flip pacing by events, connector loss, CRTC restore. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/log.h"
#include "fakes/fake_drm.h"
#include "platform/kms.h"

/* ---- fake GBM / EGL ops: three buffers, like a triple-buffered GBM surface ---- */
struct fake_bo {
    int id;
    bool locked;
    void *user;
    void (*destroy)(struct gbm_bo *, void *);
};
static struct fake_bo bos[3];
static int next_bo, swaps, locked_max;

static struct gbm_device *f_create_device(int fd) { (void)fd; return (struct gbm_device *)&bos; }
static void f_destroy_device(struct gbm_device *d) { (void)d; }
static struct gbm_surface *f_surface_create(struct gbm_device *d, uint32_t w, uint32_t h, uint32_t f, uint32_t fl)
{
    (void)d; (void)w; (void)h; (void)f; (void)fl;
    memset(bos, 0, sizeof bos);
    for (int i = 0; i < 3; i++)
        bos[i].id = i + 1;
    next_bo = swaps = locked_max = 0;
    return (struct gbm_surface *)&next_bo;
}
static void f_surface_destroy(struct gbm_surface *s)
{
    (void)s;
    for (int i = 0; i < 3; i++)
        if (bos[i].user && bos[i].destroy)
            bos[i].destroy((struct gbm_bo *)&bos[i], bos[i].user);
}
static struct gbm_bo *f_lock(struct gbm_surface *s)
{
    (void)s;
    for (int k = 0; k < 3; k++) {
        struct fake_bo *b = &bos[(next_bo + k) % 3];
        if (!b->locked) {
            b->locked = true;
            next_bo = (next_bo + k + 1) % 3;
            int n = 0;
            for (int i = 0; i < 3; i++)
                n += bos[i].locked;
            if (n > locked_max)
                locked_max = n;
            return (struct gbm_bo *)b;
        }
    }
    return NULL; /* all locked: the backend forgot to release */
}
static void f_release(struct gbm_surface *s, struct gbm_bo *bo) { (void)s; ((struct fake_bo *)bo)->locked = false; }
static void *f_get_user(struct gbm_bo *bo) { return ((struct fake_bo *)bo)->user; }
static void f_set_user(struct gbm_bo *bo, void *data, void (*destroy)(struct gbm_bo *, void *))
{
    ((struct fake_bo *)bo)->user = data;
    ((struct fake_bo *)bo)->destroy = destroy;
}
static void f_describe(struct gbm_bo *bo, gk_bo_desc *out)
{
    *out = (gk_bo_desc){.width = 1920, .height = 1080, .format = GBM_FORMAT_XRGB8888,
                        .handle = (uint32_t)((struct fake_bo *)bo)->id, .stride = 1920 * 4};
}
static int f_egl_setup(gk_gbm_egl *g, bool debug, gk_err *e) { (void)debug; (void)e; g->gles_version = 32; return 0; }
static int f_swap(gk_gbm_egl *g) { (void)g; swaps++; return 0; }
static void f_egl_teardown(gk_gbm_egl *g) { (void)g; }

static const struct gk_gbm_egl_ops fake_ops = {
    .create_device = f_create_device, .destroy_device = f_destroy_device, .surface_create = f_surface_create,
    .surface_destroy = f_surface_destroy, .lock_front_buffer = f_lock, .release_buffer = f_release,
    .bo_get_user_data = f_get_user, .bo_set_user_data = f_set_user, .bo_describe = f_describe,
    .egl_setup = f_egl_setup, .swap_buffers = f_swap, .egl_teardown = f_egl_teardown,
};

static int setup(void **state)
{
    (void)state;
    fake_drm_enable();
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    fake_drm_disable();
    return 0;
}

static gk_platform *open_fake(const char *mode, gk_err *e, bool *no_display)
{
    gk_platform_desc d;
    gk_platform_desc_defaults(&d);
    d.kind = GK_PLATFORM_KMS;
    d.width = d.height = 0;
    snprintf(d.device, sizeof d.device, "%s", fake_drm.device_path);
    snprintf(d.mode, sizeof d.mode, "%s", mode);
    bool nd = false;
    gk_platform *p = gk_kms_open_with(&d, &fake_ops, "/nonexistent", no_display ? no_display : &nd, e);
    return p;
}

/* ---- mode choice (pure) ---- */

static void mode_choice_preferred_configured_and_missing(void **state)
{
    (void)state;
    drmModeModeInfo modes[3] = {fake_drm_mode(1280, 720, 60, false), fake_drm_mode(1920, 1080, 50, false),
                                fake_drm_mode(1920, 1080, 60, true)};
    drmModeConnector c = {.count_modes = 3, .modes = modes};
    drmModeModeInfo m;
    gk_err e = {0};
    assert_int_equal(gk_kms_choose_mode(&c, "", 0, 0, &m, &e), 0);
    assert_int_equal(m.hdisplay, 1920);
    assert_int_equal(m.vrefresh, 60); /* the preferred one */
    assert_int_equal(gk_kms_choose_mode(&c, "1920x1080@50", 0, 0, &m, &e), 0);
    assert_int_equal(m.vrefresh, 50);
    assert_int_equal(gk_kms_choose_mode(&c, "1280x720", 0, 0, &m, &e), 0);
    assert_int_equal(m.hdisplay, 1280);
    assert_int_equal(gk_kms_choose_mode(&c, "", 1280, 720, &m, &e), 0); /* size as a wish */
    assert_int_equal(m.hdisplay, 1280);
    assert_int_equal(gk_kms_choose_mode(&c, "", 800, 600, &m, &e), 0);  /* a wish not offered */
    assert_int_equal(m.hdisplay, 1920);
    assert_int_equal(gk_kms_choose_mode(&c, "3840x2160", 0, 0, &m, &e), -1);
    assert_int_equal(e.code, GK_ERUNTIME);
    assert_non_null(strstr(e.msg, "3840x2160 not offered"));
    assert_non_null(strstr(e.msg, "1920x1080@50"));
    assert_int_equal(gk_kms_choose_mode(&c, "1920x1080@75", 0, 0, &m, &e), -1);
    assert_int_equal(gk_kms_choose_mode(&c, "1920*1080", 0, 0, &m, &e), -1);
    assert_int_equal(e.code, GK_EINPUT);
    assert_int_equal(gk_kms_choose_mode(&c, "1920x1080@60Hz", 0, 0, &m, &e), -1);
    assert_int_equal(e.code, GK_EINPUT);
}

/* ---- the backend over the fake ---- */

static void atomic_path_modesets_then_flips_on_events(void **state)
{
    (void)state;
    gk_err e = {0};
    gk_platform *p = open_fake("", &e, NULL);
    assert_non_null(p);
    gk_kms *k = p->impl;
    assert_ptr_equal(k->commit, gk_kms_atomic_commit);
    assert_int_equal(k->plane_id, 31); /* the primary plane, not the overlay listed first */
    int w, h;
    gk_platform_size(p, &w, &h);
    assert_int_equal(w, 1920);
    assert_int_equal(h, 1080);
    assert_int_equal(gk_platform_framebuffer(p), 0);
    fake_drm.hold_events = true;
    assert_int_equal(gk_platform_present(p, &e), 0);
    assert_int_equal(fake_drm.atomic_modesets, 1);
    assert_true(k->flip_pending);
    /* the flip has not completed: the event is not there, waiting does not clear it */
    assert_int_equal(gk_kms_wait(k, 0), 0);
    assert_true(k->flip_pending);
    assert_int_equal(fake_drm.flip_events_delivered, 0);
    /* the event arrives: the handler runs, the next present commits a new buffer */
    fake_drm.hold_events = false;
    fake_drm_release_events();
    assert_int_equal(gk_kms_wait(k, 100), 0);
    assert_false(k->flip_pending);
    assert_int_equal(k->flips_completed, 1);
    for (int i = 0; i < 10; i++)
        assert_int_equal(gk_platform_present(p, &e), 0);
    assert_int_equal(fake_drm.atomic_commits, 11);
    assert_int_equal(fake_drm.atomic_modesets, 1);
    assert_int_equal(k->flips_completed, 10); /* each present waited for the previous flip */
    assert_true(locked_max <= 2);               /* on screen + pending, never a third */
    assert_int_equal(fake_drm.addfb_calls, 3);  /* one framebuffer per buffer, then the cache */
    gk_platform_close(p);
    assert_int_equal(fake_drm.rmfb_calls, 3);
}

static void atomic_refused_falls_back_to_legacy(void **state)
{
    (void)state;
    fake_drm.atomic_modeset_refused = true;
    gk_err e = {0};
    gk_platform *p = open_fake("1280x720", &e, NULL);
    assert_non_null(p);
    gk_kms *k = p->impl;
    assert_int_equal(gk_platform_present(p, &e), 0);
    assert_ptr_equal(k->commit, gk_kms_legacy_commit);
    assert_int_equal(fake_drm.setcrtc_calls, 1);
    assert_int_equal(fake_drm.setcrtc_mode.hdisplay, 1280);
    assert_false(k->flip_pending); /* SetCrtc is synchronous */
    assert_int_equal(gk_platform_present(p, &e), 0);
    assert_int_equal(fake_drm.pageflip_calls, 1);
    assert_true(k->flip_pending);
    assert_int_equal(gk_platform_present(p, &e), 0);
    assert_int_equal(fake_drm.pageflip_calls, 2);
    assert_int_equal(fake_drm.flip_events_delivered, 1);
    gk_platform_close(p);
}

static void no_atomic_cap_uses_legacy_from_the_start(void **state)
{
    (void)state;
    fake_drm.atomic_cap_refused = true;
    gk_err e = {0};
    gk_platform *p = open_fake("", &e, NULL);
    assert_non_null(p);
    assert_ptr_equal(((gk_kms *)p->impl)->commit, gk_kms_legacy_commit);
    assert_int_equal(gk_platform_present(p, &e), 0);
    assert_int_equal(fake_drm.atomic_commits, 0);
    assert_int_equal(fake_drm.setcrtc_calls, 1);
    gk_platform_close(p);
}

static void close_restores_the_saved_crtc(void **state)
{
    (void)state;
    fake_drm.encoder_crtc = 21; /* the console drives CRTC 21 through encoder 50: keep using it */
    fake_drm.conn[0].current_encoder = 50;
    gk_err e = {0};
    gk_platform *p = open_fake("", &e, NULL);
    assert_non_null(p);
    assert_int_equal(((gk_kms *)p->impl)->crtc_id, 21);
    assert_int_equal(gk_platform_present(p, &e), 0);
    assert_int_equal(gk_platform_present(p, &e), 0);
    int before = fake_drm.setcrtc_calls;
    gk_platform_close(p);
    assert_int_equal(fake_drm.setcrtc_calls, before + 1);
    assert_int_equal(fake_drm.setcrtc_crtc, 21);
    assert_int_equal(fake_drm.setcrtc_fb, fake_drm.initial_fb);
    assert_true(fake_drm.setcrtc_had_mode);
    assert_int_equal(fake_drm.setcrtc_mode.hdisplay, 1024);
}

static void connector_loss_is_survived_and_return_remodesets(void **state)
{
    (void)state;
    gk_err e = {0};
    gk_platform *p = open_fake("", &e, NULL);
    assert_non_null(p);
    gk_kms *k = p->impl;
    assert_int_equal(gk_platform_present(p, &e), 0);
    fake_drm.conn[0].connected = false;
    fake_drm.flip_fails = true; /* what a flip on an unplugged display does */
    int commits = fake_drm.atomic_commits;
    assert_int_equal(gk_platform_present(p, &e), 0); /* not an error */
    assert_false(k->connected);
    for (int i = 0; i < 3; i++)
        assert_int_equal(gk_platform_present(p, &e), 0);
    assert_int_equal(fake_drm.atomic_commits, commits); /* nothing shown while unplugged */
    for (int i = 0; i < 3; i++)
        assert_false(bos[i].locked && bos[i].id != ((struct fake_bo *)k->bo_on_screen)->id);
    fake_drm.conn[0].connected = true;
    fake_drm.flip_fails = false;
    gk_kms_probe_connector(k, true);
    assert_true(k->connected);
    assert_int_equal(gk_platform_present(p, &e), 0);
    assert_int_equal(fake_drm.atomic_modesets, 2);
    gk_platform_close(p);
}

static void no_connected_display_is_a_clear_runtime_error(void **state)
{
    (void)state;
    fake_drm.conn[0].connected = false;
    gk_err e = {0};
    bool no_display = false;
    assert_null(open_fake("", &e, &no_display));
    assert_int_equal(e.code, GK_ERUNTIME);
    assert_true(no_display);
    assert_non_null(strstr(e.msg, "no connected display"));
    /* a missing device */
    gk_platform_desc d;
    gk_platform_desc_defaults(&d);
    snprintf(d.device, sizeof d.device, "/nonexistent/card0");
    assert_null(gk_kms_open_with(&d, &fake_ops, "/nonexistent", &no_display, &e));
    assert_true(no_display);
    assert_non_null(strstr(e.msg, "/nonexistent/card0"));
    /* no device at all in the scan directory */
    d.device[0] = '\0';
    assert_null(gk_kms_open_with(&d, &fake_ops, "/nonexistent", &no_display, &e));
    assert_true(no_display);
    assert_non_null(strstr(e.msg, "no DRM device"));
}

static void mode_not_offered_is_not_no_display(void **state)
{
    (void)state;
    gk_err e = {0};
    bool no_display = true;
    assert_null(open_fake("640x480", &e, &no_display));
    assert_false(no_display); /* AUTO must not hide this behind the mock */
    assert_non_null(strstr(e.msg, "640x480 not offered"));
}

static void scan_picks_the_first_card_with_a_display(void **state)
{
    (void)state;
    char dir[] = "/tmp/gk-dri-XXXXXX";
    assert_non_null(mkdtemp(dir));
    char card0[64], card1[64], render[64];
    snprintf(card0, sizeof card0, "%s/card0", dir);
    snprintf(card1, sizeof card1, "%s/card1", dir);
    snprintf(render, sizeof render, "%s/renderD128", dir);
    assert_int_equal(symlink(fake_drm.device_path, card0), 0);
    assert_int_equal(symlink(fake_drm.device_path, card1), 0);
    assert_int_equal(symlink(fake_drm.device_path, render), 0);
    fake_drm.resources_fail_calls = 1; /* card0 is not a KMS device (e.g. a GPU without outputs) */
    gk_platform_desc d;
    gk_platform_desc_defaults(&d);
    d.width = d.height = 0;
    bool no_display = false;
    gk_err e = {0};
    gk_platform *p = gk_kms_open_with(&d, &fake_ops, dir, &no_display, &e);
    assert_non_null(p);
    assert_string_equal(((gk_kms *)p->impl)->device, card1);
    gk_platform_close(p);
    unlink(card0);
    unlink(card1);
    unlink(render);
    rmdir(dir);
}

int main(void)
{
    gk_log_set_quiet(1);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(mode_choice_preferred_configured_and_missing),
        cmocka_unit_test_setup_teardown(atomic_path_modesets_then_flips_on_events, setup, teardown),
        cmocka_unit_test_setup_teardown(atomic_refused_falls_back_to_legacy, setup, teardown),
        cmocka_unit_test_setup_teardown(no_atomic_cap_uses_legacy_from_the_start, setup, teardown),
        cmocka_unit_test_setup_teardown(close_restores_the_saved_crtc, setup, teardown),
        cmocka_unit_test_setup_teardown(connector_loss_is_survived_and_return_remodesets, setup, teardown),
        cmocka_unit_test_setup_teardown(no_connected_display_is_a_clear_runtime_error, setup, teardown),
        cmocka_unit_test_setup_teardown(mode_not_offered_is_not_no_display, setup, teardown),
        cmocka_unit_test_setup_teardown(scan_picks_the_first_card_with_a_display, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
