/* Small vector/matrix library shared by the scene model, the renderer and the path tracer, so both
 * renderers transform the same way. Matrices are column-major (as glTF and GL): m[col*4 + row]. */
#ifndef GK_VECMATH_H
#define GK_VECMATH_H

#include <math.h>

typedef struct { float x, y, z; } vec3;
typedef struct { float x, y, z, w; } vec4;
typedef struct { float x, y, z, w; } quat; /* glTF order: x, y, z, w */
typedef struct { float m[16]; } mat4;

static inline vec3 v3(float x, float y, float z) { return (vec3){x, y, z}; }
static inline vec3 v3_add(vec3 a, vec3 b) { return v3(a.x + b.x, a.y + b.y, a.z + b.z); }
static inline vec3 v3_sub(vec3 a, vec3 b) { return v3(a.x - b.x, a.y - b.y, a.z - b.z); }
static inline vec3 v3_mul(vec3 a, vec3 b) { return v3(a.x * b.x, a.y * b.y, a.z * b.z); }
static inline vec3 v3_scale(vec3 a, float s) { return v3(a.x * s, a.y * s, a.z * s); }
static inline float v3_dot(vec3 a, vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline vec3 v3_cross(vec3 a, vec3 b)
{
    return v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static inline float v3_len(vec3 a) { return sqrtf(v3_dot(a, a)); }
static inline vec3 v3_norm(vec3 a)
{
    float l = v3_len(a);
    return l > 0.0f ? v3_scale(a, 1.0f / l) : a;
}
static inline vec3 v3_min(vec3 a, vec3 b) { return v3(fminf(a.x, b.x), fminf(a.y, b.y), fminf(a.z, b.z)); }
static inline vec3 v3_max(vec3 a, vec3 b) { return v3(fmaxf(a.x, b.x), fmaxf(a.y, b.y), fmaxf(a.z, b.z)); }
static inline vec3 v3_lerp(vec3 a, vec3 b, float t) { return v3_add(a, v3_scale(v3_sub(b, a), t)); }
static inline float v3_maxc(vec3 a) { return fmaxf(a.x, fmaxf(a.y, a.z)); }

mat4 m4_identity(void);
mat4 m4_mul(mat4 a, mat4 b);                      /* a * b */
mat4 m4_trs(vec3 t, quat r, vec3 s);              /* glTF node transform T * R * S */
mat4 m4_inverse(mat4 a);                          /* general 4x4 inverse (identity if singular) */
mat4 m4_transpose(mat4 a);
mat4 m4_perspective(float yfov, float aspect, float znear, float zfar);
mat4 m4_ortho(float l, float r, float b, float t, float n, float f);
mat4 m4_look_at(vec3 eye, vec3 target, vec3 up);
vec3 m4_point(mat4 a, vec3 p);                     /* a * (p, 1), no divide */
vec3 m4_dir(mat4 a, vec3 d);                       /* a * (d, 0) */
vec4 m4_vec4(mat4 a, vec4 v);
quat q_slerp(quat a, quat b, float t);
quat q_normalize(quat q);
vec3 q_rotate(quat q, vec3 v);

#endif
