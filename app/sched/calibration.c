#include "calibration.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define MAX_ROWS 4096
#define MAX_FILE_BYTES (4L << 20) /* a table of every scene x method is a few kB */

void gk_calibration_class(const char *renderer, char *out, int out_len)
{
    int n = 0;
    for (const char *p = renderer ? renderer : ""; *p && !isspace((unsigned char)*p) && n < out_len - 1; p++)
        if (isalnum((unsigned char)*p) || *p == '_' || *p == '-')
            out[n++] = (char)tolower((unsigned char)*p);
    if (n == 0 && out_len > 7)
        n = snprintf(out, (size_t)out_len, "unknown");
    out[n] = '\0';
}

void gk_calibration_path(const char *scenes_dir, const char *renderer, char *out, int out_len)
{
    char cls[64];
    gk_calibration_class(renderer, cls, sizeof cls);
    const char *dir = scenes_dir ? scenes_dir : "config/scenes";
    const char *slash = strrchr(dir, '/');
    int parent = slash ? (int)(slash - dir) : 0;
    snprintf(out, (size_t)out_len, "%.*s%scalibration/%s.csv", parent, dir, slash ? "/" : "", cls);
}

void gk_calibration_free(gk_calibration *c)
{
    free(c->rows);
    memset(c, 0, sizeof *c);
}

static bool parse_double(const char *s, double *v)
{
    char *end = NULL;
    errno = 0;
    *v = strtod(s, &end);
    return end != s && *end == '\0' && errno == 0 && isfinite(*v) && *v >= 0.0;
}

static bool parse_int(const char *s, int *v)
{
    char *end = NULL;
    long x = strtol(s, &end, 10);
    *v = (int)x;
    return end != s && *end == '\0' && x > 0 && x <= 65536;
}

static const char *const header_v1 = "scene,method,width,height,frame_ms,error,metric,ruler";
static const char *const header = "scene,method,width,height,frame_ms,error,metric,ruler,knob,value,passes";

/* "PATH=MS PATH=MS ...": names of dotted identifiers, finite non-negative times. */
static bool valid_passes(const char *s)
{
    while (*s) {
        const char *eq = strchr(s, '=');
        if (!eq || eq == s)
            return false;
        for (const char *p = s; p < eq; p++)
            if (!isalnum((unsigned char)*p) && *p != '_' && *p != '.')
                return false;
        char *end = NULL;
        errno = 0;
        double v = strtod(eq + 1, &end);
        if (end == eq + 1 || errno || !isfinite(v) || v < 0 || (*end && *end != ' '))
            return false;
        s = *end ? end + 1 : end;
    }
    return true;
}

/* One data line into r (fields: 8 in the first format, 11 now); false with what is wrong in why. */
static bool parse_row(char *line, int want, gk_calib_row *r, const char **why)
{
    char *f[11];
    int n = 0;
    memset(r, 0, sizeof *r);
    for (char *p = line; n < want; n++) {
        f[n] = p;
        char *comma = strchr(p, ',');
        if (!comma) {
            n++;
            break;
        }
        *comma = '\0';
        p = comma + 1;
    }
    if (n != want) {
        *why = want == 8 ? "expected 8 fields (scene,method,width,height,frame_ms,error,metric,ruler)"
                         : "expected 11 fields (scene,method,width,height,frame_ms,error,metric,ruler,knob,value,passes)";
        return false;
    }
    if (!f[0][0] || strlen(f[0]) >= sizeof r->scene || !f[1][0] || strlen(f[1]) >= sizeof r->method) {
        *why = "scene or method name empty or too long";
        return false;
    }
    snprintf(r->scene, sizeof r->scene, "%s", f[0]);
    snprintf(r->method, sizeof r->method, "%s", f[1]);
    if (!parse_int(f[2], &r->width) || !parse_int(f[3], &r->height)) {
        *why = "width and height must be whole numbers 1..65536";
        return false;
    }
    if (!parse_double(f[4], &r->frame_ms) || r->frame_ms <= 0.0) {
        *why = "frame_ms must be a positive number";
        return false;
    }
    if (!parse_double(f[5], &r->error)) {
        *why = "error must be a finite number >= 0";
        return false;
    }
    if (strcmp(f[6], "rel_rmse") != 0 && strcmp(f[6], "rmse") != 0) {
        *why = "metric must be rel_rmse or rmse";
        return false;
    }
    if (want == 8)
        return true;
    if (strlen(f[8]) >= sizeof r->knob || strlen(f[9]) >= sizeof r->value || !f[8][0] != !f[9][0]) {
        *why = "knob and value: both empty (the default row) or both set, at most 31 and 23 bytes";
        return false;
    }
    snprintf(r->knob, sizeof r->knob, "%s", f[8]);
    snprintf(r->value, sizeof r->value, "%s", f[9]);
    if (strlen(f[10]) >= sizeof r->passes || !valid_passes(f[10])) {
        *why = "passes must be 'PATH=MS PATH=MS ...' (dotted pass paths, times >= 0)";
        return false;
    }
    snprintf(r->passes, sizeof r->passes, "%s", f[10]);
    return true;
}

double gk_calib_row_pass_ms(const gk_calib_row *r, const char *path)
{
    size_t len = strlen(path);
    for (const char *p = r->passes; *p;) {
        if (!strncmp(p, path, len) && p[len] == '=')
            return strtod(p + len + 1, NULL);
        const char *space = strchr(p, ' ');
        if (!space)
            break;
        p = space + 1;
    }
    return NAN;
}

int gk_calibration_load(const char *path, gk_calibration *c, gk_err *e)
{
    memset(c, 0, sizeof *c);
    snprintf(c->path, sizeof c->path, "%s", path);
    struct stat st;
    if (stat(path, &st) != 0)
        return gk_fail(e, GK_ERUNTIME, "%s: %s", path, strerror(errno));
    if (!S_ISREG(st.st_mode) || st.st_size > MAX_FILE_BYTES)
        return gk_fail(e, GK_EINPUT, "%s: not a regular file of at most %ld bytes", path, MAX_FILE_BYTES);
    FILE *f = fopen(path, "r");
    if (!f)
        return gk_fail(e, GK_ERUNTIME, "%s: %s", path, strerror(errno));
    c->rows = calloc(MAX_ROWS, sizeof *c->rows);
    if (!c->rows) {
        fclose(f);
        return gk_fail(e, GK_ERUNTIME, "%s: out of memory", path);
    }
    char line[1024];
    int line_no = 0, rc = 0, fields = 0;
    bool have_header = false;
    while (rc == 0 && fgets(line, sizeof line, f)) {
        line_no++;
        size_t len = strlen(line);
        if (len == sizeof line - 1 && line[len - 1] != '\n') {
            rc = gk_fail(e, GK_EINPUT, "%s:%d: line longer than %zu bytes", path, line_no, sizeof line - 2);
            break;
        }
        while (len && (line[len - 1] == '\n' || line[len - 1] == '\r'))
            line[--len] = '\0';
        if (len == 0 || line[0] == '#')
            continue;
        if (!have_header) {
            fields = !strcmp(line, header) ? 11 : !strcmp(line, header_v1) ? 8 : 0;
            if (!fields)
                rc = gk_fail(e, GK_EINPUT, "%s:%d: expected the header '%s'", path, line_no, header);
            have_header = true;
            continue;
        }
        if (c->n == MAX_ROWS) {
            rc = gk_fail(e, GK_EINPUT, "%s:%d: more than %d rows", path, line_no, MAX_ROWS);
            break;
        }
        const char *why = NULL;
        gk_calib_row *r = &c->rows[c->n];
        if (!parse_row(line, fields, r, &why))
            rc = gk_fail(e, GK_EINPUT, "%s:%d: %s", path, line_no, why);
        else if (r->knob[0] ? (bool)gk_calibration_find_level(c, r->scene, r->method, r->knob, r->value)
                            : (bool)gk_calibration_find(c, r->scene, r->method))
            rc = gk_fail(e, GK_EINPUT, "%s:%d: %s/%s%s%s%s%s listed twice", path, line_no, r->scene, r->method,
                         r->knob[0] ? " " : "", r->knob, r->knob[0] ? "=" : "", r->value);
        else
            c->n++;
    }
    if (rc == 0 && ferror(f))
        rc = gk_fail(e, GK_ERUNTIME, "%s: read error", path);
    if (rc == 0 && !have_header)
        rc = gk_fail(e, GK_EINPUT, "%s: no header '%s'", path, header);
    fclose(f);
    if (rc != 0)
        gk_calibration_free(c);
    return rc;
}

const gk_calib_row *gk_calibration_find(const gk_calibration *c, const char *scene, const char *method)
{
    for (int i = 0; i < c->n; i++)
        if (!c->rows[i].knob[0] && !strcmp(c->rows[i].scene, scene) && !strcmp(c->rows[i].method, method))
            return &c->rows[i];
    return NULL;
}

const gk_calib_row *gk_calibration_find_level(const gk_calibration *c, const char *scene, const char *method,
                                              const char *knob, const char *value)
{
    for (int i = 0; i < c->n; i++)
        if (!strcmp(c->rows[i].knob, knob) && !strcmp(c->rows[i].value, value) &&
            !strcmp(c->rows[i].scene, scene) && !strcmp(c->rows[i].method, method))
            return &c->rows[i];
    return NULL;
}

int gk_calibration_choose(const gk_calibration *c, const char *scene, const char *const *methods, int n,
                          double target_ms, double run_pixels, char *why, int why_len)
{
    if (why && why_len > 0)
        why[0] = '\0';
    const gk_calib_row *none = gk_calibration_find(c, scene, "none");
    int best = -1, fastest = -1, none_index = -1;
    double best_err = INFINITY, fastest_ms = INFINITY, ms_of[64];
    char worse[256] = "";
    for (int i = 0; i < n && i < 64; i++) {
        const gk_calib_row *r = gk_calibration_find(c, scene, methods[i]);
        ms_of[i] = NAN;
        if (!r)
            continue;
        if (!strcmp(methods[i], "none"))
            none_index = i;
        if (none && r->error > none->error) {
            snprintf(worse + strlen(worse), sizeof worse - strlen(worse), ", %s %.3f worse than none", methods[i],
                     r->error);
            continue;
        }
        double scale = run_pixels > 0 ? run_pixels / ((double)r->width * r->height) : 1.0;
        ms_of[i] = r->frame_ms * scale;
        if (ms_of[i] < fastest_ms)
            fastest_ms = ms_of[i], fastest = i;
        if (ms_of[i] <= target_ms && r->error < best_err)
            best_err = r->error, best = i;
    }
    int pick = best >= 0 ? best : fastest;
    if (pick < 0 && none_index >= 0)
        pick = none_index; /* every GI method is worse than none */
    if (pick >= 0 && why && why_len > 0) {
        const gk_calib_row *r = gk_calibration_find(c, scene, methods[pick]);
        snprintf(why, (size_t)why_len, "%s: error %.3f at ~%.0f ms%s (none %.3f%s)", methods[pick], r->error,
                 isnan(ms_of[pick]) ? r->frame_ms : ms_of[pick], best >= 0 ? "" : ", over the target: the fastest",
                 none ? none->error : NAN, worse);
    }
    return pick;
}
