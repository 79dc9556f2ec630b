// The seed's two IIMs "switched with a blend" to avoid popping (B.1.5): the displayed map moves
// towards the gathered one by u_alpha = 1 - exp(-dt / τ) a frame (research B.2: τ = 0.25 s).
// BLEND_COUNT_FETCHES: the bench's counting variant (#21, app/gi/lightmap/lm_work.c), one atomic add
// of the two texel reads per atlas texel. Never in the kiosk's frames.
// @variant -
// @variant BLEND_COUNT_FETCHES
precision highp float;
#ifdef BLEND_COUNT_FETCHES
layout(std430, binding = 6) buffer BlendFetches { highp uint texels; } blend_counted;
#endif
layout(local_size_x = 8, local_size_y = 8) in;
uniform highp sampler2D u_gathered;
uniform highp sampler2D u_shown;
layout(rgba16f, binding = 0) uniform writeonly highp image2D u_next;
uniform float u_alpha;
void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = textureSize(u_gathered, 0);
    if (p.x >= size.x || p.y >= size.y)
        return;
#ifdef BLEND_COUNT_FETCHES
    atomicAdd(blend_counted.texels, 2u);
#endif
    imageStore(u_next, p, mix(texelFetch(u_shown, p, 0), texelFetch(u_gathered, p, 0), u_alpha));
}
