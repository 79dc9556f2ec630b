/* Shared by the fuzz targets that read their input from files, as the program does: one private
 * temporary folder per fuzzing process (made on first use, removed at exit), and a helper that
 * writes bytes to a file in it. Header-only: each target is one translation unit. */
#ifndef GK_FUZZ_FILES_H
#define GK_FUZZ_FILES_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static char fuzz_dir_path[256];

static void fuzz_dir_remove(void)
{
    if (!fuzz_dir_path[0])
        return;
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", fuzz_dir_path);
    if (system(cmd) != 0)
        fprintf(stderr, "fuzz: could not remove %s\n", fuzz_dir_path);
}

/* The process's temporary folder (under $TMPDIR or /tmp); aborts when it cannot be made, since
 * no input could then be tried. */
static const char *fuzz_dir(void)
{
    if (fuzz_dir_path[0])
        return fuzz_dir_path;
    const char *tmp = getenv("TMPDIR");
    snprintf(fuzz_dir_path, sizeof fuzz_dir_path, "%s/gikiosk-fuzz-files.XXXXXX", tmp && *tmp ? tmp : "/tmp");
    if (!mkdtemp(fuzz_dir_path)) {
        perror("fuzz: mkdtemp");
        abort();
    }
    atexit(fuzz_dir_remove);
    return fuzz_dir_path;
}

/* Writes size bytes to path (replacing it); aborts on a write error: the harness, not the code
 * under test, would have failed. */
static void fuzz_write_file(const char *path, const void *data, size_t size)
{
    FILE *f = fopen(path, "wb");
    if (!f || (size && fwrite(data, 1, size, f) != size) || fclose(f) != 0) {
        perror(path);
        abort();
    }
}

/* A failure must be reported as an error whose message starts with "PREFIX" (the file's name). */
static void fuzz_require_named(const char *msg, const char *prefix)
{
    if (strncmp(msg, prefix, strlen(prefix)) != 0) {
        fprintf(stderr, "fuzz: error message does not start with '%s': %s\n", prefix, msg);
        abort();
    }
}

#endif
