/* Shaders compiled into the binary by tools/embed_shaders.sh (paths relative to shaders_gles/). */
#ifndef GK_SHADER_EMBED_H
#define GK_SHADER_EMBED_H

typedef struct gk_embedded_shader {
    const char *path;   /* "direct/light.frag" */
    const char *source;
} gk_embedded_shader;

extern const gk_embedded_shader gk_embedded_shaders[];
extern const int gk_embedded_shader_count;

#endif
