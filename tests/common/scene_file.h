/* The shipped scenes as the tests read them: config/scenes/NAME.gltf loaded and evaluated at t = 0
 * (node world matrices valid), as the kiosk shows them. Many tests still carry their own copy of
 * this; new ones use it. Compiled into every unit and gpu test (TESTLIB_SRCS). */
#ifndef GK_TEST_SCENE_FILE_H
#define GK_TEST_SCENE_FILE_H

#include "base/err.h"
#include "scene/scene.h"

/* NULL with e filled when the file does not load. */
gk_scene *gkt_load_scene(const char *name, gk_err *e);

#endif
