/* PLACEHOLDER: replaced by the module that owns this command. */
#include <stdio.h>

#include "commands.h"

int gk_cmd_bench(int argc, char **argv)
{
    (void)argc;
    fprintf(stderr, "gikiosk: %s: not implemented yet\n", argv[0]);
    return 1;
}
