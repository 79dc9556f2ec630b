// Selects the shadow method of the lighting pass by #define (app/render/shadow/shadow.h):
//   SHADOW_HARD, SHADOW_PCSS, SHADOW_VSSM, SHADOW_CSSM, SHADOW_MASK (a GI method's mask), none: unshadowed.
// Every method provides  highp float shadow_visibility(highp vec3 world_pos, highp vec3 world_normal)
// in [0, 1]. Included files are expanded textually; the preprocessor drops the unused ones. A file
// is expanded once per program, so helpers shared by two methods are included here, outside the
// method branches (else the first branch's copy would be the only one, and dropped).
#if defined(SHADOW_HARD) || defined(SHADOW_PCSS) || defined(SHADOW_VSSM) || defined(SHADOW_CSSM)
#include "shadow/common.glsl"
#endif
#if defined(SHADOW_VSSM) || defined(SHADOW_CSSM)
#include "shadow/vssm_sat.glsl"
#endif
#if defined(SHADOW_HARD)
#include "shadow/hard.glsl"
#elif defined(SHADOW_PCSS)
#include "shadow/pcss.glsl"
#elif defined(SHADOW_VSSM)
#include "shadow/vssm.glsl"
#elif defined(SHADOW_CSSM)
#include "shadow/cssm.glsl"
#elif defined(SHADOW_MASK)
#include "shadow/mask.glsl"
#else
highp float shadow_visibility(highp vec3 world_pos, highp vec3 world_normal) { return 1.0; }
#endif
