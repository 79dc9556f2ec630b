// The roofline's raster kind (app/bench/roofline_fill.c): a flat value into an R16F target, as a
// shadow or VAL map's depth pass writes one. FILL_COUNT: the untimed counting run, one atomic add
// per fragment, which the host compares with the fragments it asked for.
// @variant -
// @variant FILL_COUNT
precision highp float;
layout(location = 0) out vec4 o_value;
#ifdef FILL_COUNT
layout(std430, binding = 0) buffer FillCounted { highp uint fragments; };
#endif
void main()
{
#ifdef FILL_COUNT
    atomicAdd(fragments, 1u);
#endif
    o_value = vec4(0.5, 0.0, 0.0, 1.0);
}
