// Area-light integrals for Lambertian receivers, all returning E / L (irradiance per unit of
// emitted radiance), so E = L * result:
//  - polygons (rect, disc as an equal-area 16-gon): the exact closed-form edge integral
//    E/L = 1/2 sum_i acos(v_i . v_i+1) (n . normalize(v_i x v_i+1)), after clipping the polygon
//    to the receiver's upper hemisphere (Lambert 1760; e.g. Arvo 1995);
//  - sphere: the exact form factor with horizon clipping (Snyder 1996, as in Frostbite's
//    illuminanceSphereOrDisk), pi sin^2(sigma) cos(theta) when fully above the horizon.
// GGX over rectangle lights uses linearly transformed cosines (common/ltc.glsl, tables fitted by
// tools/ltc_fit.c); over spheres and discs a representative point (Karis 2013).
#define GK_POLY_MAX 18

highp float gk_polygon_irradiance(highp vec3 p, highp vec3 n, highp vec3 verts[GK_POLY_MAX], int count)
{
    // Clip against the plane dot(n, x - p) > 0 (Sutherland-Hodgman).
    highp vec3 clipped[GK_POLY_MAX];
    int m = 0;
    for (int i = 0; i < count; i++) {
        highp vec3 a = verts[i] - p;
        highp vec3 b = verts[(i + 1) % count] - p;
        highp float da = dot(a, n), db = dot(b, n);
        if (da > 0.0 && m < GK_POLY_MAX)
            clipped[m++] = a;
        if ((da > 0.0) != (db > 0.0) && m < GK_POLY_MAX)
            clipped[m++] = a + (b - a) * (da / (da - db));
    }
    if (m < 3)
        return 0.0;
    highp float sum = 0.0;
    for (int i = 0; i < m; i++) {
        highp vec3 a = normalize(clipped[i]);
        highp vec3 b = normalize(clipped[(i + 1) % m]);
        highp vec3 c = cross(a, b);
        highp float len = length(c);
        if (len < 1e-9)
            continue;
        highp float theta = atan(len, dot(a, b));  // robust angle between a and b
        sum += theta * dot(c / len, n);
    }
    return 0.5 * abs(sum);
}

highp float gk_rect_irradiance(highp vec3 p, highp vec3 n, highp vec3 c, highp vec3 hu, highp vec3 hv)
{
    highp vec3 v[GK_POLY_MAX];
    v[0] = c - hu - hv;
    v[1] = c + hu - hv;
    v[2] = c + hu + hv;
    v[3] = c - hu + hv;
    return gk_polygon_irradiance(p, n, v, 4);
}

// A disc as a 16-gon of the same area (circumradius R sqrt(pi / (8 sin(pi/8)))): the irradiance
// error against the true disc is below 0.1% at the distances of interest.
highp float gk_disc_irradiance(highp vec3 p, highp vec3 n, highp vec3 c, highp vec3 u, highp vec3 v, highp float r)
{
    const int N = 16;
    highp float rr = r * sqrt(GK_PI / (float(N) * 0.5 * sin(2.0 * GK_PI / float(N))));
    highp vec3 verts[GK_POLY_MAX];
    for (int i = 0; i < N; i++) {
        highp float a = 2.0 * GK_PI * float(i) / float(N);
        verts[i] = c + rr * (cos(a) * u + sin(a) * v);
    }
    return gk_polygon_irradiance(p, n, verts, N);
}

highp float gk_sphere_irradiance(highp vec3 p, highp vec3 n, highp vec3 c, highp float r)
{
    highp vec3 to_c = c - p;
    highp float d2 = dot(to_c, to_c);
    if (d2 <= r * r)
        return GK_PI; // inside the sphere: it fills the hemisphere
    highp float sin2 = r * r / d2;
    highp float cos_t = dot(n, to_c) * inversesqrt(d2);
    if (cos_t * cos_t > sin2)
        return GK_PI * sin2 * max(cos_t, 0.0);
    highp float sin_t = sqrt(max(1.0 - cos_t * cos_t, 0.0));
    highp float x = sqrt(1.0 / sin2 - 1.0);
    highp float y = -x * (cos_t / sin_t);
    highp float sin_t_sqrt_y = sin_t * sqrt(max(1.0 - y * y, 0.0));
    return max((cos_t * acos(y) - x * sin_t_sqrt_y) * sin2 + atan(sin_t_sqrt_y / x), 0.0);
}

highp vec3 gk_sphere_rep_dir(highp vec3 p, highp vec3 n, highp vec3 v, highp vec3 c, highp float r)
{
    highp vec3 refl = reflect(-v, n);
    highp vec3 to_c = c - p;
    highp vec3 c2ray = dot(to_c, refl) * refl - to_c;
    highp vec3 closest = to_c + c2ray * clamp(r / max(length(c2ray), 1e-6), 0.0, 1.0);
    return normalize(closest);
}

// Closest point of a rect (half sizes h) or disc (radius h.x) to the reflection ray's hit on the
// emitter plane; falls back to the centre when the ray points away from the plane.
highp vec3 gk_planar_rep_dir(highp vec3 p, highp vec3 n, highp vec3 v, highp vec3 c, highp vec3 axis, highp vec3 u,
                             highp vec3 w, highp vec2 h, bool disc)
{
    highp vec3 refl = reflect(-v, n);
    highp float denom = dot(refl, axis);
    highp vec3 hit = c;
    if (denom < -1e-4) {
        highp float t = dot(c - p, axis) / denom;
        if (t > 0.0)
            hit = p + refl * t;
    }
    highp vec2 local = vec2(dot(hit - c, u), dot(hit - c, w));
    if (disc) {
        highp float len = length(local);
        if (len > h.x)
            local *= h.x / len;
    } else {
        local = clamp(local, -h, h);
    }
    return normalize(c + local.x * u + local.y * w - p);
}
