// Linear radial distance / far; the negative half-space and geometry nearer than r_near to the
// centre are left out ("geometry located near the cluster center has to be ignored", §6.3.2).
// VAL_COUNT_FRAGMENTS: the bench's counting variant (app/gi/vpl/vpl_work.c), one atomic add per
// fragment shaded, discarded or not (fragment-stage storage buffers capability-checked by the
// caller). Never in the kiosk's frames.
// @variant -
// @variant VAL_COUNT_FRAGMENTS
precision highp float;
in vec3 v_world;
uniform vec3 u_c, u_n;
uniform float u_far, u_rnear;
layout(location = 0) out vec4 o_z;
#ifdef VAL_COUNT_FRAGMENTS
layout(std430, binding = 6) buffer ValFragments { highp uint fragments; } val_counted;
#endif
void main()
{
#ifdef VAL_COUNT_FRAGMENTS
    atomicAdd(val_counted.fragments, 1u);
#endif
    vec3 v = v_world - u_c;
    float r = length(v);
    if (dot(v, u_n) < 0.0 || r < u_rnear)
        discard;
    float z = r / u_far;
    gl_FragDepth = clamp(z, 0.0, 1.0);
    o_z = vec4(z, 0.0, 0.0, 0.0);
}
