/* libFuzzer target for the kiosk configuration (INI through libinih, app/kiosk/config.c): the
 * input is written to a file and read by gk_kiosk_config_load, as `gikiosk run --config` does, so
 * the file reader's checks (size, NUL bytes) run too. Any input must load, or fail with GK_EINPUT
 * and a message starting with the file's path; no crash, leak, hang or undefined behaviour. A
 * config that loads has its [budgets] ranges applied to the renderer's kind of knobs and its
 * per-scene method lists looked up, as the kiosk does next. */
#include <stdint.h>

#include "base/log.h"
#include "fuzz_files.h"
#include "kiosk/config.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* Two knobs shaped like the renderer's (app/render/renderer_knobs.c): one numeric, one named. */
static const gk_knob_def knob_scale = {
    .name = "render_scale", .owner = "render", .n_values = 4, .values = {"0.5", "0.75", "0.9", "1.0"},
    .cost = {1, 2, 3, 4}, .default_level = 3};
static const gk_knob_def knob_shadow = {
    .name = "shadow", .owner = "render", .n_values = 3, .values = {"hard", "pcf", "pcss"},
    .cost = {1, 2, 4}, .default_level = 1};

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    gk_log_set_quiet(1);
    char path[300];
    snprintf(path, sizeof path, "%s/kiosk.ini", fuzz_dir());
    fuzz_write_file(path, data, size);
    gk_kiosk_config c;
    gk_kiosk_config_defaults(&c);
    gk_err e = {0};
    if (gk_kiosk_config_load(&c, path, &e) != 0) {
        if (e.code != GK_EINPUT)
            abort(); /* bad input is GK_EINPUT (exit 2), never a runtime failure */
        fuzz_require_named(e.msg, path);
        return 0;
    }
    gk_budget b;
    gk_budget_init(&b);
    gk_budget_add(&b, &knob_scale);
    gk_budget_add(&b, &knob_shadow);
    gk_err be = {0};
    if (gk_kiosk_config_apply_budgets(&c, &b, &be) != 0)
        fuzz_require_named(be.msg, path);
    for (int i = 0; i < c.n_scenes; i++)
        (void)gk_kiosk_config_methods(&c, c.scenes[i]);
    return 0;
}
