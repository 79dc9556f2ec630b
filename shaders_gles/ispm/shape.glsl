// The shape operator of the surface a fragment lies on (fragment shaders only: screen derivatives),
// for the list nodes of both tiers (ll_build.frag, peel.frag): the 2×2 map S with dn = S·dp from an
// in-plane displacement dp to the change of the shading normal, both in the tangent frame of the
// stored (encoded) normal (ispm_tangent_frame), packed by ispm_pack_shape. From the screen
// derivatives of the world position and of the normal: on a triangle both are affine in the same
// barycentrics, so S is exact there (the normalisation aside). A mirror's further bounces
// (trace.comp) reflect about the normal at the hit: the pixel centre's normal is up to a pixel
// footprint away, which on a curved mirror turns the reflection by twice that arc over the radius
// (caustic-ring at 256²: 15% of the two-bounce photon power landed over 3 cm off the tracer's, 30%
// at 128²). Call in uniform control flow (before any discard): derivatives are undefined elsewhere.
highp uint ispm_shape_operator(highp vec3 p, highp vec3 n)
{
    highp vec3 t, b;
    ispm_tangent_frame(ispm_decode_normal(ispm_encode_normal(n)), t, b);
    highp vec3 dpx = dFdx(p), dpy = dFdy(p), dnx = dFdx(n), dny = dFdy(n);
    highp mat2 U = mat2(dot(dpx, t), dot(dpx, b), dot(dpy, t), dot(dpy, b));
    highp mat2 M = mat2(dot(dnx, t), dot(dnx, b), dot(dny, t), dot(dny, b));
    highp float det = determinant(U);
    if (!(abs(det) > 1e-12))
        return 0u;   // a fragment seen edge-on: no in-plane extent to differentiate over
    return ispm_pack_shape(M * inverse(U));
}
