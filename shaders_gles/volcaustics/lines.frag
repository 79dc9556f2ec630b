// volcaustics pass 4 + 5, light-ray blending (research §6.2-6.4): one fragment where a light line
// crosses a pixel adds the single scattering at the crossing of the view ray and the line,
//   x_l = the closest point of the view ray to the line (t_v along the view ray),
// emulating the seed's regular ray-march step Delta x: the sample is spread over the regular points
// k Delta x within r_f of t_v by the normalised Gaussian filter [Jensen01] (research §6.2),
//   w(delta) = alpha [1 - (1 - e^(-beta delta^2 / (2 r_f^2))) / (1 - e^(-beta))], alpha 0.918,
//   beta 1.953, divided by its integral over [-r_f, r_f] (u_filter_norm, vc_lines.c) so that
//   sum_k w(k Delta x - t_v) Delta x is 1 on average: the filter moves light, never adds any.
// The normalisation the seed leaves out (research §6.4): a line stands for a beam of flux Phi (the
// texel's I dOmega F T(s, p1), raygen.comp); a pixel seeing a stretch l of a thin beam receives the
// in-scattered radiance T(v, x) sigma_s p(cos) T(p1, x) Phi l / A_pix, A_pix = d^2 a_pix cos^3 the
// pixel's cross-section at the distance d of x (a_pix its area on the image plane at distance 1,
// cos its angle off the optical axis). GL_LINES rasterises one fragment per pixel step along the
// line's major screen axis, so each fragment stands for the beam length l = (3D length per pixel of
// that axis), measured here from the line's projection. Then the mean image is independent of the
// caustic-buffer resolution (Phi per line ~ 1/R^2, lines ~ R^2) and of the screen's (fragments per
// line ~ pixels, l ~ 1/pixels, 1/A_pix ~ pixels^2 ... per pixel: the same radiance).
// Pass 5, visibility: a crossing behind the scene's surface at this pixel (G-buffer depth) is culled,
// and so are the regular points behind it.
// LINES_COUNT_FRAGMENTS: the bench's counting variant (app/gi/volcaustics/vc_work.c), one atomic
// add per fragment of the lines (fragment-stage storage buffers capability-checked by the caller).
// Never in the kiosk's frames.
// @variant -
// @variant LINES_COUNT_FRAGMENTS
precision highp float;
precision highp int;
#include "volcaustics/medium.glsl"
flat in vec3 v_p1;
flat in vec3 v_a;
flat in vec3 v_b;
flat in vec3 v_flux;
uniform highp sampler2D u_depth;     // the G-buffer depth
uniform mat4 u_view_proj;
uniform mat4 u_inv_view_proj;
uniform vec3 u_eye;
uniform vec3 u_fwd;                  // the camera's optical axis
uniform vec2 u_size;                 // screen pixels
uniform float u_pix_area;            // a_pix: a pixel's area on the image plane at distance 1
uniform float u_dx;                  // Delta x (m)
uniform float u_rf;                  // r_f (m)
uniform float u_filter_norm;         // 1 / integral of w over [-r_f, r_f]
layout(location = 0) out vec4 o_rad;
#ifdef LINES_COUNT_FRAGMENTS
layout(std430, binding = 6) buffer LineFragments { highp uint fragments; } lines_counted;
#endif

vec3 unproject(vec2 frag, float depth)
{
    vec4 c = u_inv_view_proj * vec4(vec3(frag / u_size, depth) * 2.0 - 1.0, 1.0);
    return c.xyz / c.w;
}

vec2 to_pixels(vec3 x)
{
    vec4 c = u_view_proj * vec4(x, 1.0);
    return (c.xy / c.w * 0.5 + 0.5) * u_size;
}

float gauss_norm(float delta)
{
    const float alpha = 0.918, beta = 1.953;
    if (abs(delta) >= u_rf)
        return 0.0;
    float w = alpha * (1.0 - (1.0 - exp(-beta * delta * delta / (2.0 * u_rf * u_rf))) / (1.0 - exp(-beta)));
    return w * u_filter_norm;
}

void main()
{
#ifdef LINES_COUNT_FRAGMENTS
    atomicAdd(lines_counted.fragments, 1u);
#endif
    vec3 dv = normalize(unproject(gl_FragCoord.xy, 1.0) - u_eye);
    float depth = texelFetch(u_depth, ivec2(gl_FragCoord.xy), 0).r;
    float t_surf = depth < 1.0 ? distance(unproject(gl_FragCoord.xy, depth), u_eye) : 1e30;
    vec3 ab = v_b - v_a;
    float len = length(ab);
    if (len <= 0.0)
        discard;
    vec3 u = ab / len;
    // closest points of the view ray u_eye + t_v dv and the segment v_a + t_l u
    vec3 w0 = u_eye - v_a;
    float b = dot(dv, u), dd = dot(dv, w0), e = dot(u, w0), den = max(1.0 - b * b, 1e-6);
    float tv = (b * e - dd) / den;
    float tl = clamp((e - b * dd) / den, 0.0, len);
    vec3 xl = v_a + u * tl;
    tv = dot(xl - u_eye, dv);
    if (tv <= 0.0 || tv > t_surf)
        discard;                      // pass 5: behind the surface (or behind the eye)
    // the beam length this fragment stands for: 3D length per pixel step of the major screen axis
    float eps = 1e-3 * max(tv, 1e-2);
    vec2 s0 = to_pixels(xl), s1 = to_pixels(xl + u * eps);
    float px = max(abs(s1.x - s0.x), abs(s1.y - s0.y));
    float l = px > 0.0 ? min(eps / px, len) : len;
    float c = max(dot(dv, u_fwd), 1e-3);
    float a_pix = tv * tv * u_pix_area * c * c * c;   // the pixel's solid angle a_pix cos^3 at distance t_v
    float ph = vc_phase(dot(u, -dv));
    vec3 acc = vec3(0.0);
    float k0 = ceil((tv - u_rf) / u_dx), k1 = floor((tv + u_rf) / u_dx);
    for (float k = k0; k <= k1; k += 1.0) {
        float t = k * u_dx;
        if (t <= 0.0 || t > t_surf)
            continue;
        vec3 xk = u_eye + dv * t;
        float wgt = gauss_norm(t - tv) * u_dx;
        acc += vc_transmittance(u_eye, xk) * vc_transmittance(v_p1, xk) * wgt;
    }
    o_rad = vec4(acc * u_sigma_s * ph * v_flux * (l / a_pix), 0.0);
}
