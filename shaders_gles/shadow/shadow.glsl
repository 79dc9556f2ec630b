// Selects the shadow method of the lighting pass by #define (app/render/shadow/shadow.h):
//   SHADOW_HARD, SHADOW_PCSS (later SHADOW_VSSM, SHADOW_CSSM), none: unshadowed.
// Every method provides  highp float shadow_visibility(highp vec3 world_pos, highp vec3 world_normal)
// in [0, 1]. Included files are expanded textually; the preprocessor drops the unused ones.
#if defined(SHADOW_HARD) || defined(SHADOW_PCSS)
#include "shadow/common.glsl"
#endif
#if defined(SHADOW_HARD)
#include "shadow/hard.glsl"
#elif defined(SHADOW_PCSS)
#include "shadow/pcss.glsl"
#else
highp float shadow_visibility(highp vec3 world_pos, highp vec3 world_normal) { return 1.0; }
#endif
