// Hard shadows: one depth comparison at the receiver's texel.
highp float shadow_visibility(highp vec3 world_pos, highp vec3 world_normal)
{
    gk_shadow_coord c = gk_shadow_project(gk_shadow_offset(world_pos, world_normal));
    if (!c.inside)
        return 1.0;
    highp float z = gk_shadow_fetch(c.uv, c.layer);
    return c.d <= z + 0.5 * gk_shadow_texel_world(c.d) ? 1.0 : 0.0;
}
