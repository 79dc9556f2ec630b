// The injected LGV (fixed-point ints, trace.comp) to floats: the first source of the gathering
// iterations and the start of their accumulated sum.
precision highp float;
precision highp int;
layout(local_size_x = 64) in;
layout(std430, binding = 1) readonly buffer Lgv { highp int lgv[]; };
layout(std430, binding = 5) writeonly buffer Src { highp float src[]; };
layout(std430, binding = 6) writeonly buffer Acc { highp float acc[]; };
uniform int u_values;         // 12 per cell
uniform float u_fixed;
void main()
{
    int i = int(gl_GlobalInvocationID.x);
    if (i >= u_values)
        return;
    float v = float(lgv[i]) / u_fixed;
    src[i] = v;
    acc[i] = v;
}
