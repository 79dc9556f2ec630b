/* The GPU tests of the work models (#21, app/gl/pass_work.h; included by tests/gpu/test_*_work.c,
 * not a program itself): one entry of a method's last frame's work. */
#ifndef TEST_PASS_WORK_H
#define TEST_PASS_WORK_H

#include <string.h>

#include "gi/gi.h"

/* The fetches of the entry for pass and kind in m's gk_gi_method.pass_work, or -1 when it reports
   none (not a counting frame, the pass did not run, or its kind is another). */
static inline double tpw_fetches(const gk_gi_method *m, void *self, const char *pass, const char *kind)
{
    gk_pass_work w[GK_MAX_PASS_WORK];
    int n = m->pass_work(self, w, GK_MAX_PASS_WORK);
    for (int i = 0; i < n; i++)
        if (!strcmp(w[i].pass, pass) && !strcmp(w[i].kind, kind))
            return w[i].fetches;
    return -1.0;
}

#endif
