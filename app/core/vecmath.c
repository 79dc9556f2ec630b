#include "vecmath.h"

#include <string.h>

mat4 m4_identity(void)
{
    mat4 r;
    memset(&r, 0, sizeof r);
    r.m[0] = r.m[5] = r.m[10] = r.m[15] = 1.0f;
    return r;
}

mat4 m4_mul(mat4 a, mat4 b)
{
    mat4 r;
    for (int c = 0; c < 4; c++)
        for (int row = 0; row < 4; row++) {
            float s = 0.0f;
            for (int k = 0; k < 4; k++)
                s += a.m[k * 4 + row] * b.m[c * 4 + k];
            r.m[c * 4 + row] = s;
        }
    return r;
}

mat4 m4_trs(vec3 t, quat q, vec3 s)
{
    float x = q.x, y = q.y, z = q.z, w = q.w;
    mat4 r = m4_identity();
    r.m[0] = (1 - 2 * (y * y + z * z)) * s.x;
    r.m[1] = (2 * (x * y + z * w)) * s.x;
    r.m[2] = (2 * (x * z - y * w)) * s.x;
    r.m[4] = (2 * (x * y - z * w)) * s.y;
    r.m[5] = (1 - 2 * (x * x + z * z)) * s.y;
    r.m[6] = (2 * (y * z + x * w)) * s.y;
    r.m[8] = (2 * (x * z + y * w)) * s.z;
    r.m[9] = (2 * (y * z - x * w)) * s.z;
    r.m[10] = (1 - 2 * (x * x + y * y)) * s.z;
    r.m[12] = t.x;
    r.m[13] = t.y;
    r.m[14] = t.z;
    return r;
}

mat4 m4_transpose(mat4 a)
{
    mat4 r;
    for (int c = 0; c < 4; c++)
        for (int row = 0; row < 4; row++)
            r.m[c * 4 + row] = a.m[row * 4 + c];
    return r;
}

mat4 m4_inverse(mat4 a)
{
    /* Gauss-Jordan with partial pivoting in double precision. */
    double m[4][8];
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++) {
            m[r][c] = a.m[c * 4 + r];
            m[r][c + 4] = (r == c);
        }
    for (int c = 0; c < 4; c++) {
        int piv = c;
        for (int r = c + 1; r < 4; r++)
            if (fabs(m[r][c]) > fabs(m[piv][c]))
                piv = r;
        if (fabs(m[piv][c]) < 1e-30)
            return m4_identity();
        if (piv != c)
            for (int k = 0; k < 8; k++) {
                double t = m[c][k];
                m[c][k] = m[piv][k];
                m[piv][k] = t;
            }
        double inv = 1.0 / m[c][c];
        for (int k = 0; k < 8; k++)
            m[c][k] *= inv;
        for (int r = 0; r < 4; r++)
            if (r != c) {
                double f = m[r][c];
                for (int k = 0; k < 8; k++)
                    m[r][k] -= f * m[c][k];
            }
    }
    mat4 out;
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++)
            out.m[c * 4 + r] = (float)m[r][c + 4];
    return out;
}

mat4 m4_perspective(float yfov, float aspect, float n, float f)
{
    mat4 r;
    memset(&r, 0, sizeof r);
    float t = 1.0f / tanf(yfov * 0.5f);
    r.m[0] = t / aspect;
    r.m[5] = t;
    r.m[10] = (f + n) / (n - f);
    r.m[11] = -1.0f;
    r.m[14] = 2.0f * f * n / (n - f);
    return r;
}

mat4 m4_ortho(float l, float rt, float b, float t, float n, float f)
{
    mat4 r = m4_identity();
    r.m[0] = 2.0f / (rt - l);
    r.m[5] = 2.0f / (t - b);
    r.m[10] = -2.0f / (f - n);
    r.m[12] = -(rt + l) / (rt - l);
    r.m[13] = -(t + b) / (t - b);
    r.m[14] = -(f + n) / (f - n);
    return r;
}

mat4 m4_look_at(vec3 eye, vec3 target, vec3 up)
{
    vec3 f = v3_norm(v3_sub(target, eye));
    if (fabsf(v3_dot(f, v3_norm(up))) > 0.999f)
        up = fabsf(f.y) < 0.9f ? v3(0, 1, 0) : v3(1, 0, 0);
    vec3 s = v3_norm(v3_cross(f, up));
    vec3 u = v3_cross(s, f);
    mat4 r = m4_identity();
    r.m[0] = s.x; r.m[4] = s.y; r.m[8] = s.z;
    r.m[1] = u.x; r.m[5] = u.y; r.m[9] = u.z;
    r.m[2] = -f.x; r.m[6] = -f.y; r.m[10] = -f.z;
    r.m[12] = -v3_dot(s, eye);
    r.m[13] = -v3_dot(u, eye);
    r.m[14] = v3_dot(f, eye);
    return r;
}

vec3 m4_point(mat4 a, vec3 p)
{
    return v3(a.m[0] * p.x + a.m[4] * p.y + a.m[8] * p.z + a.m[12],
              a.m[1] * p.x + a.m[5] * p.y + a.m[9] * p.z + a.m[13],
              a.m[2] * p.x + a.m[6] * p.y + a.m[10] * p.z + a.m[14]);
}

vec3 m4_dir(mat4 a, vec3 d)
{
    return v3(a.m[0] * d.x + a.m[4] * d.y + a.m[8] * d.z,
              a.m[1] * d.x + a.m[5] * d.y + a.m[9] * d.z,
              a.m[2] * d.x + a.m[6] * d.y + a.m[10] * d.z);
}

vec4 m4_vec4(mat4 a, vec4 v)
{
    vec4 r;
    r.x = a.m[0] * v.x + a.m[4] * v.y + a.m[8] * v.z + a.m[12] * v.w;
    r.y = a.m[1] * v.x + a.m[5] * v.y + a.m[9] * v.z + a.m[13] * v.w;
    r.z = a.m[2] * v.x + a.m[6] * v.y + a.m[10] * v.z + a.m[14] * v.w;
    r.w = a.m[3] * v.x + a.m[7] * v.y + a.m[11] * v.z + a.m[15] * v.w;
    return r;
}

quat q_normalize(quat q)
{
    float l = sqrtf(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
    if (l <= 0.0f)
        return (quat){0, 0, 0, 1};
    return (quat){q.x / l, q.y / l, q.z / l, q.w / l};
}

quat q_slerp(quat a, quat b, float t)
{
    float d = a.x * b.x + a.y * b.y + a.z * b.z + a.w * b.w;
    if (d < 0.0f) {
        b = (quat){-b.x, -b.y, -b.z, -b.w};
        d = -d;
    }
    if (d > 0.9995f) {
        quat r = {a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), a.z + t * (b.z - a.z), a.w + t * (b.w - a.w)};
        return q_normalize(r);
    }
    float th = acosf(d), s = sinf(th);
    float wa = sinf((1 - t) * th) / s, wb = sinf(t * th) / s;
    return (quat){wa * a.x + wb * b.x, wa * a.y + wb * b.y, wa * a.z + wb * b.z, wa * a.w + wb * b.w};
}

vec3 q_rotate(quat q, vec3 v)
{
    vec3 u = v3(q.x, q.y, q.z);
    vec3 t = v3_scale(v3_cross(u, v), 2.0f);
    return v3_add(v3_add(v, v3_scale(t, q.w)), v3_cross(u, t));
}
