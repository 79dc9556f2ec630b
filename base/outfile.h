/* Outputs that are never half-written (DESIGN §4): every result file the program writes (stats
 * CSV, captures, references, bench output, scenes) goes to a temporary file in the target's own
 * directory and is renamed over the target only once it is complete and on disk. A run that fails,
 * a full disk or a signal therefore leaves the previous file as it was, never a truncated one.
 *
 * The temporary file is DIR/.NAME.XXXXXX.EXT: hidden, unique, and with the target's extension, so
 * a writer that picks the format by extension (OpenImageIO, gnuplot's terminal) writes the same
 * format into it. */
#ifndef GK_OUTFILE_H
#define GK_OUTFILE_H

#include <stdio.h>

#include "err.h"

typedef struct gk_outfile {
    char *path;  /* the target */
    char *tmp;   /* the temporary file beside it; NULL once committed or discarded */
    FILE *f;     /* open for writing (gk_outfile_open); NULL for gk_outfile_reserve */
} gk_outfile;

/* Creates the temporary file beside path and opens it as o->f ("w"). The target is not touched.
 * Returns 0, or -1 with GK_ERUNTIME naming path and the system's reason. */
int gk_outfile_open(gk_outfile *o, const char *path, gk_err *e);
/* Same, but only creates (and closes) the temporary file, for writers that open the file by name
 * themselves (OpenImageIO, gnuplot): write to o->tmp, then commit. */
int gk_outfile_reserve(gk_outfile *o, const char *path, gk_err *e);
/* Flushes o->f (when open) and checks every write (a full disk, a file-size limit), syncs the
 * temporary file to disk and renames it over the target. On any failure the temporary file is
 * removed, the target is left as it was, and e names the target and the reason. Frees o. */
int gk_outfile_commit(gk_outfile *o, gk_err *e);
/* Removes the temporary file; the target is left as it was. Frees o. Safe after commit. */
void gk_outfile_discard(gk_outfile *o);

#endif
