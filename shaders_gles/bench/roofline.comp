// The roofline micro-benchmark (app/bench/roofline.c): every invocation does u_fetches fetches of
// one texture or image, in the way the GI passes do them, so the time of a dispatch gives this
// machine's fetch rate for that kind of fetch:
//   TEX3D  textureLod of a 3D texture at a fractional LOD with LINEAR_MIPMAP_LINEAR: a trilinear
//          fetch between two mips, as a cone-trace sample (vct_trace) does it;
//   TEX2D  textureLod of a 2D texture at a fractional LOD (trilinear between two mips), or
//          texelFetch (NEAREST) where the format is not filterable or the pass reads it unfiltered
//          (RGBA32F tables, a depth map, R32F min/max mips, R32UI summed-area tables: FORMAT_UINT);
//   IMAGE3D imageLoad of a 3D image, as the voxel passes read their volumes;
//   SSBO   a vec4 load from a storage buffer of size³ of them (a diagonal walk, integer-indexed), as
//          radiosity's bounces read their links' radiance; with FORMAT_UINT an atomicAdd to a
//          buffer of size³ uints on the same walk, as vct's voxelizer sums into its scratch buffer.
// Each invocation walks a line through the texture, one texel per step at the fetched level, so
// neighbouring invocations read neighbouring texels, as a screen of cones does. The sum is stored
// so the compiler keeps every fetch; the loop's own count goes to u_counted (one atomic add per
// invocation, negligible beside the fetches), which the host compares with fetches × invocations.
// @variant TEX3D
// @variant TEX3D FORMAT_RGBA8
// @variant TEX2D
// @variant TEX2D NEAREST
// @variant TEX2D NEAREST FORMAT_UINT
// @variant IMAGE3D
// @variant IMAGE3D FORMAT_RGBA8
// @variant SSBO
// @variant SSBO FORMAT_UINT
precision highp float;
precision highp int;
layout(local_size_x = 64) in;
layout(std430, binding = 0) buffer Counted { uint counted; };
layout(std430, binding = 1) buffer Sums { vec4 sums[]; };
uniform int u_fetches;   // fetches per invocation
uniform float u_lod;     // level fetched (fractional: trilinear)
uniform int u_size;      // the texture's level-0 side in texels
#if defined(TEX3D)
uniform highp sampler3D u_tex;
#elif defined(TEX2D) && defined(FORMAT_UINT)
uniform highp usampler2D u_tex;
#elif defined(TEX2D)
uniform highp sampler2D u_tex;
#elif defined(SSBO) && defined(FORMAT_UINT)
layout(std430, binding = 2) buffer Target { uint target[]; };
#elif defined(SSBO)
layout(std430, binding = 2) readonly buffer Source { vec4 source[]; };
#elif defined(IMAGE3D)
#ifdef FORMAT_RGBA8
layout(rgba8, binding = 0) readonly uniform highp image3D u_img;
#else
layout(rgba16f, binding = 0) readonly uniform highp image3D u_img;
#endif
#endif

void main()
{
    uint id = gl_GlobalInvocationID.x;
    // start: the invocation's own texel of a size³ (or size²) grid; direction: one of a few
    // diagonals, so the walk crosses texels as a cone does rather than sitting in one
    vec3 start = vec3(float(id % uint(u_size)), float((id / uint(u_size)) % uint(u_size)),
                      float((id / uint(u_size * u_size)) % uint(u_size))) + 0.5;
    vec3 dir = normalize(vec3(1.0, 0.7 + 0.1 * float(id % 3u), 0.4));
    float step_texels = exp2(floor(u_lod));   // one texel of the fetched level per step
    vec4 sum = vec4(0.0);
    uint done = 0u;
#ifdef SSBO
    // integer addressing, as a gather indexes its links, with what does not change hoisted out of
    // the loop (llvmpipe recomputes the uniforms' products per fetch: 110-147 M loads/s against
    // 155-203 hoisted, 4 interleaved pairs under a load of 9): one step of the diagonal (1, 1, 1)
    // of the size³ grid per fetch, size³ a power of two
    uint stride = uint(u_size * u_size + u_size + 1), mask = uint(u_size * u_size * u_size - 1);
#endif
    for (int i = 0; i < u_fetches; i++) {
        vec3 p = start + dir * (step_texels * float(i));
#if defined(TEX3D)
        sum += textureLod(u_tex, p / float(u_size), u_lod);
#elif defined(TEX2D) && defined(NEAREST)
        sum += vec4(texelFetch(u_tex, ivec2(mod(p.xy, float(u_size))), 0));
#elif defined(TEX2D)
        sum += textureLod(u_tex, p.xy / float(u_size), u_lod);
#elif defined(IMAGE3D)
        sum += imageLoad(u_img, ivec3(mod(p, float(u_size))));
#elif defined(SSBO) && defined(FORMAT_UINT)
        sum.x += float(atomicAdd(target[(id + uint(i) * stride) & mask], 1u));
#elif defined(SSBO)
        sum += source[(id + uint(i) * stride) & mask];
#endif
        done++;
    }
    sums[id] = sum;
    atomicAdd(counted, done);
}
