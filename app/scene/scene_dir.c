/* Where the scene files are when no --scenes-dir is given. */
#include <limits.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "scene.h"

#ifndef GK_SHARE_SCENES
#define GK_SHARE_SCENES "/usr/local/share/gikiosk/scenes"
#endif

static bool is_dir(const char *p)
{
    struct stat st;
    return stat(p, &st) == 0 && S_ISDIR(st.st_mode);
}

const char *gk_scene_default_dir(void)
{
    /* Resolved once per process (a path, not state that changes): a checkout's config/scenes, else
       the share folder next to the installed binary (make install PREFIX=...), else /usr/local's. */
    static char found[PATH_MAX];
    if (found[0])
        return found;
    if (is_dir("config/scenes")) {
        snprintf(found, sizeof found, "config/scenes");
        return found;
    }
    char exe[PATH_MAX];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n > 0) {
        exe[n] = '\0';
        char *slash = strrchr(exe, '/');
        if (slash) {
            *slash = '\0';
            static const char rel[] = "/../share/gikiosk/scenes";
            size_t len = strlen(exe);
            if (len + sizeof rel <= sizeof found) {
                memcpy(found, exe, len);
                memcpy(found + len, rel, sizeof rel);
                if (is_dir(found))
                    return found;
            }
        }
    }
    snprintf(found, sizeof found, "%s", GK_SHARE_SCENES);
    return found;
}
