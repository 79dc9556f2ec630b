// Visibility from a screen-space mask the GI method traced for this light before the direct pass
// (gi.h shadow_mask; vct: the soft-shadow cone, vct/shadow_cone.comp), one texel per G-buffer pixel.
uniform highp sampler2D u_shadow_mask;

highp float shadow_visibility(highp vec3 world_pos, highp vec3 world_normal)
{
    return texelFetch(u_shadow_mask, ivec2(gl_FragCoord.xy), 0).r;
}
