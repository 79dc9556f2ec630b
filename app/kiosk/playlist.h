/* The playlist and attract mode: pure logic over times and button events (no GL, no clock of its
 * own), so it is unit-tested with synthetic events.
 *
 * Attract mode: the current scene stays for dwell_s, then the next one comes. A button event
 * postpones auto-advance until pause_after_input_s after the last input: the next automatic change
 * happens at max(visit start + dwell_s, last input + pause_after_input_s).
 * Buttons (clicks): next/prev change scene (wrapping, skipping scenes that failed to load); mode
 * cycles the GI methods that apply to the current scene; info toggles the HUD. Holding mode resets
 * to the scene's default method; holding info toggles the split view (the real-time image left,
 * the live ground truth right, when [truth] is enabled); holding prev pauses and resumes the scene's
 * animation (its time frozen, so the live ground truth can run on it). Presses and releases only
 * count as input (they pause attract).
 *
 * Animation time: the time since the visit began, less the time spent paused; a scene change ends
 * a pause (the new visit starts at time 0, running). */
#ifndef GK_KIOSK_PLAYLIST_H
#define GK_KIOSK_PLAYLIST_H

#include <stdbool.h>

#include "../../platform/platform.h"
#include "config.h"

#define GK_PL_MAX_METHODS 8
#define GK_METHOD_LEN 32

enum { GK_PL_SCENE = 1, GK_PL_METHOD = 2, GK_PL_HUD = 4, GK_PL_INPUT = 8, GK_PL_SPLIT = 16, GK_PL_PAUSE = 32 };

typedef struct gk_playlist {
    int n;
    char names[GK_MAX_PLAYLIST][GK_NAME_LEN];
    bool failed[GK_MAX_PLAYLIST];      /* failed to load: skipped */
    int current;
    double dwell_s, pause_s;
    double visit_start_s;
    double last_input_s;
    bool had_input;
    bool hud_visible;
    bool split_view;                   /* info held: real-time left, ground truth right */
    bool paused;                       /* prev held: the animation time stands still */
    double paused_at_s;                /* the platform time the pause began */
    double paused_total_s;             /* platform time spent paused in this visit, before it */
    int n_methods;                     /* methods of the current scene, set by the kiosk */
    char methods[GK_PL_MAX_METHODS][GK_METHOD_LEN];
    int method, default_method;
} gk_playlist;

void gk_playlist_init(gk_playlist *pl, const char names[][GK_NAME_LEN], int n, double dwell_s, double pause_s);
/* Starts the first visit at now (scene 0, or the first that has not failed). */
void gk_playlist_start(gk_playlist *pl, double now);
/* Marks a scene unusable; returns the number of scenes still usable. */
int gk_playlist_mark_failed(gk_playlist *pl, int index);
int gk_playlist_usable(const gk_playlist *pl);
/* Moves to the next (dir = +1) or previous (-1) usable scene, starting a visit at now.
 * Returns GK_PL_SCENE if the scene changed (not with a single usable scene). */
int gk_playlist_step(gk_playlist *pl, int dir, double now);
/* Attract mode: advances when the dwell (and any input pause) has run out. Returns GK_PL_SCENE or 0. */
int gk_playlist_tick(gk_playlist *pl, double now);
/* Time of the next automatic scene change. */
double gk_playlist_next_change(const gk_playlist *pl);
/* The scene's animation time at platform time now: now - visit start - time paused; while paused,
 * the time the pause began at. */
double gk_playlist_anim_time(const gk_playlist *pl, double now);
/* Applies one input event; returns GK_PL_* flags of what changed (GK_PL_INPUT for any event). */
int gk_playlist_input(gk_playlist *pl, const gk_input_event *ev);

const char *gk_playlist_scene(const gk_playlist *pl);
/* Sets the current scene's methods; the current method becomes the default. */
void gk_playlist_set_methods(gk_playlist *pl, char methods[][GK_METHOD_LEN], int n, int default_index);
const char *gk_playlist_method(const gk_playlist *pl);

/* Chooses a scene's method list (pure, see playlist.c): applicable = the renderer's methods for the
 * scene ("none" first); configured = [playlist] methods.SCENE or the scene file's own list (may be
 * NULL); forced = --method (may be NULL). Fills out (at most GK_PL_MAX_METHODS), *default_index, and
 * note with what was dropped or overridden ("" when nothing). Returns the count (>= 1). */
int gk_methods_for_scene(const char *const *applicable, int n_applicable, const char *configured,
                         const char *forced, char out[][GK_METHOD_LEN], int *default_index,
                         char *note, int note_len);

#endif
