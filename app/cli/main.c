/* gikiosk: parses the command and dispatches (DESIGN §3). */
#include <stdio.h>
#include <string.h>

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

int main(int argc, char **argv)
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
