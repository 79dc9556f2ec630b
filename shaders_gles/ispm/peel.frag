// Tier B (no fragment storage blocks): K-layer depth peeling, core GLES 3.0. Layer k keeps the
// nearest fragment behind layer k-1 (depth test LESS on a cleared depth buffer, fragments not behind
// the previous layer discarded) and writes (linear depth bits, encoded geometric normal, Node.spec,
// Node.shape) into its own RGBA32UI texture; peel_lists.comp turns the layers into the same lists the trace reads. What lies
// beyond K layers is missing: the leak of the seed's Fig. 4.2b (research L8).
precision highp float;
precision highp int;
#include "ispm/common.glsl"
#include "ispm/shape.glsl"
uniform highp usampler2D u_prev;        // layer u_layer - 1
uniform int u_layer;                    // layer drawn
uniform mat4 u_model;                   // the draw_scene contract (gi.h)
uniform vec4 u_base_color;
uniform vec2 u_metallic_roughness;
uniform vec4 u_specular;                // the draw_scene contract (gi.h)
uniform vec3 u_emissive;
uniform int u_mat_flags;
in vec3 v_normal;
in vec3 v_world;
layout(location = 0) out uvec4 o_layer;

const int MAT_LIGHT_PROXY = 4;

void main()
{
    vec3 n = normalize(v_normal);
    uint shape = ispm_shape_operator(v_world, n);   // derivatives: before any discard
    if ((u_mat_flags & MAT_LIGHT_PROXY) != 0)
        discard;
    float z = 1.0 / gl_FragCoord.w;
    if (u_layer > 0) {
        uint prev = texelFetch(u_prev, ivec2(gl_FragCoord.xy), 0).r;
        // strictly behind the previous layer (relative 1e-5: coplanar duplicates are one surface)
        if (prev == 0u || z <= uintBitsToFloat(prev) * (1.0 + 1e-5))
            discard;
    }
    o_layer = uvec4(floatBitsToUint(z), ispm_encode_normal(n), ispm_node_spec(u_base_color, u_metallic_roughness, u_specular),
                    shape);
}
