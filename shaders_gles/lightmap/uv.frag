// Writes the light-map UV bit-exactly into an RG32UI target (integer targets are colour-renderable
// on the GLES 3.1 floor, float ones are not). Uncharted surfaces (light proxies) write uv < 0.
// UV_COUNT_FRAGMENTS: the bench's counting variant (#21, app/gi/lightmap/lm_work.c), one atomic add
// per fragment rasterized (fragment-stage storage buffers capability-checked by the caller). Never
// in the kiosk's frames.
// @variant -
// @variant UV_COUNT_FRAGMENTS
precision highp float;
precision highp int;
#ifdef UV_COUNT_FRAGMENTS
layout(std430, binding = 5) buffer UvFragments { highp uint fragments; } uv_counted;
#endif
in vec2 v_lightmap_uv;
layout(location = 0) out uvec2 o_uv;
void main()
{
#ifdef UV_COUNT_FRAGMENTS
    atomicAdd(uv_counted.fragments, 1u);
#endif
    o_uv = floatBitsToUint(v_lightmap_uv);
}
