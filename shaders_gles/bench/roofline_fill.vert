// The roofline's raster kind (app/bench/roofline_fill.c): triangle t of u_layers covers the
// viewport at a depth nearer than triangle t - 1's, so with a LESS depth test every fragment of
// every triangle is shaded and written.
precision highp float;
uniform int u_layers;
void main()
{
    int t = gl_VertexID / 3, v = gl_VertexID % 3;
    vec2 p = vec2(float((v << 1) & 2), float(v & 2));
    float z = 1.0 - 2.0 * float(t + 1) / float(u_layers + 1);
    gl_Position = vec4(p * 2.0 - 1.0, z, 1.0);
}
