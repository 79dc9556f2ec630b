/* The kiosk's automatic choice marked among the bench's rows (issue: "the scheduler's choice
 * marked" on the chart): for each scene, the method gk_calibration_choose picks from the shipped
 * calibration -- what attract mode shows at the target -- in the row that ran it at its default
 * budgets (the levels the calibration measured). */
#include <string.h>

#include "../sched/calibration.h"
#include "bench.h"

static bool at_defaults(const gk_bench_result *r, const gk_bench_row *row)
{
    for (int k = 0; k < r->budget.n; k++)
        if (row->level[k] != r->budget.def[k]->default_level)
            return false;
    return true;
}

void gk_bench_mark_choice(gk_bench_result *r, const gk_calibration *c, double target_ms, double target_pixels)
{
    for (int i = 0; i < r->n_rows; i++) {
        gk_bench_row *row = &r->rows[i];
        bool first = true;
        for (int j = 0; j < i && first; j++)
            first = strcmp(r->rows[j].scene, row->scene) != 0;
        if (!first)
            continue;
        /* the scene's methods, in the order the bench ran them */
        const char *methods[16];
        int n = 0;
        for (int j = i; j < r->n_rows && n < 16; j++) {
            if (strcmp(r->rows[j].scene, row->scene) != 0)
                continue;
            bool seen = false;
            for (int m = 0; m < n; m++)
                seen |= !strcmp(methods[m], r->rows[j].method);
            if (!seen)
                methods[n++] = r->rows[j].method;
        }
        int pick = gk_calibration_choose(c, row->scene, methods, n, target_ms, target_pixels, NULL, 0);
        if (pick < 0)
            continue;
        for (int j = i; j < r->n_rows; j++)
            if (!strcmp(r->rows[j].scene, row->scene) && !strcmp(r->rows[j].method, methods[pick]) &&
                at_defaults(r, &r->rows[j])) {
                r->rows[j].chosen = true;
                break;
            }
    }
}
