/* Kiosk configuration reader (see config.h). libinih in Debian is built without
 * INI_HANDLER_LINENO, so the handler never learns the line number: we feed inih through
 * ini_parse_stream with a reader that counts lines, and the handler reads the count. The reader
 * also sees section headers, which inih does not pass to the handler for empty sections. */
#include "config.h"

#include "base/readfile.h"

#include <ctype.h>
#include <errno.h>
#include <ini.h>
#include <linux/input-event-codes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gi/gi_catalogue.h"

static char *trim(char *s)
{
    while (isspace((unsigned char)*s))
        s++;
    size_t n = strlen(s);
    while (n > 0 && isspace((unsigned char)s[n - 1]))
        s[--n] = '\0';
    return s;
}

int gk_method_list_check(const char *list, const char *what, gk_err *e)
{
    char buf[256];
    snprintf(buf, sizeof buf, "%s", list);
    char *save = NULL;
    int n = 0;
    for (char *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        tok = trim(tok);
        if (!gk_gi_is_method(tok)) {
            char known[256];
            gk_gi_method_names(known, sizeof known, ", ");
            return gk_fail(e, GK_EINPUT, "%s: unknown method '%s' (known: %s)", what, tok, known);
        }
        n++;
    }
    if (n == 0)
        return gk_fail(e, GK_EINPUT, "%s: empty method list", what);
    return 0;
}

int gk_parse_double(const char *s, double *out)
{
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || *end != '\0' || errno || !isfinite(v))
        return -1;
    *out = v;
    return 0;
}

int gk_parse_int(const char *s, long *out)
{
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (end == s || *end != '\0' || errno)
        return -1;
    *out = v;
    return 0;
}

int gk_parse_size(const char *s, int *w, int *h)
{
    long a, b;
    char buf[64], *x;
    snprintf(buf, sizeof buf, "%s", s);
    if (!(x = strchr(buf, 'x')))
        return -1;
    *x = '\0';
    if (gk_parse_int(buf, &a) || gk_parse_int(x + 1, &b) || a < 1 || b < 1 || a > 16384 || b > 16384)
        return -1;
    if (!isdigit((unsigned char)buf[0]) || !isdigit((unsigned char)x[1]))
        return -1; /* no signs or spaces */
    *w = (int)a;
    *h = (int)b;
    return 0;
}

int gk_parse_platform(const char *s, enum gk_platform_kind *k)
{
    if (!strcmp(s, "auto"))
        *k = GK_PLATFORM_AUTO;
    else if (!strcmp(s, "kms"))
        *k = GK_PLATFORM_KMS;
    else if (!strcmp(s, "mock"))
        *k = GK_PLATFORM_MOCK;
    else
        return -1;
    return 0;
}

void gk_kiosk_config_defaults(gk_kiosk_config *c)
{
    memset(c, 0, sizeof *c);
    c->platform = GK_PLATFORM_AUTO;
    c->width = 1280;
    c->height = 720;
    c->target_ms = 16.7;
    gk_button_config *b = &c->buttons;
    b->backend = GK_BUTTONS_NONE;
    snprintf(b->chip, sizeof b->chip, "gpiochip0");
    for (int i = 0; i < GK_BTN_COUNT; i++)
        b->line[i] = -1;
    b->active_low = true;
    snprintf(b->bias, sizeof b->bias, "pull-up");
    b->debounce_ms = 10;
    b->hold_ms = 800;
    b->evdev_code[GK_BTN_NEXT] = KEY_RIGHT;
    b->evdev_code[GK_BTN_PREV] = KEY_LEFT;
    b->evdev_code[GK_BTN_MODE] = KEY_M;
    b->evdev_code[GK_BTN_INFO] = KEY_I;
    c->dwell_s = 30;
    c->pause_after_input_s = 60;
    c->truth_max_w = 160; /* GK_TRUTH_MAX_W x GK_TRUTH_MAX_H (truth.h) */
    c->truth_max_h = 120;
}

/* ---- the parser -------------------------------------------------------------------------- */

typedef struct parse_ctx {
    gk_kiosk_config *c;
    const char *name;        /* file name for messages */
    const char *text;        /* remaining input */
    int line;                /* line the reader handed out last */
    bool failed;
    int fail_line;
    gk_err *e;
} parse_ctx;

static const char *const sections[] = {"display", "frame", "buttons", "playlist", "cpu", "budgets", "truth", NULL};

static int fail_at(parse_ctx *p, const char *fmt, const char *a, const char *b)
{
    if (p->failed)
        return 0;
    char what[768];
    snprintf(what, sizeof what, fmt, a, b);
    gk_fail(p->e, GK_EINPUT, "%s:%d: %s", p->name, p->line, what);
    p->failed = true;
    p->fail_line = p->line;
    return 0;
}

/* ini_reader: hands inih one line at a time and counts them. Lines longer than the buffer are an
 * error of ours (inih would split them silently). */
static char *reader(char *str, int num, void *stream)
{
    parse_ctx *p = stream;
    if (!*p->text)
        return NULL;
    const char *nl = strchr(p->text, '\n');
    size_t len = nl ? (size_t)(nl - p->text) + 1 : strlen(p->text);
    p->line++;
    if (len >= (size_t)num) {
        fail_at(p, "line longer than %s characters%s", "199", "");
        len = (size_t)num - 1;
    }
    memcpy(str, p->text, len);
    str[len] = '\0';
    p->text = nl ? nl + 1 : p->text + strlen(p->text);
    /* Section headers: check the name here, where empty sections are seen too. */
    char tmp[256];
    snprintf(tmp, sizeof tmp, "%s", str);
    char *t = trim(tmp);
    if (t[0] == '[') {
        char *close = strchr(t, ']');
        if (close) {
            *close = '\0';
            char *sec = trim(t + 1);
            bool known = false;
            for (int i = 0; sections[i]; i++)
                known |= !strcmp(sections[i], sec);
            if (!known)
                fail_at(p, "unknown section [%s] (known: display, frame, buttons, playlist, cpu, budgets, truth)%s", sec, "");
        }
    }
    return str;
}

static bool parse_bool(const char *v, bool *out)
{
    if (!strcmp(v, "true") || !strcmp(v, "yes") || !strcmp(v, "on") || !strcmp(v, "1"))
        *out = true;
    else if (!strcmp(v, "false") || !strcmp(v, "no") || !strcmp(v, "off") || !strcmp(v, "0"))
        *out = false;
    else
        return false;
    return true;
}

static int int_in(parse_ctx *p, const char *key, const char *v, long lo, long hi, int *out)
{
    long x;
    char range[64];
    if (gk_parse_int(v, &x))
        return fail_at(p, "%s: '%s' is not an integer", key, v);
    if (x < lo || x > hi) {
        snprintf(range, sizeof range, "'%s' is out of range %ld..%ld", v, lo, hi);
        return fail_at(p, "%s: %s", key, range);
    }
    *out = (int)x;
    return 1;
}

static int double_in(parse_ctx *p, const char *key, const char *v, double lo, double hi, double *out)
{
    double x;
    char range[96];
    if (gk_parse_double(v, &x))
        return fail_at(p, "%s: '%s' is not a number", key, v);
    if (x < lo || x > hi) {
        snprintf(range, sizeof range, "'%s' is out of range %g..%g", v, lo, hi);
        return fail_at(p, "%s: %s", key, range);
    }
    *out = x;
    return 1;
}

static int copy_str(parse_ctx *p, const char *key, const char *v, char *dst, size_t cap)
{
    if (strlen(v) >= cap)
        return fail_at(p, "%s: value '%s' is too long", key, v);
    snprintf(dst, cap, "%s", v);
    return 1;
}

static const char *const button_names[GK_BTN_COUNT] = {"next", "prev", "mode", "info"};

static int key_code(parse_ctx *p, const char *key, const char *v, int *out)
{
    static const struct { const char *name; int code; } names[] = {
        {"KEY_RIGHT", KEY_RIGHT}, {"KEY_LEFT", KEY_LEFT}, {"KEY_UP", KEY_UP}, {"KEY_DOWN", KEY_DOWN},
        {"KEY_ENTER", KEY_ENTER}, {"KEY_SPACE", KEY_SPACE}, {"KEY_ESC", KEY_ESC}, {"KEY_TAB", KEY_TAB},
        {"KEY_N", KEY_N}, {"KEY_P", KEY_P}, {"KEY_M", KEY_M}, {"KEY_I", KEY_I},
        {"KEY_1", KEY_1}, {"KEY_2", KEY_2}, {"KEY_3", KEY_3}, {"KEY_4", KEY_4},
        {"KEY_PAGEUP", KEY_PAGEUP}, {"KEY_PAGEDOWN", KEY_PAGEDOWN}, {"KEY_HOME", KEY_HOME},
        {"KEY_NEXTSONG", KEY_NEXTSONG}, {"KEY_PREVIOUSSONG", KEY_PREVIOUSSONG}, {"KEY_MENU", KEY_MENU},
        {"KEY_INFO", KEY_INFO}, {"KEY_SELECT", KEY_SELECT}, {"KEY_PROG1", KEY_PROG1}, {"KEY_PROG2", KEY_PROG2},
        {"BTN_0", BTN_0}, {"BTN_1", BTN_1}, {"BTN_2", BTN_2}, {"BTN_3", BTN_3},
    };
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        if (!strcmp(names[i].name, v)) {
            *out = names[i].code;
            return 1;
        }
    long x;
    if (gk_parse_int(v, &x) || x < 0 || x > KEY_MAX)
        return fail_at(p, "%s: '%s' is not a key code (0..767 or a KEY_ name such as KEY_RIGHT)", key, v);
    *out = (int)x;
    return 1;
}

static int display_key(parse_ctx *p, const char *key, const char *v)
{
    gk_kiosk_config *c = p->c;
    if (!strcmp(key, "platform")) {
        if (gk_parse_platform(v, &c->platform))
            return fail_at(p, "platform: '%s' is not auto, kms or mock%s", v, "");
        return 1;
    }
    if (!strcmp(key, "device"))
        return copy_str(p, key, v, c->device, sizeof c->device);
    if (!strcmp(key, "mode")) {
        int w, h;
        char size[32];
        snprintf(size, sizeof size, "%s", v);
        char *at = strchr(size, '@');
        double hz = 60;
        if (at)
            *at = '\0';
        if (v[0] && (gk_parse_size(size, &w, &h) || (at && (gk_parse_double(at + 1, &hz) || hz <= 0 || hz > 1000))))
            return fail_at(p, "mode: '%s' is not WxH or WxH@HZ (e.g. 1920x1080@60)%s", v, "");
        return copy_str(p, key, v, c->mode, sizeof c->mode);
    }
    if (!strcmp(key, "size")) {
        if (gk_parse_size(v, &c->width, &c->height))
            return fail_at(p, "size: '%s' is not WxH%s", v, "");
        return 1;
    }
    return fail_at(p, "unknown key '%s' in [%s]", key, "display");
}

static int buttons_key(parse_ctx *p, const char *key, const char *v)
{
    gk_button_config *b = &p->c->buttons;
    if (!strcmp(key, "backend")) {
        if (!strcmp(v, "none"))
            b->backend = GK_BUTTONS_NONE;
        else if (!strcmp(v, "gpiod"))
            b->backend = GK_BUTTONS_GPIOD;
        else if (!strcmp(v, "evdev"))
            b->backend = GK_BUTTONS_EVDEV;
        else
            return fail_at(p, "backend: '%s' is not none, gpiod or evdev%s", v, "");
        return 1;
    }
    if (!strcmp(key, "chip"))
        return copy_str(p, key, v, b->chip, sizeof b->chip);
    if (!strcmp(key, "evdev_device"))
        return copy_str(p, key, v, b->evdev_device, sizeof b->evdev_device);
    if (!strcmp(key, "active_low")) {
        if (!parse_bool(v, &b->active_low))
            return fail_at(p, "active_low: '%s' is not true or false%s", v, "");
        return 1;
    }
    if (!strcmp(key, "bias")) {
        if (strcmp(v, "as-is") && strcmp(v, "pull-up") && strcmp(v, "pull-down") && strcmp(v, "disabled"))
            return fail_at(p, "bias: '%s' is not as-is, pull-up, pull-down or disabled%s", v, "");
        return copy_str(p, key, v, b->bias, sizeof b->bias);
    }
    /* Above ~100 ms a debounce swallows real clicks; a hold shorter than 100 ms is a click. */
    if (!strcmp(key, "debounce_ms"))
        return int_in(p, key, v, 0, 100, &b->debounce_ms);
    if (!strcmp(key, "hold_ms"))
        return int_in(p, key, v, 100, 10000, &b->hold_ms);
    for (int i = 0; i < GK_BTN_COUNT; i++) {
        char name[32];
        snprintf(name, sizeof name, "line_%s", button_names[i]);
        if (!strcmp(key, name)) /* -1 = not wired; GPIO chips have at most a few hundred lines */
            return int_in(p, key, v, -1, 1023, &b->line[i]);
        snprintf(name, sizeof name, "key_%s", button_names[i]);
        if (!strcmp(key, name))
            return key_code(p, key, v, &b->evdev_code[i]);
    }
    return fail_at(p, "unknown key '%s' in [%s]", key, "buttons");
}

static int playlist_key(parse_ctx *p, const char *key, const char *v)
{
    gk_kiosk_config *c = p->c;
    if (!strcmp(key, "scenes")) {
        char buf[1024];
        snprintf(buf, sizeof buf, "%s", v);
        c->n_scenes = 0;
        c->scenes_line = p->line;
        char *save = NULL;
        for (char *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
            tok = trim(tok);
            if (!*tok)
                continue;
            if (c->n_scenes == GK_MAX_PLAYLIST)
                return fail_at(p, "scenes: more than %s scenes%s", "32", "");
            if (strlen(tok) >= GK_NAME_LEN || strchr(tok, '/'))
                return fail_at(p, "scenes: '%s' is not a scene name%s", tok, "");
            snprintf(c->scenes[c->n_scenes++], GK_NAME_LEN, "%s", tok);
        }
        if (c->n_scenes == 0)
            return fail_at(p, "scenes: empty list (leave the key out to show every scene)%s%s", "", "");
        return 1;
    }
    if (!strcmp(key, "dwell_s")) /* a second is the least a viewer can see; a day the most sensible */
        return double_in(p, key, v, 1, 86400, &c->dwell_s);
    if (!strcmp(key, "pause_after_input_s"))
        return double_in(p, key, v, 0, 86400, &c->pause_after_input_s);
    if (!strncmp(key, "methods.", 8) && key[8]) {
        const char *scene = key + 8;
        gk_err e2 = {0};
        if (gk_method_list_check(v, key, &e2)) {
            char m[600];
            snprintf(m, sizeof m, "%.590s", e2.msg);
            return fail_at(p, "%s%s", m, "");
        }
        gk_method_entry *m = NULL;
        for (int i = 0; i < c->n_methods; i++)
            if (!strcmp(c->methods[i].scene, scene))
                m = &c->methods[i];
        if (!m) {
            if (c->n_methods == GK_MAX_PLAYLIST || strlen(scene) >= GK_NAME_LEN)
                return fail_at(p, "too many methods.SCENE keys or scene name too long: '%s'%s", key, "");
            m = &c->methods[c->n_methods++];
        }
        snprintf(m->scene, sizeof m->scene, "%s", scene);
        char list[256];
        snprintf(list, sizeof list, "%s", v);
        /* normalise "vct, none" to "vct,none" */
        m->methods[0] = '\0';
        char *save = NULL;
        for (char *tok = strtok_r(list, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
            size_t used = strlen(m->methods);
            snprintf(m->methods + used, sizeof m->methods - used, "%s%s", used ? "," : "", trim(tok));
        }
        m->line = p->line;
        return 1;
    }
    return fail_at(p, "unknown key '%s' in [%s]", key, "playlist");
}

static int budgets_key(parse_ctx *p, const char *key, const char *v)
{
    gk_kiosk_config *c = p->c;
    const char *dots = strstr(v, "..");
    if (!dots || dots == v || !dots[2] || strstr(dots + 2, ".."))
        return fail_at(p, "budget '%s': '%s' is not MIN..MAX", key, v);
    if (c->n_ranges == GK_MAX_KNOBS)
        return fail_at(p, "more than %s budget ranges%s", "32", "");
    gk_budget_range *r = &c->ranges[c->n_ranges];
    size_t lo_len = (size_t)(dots - v);
    if (strlen(key) >= sizeof r->knob || lo_len >= sizeof r->min || strlen(dots + 2) >= sizeof r->max)
        return fail_at(p, "budget '%s': '%s' is too long", key, v);
    snprintf(r->knob, sizeof r->knob, "%s", key);
    memcpy(r->min, v, lo_len);
    r->min[lo_len] = '\0';
    snprintf(r->max, sizeof r->max, "%s", dots + 2);
    char *t = trim(r->min); /* trim returns a pointer into the buffer: move, not snprintf */
    memmove(r->min, t, strlen(t) + 1);
    t = trim(r->max);
    memmove(r->max, t, strlen(t) + 1);
    r->line = p->line;
    for (int i = 0; i < c->n_ranges; i++)
        if (!strcmp(c->ranges[i].knob, key)) { /* a later line overrides an earlier one */
            c->ranges[i] = *r;
            return 1;
        }
    c->n_ranges++;
    return 1;
}

static int handler(void *user, const char *section, const char *name, const char *value)
{
    parse_ctx *p = user;
    if (p->failed)
        return 1; /* keep the first error; inih goes on reading */
    char v[256];
    snprintf(v, sizeof v, "%s", value ? value : "");
    char *val = trim(v);
    if (!strcmp(section, "display"))
        return display_key(p, name, val);
    if (!strcmp(section, "frame")) {
        if (!strcmp(name, "target_ms")) /* 1 ms (1000 Hz) .. 1 s: anything else is a typo */
            return double_in(p, name, val, 1, 1000, &p->c->target_ms);
        return fail_at(p, "unknown key '%s' in [%s]", name, "frame");
    }
    if (!strcmp(section, "buttons"))
        return buttons_key(p, name, val);
    if (!strcmp(section, "playlist"))
        return playlist_key(p, name, val);
    if (!strcmp(section, "cpu")) {
        if (!strcmp(name, "workers")) /* 0 = cores - 1; 64 is more threads than any board has cores */
            return int_in(p, name, val, 0, 64, &p->c->cpu_workers);
        return fail_at(p, "unknown key '%s' in [%s]", name, "cpu");
    }
    if (!strcmp(section, "budgets"))
        return budgets_key(p, name, val);
    if (!strcmp(section, "truth")) {
        if (!strcmp(name, "enabled")) {
            if (!parse_bool(val, &p->c->truth_enabled))
                return fail_at(p, "enabled: '%s' is not true or false%s", val, "");
            return 1;
        }
        if (!strcmp(name, "workers")) /* 0 = cores - 1, at least 1 */
            return int_in(p, name, val, 0, 64, &p->c->truth_workers);
        if (!strcmp(name, "size")) {
            if (gk_parse_size(val, &p->c->truth_max_w, &p->c->truth_max_h))
                return fail_at(p, "size: '%s' is not WxH (e.g. 160x120)%s", val, "");
            return 1;
        }
        return fail_at(p, "unknown key '%s' in [%s]", name, "truth");
    }
    if (!section[0])
        return fail_at(p, "key '%s' outside any section%s", name, "");
    return 0; /* unknown section: already reported by the reader */
}

int gk_kiosk_config_parse(gk_kiosk_config *c, const char *text, const char *name, gk_err *e)
{
    parse_ctx p = {.c = c, .name = name, .text = text, .e = e};
    int rc = ini_parse_stream(reader, &p, handler, &p);
    /* inih's rc is the first line it saw an error on, ours included (the handler returns 0). */
    if (p.failed && (rc <= 0 || p.fail_line <= rc))
        return -1;
    if (rc > 0)
        return gk_fail(e, GK_EINPUT, "%s:%d: syntax error (expected [section] or key = value)", name, rc);
    if (rc < 0)
        return gk_fail(e, GK_ERUNTIME, "%s: out of memory while parsing", name);
    snprintf(c->path, sizeof c->path, "%s", name);
    return 0;
}

/* A kiosk config is a page of INI; anything beyond this is not one (and /dev/zero never ends). */
#define CONFIG_MAX_BYTES ((size_t)1 << 20)

int gk_kiosk_config_load(gk_kiosk_config *c, const char *path, gk_err *e)
{
    char *text;
    size_t len;
    if (gk_read_text_file(path, "config", CONFIG_MAX_BYTES, &text, &len, e))
        return -1;
    int rc = gk_kiosk_config_parse(c, text, path, e);
    free(text);
    return rc;
}

int gk_kiosk_config_apply_budgets(const gk_kiosk_config *c, gk_budget *b, gk_err *e)
{
    for (int i = 0; i < c->n_ranges; i++) {
        const gk_budget_range *r = &c->ranges[i];
        if (gk_budget_set_range(b, r->knob, r->min, r->max, e))
            return gk_fail_prefix(e, "%s:%d: [budgets] ", c->path[0] ? c->path : "config", r->line);
    }
    return 0;
}

const char *gk_kiosk_config_methods(const gk_kiosk_config *c, const char *scene)
{
    for (int i = 0; i < c->n_methods; i++)
        if (!strcmp(c->methods[i].scene, scene))
            return c->methods[i].methods;
    return NULL;
}
