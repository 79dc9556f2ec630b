// The scene environment from the scene's extras (scene.h, gk_environment):
//   "extras": {"gikiosk": {"environment": {"uri": "sky.exr", "intensity": 1.0}}}
// Only the keys are read here; the map itself is read and checked by gk_env_load (environment.c)
// when the scene is finished, so a broken map is refused naming the file and the key.
#include <cmath>

#include "gltf_internal.hpp"

namespace gkgltf {

bool read_environment(Loader &L, const Value *g, gk_scene *s)
{
    const Value *env = member(g, "environment");
    if (!env)
        return true;
    if (!env->IsObject())
        return L.fail("scene extras gikiosk.environment must be an object {uri, intensity}");
    for (const std::string &key : env->Keys())
        if (key != "uri" && key != "intensity")
            return L.fail("scene extras gikiosk.environment: unknown key '%s' (uri, intensity)", key.c_str());
    const Value *uri = member(env, "uri"), *intensity = member(env, "intensity");
    if (!uri || !uri->IsString() || uri->Get<std::string>().empty())
        return L.fail("scene extras gikiosk.environment.uri must name an image next to the scene (a lat-long EXR)");
    const std::string &u = uri->Get<std::string>();
    if (u.size() >= sizeof s->environment.uri)
        return L.fail("scene extras gikiosk.environment.uri is longer than %zu characters",
                      sizeof s->environment.uri - 1);
    gk_environment *e = &s->environment;
    copy_name(e->uri, sizeof e->uri, u);
    e->intensity = 1.0f;
    if (intensity) {
        if (!intensity->IsNumber())
            return L.fail("scene extras gikiosk.environment.intensity must be a number");
        double v = intensity->GetNumberAsDouble();
        if (!std::isfinite(v) || v < 0.0 || v > 1e9)
            return L.fail("scene extras gikiosk.environment.intensity: %g is not a finite number >= 0", v);
        e->intensity = (float)v;
    }
    e->present = true;
    return true;
}

} // namespace gkgltf
