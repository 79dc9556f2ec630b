/* The mock platform's button script (DESIGN §4): one event a line, `TIME_S BUTTON ACTION [MS]`,
 * ACTION = click | press | release | hold MS; `#` comments and blank lines. It becomes a timeline
 * of raw press/release edges (click = press + release 50 ms later, hold MS = press + release MS
 * later) that the mock feeds through the same gesture detector as real buttons. */
#ifndef GK_PLATFORM_SCRIPT_H
#define GK_PLATFORM_SCRIPT_H

#include "gesture.h"

#define GK_SCRIPT_CLICK_S 0.050 /* how long a scripted click holds the button down */

typedef struct gk_script {
    gk_raw_edge *edges; /* sorted by time; equal times keep the script's order */
    int count;
    int next;           /* first edge not yet delivered */
} gk_script;

/* Parses text; name is used in error messages ("NAME:LINE: what is wrong", GK_EINPUT). */
int gk_script_parse(const char *text, const char *name, gk_script *out, gk_err *e);
/* Reads and parses a file; a missing or unreadable file is GK_EINPUT naming it. */
int gk_script_load(const char *path, gk_script *out, gk_err *e);
void gk_script_free(gk_script *s);
/* Sorts edges by time, stably (equal times keep their order), in O(n log n); returns the number
 * of comparisons it made (the tests bound it by n log2 n). */
long gk_script_sort_edges(gk_raw_edge *edges, int n);

/* "next" -> GK_BTN_NEXT; -1 when unknown. Also used by the config reader. */
int gk_button_from_name(const char *name);
const char *gk_button_name(enum gk_button b);

#endif
