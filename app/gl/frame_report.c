#include "frame_report.h"

#include <stdio.h>
#include <string.h>

double gk_frame_report_top_sum(const gk_frame_report *r)
{
    double sum = 0.0;
    for (int i = 0; i < r->n; i++)
        if (r->pass[i].parent < 0)
            sum += r->pass[i].ms;
    return sum;
}

int gk_frame_report_path(const gk_frame_report *r, int i, char *out, size_t out_len)
{
    int chain[GK_MAX_PASSES], depth = 0;
    for (int k = i; k >= 0 && depth < GK_MAX_PASSES; k = r->pass[k].parent)
        chain[depth++] = k;
    size_t len = 0;
    if (out_len)
        out[0] = '\0';
    for (int d = depth - 1; d >= 0; d--) {
        int n = snprintf(out + len, len < out_len ? out_len - len : 0, "%s%s", d == depth - 1 ? "" : ".",
                         r->pass[chain[d]].name);
        if (n > 0)
            len += (size_t)n;
    }
    return (int)len;
}

int gk_frame_report_find(const gk_frame_report *r, const char *path)
{
    char p[GK_PASS_PATH_LEN];
    for (int i = 0; i < r->n; i++) {
        gk_frame_report_path(r, i, p, sizeof p);
        if (strcmp(p, path) == 0)
            return i;
    }
    return -1;
}

double gk_frame_report_ms(const gk_frame_report *r, const char *path)
{
    int i = gk_frame_report_find(r, path);
    return i >= 0 ? r->pass[i].ms : 0.0;
}
