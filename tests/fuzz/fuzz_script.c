/* libFuzzer target for the mock platform's button script (platform/script.c): the input is written
 * to a file and read by gk_script_load, as `gikiosk run --script` does. Any input must load, or
 * fail with GK_EINPUT and a message starting with the file's path; no crash, leak, hang (the
 * loader is O(n log n): a quadratic case shows as a libFuzzer timeout) or undefined behaviour. A
 * script that loads must hold its documented invariants: edges sorted by time, finite times,
 * known buttons. */
#include <math.h>
#include <stdint.h>

#include "base/log.h"
#include "fuzz_files.h"
#include "platform/script.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    gk_log_set_quiet(1);
    char path[300];
    snprintf(path, sizeof path, "%s/buttons.txt", fuzz_dir());
    fuzz_write_file(path, data, size);
    gk_script s = {0};
    gk_err e = {0};
    if (gk_script_load(path, &s, &e) != 0) {
        if (e.code != GK_EINPUT)
            abort();
        fuzz_require_named(e.msg, path);
        gk_script_free(&s);
        return 0;
    }
    for (int i = 0; i < s.count; i++) {
        if (!isfinite(s.edges[i].time_s) || (unsigned)s.edges[i].button >= GK_BTN_COUNT)
            abort();
        if (i > 0 && s.edges[i].time_s < s.edges[i - 1].time_s)
            abort(); /* the timeline must be sorted */
    }
    gk_script_free(&s);
    return 0;
}
