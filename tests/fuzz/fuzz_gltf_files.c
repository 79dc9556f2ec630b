/* libFuzzer target for the glTF loader FROM FILES (gk_scene_load, as `gikiosk run` loads a scene):
 * the input is split at every "@@GK-FILE@@" into a scene and its sidecar files, written into a
 * scene folder, and the scene is loaded from its path, so buffer and image URIs resolve, the
 * confinement to the scene's folder and the file readers (buffers: the loader's own; images:
 * OpenImageIO) run on fuzzed bytes:
 *
 *     part 0 -> scene/scene.gltf (or GLB)   part 2 -> scene/tex.png
 *     part 1 -> scene/buf.bin               part 3 -> scene/sub/more.bin
 *
 * (a missing part leaves no file). Beside the scene folder lies outside.bin, a valid buffer and a
 * valid PNG reachable only by escaping the folder ("../outside.bin", "sub/../../outside.bin",
 * percent-encoded dots, or the symlinks scene/link.bin and scene/link.png that point at it); an
 * inotify watch on the parent folder sees every open of it, so a load that reads it aborts, and an
 * error message must never quote its bytes. Otherwise as fuzz_gltf.c: load, or fail naming the
 * file; no crash, leak, hang or undefined behaviour. */
#include <errno.h>
#include <fcntl.h>
#include <stdint.h>
#include <sys/inotify.h>
#include <sys/stat.h>

#include "base/log.h"
#include "fuzz_files.h"
#include "scene/scene.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define SEPARATOR "@@GK-FILE@@"
#define N_PARTS 4
static const char *const part_names[N_PARTS] = {"scene.gltf", "buf.bin", "tex.png", "sub/more.bin"};
/* Begins every line of outside.bin's text chunk: an error message quoting the file would show it. */
#define OUTSIDE_MARK "GKOUTSIDE"

static int watch_fd = -1;

/* outside.bin: a 1x1 8-bit grey PNG (so it also reads as an image), followed by OUTSIDE_MARK every
   64 bytes up to 4 KiB (so it also reads as any small buffer, and a message quoting it shows). */
static const uint8_t outside_png[] = {
    0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 13, 'I', 'H', 'D', 'R', 0, 0, 0, 1, 0, 0, 0, 1, 8, 0, 0, 0,
    0, 0x3a, 0x7e, 0x9b, 0x55, 0, 0, 0, 10, 'I', 'D', 'A', 'T', 0x78, 0x9c, 0x63, 0x60, 0, 0, 0, 2, 0, 1, 0x73, 0x75,
    0x01, 0x18, 0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xae, 0x42, 0x60, 0x82};

static void setup(const char *root)
{
    char path[400];
    snprintf(path, sizeof path, "%s/scene", root);
    mkdir(path, 0700);
    snprintf(path, sizeof path, "%s/scene/sub", root);
    mkdir(path, 0700);
    uint8_t outside[4096];
    memset(outside, 0, sizeof outside);
    memcpy(outside, outside_png, sizeof outside_png);
    for (size_t at = sizeof outside_png; at + sizeof OUTSIDE_MARK < sizeof outside; at += 64)
        memcpy(outside + at, OUTSIDE_MARK, sizeof OUTSIDE_MARK - 1);
    snprintf(path, sizeof path, "%s/outside.bin", root);
    fuzz_write_file(path, outside, sizeof outside);
    snprintf(path, sizeof path, "%s/scene/link.bin", root);
    if (symlink("../outside.bin", path) != 0 && errno != EEXIST)
        abort();
    snprintf(path, sizeof path, "%s/scene/link.png", root);
    if (symlink("../outside.bin", path) != 0 && errno != EEXIST)
        abort();
    /* only entries directly in root are reported: the scene folder's own files are not */
    watch_fd = inotify_init1(IN_NONBLOCK | IN_CLOEXEC);
    if (watch_fd < 0 || inotify_add_watch(watch_fd, root, IN_OPEN | IN_ACCESS) < 0) {
        perror("fuzz: inotify");
        abort();
    }
}

/* Aborts when anything opened a file directly in root since the last call (outside.bin: an
   escape from the scene folder). Opening the scene folder itself is reported with IN_ISDIR. */
static void check_no_escape(void)
{
    char buf[4096] __attribute__((aligned(__alignof__(struct inotify_event))));
    for (;;) {
        ssize_t n = read(watch_fd, buf, sizeof buf);
        if (n <= 0)
            return;
        for (char *p = buf; p < buf + n;) {
            const struct inotify_event *ev = (const struct inotify_event *)p;
            if (!(ev->mask & IN_ISDIR)) {
                fprintf(stderr, "fuzz: the loader opened %s outside the scene folder\n", ev->len ? ev->name : "?");
                abort();
            }
            p += sizeof *ev + ev->len;
        }
    }
}

static const uint8_t *find(const uint8_t *from, const uint8_t *end, const char *needle, size_t n)
{
    for (const uint8_t *p = from; p + n <= end; p++)
        if (memcmp(p, needle, n) == 0)
            return p;
    return NULL;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    gk_log_set_quiet(1);
    const char *root = fuzz_dir();
    if (watch_fd < 0)
        setup(root);
    const uint8_t *at = data, *end = data + size;
    char path[400];
    for (int i = 0; i < N_PARTS; i++) {
        snprintf(path, sizeof path, "%s/scene/%s", root, part_names[i]);
        if (!at) {
            unlink(path);
            continue;
        }
        const uint8_t *sep = find(at, end, SEPARATOR, sizeof SEPARATOR - 1);
        fuzz_write_file(path, at, (size_t)((sep ? sep : end) - at));
        at = sep ? sep + sizeof SEPARATOR - 1 : NULL;
    }
    check_no_escape(); /* our own writes are in the scene folder; drain anything stale */
    snprintf(path, sizeof path, "%s/scene/scene.gltf", root);
    gk_err e = {0};
    gk_scene *s = gk_scene_load(path, &e);
    check_no_escape();
    if (!s) {
        if (e.code != GK_EINPUT)
            abort();
        fuzz_require_named(e.msg, path);
        if (strstr(e.msg, OUTSIDE_MARK) && !find(data, end, OUTSIDE_MARK, sizeof OUTSIDE_MARK - 1))
            abort(); /* bytes of a file outside the folder reached the message (not ones the input had) */
        return 0;
    }
    gk_scene_evaluate(s, 1.25f);
    mat4 view, proj;
    vec3 eye;
    gk_scene_camera(s, 1.5f, &view, &proj, &eye);
    for (int i = 0; i < s->n_nodes; i++)
        if (s->nodes[i].light >= 0) {
            vec3 p, d, u, v;
            gk_scene_light_frame(s, i, &p, &d, &u, &v);
        }
    const char *names[8];
    gk_scene_methods(s, names, 8);
    gk_scene_free(s);
    return 0;
}
