// Linear radial distance / far; the negative half-space and geometry nearer than r_near to the
// centre are left out ("geometry located near the cluster center has to be ignored", §6.3.2).
// VAL_COUNT_FRAGMENTS: the bench's counting variant (app/gi/vpl/vpl_work.c), one atomic add per
// fragment shaded, discarded or not (fragment-stage storage buffers capability-checked by the
// caller). Never in the kiosk's frames.
// @variant -
// @variant VAL_COUNT_FRAGMENTS
// The second output is level 0 of the chain of maxima (val_zmax.frag) when the pass binds one
// (vpl_umbra=on; without a second draw buffer that write is dropped): the depth and its slope per
// texel. Texels nothing is drawn into keep the clear (1, 0): their edge against a surface is a gap
// rays pass through (the sky). What is left out is not a gap: the VAL's own side (the negative
// half-space, where its surface lies) and its surface near the centre, since a ray that reaches
// them has reached the VAL. There the depth stays the clear value 1 (the CSSM basis is unchanged)
// and the slope is 1, which no jump exceeds, at a depth-buffer value behind every drawn surface
// (those lie within 0.91 of far). Counted as gaps, they left light-leak at RMSE 0.0323 instead of
// 0.0215 (rays to the VPLs end on the VAL's side of its plane).
// The third output (vpl_umbra=plane) is the plane of the surface at each texel: its unit normal,
// turned towards the centre, and the centre's distance to it, -dot(p - c, n) / far. The triangle's
// own derivatives give it, so it is the proxy's plane wherever the texel's ray meets it, whatever
// the paraboloid's chord error. Texels nothing is drawn into, the left-out ones and those of a
// triangle seen edge-on hold (0, 0, 0, 0): no plane, nothing lies behind it.
precision highp float;
in vec3 v_world;
uniform vec3 u_c, u_n;
uniform float u_far, u_rnear;
layout(location = 0) out vec4 o_z;
#ifdef VAL_COUNT_FRAGMENTS
layout(std430, binding = 6) buffer ValFragments { highp uint fragments; } val_counted;
#endif
layout(location = 1) out vec4 o_zmax;
layout(location = 2) out vec4 o_plane;
const float NEAR_MARK_DEPTH = 0.9999;
void main()
{
#ifdef VAL_COUNT_FRAGMENTS
    atomicAdd(val_counted.fragments, 1u);
#endif
    vec3 v = v_world - u_c;
    float r = length(v);
    float z = r / u_far;
    float slope = abs(dFdx(z)) + abs(dFdy(z));   // before any discard: derivatives need the quad
    vec3 tangent_normal = cross(dFdx(v_world), dFdy(v_world));
    if (dot(v, u_n) < 0.0 || r < u_rnear) {
        gl_FragDepth = NEAR_MARK_DEPTH;
        o_z = vec4(1.0, 0.0, 0.0, 0.0);
        o_zmax = vec4(1.0, 1.0, 0.0, 0.0);
        o_plane = vec4(0.0);
        return;
    }
    gl_FragDepth = clamp(z, 0.0, 1.0);
    o_z = vec4(z, 0.0, 0.0, 0.0);
    o_zmax = vec4(z, slope, 0.0, 0.0);
    // The cross product's length over the derivatives' lengths is the sine between them; under
    // 1e-3 (0.06°) they are parallel but for rounding: the triangle is seen edge-on.
    float area = length(tangent_normal);
    vec3 n = area > 1e-3 * length(dFdx(v_world)) * length(dFdy(v_world)) ? tangent_normal / area : vec3(0.0);
    float h = dot(v, n);
    o_plane = dot(n, n) > 0.0 ? vec4(h <= 0.0 ? n : -n, abs(h) / u_far) : vec4(0.0);
}
