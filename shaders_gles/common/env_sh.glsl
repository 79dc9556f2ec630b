// The environment's residual ambient (app/render/render_env.h): the irradiance E(n) as order-2 SH,
// coefficients already convolved with the clamped cosine (scene/env_split.h). Read by the
// environment pass (direct/environment.frag) and the forward pass of blended surfaces.
uniform highp vec3 u_env_sh[9];
// The SH basis of scene/env_split.c (gk_sh9_basis), the same constants.
highp vec3 env_irradiance(highp vec3 n)
{
    return u_env_sh[0] * 0.282095
         + u_env_sh[1] * (0.488603 * n.y) + u_env_sh[2] * (0.488603 * n.z) + u_env_sh[3] * (0.488603 * n.x)
         + u_env_sh[4] * (1.092548 * n.x * n.y) + u_env_sh[5] * (1.092548 * n.y * n.z)
         + u_env_sh[6] * (0.315392 * (3.0 * n.z * n.z - 1.0)) + u_env_sh[7] * (1.092548 * n.x * n.z)
         + u_env_sh[8] * (0.546274 * (n.x * n.x - n.y * n.y));
}
