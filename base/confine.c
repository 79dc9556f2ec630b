/* See confine.h. */
#include "confine.h"

#include <stdlib.h>
#include <string.h>

bool gk_path_inside_dir(const char *path, const char *dir)
{
    char *root = realpath(dir, NULL), *file = realpath(path, NULL);
    bool inside = false;
    if (root && file) {
        size_t n = strlen(root);
        inside = strncmp(file, root, n) == 0 && (file[n] == '/' || (n == 1 && root[0] == '/'));
    }
    free(root);
    free(file);
    return inside;
}
