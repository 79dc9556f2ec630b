/* CSV as RFC 4180 writes it: a field holding a comma, a double quote, CR or LF is enclosed in
 * double quotes with its quotes doubled, so a scene named "a,b" stays one field. Used by every
 * CSV the program writes (stats, its spool, bench) and to read its own spool back. */
#ifndef GK_CSV_H
#define GK_CSV_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

/* Writes one field, quoted when RFC 4180 requires it (no separator: the caller writes ','). */
void gk_csv_field(FILE *f, const char *s);
bool gk_csv_needs_quotes(const char *s);

/* One record read back: n fields, each a NUL-terminated string inside buf. */
typedef struct gk_csv_record {
    char *buf;
    size_t len, cap;
    size_t *start;   /* offset of each field in buf */
    int n, cap_fields;
} gk_csv_record;

/* Reads the next record (CRLF or LF ends it outside quotes). Returns 1 with a record, 0 at the end
 * of the file, -1 for a quote left open at the end or out of memory. */
int gk_csv_read(FILE *f, gk_csv_record *r);
const char *gk_csv_get(const gk_csv_record *r, int i); /* field i, "" when the record is shorter */
void gk_csv_record_free(gk_csv_record *r);

#endif
