/* gikiosk: parses the command and dispatches (DESIGN §3). */
#include <errno.h>
#include <fcntl.h>
#include <stdbool.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "cli/commands.h"

static void usage(FILE *f)
{
    fputs("usage: gikiosk COMMAND [options]\n"
          "\n"
          "commands:\n"
          "  run        show the GI showcase (kiosk); offscreen on the mock platform without a display\n"
          "  reference  render a path-traced reference image of a scene (EXR)\n"
          "  compare    error metrics between a reference and a test image\n"
          "  bench      sweep methods and budgets, chart speed against accuracy\n"
          "  scenes     list the scenes with their features and the methods that apply\n"
          "\n"
          "`gikiosk COMMAND --help` describes a command's options. `gikiosk --version` prints the version.\n",
          f);
}

/* Started with descriptor 0, 1 or 2 closed, the next file the program opens (the stats spool, a
   capture, the DRM device) would get that number, and the log or the summary would be written into
   it. Each closed one is opened on a device instead: stdin on /dev/null, stdout and stderr on
   /dev/full, where every write fails (ENOSPC), so output that has nowhere to go is still an error
   at exit. Returns whether stdout was closed. */
static bool reserve_std_descriptors(void)
{
    bool stdout_closed = false;
    for (int fd = 0; fd <= 2; fd++) {
        if (fcntl(fd, F_GETFD) != -1 || errno != EBADF)
            continue;
        int got = open(fd == 0 ? "/dev/null" : "/dev/full", fd == 0 ? O_RDONLY : O_WRONLY);
        if (got >= 0 && got != fd) { /* a lower one was closed too and took it: move it up */
            dup2(got, fd);
            close(got);
        }
        stdout_closed |= fd == 1;
    }
    return stdout_closed;
}

static bool stdout_was_closed;

/* A write that failed on stdout or stderr (a closed descriptor, a dead pipe, a full disk) turns a
   successful exit into exit 1: the output a caller relies on (the summary, compare's metrics) is
   lost. Said on stderr when stderr still works. */
static int check_std_streams(int rc)
{
    int out_err = 0;
    errno = 0;
    if (fflush(stdout) != 0 || ferror(stdout))
        out_err = errno ? errno : EIO;
    int reason_known = errno != 0;
    if (out_err) { /* the reason is lost when an earlier flush (the kiosk's summary) failed first */
        if (stdout_was_closed)
            fputs("gikiosk: cannot write to standard output: it was closed\n", stderr);
        else if (!reason_known)
            fputs("gikiosk: cannot write to standard output\n", stderr);
        else
            fprintf(stderr, "gikiosk: cannot write to standard output: %s\n", strerror(out_err));
        rc = rc ? rc : 1;
    }
    if (fflush(stderr) != 0 || ferror(stderr))
        rc = rc ? rc : 1;
    return rc;
}

static int dispatch(int argc, char **argv);

int main(int argc, char **argv)
{
    /* A reader that goes away (`gikiosk scenes | head -1`, a dead log pipe) is a write error, not a
       signal that kills the kiosk before it restores the display; and a file-size limit is a write
       error (EFBIG) like a full disk, reported by whoever writes. */
    stdout_was_closed = reserve_std_descriptors();
    signal(SIGPIPE, SIG_IGN);
    signal(SIGXFSZ, SIG_IGN);
    return check_std_streams(dispatch(argc, argv));
}

static int dispatch(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    const char *cmd = argv[1];
    if (!strcmp(cmd, "--help") || !strcmp(cmd, "-h") || !strcmp(cmd, "help")) {
        usage(stdout);
        return 0;
    }
    if (!strcmp(cmd, "--version")) {
        printf("gikiosk %s\n", GK_VERSION);
        return 0;
    }
    static const struct {
        const char *name;
        int (*fn)(int, char **);
    } commands[] = {
        {"run", gk_cmd_run},         {"reference", gk_cmd_reference}, {"compare", gk_cmd_compare},
        {"bench", gk_cmd_bench},     {"scenes", gk_cmd_scenes},       {"build-scenes", gk_cmd_build_scenes},
    };
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
        if (!strcmp(cmd, commands[i].name))
            return commands[i].fn(argc - 1, argv + 1);
    fprintf(stderr, "gikiosk: unknown command '%s'\n", cmd);
    usage(stderr);
    return 2;
}
