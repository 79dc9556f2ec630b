/* Playlist and attract mode (see playlist.h). */
#include "playlist.h"

#include <stdio.h>
#include <string.h>

void gk_playlist_init(gk_playlist *pl, const char names[][GK_NAME_LEN], int n, double dwell_s, double pause_s)
{
    memset(pl, 0, sizeof *pl);
    if (n > GK_MAX_PLAYLIST)
        n = GK_MAX_PLAYLIST;
    pl->n = n;
    for (int i = 0; i < n; i++)
        snprintf(pl->names[i], GK_NAME_LEN, "%s", names[i]);
    pl->dwell_s = dwell_s;
    pl->pause_s = pause_s;
    pl->hud_visible = true;
    pl->n_methods = 1;
    snprintf(pl->methods[0], GK_METHOD_LEN, "none");
}

int gk_playlist_usable(const gk_playlist *pl)
{
    int k = 0;
    for (int i = 0; i < pl->n; i++)
        k += !pl->failed[i];
    return k;
}

static void begin_visit(gk_playlist *pl, int index, double now)
{
    pl->current = index;
    pl->visit_start_s = now;
    pl->paused = false; /* a new scene starts moving at its time 0 */
    pl->paused_total_s = 0;
}

void gk_playlist_start(gk_playlist *pl, double now)
{
    int first = 0;
    while (first < pl->n && pl->failed[first])
        first++;
    begin_visit(pl, first < pl->n ? first : 0, now);
}

int gk_playlist_mark_failed(gk_playlist *pl, int index)
{
    if (index >= 0 && index < pl->n)
        pl->failed[index] = true;
    return gk_playlist_usable(pl);
}

int gk_playlist_step(gk_playlist *pl, int dir, double now)
{
    if (pl->n == 0)
        return 0;
    int i = pl->current;
    for (int k = 0; k < pl->n; k++) {
        i = ((i + dir) % pl->n + pl->n) % pl->n;
        if (!pl->failed[i])
            break;
    }
    if (pl->failed[i] || (i == pl->current && !pl->failed[pl->current])) {
        pl->visit_start_s = now; /* one usable scene: the visit simply goes on, from time 0 */
        pl->paused_at_s = now;    /* (a pause stays, at time 0) */
        pl->paused_total_s = 0;
        return 0;
    }
    begin_visit(pl, i, now);
    return GK_PL_SCENE;
}

double gk_playlist_next_change(const gk_playlist *pl)
{
    double t = pl->visit_start_s + pl->dwell_s;
    if (pl->had_input && pl->last_input_s + pl->pause_s > t)
        t = pl->last_input_s + pl->pause_s;
    return t;
}

int gk_playlist_tick(gk_playlist *pl, double now)
{
    if (now < gk_playlist_next_change(pl))
        return 0;
    return gk_playlist_step(pl, +1, now);
}

int gk_playlist_input(gk_playlist *pl, const gk_input_event *ev)
{
    if (ev->kind == GK_INPUT_QUIT)
        return 0;
    pl->had_input = true;
    pl->last_input_s = ev->time_s;
    int changed = GK_PL_INPUT;
    if (ev->kind == GK_INPUT_CLICK) {
        switch (ev->button) {
        case GK_BTN_NEXT: changed |= gk_playlist_step(pl, +1, ev->time_s); break;
        case GK_BTN_PREV: changed |= gk_playlist_step(pl, -1, ev->time_s); break;
        case GK_BTN_MODE:
            if (pl->n_methods > 1) {
                pl->method = (pl->method + 1) % pl->n_methods;
                changed |= GK_PL_METHOD;
            }
            break;
        case GK_BTN_INFO:
            pl->hud_visible = !pl->hud_visible;
            changed |= GK_PL_HUD;
            break;
        default: break;
        }
    } else if (ev->kind == GK_INPUT_HOLD && ev->button == GK_BTN_INFO) {
        pl->split_view = !pl->split_view;
        changed |= GK_PL_SPLIT;
    } else if (ev->kind == GK_INPUT_HOLD && ev->button == GK_BTN_PREV) {
        if (pl->paused)
            pl->paused_total_s += ev->time_s - pl->paused_at_s;
        else
            pl->paused_at_s = ev->time_s;
        pl->paused = !pl->paused;
        changed |= GK_PL_PAUSE;
    } else if (ev->kind == GK_INPUT_HOLD && ev->button == GK_BTN_MODE && pl->method != pl->default_method) {
        pl->method = pl->default_method;
        changed |= GK_PL_METHOD;
    }
    return changed;
}

double gk_playlist_anim_time(const gk_playlist *pl, double now)
{
    return (pl->paused ? pl->paused_at_s : now) - pl->visit_start_s - pl->paused_total_s;
}

const char *gk_playlist_scene(const gk_playlist *pl) { return pl->n ? pl->names[pl->current] : ""; }

void gk_playlist_set_methods(gk_playlist *pl, char methods[][GK_METHOD_LEN], int n, int default_index)
{
    if (n < 1) {
        n = 1;
        snprintf(pl->methods[0], GK_METHOD_LEN, "none");
        default_index = 0;
    } else {
        if (n > GK_PL_MAX_METHODS)
            n = GK_PL_MAX_METHODS;
        for (int i = 0; i < n; i++)
            snprintf(pl->methods[i], GK_METHOD_LEN, "%s", methods[i]);
    }
    pl->n_methods = n;
    pl->default_method = default_index >= 0 && default_index < n ? default_index : 0;
    pl->method = pl->default_method;
}

const char *gk_playlist_method(const gk_playlist *pl) { return pl->methods[pl->method]; }

static int index_of(const char *const *names, int n, const char *name)
{
    for (int i = 0; i < n; i++)
        if (!strcmp(names[i], name))
            return i;
    return -1;
}

static void note_add(char *note, int len, const char *fmt, const char *a, const char *b)
{
    int used = (int)strlen(note);
    if (used >= len - 1)
        return;
    if (used)
        used += snprintf(note + used, (size_t)(len - used), "; ");
    if (used < len - 1)
        snprintf(note + used, (size_t)(len - used), fmt, a, b);
}

int gk_methods_for_scene(const char *const *applicable, int n_applicable, const char *configured,
                         const char *forced, char out[][GK_METHOD_LEN], int *default_index,
                         char *note, int note_len)
{
    note[0] = '\0';
    int n = 0;
    *default_index = 0;
    if (configured && *configured) {
        char buf[256], *save = NULL;
        snprintf(buf, sizeof buf, "%s", configured);
        for (char *tok = strtok_r(buf, ", ", &save); tok; tok = strtok_r(NULL, ", ", &save)) {
            if (index_of(applicable, n_applicable, tok) < 0) {
                note_add(note, note_len, "method '%s' does not apply%s", tok, "");
                continue;
            }
            bool dup = false;
            for (int i = 0; i < n; i++)
                dup |= !strcmp(out[i], tok);
            if (!dup && n < GK_PL_MAX_METHODS)
                snprintf(out[n++], GK_METHOD_LEN, "%s", tok);
        }
    }
    if (n == 0) {
        /* No usable list: everything that applies; the richest applicable method (the first after
         * "none") is the default, as a kiosk should show GI unless told otherwise. */
        for (int i = 0; i < n_applicable && n < GK_PL_MAX_METHODS; i++)
            snprintf(out[n++], GK_METHOD_LEN, "%s", applicable[i]);
        if (n == 0)
            snprintf(out[n++], GK_METHOD_LEN, "none");
        *default_index = n > 1 && !strcmp(out[0], "none") ? 1 : 0;
    }
    if (forced) {
        int k = -1;
        for (int i = 0; i < n; i++)
            if (!strcmp(out[i], forced))
                k = i;
        if (k < 0 && index_of(applicable, n_applicable, forced) >= 0 && n < GK_PL_MAX_METHODS) {
            snprintf(out[n], GK_METHOD_LEN, "%s", forced);
            k = n++;
        }
        if (k >= 0)
            *default_index = k;
        else
            note_add(note, note_len, "--method %s does not apply to this scene; using %s", forced,
                     out[*default_index]);
    }
    return n;
}
