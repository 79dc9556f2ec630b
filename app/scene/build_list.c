/* The list of procedural scenes that `gikiosk build-scenes` / `make scenes` writes. */
#include "scene/build_geom.h"

const gk_scene_builder gk_scene_builders[] = {
    {"cornell", gk_build_cornell},
    {"cornell-spot", gk_build_cornell_spot},
    {"cornell-spot-anim", gk_build_cornell_spot_anim},
    {"shadow-planes", gk_build_shadow_planes},
    {"shadow-planes-stacked", gk_build_shadow_planes_stacked},
    {"light-leak", gk_build_light_leak},
    {"caustic-ring", gk_build_caustic_ring},
    {"atrium", gk_build_atrium},
    {"furnace", gk_build_furnace},
    {.name = "glass", .build = gk_build_glass},
    {.name = "caustic-ring-fog", .build = gk_build_caustic_ring_fog},
    {.name = "env-studio", .build = gk_build_env_studio},
    {.name = "glass-fog", .build = gk_build_glass_fog},
};
const int gk_n_scene_builders = (int)(sizeof gk_scene_builders / sizeof gk_scene_builders[0]);
