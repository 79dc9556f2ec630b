/* Confinement of files named by a document (a glTF's buffer and image URIs) to the document's
 * folder: the test every reader of such a name passes before it opens anything. */
#ifndef GK_CONFINE_H
#define GK_CONFINE_H

#include <stdbool.h>

/* True when path exists and, with every symlink and `..` resolved (realpath), lies inside dir
 * (itself resolved the same way); false otherwise, also when either cannot be resolved. A lexical
 * check of the name is not enough: a symlink in the folder may point anywhere. */
bool gk_path_inside_dir(const char *path, const char *dir);

#endif
