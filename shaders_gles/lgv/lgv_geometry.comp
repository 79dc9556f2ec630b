// The geometry volume of eq. (6)'s fuzzy occlusion G (seed 002 §4.2 leaves its construction open;
// research B.1.3: a CLPV-style volume of blocking potentials from surfels, offset by half a cell, the
// cube-map texels as the surfels). One invocation per texel of one lattice map (u_map): the texel's
// surface point, its area (the texel's solid angle x distance^2 / |cos|) and its normal; the point's
// projected areas on the three axis planes, in units of the cell's face l^2, added (fixed point)
// into the geometry cell around it. Geometry cells sit on the LGV's cell corners (half a cell off
// the LGV), so a face between two LGV cells has a geometry cell on each of its 4 corners.
// Blocking is two-sided (|n . axis|): a map sees only the side of a wall that faces it, and a 2-band
// SH of |cos| keeps band 0 alone (no direction left), so the volume keeps the three axis projections,
// which is all eq. (6) needs: G_{S_i -> D} depends on the pair of cells, whose link is an axis.
// GEOMETRY_COUNT_FETCHES: the bench's counting variant (#21, app/gi/lgv/lgv_work.c): the distance
// texels read and the atomics added, in the bench's untimed frame only.
// @variant -
// @variant GEOMETRY_COUNT_FETCHES
precision highp float;
precision highp int;
layout(local_size_x = 8, local_size_y = 8) in;
#ifdef GEOMETRY_COUNT_FETCHES
layout(std430, binding = 5) buffer GeometryWork { highp uint dist_fetches; highp uint atomics; } geometry_counted;
#endif
#include "lgv/common.glsl"
#include "lgv/tracer.glsl"
layout(std430, binding = 1) buffer Tmp { highp uint tmp[]; }; // 3 per geometry cell: x, y, z
uniform int u_map;
uniform vec3 u_grid_min;
uniform float u_cell;
uniform ivec3 u_gdims;        // geometry cells: the LGV's dims + 1
uniform float u_fixed;        // fixed-point units per unit of opacity
const highp float MIN_COS = 0.1; // a grazing texel's area is capped at 10x its solid angle's
void main()
{
    ivec3 id = ivec3(gl_GlobalInvocationID);
    if (id.x >= u_res || id.y >= u_res)
        return;
    int face = id.z;
    ivec3 t = ivec3(id.xy, u_map * 6 + face);
    highp float dist = uintBitsToFloat(texelFetch(u_dist, t, 0).r);
#ifdef GEOMETRY_COUNT_FETCHES
    atomicAdd(geometry_counted.dist_fetches, 1u);
#endif
    if (dist >= 0.5 * LGV_FAR)
        return;
    int code = int(texelFetch(u_alb, t, 0).a * 255.0 + 0.5);
    if (code >= 128)
        return; // glass transmits: it does not block the gathering
    highp vec2 uv = (vec2(id.xy) + 0.5) / float(u_res) * 2.0 - 1.0;
    highp vec3 d = lgv_face_w(face) + uv.x * lgv_face_u(face) + uv.y * lgv_face_v(face);
    highp float len2 = dot(d, d);
    highp vec3 dir = d * inversesqrt(len2);
    highp float texel = 2.0 / float(u_res);
    highp float omega = texel * texel / (len2 * sqrt(len2)); // the texel's solid angle
    highp vec3 n = normalize(texelFetch(u_nrm, t, 0).xyz * 2.0 - 1.0);
    highp float area = omega * dist * dist / max(abs(dot(n, dir)), MIN_COS);
    highp vec3 p = centre[u_map].xyz + dist * dir;
    ivec3 g = clamp(ivec3(floor((p - u_grid_min) / u_cell + 0.5)), ivec3(0), u_gdims - 1);
    highp vec3 opacity = area * abs(n) / (u_cell * u_cell);
    int b = 3 * ((g.z * u_gdims.y + g.y) * u_gdims.x + g.x);
#ifdef GEOMETRY_COUNT_FETCHES
    atomicAdd(geometry_counted.atomics, 3u);
#endif
    for (int a = 0; a < 3; a++)
        atomicAdd(tmp[b + a], uint(opacity[a] * u_fixed + 0.5));
}
