// Lights (KHR_lights_punctual), cameras, the node hierarchy, animations and the scene's
// "gikiosk" extras.
#include "gltf_internal.hpp"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>

namespace gkgltf {

bool read_lights(Loader &L, const Model &m, gk_scene *s)
{
    s->n_lights = (int)m.lights.size();
    s->lights = (gk_light *)calloc(m.lights.size() + 1, sizeof(gk_light));
    if (!s->lights)
        return L.fail("out of memory");
    for (size_t i = 0; i < m.lights.size(); i++) {
        const tinygltf::Light &src = m.lights[i];
        gk_light *d = &s->lights[i];
        copy_name(d->name, sizeof d->name, src.name);
        if (src.type == "point")
            d->type = GK_LIGHT_POINT;
        else if (src.type == "spot")
            d->type = GK_LIGHT_SPOT;
        else if (src.type == "directional")
            d->type = GK_LIGHT_DIRECTIONAL;
        else
            return L.fail("light %zu: unknown type '%s'", i, src.type.c_str());
        for (int c = 0; c < 3; c++)
            d->color[c] = src.color.size() == 3 ? (float)src.color[(size_t)c] : 1.0f;
        d->intensity = (float)src.intensity;
        d->range = (float)src.range;
        d->inner_cone = (float)src.spot.innerConeAngle;
        d->outer_cone = (float)src.spot.outerConeAngle;
        d->shape = GK_SHAPE_POINT;
        const Value *g = gikiosk_extras(src.extras);
        const Value *radius = member(g, "radius"), *size = member(g, "size");
        if (radius) {
            if (!radius->IsNumber())
                return L.fail("light %zu: extras gikiosk.radius must be a number", i);
            d->radius = (float)radius->GetNumberAsDouble();
            d->shape = d->type == GK_LIGHT_POINT ? GK_SHAPE_SPHERE : GK_SHAPE_DISC;
        }
        if (size) {
            if (d->type == GK_LIGHT_DIRECTIONAL || radius)
                return L.fail("light %zu: extras gikiosk.size applies to point and spot lights without a radius", i);
            if (!size->IsArray() || size->ArrayLen() != 2 || !size->Get(0).IsNumber() || !size->Get(1).IsNumber())
                return L.fail("light %zu: extras gikiosk.size must be [W, H]", i);
            d->size[0] = (float)size->Get(0).GetNumberAsDouble();
            d->size[1] = (float)size->Get(1).GetNumberAsDouble();
            d->shape = GK_SHAPE_RECT;
        }
    }
    return true;
}

bool read_cameras(Loader &L, const Model &m, gk_scene *s)
{
    s->n_cameras = (int)m.cameras.size();
    s->cameras = (gk_camera *)calloc(m.cameras.size() + 1, sizeof(gk_camera));
    if (!s->cameras)
        return L.fail("out of memory");
    for (size_t i = 0; i < m.cameras.size(); i++) {
        const tinygltf::Camera &c = m.cameras[i];
        gk_camera *d = &s->cameras[i];
        if (c.type == "orthographic") {
            // Kept so the file loads; the renderers draw perspective only, so a node that uses it
            // is passed over when the view camera is chosen (gk_scene_finish says so).
            d->orthographic = true;
            L.use.orthographic_cameras++;
            d->xmag = (float)c.orthographic.xmag;
            d->ymag = (float)c.orthographic.ymag;
            d->znear = (float)c.orthographic.znear;
            d->zfar = (float)c.orthographic.zfar;
            continue;
        }
        if (c.type != "perspective")
            return L.fail("camera %zu: type '%s' is not a glTF camera type", i, c.type.c_str());
        d->yfov = (float)c.perspective.yfov;
        d->aspect = (float)c.perspective.aspectRatio;
        d->znear = (float)c.perspective.znear;
        d->zfar = (float)c.perspective.zfar;
    }
    return true;
}

// A node matrix (column-major) split into T, R, S; nodes with shear cannot be represented.
namespace {

bool decompose(const std::vector<double> &mx, gk_node *n)
{
    double c[3][3];
    for (int j = 0; j < 3; j++)
        for (int r = 0; r < 3; r++)
            c[j][r] = mx[(size_t)(j * 4 + r)];
    double sx = std::sqrt(c[0][0] * c[0][0] + c[0][1] * c[0][1] + c[0][2] * c[0][2]);
    double sy = std::sqrt(c[1][0] * c[1][0] + c[1][1] * c[1][1] + c[1][2] * c[1][2]);
    double sz = std::sqrt(c[2][0] * c[2][0] + c[2][1] * c[2][1] + c[2][2] * c[2][2]);
    if (!(sx > 0 && sy > 0 && sz > 0))
        return false;
    double det = c[0][0] * (c[1][1] * c[2][2] - c[2][1] * c[1][2]) - c[1][0] * (c[0][1] * c[2][2] - c[2][1] * c[0][2]) +
                 c[2][0] * (c[0][1] * c[1][2] - c[1][1] * c[0][2]);
    if (det < 0)
        sx = -sx;
    double r[3][3]; // r[col][row]
    for (int rr = 0; rr < 3; rr++) {
        r[0][rr] = c[0][rr] / sx;
        r[1][rr] = c[1][rr] / sy;
        r[2][rr] = c[2][rr] / sz;
    }
    double m00 = r[0][0], m11 = r[1][1], m22 = r[2][2];
    double qw, qx, qy, qz, tr = m00 + m11 + m22;
    if (tr > 0) {
        double k = std::sqrt(tr + 1.0) * 2;
        qw = 0.25 * k; qx = (r[1][2] - r[2][1]) / k; qy = (r[2][0] - r[0][2]) / k; qz = (r[0][1] - r[1][0]) / k;
    } else if (m00 > m11 && m00 > m22) {
        double k = std::sqrt(1.0 + m00 - m11 - m22) * 2;
        qw = (r[1][2] - r[2][1]) / k; qx = 0.25 * k; qy = (r[1][0] + r[0][1]) / k; qz = (r[2][0] + r[0][2]) / k;
    } else if (m11 > m22) {
        double k = std::sqrt(1.0 + m11 - m00 - m22) * 2;
        qw = (r[2][0] - r[0][2]) / k; qx = (r[1][0] + r[0][1]) / k; qy = 0.25 * k; qz = (r[2][1] + r[1][2]) / k;
    } else {
        double k = std::sqrt(1.0 + m22 - m00 - m11) * 2;
        qw = (r[0][1] - r[1][0]) / k; qx = (r[2][0] + r[0][2]) / k; qy = (r[2][1] + r[1][2]) / k; qz = 0.25 * k;
    }
    n->translation = v3((float)mx[12], (float)mx[13], (float)mx[14]);
    n->scale = v3((float)sx, (float)sy, (float)sz);
    n->rotation = quat{(float)qx, (float)qy, (float)qz, (float)qw};
    return true;
}


} // namespace

bool read_nodes(Loader &L, const Model &m, gk_scene *s, const std::vector<int> &mesh_first,
                const std::vector<int> &mesh_count)
{
    s->n_nodes = (int)m.nodes.size();
    s->nodes = (gk_node *)calloc(m.nodes.size() + 1, sizeof(gk_node));
    if (!s->nodes)
        return L.fail("out of memory");
    for (size_t i = 0; i < m.nodes.size(); i++)
        s->nodes[i].parent = -1;
    for (size_t i = 0; i < m.nodes.size(); i++) {
        const tinygltf::Node &src = m.nodes[i];
        gk_node *d = &s->nodes[i];
        copy_name(d->name, sizeof d->name, src.name);
        d->translation = v3(0, 0, 0);
        d->rotation = quat{0, 0, 0, 1};
        d->scale = v3(1, 1, 1);
        if (src.translation.size() == 3)
            d->translation = v3((float)src.translation[0], (float)src.translation[1], (float)src.translation[2]);
        else if (!src.translation.empty())
            return L.fail("node %zu: translation must have 3 numbers", i);
        if (src.rotation.size() == 4)
            d->rotation = quat{(float)src.rotation[0], (float)src.rotation[1], (float)src.rotation[2],
                               (float)src.rotation[3]};
        else if (!src.rotation.empty())
            return L.fail("node %zu: rotation must have 4 numbers", i);
        if (src.scale.size() == 3)
            d->scale = v3((float)src.scale[0], (float)src.scale[1], (float)src.scale[2]);
        else if (!src.scale.empty())
            return L.fail("node %zu: scale must have 3 numbers", i);
        if (src.matrix.size() == 16) {
            if (!finite_all(src.matrix) || !decompose(src.matrix, d))
                return L.fail("node %zu: matrix is not a finite, invertible TRS matrix", i);
        } else if (!src.matrix.empty()) {
            return L.fail("node %zu: matrix must have 16 numbers", i);
        }
        d->mesh_first = 0;
        d->mesh_count = 0;
        if (src.mesh >= 0) {
            if ((size_t)src.mesh >= m.meshes.size())
                return L.fail("node %zu: mesh %d does not exist", i, src.mesh);
            d->mesh_first = mesh_first[(size_t)src.mesh];
            d->mesh_count = mesh_count[(size_t)src.mesh];
        }
        d->camera = -1;
        if (src.camera >= 0) {
            if ((size_t)src.camera >= m.cameras.size())
                return L.fail("node %zu: camera %d does not exist", i, src.camera);
            d->camera = src.camera;
        }
        d->light = -1;
        auto it = src.extensions.find("KHR_lights_punctual");
        if (it != src.extensions.end()) {
            const Value *li = member(&it->second, "light");
            if (!li || !li->IsNumber() || li->GetNumberAsInt() < 0 || (size_t)li->GetNumberAsInt() >= m.lights.size())
                return L.fail("node %zu: KHR_lights_punctual light index is missing or out of range", i);
            d->light = li->GetNumberAsInt();
        }
        for (int child : src.children) {
            if (child < 0 || (size_t)child >= m.nodes.size() || (size_t)child == i)
                return L.fail("node %zu: child %d does not exist", i, child);
            if (s->nodes[child].parent >= 0)
                return L.fail("node %d has two parents (%d and %zu)", child, s->nodes[child].parent, i);
            s->nodes[child].parent = (int)i;
        }
        if (src.skin >= 0) {
            gk_log("%s: node %zu: skin ignored: drawn at its node transform (no skinning)", L.path, i);
            L.use.skins++;
        }
    }
    return true;
}

bool read_animations(Loader &L, const Model &m, gk_scene *s)
{
    size_t total = 0;
    for (const auto &a : m.animations)
        total += a.channels.size();
    s->channels = (gk_anim_channel *)calloc(total + 1, sizeof(gk_anim_channel));
    if (!s->channels)
        return L.fail("out of memory");
    for (size_t ai = 0; ai < m.animations.size(); ai++) {
        const tinygltf::Animation &an = m.animations[ai];
        for (size_t ci = 0; ci < an.channels.size(); ci++) {
            const tinygltf::AnimationChannel &ch = an.channels[ci];
            if (ch.sampler < 0 || (size_t)ch.sampler >= an.samplers.size())
                return L.fail("animation %zu channel %zu: sampler %d does not exist", ai, ci, ch.sampler);
            if (ch.target_node < 0 || (size_t)ch.target_node >= m.nodes.size())
                return L.fail("animation %zu channel %zu: node %d does not exist", ai, ci, ch.target_node);
            gk_anim_channel *d = &s->channels[s->n_channels];
            int comps = 3;
            if (ch.target_path == "translation")
                d->path = GK_ANIM_TRANSLATION;
            else if (ch.target_path == "scale")
                d->path = GK_ANIM_SCALE;
            else if (ch.target_path == "rotation")
                d->path = GK_ANIM_ROTATION, comps = 4;
            else {
                gk_log("%s: animation %zu channel %zu: path '%s' is ignored", L.path, ai, ci, ch.target_path.c_str());
                continue;
            }
            const tinygltf::AnimationSampler &sm = an.samplers[(size_t)ch.sampler];
            // CUBICSPLINE is converted to LINEAR through its key values (the tangents are dropped):
            // our animations are authored linear; a cubic file still plays, slightly differently.
            bool cubic = sm.interpolation == "CUBICSPLINE";
            if (sm.interpolation == "LINEAR" || cubic)
                d->interp = GK_INTERP_LINEAR;
            else if (sm.interpolation == "STEP")
                d->interp = GK_INTERP_STEP;
            else
                return L.fail("animation %zu sampler %d: unknown interpolation '%s'", ai, ch.sampler,
                              sm.interpolation.c_str());
            if (cubic)
                gk_log("%s: animation %zu: CUBICSPLINE converted to LINEAR (tangents ignored)", L.path, ai);
            d->node = ch.target_node;
            s->n_channels++; // owned by the scene from here on, so freed on failure
            char what[96];
            size_t nt = 0, nvals = 0;
            snprintf(what, sizeof what, "animation %zu input", ai);
            d->times = read_floats(L, m, sm.input, what, TINYGLTF_TYPE_SCALAR, Ints::none, &nt);
            if (!d->times)
                return false;
            snprintf(what, sizeof what, "animation %zu output", ai);
            float *vals = read_floats(L, m, sm.output, what, comps == 4 ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3,
                                      comps == 4 ? Ints::normalized : Ints::none, &nvals);
            if (!vals)
                return false;
            d->values = vals;
            if (nt == 0 || nvals != nt * (cubic ? 3 : 1))
                return L.fail("animation %zu sampler %d: %zu keys but %zu output values", ai, ch.sampler, nt, nvals);
            if (cubic) // keep the value of each (in-tangent, value, out-tangent) triple
                for (size_t k = 0; k < nt; k++)
                    memmove(vals + k * (size_t)comps, vals + (3 * k + 1) * (size_t)comps, (size_t)comps * sizeof(float));
            d->n_keys = (uint32_t)nt;
        }
    }
    return true;
}

// One medium coefficient: a number or [r, g, b], finite and >= 0 (scene.h, gk_medium).
bool read_medium_rgb(Loader &L, const Value *v, const char *key, float out[3])
{
    if (!v)
        return true;
    double c[3];
    if (v->IsNumber()) {
        c[0] = c[1] = c[2] = v->GetNumberAsDouble();
    } else if (v->IsArray() && v->ArrayLen() == 3 && v->Get(0).IsNumber() && v->Get(1).IsNumber() &&
               v->Get(2).IsNumber()) {
        for (int k = 0; k < 3; k++)
            c[k] = v->Get(k).GetNumberAsDouble();
    } else {
        return L.fail("scene extras gikiosk.medium.%s must be a number or [r, g, b]", key);
    }
    for (int k = 0; k < 3; k++) {
        if (!std::isfinite(c[k]) || c[k] < 0.0)
            return L.fail("scene extras gikiosk.medium.%s: %g is not a finite number >= 0 (1/m)", key, c[k]);
        out[k] = (float)c[k];
    }
    return true;
}

bool read_medium_point(Loader &L, const Value &v, const char *which, vec3 *out)
{
    if (!v.IsArray() || v.ArrayLen() != 3)
        return L.fail("scene extras gikiosk.medium.bounds: %s corner must be [x, y, z]", which);
    float c[3];
    for (int k = 0; k < 3; k++) {
        if (!v.Get(k).IsNumber() || !std::isfinite(v.Get(k).GetNumberAsDouble()))
            return L.fail("scene extras gikiosk.medium.bounds: %s corner must be 3 finite numbers", which);
        c[k] = (float)v.Get(k).GetNumberAsDouble();
    }
    *out = v3(c[0], c[1], c[2]);
    return true;
}

// The scene medium, "extras": {"gikiosk": {"medium": {...}}} (scene.h, gk_medium).
bool read_medium(Loader &L, const Value *g, gk_scene *s)
{
    const Value *med = member(g, "medium");
    if (!med)
        return true;
    if (!med->IsObject())
        return L.fail("scene extras gikiosk.medium must be an object {sigma_s, sigma_a, g, bounds}");
    for (const std::string &key : med->Keys())
        if (key != "sigma_s" && key != "sigma_a" && key != "g" && key != "bounds")
            return L.fail("scene extras gikiosk.medium: unknown key '%s' (sigma_s, sigma_a, g, bounds)", key.c_str());
    gk_medium *md = &s->medium;
    if (!read_medium_rgb(L, member(med, "sigma_s"), "sigma_s", md->sigma_s) ||
        !read_medium_rgb(L, member(med, "sigma_a"), "sigma_a", md->sigma_a))
        return false;
    const Value *gv = member(med, "g");
    if (gv) {
        double g_hg = gv->IsNumber() ? gv->GetNumberAsDouble() : NAN;
        if (!(g_hg > -1.0 && g_hg < 1.0))
            return L.fail("scene extras gikiosk.medium.g must be a number in (-1, 1) (Henyey-Greenstein)");
        md->g = (float)g_hg;
    }
    const Value *b = member(med, "bounds");
    if (b) {
        if (!b->IsArray() || b->ArrayLen() != 2)
            return L.fail("scene extras gikiosk.medium.bounds must be [[x0, y0, z0], [x1, y1, z1]]");
        if (!read_medium_point(L, b->Get(0), "min", &md->box_min) ||
            !read_medium_point(L, b->Get(1), "max", &md->box_max))
            return false;
        if (!(md->box_min.x < md->box_max.x && md->box_min.y < md->box_max.y && md->box_min.z < md->box_max.z))
            return L.fail("scene extras gikiosk.medium.bounds: min must be below max on every axis");
        md->bounded = true;
    }
    md->present = true;
    return true;
}

const Value *scene_gikiosk_extras(const Model &m)
{
    const Value *g = nullptr;
    if (!m.scenes.empty()) {
        size_t si = m.defaultScene >= 0 && (size_t)m.defaultScene < m.scenes.size() ? (size_t)m.defaultScene : 0;
        g = gikiosk_extras(m.scenes[si].extras);
    }
    return g ? g : gikiosk_extras(m.extras);
}

void read_scene_extras(const Model &m, gk_scene *s)
{
    const Value *g = nullptr;
    if (!m.scenes.empty()) {
        size_t si = m.defaultScene >= 0 && (size_t)m.defaultScene < m.scenes.size() ? (size_t)m.defaultScene : 0;
        g = gikiosk_extras(m.scenes[si].extras);
    }
    if (!g)
        g = gikiosk_extras(m.extras);
    if (!g)
        return;
    const Value *desc = member(g, "description"), *methods = member(g, "methods"), *ev = member(g, "exposure");
    if (desc && desc->IsString())
        copy_name(s->description, sizeof s->description, desc->Get<std::string>());
    if (methods && methods->IsString()) {
        copy_name(s->methods, sizeof s->methods, methods->Get<std::string>());
    } else if (methods && methods->IsArray()) {
        std::string joined;
        for (size_t i = 0; i < methods->ArrayLen(); i++)
            if (methods->Get((int)i).IsString())
                joined += (joined.empty() ? "" : ",") + methods->Get((int)i).Get<std::string>();
        copy_name(s->methods, sizeof s->methods, joined);
    }
    if (ev && ev->IsNumber() && std::isfinite(ev->GetNumberAsDouble())) {
        s->exposure_ev = (float)ev->GetNumberAsDouble();
        s->has_exposure = true;
    }
    const Value *params = member(g, "params");
    if (params && params->IsObject())
        for (const std::string &key : params->Keys()) {
            if (s->n_params >= (int)(sizeof s->params / sizeof s->params[0]) || key.size() >= sizeof s->params[0].key)
                break;
            const Value &v = params->Get(key);
            auto *p = &s->params[s->n_params];
            p->n = 0;
            if (v.IsNumber())
                p->v[p->n++] = (float)v.GetNumberAsDouble();
            for (size_t k = 0; v.IsArray() && k < v.ArrayLen() && k < 4; k++)
                if (v.Get((int)k).IsNumber())
                    p->v[p->n++] = (float)v.Get((int)k).GetNumberAsDouble();
            if (p->n > 0) {
                copy_name(p->key, sizeof p->key, key);
                s->n_params++;
            }
        }
}

} // namespace gkgltf
