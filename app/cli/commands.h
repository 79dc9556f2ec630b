/* The subcommands of the gikiosk program (DESIGN §3). Each returns the process exit code:
 * 0 success, 1 runtime failure, 2 bad usage or bad input. argv[0] is the command name. */
#ifndef GK_COMMANDS_H
#define GK_COMMANDS_H

int gk_cmd_run(int argc, char **argv);          /* app/kiosk/cmd_run.c */
int gk_cmd_reference(int argc, char **argv);    /* app/ref/cmd_reference.c */
int gk_cmd_compare(int argc, char **argv);      /* app/metrics/cmd_compare.c */
int gk_cmd_bench(int argc, char **argv);        /* app/bench/cmd_bench.c */
int gk_cmd_scenes(int argc, char **argv);       /* app/scene/cmd_scenes.c */
int gk_cmd_build_scenes(int argc, char **argv); /* app/scene/cmd_build_scenes.c (make scenes) */

#endif
