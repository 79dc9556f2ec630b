/* The scene model: plain C structs that both the real-time renderer and the reference path tracer
 * read, so their images are comparable pixel for pixel (DESIGN §1). Units are glTF's: metres,
 * candela for point/spot lights, lux for directional lights, nits (cd/m²) for emission.
 *
 * Area lights (DESIGN §4): a punctual light may carry a size in its extras:
 *   "extras": {"gikiosk": {"radius": R}}       point -> sphere of radius R;
 *                                               spot  -> disc of radius R facing the node's -Z,
 *                                                        masked by the spot cone;
 *                                               directional -> sun disc of angular radius R (radians)
 *   "extras": {"gikiosk": {"size": [W, H]}}    point or spot -> one-sided Lambertian rectangle in the
 *                                               node's local XY plane, emitting towards -Z.
 * The intensity I (cd) is the intensity along the emitter's axis, so the emitted radiance is
 * I / (pi R^2) for a sphere or disc and I / (W H) for a rectangle; the power is the same as the
 * punctual light's, so a scene keeps its brightness whichever way a renderer treats the light.
 *
 * A mesh whose material has "extras": {"gikiosk": {"light_proxy": true}} is the visible face of an
 * area light (the Cornell ceiling quad): it is drawn with its emission by the rasterizer, but the
 * path tracer does not intersect it, because the area light's own geometry stands in its place. */
#ifndef GK_SCENE_H
#define GK_SCENE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "base/err.h"
#include "../core/vecmath.h"

enum gk_light_type { GK_LIGHT_POINT, GK_LIGHT_SPOT, GK_LIGHT_DIRECTIONAL };
enum gk_light_shape { GK_SHAPE_POINT, GK_SHAPE_SPHERE, GK_SHAPE_DISC, GK_SHAPE_RECT };

/* glTF sampler wrap modes; 0 (the zeroed default) is glTF's default, REPEAT. */
enum gk_wrap { GK_WRAP_REPEAT = 0, GK_WRAP_CLAMP, GK_WRAP_MIRROR };

typedef struct gk_texture {
    char uri[256];    /* the image file, relative to the scene's folder; "" for an embedded image */
    unsigned char *embedded;   /* encoded bytes of an image inside the file (GLB chunk or data: uri), */
    size_t embedded_size;      /*   freed once decoded */
    char mime[32];             /* the image's mimeType, "" when not given */
    int width, height;
    float *rgba;      /* width*height*4 floats, linear (sRGB decoded for colour textures) */
    /* The glTF sampler: wrapS, wrapT, and one filter for magnification and minification alike
       (neither renderer has mipmaps, and the tracer no footprint to tell the two apart): NEAREST
       when magFilter is NEAREST, else bilinear. Both renderers sample the same way. */
    enum gk_wrap wrap_s, wrap_t;
    bool nearest;
} gk_texture;

/* The texture slots of a material, for gk_material.tex_uv. */
enum gk_tex_slot {
    GK_SLOT_BASE, GK_SLOT_MR, GK_SLOT_EMISSIVE, GK_SLOT_NORMAL, GK_SLOT_SPECULAR, GK_SLOT_SPECULAR_COLOR,
    GK_SLOT_OCCLUSION, GK_TEX_SLOTS
};

/* Where one texture slot reads its UVs: TEXCOORD_<texcoord> (0 or 1; glTF textureInfo.texCoord,
 * or KHR_texture_transform's override), then, when transformed, KHR_texture_transform's
 * uv' = T(offset) R(rotation) S(scale) uv as the row-major 2x3 matrix m:
 *   [ cos(r) sx   sin(r) sy   ox ]
 *   [-sin(r) sx   cos(r) sy   oy ]   (the extension's matrices multiplied out). */
typedef struct gk_tex_uv {
    int texcoord;
    bool transformed;
    float m[6];
} gk_tex_uv;

/* uv' of slot `xf` (identity when not transformed). Both renderers apply the same (the G-buffer
 * shader its own copy: shaders_gles/gbuffer/gbuffer.frag). */
static inline void gk_tex_uv_apply(const gk_tex_uv *xf, float u, float v, float *out_u, float *out_v)
{
    if (!xf->transformed) {
        *out_u = u, *out_v = v;
        return;
    }
    *out_u = xf->m[0] * u + xf->m[1] * v + xf->m[2];
    *out_v = xf->m[3] * u + xf->m[4] * v + xf->m[5];
}

typedef struct gk_material {
    char name[64];
    float base_color[4];      /* linear RGBA factor */
    int base_color_tex;       /* index into scene.textures, -1 if none */
    float metallic, roughness;
    int metallic_roughness_tex; /* G = roughness, B = metallic (glTF), -1 if none */
    /* What the material is over its surface: the factors times the metallic-roughness texture's
       mean B and G (the factors alone without one). Real PBR models put metallic 1 in the factor
       and the true values in the texture; features and method applicability read these. */
    float metallic_mean, roughness_mean;
    float emissive[3];        /* emissiveFactor * KHR_materials_emissive_strength, in nits */
    int emissive_tex;         /* RGB (sRGB-encoded) times emissive, -1 if none */
    int normal_tex;           /* tangent-space normal map (RGB data), -1 if none */
    /* glTF occlusionTexture (R, data): ambient occlusion 1 + occlusion_strength (R - 1), applied by
       the rasterizer to ambient and indirect light only (the environment's SH residual, the GI
       methods' contribution), never to direct light. The path tracer ignores it: it computes
       occlusion itself, so the texture would count it twice. -1 if none. */
    int occlusion_tex;
    float occlusion_strength; /* occlusionTexture.strength, in [0, 1] (1 by default) */
    float normal_scale;       /* normalTexture.scale: scales the map's X and Y */
    float transmission;       /* KHR_materials_transmission: 0 opaque .. 1 clear glass/water */
    float ior;                /* KHR_materials_ior, 1.5 by default */
    /* KHR_materials_specular (the dielectric lobe of brdf_spec.md): specularFactor (1 by default;
       0 = pure Lambert) times specularTexture's A, and specularColorFactor (linear, [1,1,1] by
       default, may exceed 1) times specularColorTexture's RGB (sRGB-encoded). */
    float specular;
    float specular_color[3];
    int specular_tex;         /* A = specular weight, -1 if none */
    int specular_color_tex;   /* RGB = F0 colour, -1 if none */
    bool double_sided;
    bool light_proxy;         /* see the header comment */
    gk_tex_uv tex_uv[GK_TEX_SLOTS]; /* each slot's UV set and KHR_texture_transform (zeroed: set 0, none) */
    /* glTF alphaMode MASK: a surface point whose alpha (base colour factor x texture x COLOR_0, A) is
       below alpha_cutoff is not there, for the camera, the shadow maps and the tracer's rays alike.
       OPAQUE and BLEND leave it false. */
    bool alpha_mask;
    float alpha_cutoff;       /* glTF alphaCutoff, 0.5 by default */
    /* glTF alphaMode BLEND: the surface covers alpha of what lies behind it. The rasterizer leaves it
       out of the G-buffer and draws it over the lit image (app/render/render_blend.c); the tracer's
       rays pass it with probability 1 - alpha (stochastic transparency, app/ref/materials.c). */
    bool alpha_blend;
} gk_material;

typedef struct gk_mesh {       /* one glTF primitive, triangles only, in object space */
    float *positions;          /* n_vertices * 3 */
    float *normals;            /* n_vertices * 3 (generated flat if the file has none) */
    float *uvs;                /* n_vertices * 2, or NULL */
    float *uvs1;               /* TEXCOORD_1, n_vertices * 2, or NULL (a slot reading set 1 then reads set 0) */
    float *colors;             /* COLOR_0, n_vertices * 4 linear RGBA (RGB files get A = 1), or NULL */
    float *tangents;           /* TANGENT xyz + handedness w, n_vertices * 4; generated (tangents.c)
                                  when a normal-mapped mesh has none, else NULL */
    uint32_t *indices;         /* n_triangles * 3 */
    uint32_t n_vertices, n_triangles;
    int material;              /* index into scene.materials (a default material is always there) */
    vec3 bmin, bmax;           /* object-space bounds */
} gk_mesh;

typedef struct gk_light {
    char name[64];
    enum gk_light_type type;
    enum gk_light_shape shape;
    float color[3];            /* linear RGB, multiplied by intensity */
    float intensity;           /* cd (point, spot) or lux (directional) */
    float range;               /* 0 = infinite */
    float inner_cone, outer_cone; /* spot, radians */
    float radius;              /* sphere/disc radius (m) or sun angular radius (rad) */
    float size[2];             /* rectangle W, H (m) */
    /* A light of the environment's split (env_split.h): the rasterizer draws it in place of the
       environment; the path tracer skips it, because it samples the environment map itself. */
    bool env_part;
} gk_light;

typedef struct gk_camera {
    float yfov;                /* radians */
    float aspect;              /* 0: use the viewport's */
    float znear, zfar;         /* zfar 0 = infinite */
    bool orthographic;         /* loaded, never the view camera (perspective only): yfov/aspect unused */
    float xmag, ymag;          /* orthographic half extents */
} gk_camera;

typedef struct gk_node {
    char name[64];
    int parent;                /* -1 for roots */
    vec3 translation;
    quat rotation;
    vec3 scale;
    int mesh_first, mesh_count; /* range of scene.meshes drawn by this node (count 0 = none) */
    int light;                 /* index into scene.lights or -1 */
    int camera;                /* index into scene.cameras or -1 */
    mat4 world;                /* filled by gk_scene_evaluate() */
    bool animated;             /* it or an ancestor is targeted by an animation channel */
} gk_node;

enum gk_anim_path { GK_ANIM_TRANSLATION, GK_ANIM_ROTATION, GK_ANIM_SCALE };
enum gk_anim_interp { GK_INTERP_LINEAR, GK_INTERP_STEP };

typedef struct gk_anim_channel {
    int node;
    enum gk_anim_path path;
    enum gk_anim_interp interp;
    uint32_t n_keys;
    float *times;              /* n_keys, increasing */
    float *values;             /* n_keys * 3 (T, S) or * 4 (R, xyzw) */
} gk_anim_channel;

/* What a scene contains, derived from its content at load time; the kiosk offers only the GI
 * methods a scene needs ("model no more than a scene needs"). */
typedef struct gk_scene_features {
    bool has_area_lights;
    bool has_emissive;
    bool has_specular;         /* mirrors/smooth metals (roughness < 0.2, metallic > 0.5) */
    bool has_transmission;     /* glass, water */
    bool has_caustics;         /* specular/transmissive surfaces lit by point/spot lights */
    bool has_animation;
    bool is_closed;            /* every edge shared by two triangles (furnace-type scenes) */
    bool has_medium;           /* a participating medium (gk_scene.medium) */
    bool has_interreflection;  /* light can bounce between diffuse surfaces: a light or emitter and a
                                  drawn, non-black, non-metallic surface that is not a light proxy */
} gk_scene_features;

/* What of glTF a file uses, as `gikiosk scenes --check` reports it: the extensions read and the
 * ones ignored (comma-separated), and counts of the features that are converted or left out. */
typedef struct gk_scene_gltf_use {
    char extensions_read[256];
    char extensions_ignored[256];
    int embedded_images;       /* GLB chunks and data: uris */
    int sparse_accessors;
    int quantized_accessors;   /* integer attributes read through KHR_mesh_quantization */
    int strips_fans;           /* primitives converted to triangle lists */
    int draco_primitives;      /* primitives decoded from KHR_draco_mesh_compression */
    int meshopt_views;         /* bufferViews decoded from EXT_meshopt_compression */
    int not_drawn;             /* points and lines primitives */
    int orthographic_cameras;  /* loaded, never the view */
    int skins;                 /* nodes drawn at their node transform (no skinning) */
    int samplers;              /* textures whose sampler is not REPEAT + bilinear (read, gk_texture) */
    int texture_transforms;    /* texture slots with KHR_texture_transform */
    int second_uv_slots;       /* texture slots that read TEXCOORD_1 */
    int alpha_masked;          /* materials with alphaMode MASK (read) */
    int alpha_blended;         /* materials with alphaMode BLEND (drawn after the opaque surfaces) */
    int occlusion_textures;    /* materials with an occlusionTexture (ambient and indirect light only) */
    int double_sided;          /* materials with doubleSided true (the others' back faces are culled
                                  for the camera) */
} gk_scene_gltf_use;
/* A homogeneous participating medium filling the scene (or an axis-aligned box of it), given in the
 * scene's extras (DESIGN §4):
 *   "extras": {"gikiosk": {"medium": {"sigma_s": S, "sigma_a": A, "g": G,
 *                                     "bounds": [[x0, y0, z0], [x1, y1, z1]]}}}
 * sigma_s (scattering) and sigma_a (absorption) in 1/m, each a number or [r, g, b], >= 0 and finite;
 * g the Henyey-Greenstein asymmetry in (-1, 1) (default 0, isotropic); bounds optional (default: all
 * of space). The loader refuses negative, NaN or infinite values, naming the key. Extinction
 * sigma_t = sigma_s + sigma_a; transmittance exp(-sigma_t * length inside the bounds). */
typedef struct gk_medium {
    bool present;
    float sigma_s[3], sigma_a[3];
    float g;
    bool bounded;
    vec3 box_min, box_max;
} gk_medium;

/* A distant environment around the scene (DESIGN §4), given in the scene's extras:
 *   "extras": {"gikiosk": {"environment": {"uri": "sky.exr", "intensity": 1.0}}}
 * uri: an EXR (or any float image OpenImageIO reads) next to the scene, in the lat-long layout:
 * width = 2 x height, row 0 looking straight up (+Y), column u at azimuth phi = 2 pi (u + 0.5) / W
 * measured from -Z towards +X (environment.h, gk_env_dir). intensity (default 1, finite, >= 0)
 * multiplies the map's linear RGB radiance (nits). The default studio (default_studio.c) brings a
 * built-in procedural one (uri ""). */
typedef struct gk_environment {
    bool present;
    char uri[256];             /* relative to the scene's folder; "" for a built-in map */
    float intensity;
    int width, height;         /* lat-long: width = 2 height */
    float *rgb;                /* width * height * 3 radiance, intensity applied, row 0 = up */
    /* The environment's split into area lights for the rasterizer (env_split.h): the scene's
       lights with env_part set, the first of them at index env_light_first, n_env_lights of them
       in the order the greedy fit found them; after k of them, the residual's irradiance is
       ambient_sh[k] (9 SH coefficients x RGB, E(n) = sum c_i Y_i(n), see env_split.h). */
    int env_light_first, n_env_lights;
    float (*ambient_sh)[9][3]; /* n_env_lights + 1 entries */
} gk_environment;

typedef struct gk_scene {
    char name[64];             /* file stem: "cornell" */
    char path[512];            /* file it was loaded from */
    char description[512];     /* scene extras "gikiosk": {"description": ...} */
    char methods[256];         /* scene extras "gikiosk": {"methods": "vct,vpl"}; "" = derive */
    gk_mesh *meshes;       int n_meshes;
    gk_material *materials; int n_materials;
    gk_texture *textures;  int n_textures;
    gk_light *lights;      int n_lights;
    gk_camera *cameras;    int n_cameras;
    gk_node *nodes;        int n_nodes;   /* ordered parents first (world matrices in one pass) */
    gk_anim_channel *channels; int n_channels;
    float anim_duration;       /* seconds, 0 if static; animations loop */
    int camera_node;           /* first node with a camera, -1: a default camera framing the bounds */
    vec3 bmin, bmax;           /* world bounds at t = 0 */
    uint32_t n_triangles;      /* total drawn */
    uint32_t n_degenerate_dropped;
    gk_scene_features features;
    float exposure_ev;         /* scene extras "gikiosk": {"exposure": EV}: exposure 2^EV */
    bool has_exposure;
    /* Scene extras "gikiosk": {"params": {"key": number or [numbers]}}: named numbers a scene
     * hands to tests (shadow-planes: light size, occluder size, heights). Read with gk_scene_param. */
    struct { char key[32]; float v[4]; int n; } params[16];
    int n_params;
    gk_scene_gltf_use gltf;
    bool default_lighting;     /* the file has no light and no emitter: the default studio was added */
    gk_medium medium;          /* scene extras "gikiosk": {"medium": {...}} (above) */
    gk_environment environment; /* scene extras "gikiosk": {"environment": {...}} (above) */
} gk_scene;

/* Loads .gltf/.glb; validates everything (indices, accessors, NaN/Inf, textures). On error returns
 * NULL with e->code GK_EINPUT and a message naming the file and what is wrong. Degenerate (zero-area)
 * triangles are dropped and counted. CUBICSPLINE animations are converted to LINEAR through their
 * key values (tangents dropped, logged); skins and morph weights are ignored (logged). Images are
 * files next to the scene, GLB binary chunks or base64 data: uris (PNG, JPEG); sparse accessors,
 * KHR_mesh_quantization, triangle strips and fans are read; points and lines are not drawn (logged). */
gk_scene *gk_scene_load(const char *path, gk_err *e);
void gk_scene_free(gk_scene *s);

/* Evaluates animations at time t (seconds, looped) and fills every node's world matrix. */
void gk_scene_evaluate(gk_scene *s, float t);

/* Whether a node's world transform mirrors (its 3x3 determinant is negative): glTF 2.0 3.7.2.1 then
   makes its triangles' front faces clockwise, so both renderers turn the winding they test. */
bool gk_node_mirrored(const gk_node *n);

/* The view camera after gk_scene_evaluate: view and projection for the given aspect ratio, plus
 * the eye position. Both renderers call this, so they see exactly the same camera. */
void gk_scene_camera(const gk_scene *s, float aspect, mat4 *view, mat4 *proj, vec3 *eye);

/* World-space emitter frame of a light after gk_scene_evaluate: position, direction (-Z of the
 * node), and the rectangle's axes (node X and Y, unit length). */
void gk_scene_light_frame(const gk_scene *s, int light_node, vec3 *pos, vec3 *dir, vec3 *axis_u, vec3 *axis_v);

/* Loads a glTF (JSON) or GLB document from memory; `path` is only used in messages and for the
 * scene's name, external buffers and images resolve against base_dir (NULL: none may be read).
 * Same validation as gk_scene_load. Used by the fuzz target and the tests. */
gk_scene *gk_scene_load_memory(const void *data, size_t size, const char *path, const char *base_dir,
                               gk_err *e);

/* The GI methods that apply to a scene, written to names[0..max), returns the count. The rule
 * (model no more than a scene needs): "none" always, first; then, in the catalogue's order, every
 * method of the catalogue (app/gi/gi_catalogue.h) whose needs the scene all has
 * (gk_scene_gi_needs): vct, vpl and radiosity when light bounces between diffuse surfaces
 * (features.has_interreflection) and lightmap (its photons follow animated nodes), ispm and lgv with
 * caustics, volcaustics with a participating medium (gk_scene.medium) and caustics.
 * The scene's extras "methods" list, when given, replaces the derived list ("none" stays first). */
int gk_scene_methods(const gk_scene *s, const char **names, int max);
/* The GK_GI_NEEDS_* bits (app/gi/gi_catalogue.h) a scene with these features has. */
unsigned gk_scene_gi_needs(const gk_scene_features *f);

/* A named number (or up to 4) from the scene's extras params: returns how many values were copied
 * to out (at most max), or -1 if the scene has no such key. */
int gk_scene_param(const gk_scene *s, const char *key, float *out, int max);

/* "area,emissive,specular,..." (or "-" for none) for listings. */
void gk_scene_features_string(const gk_scene_features *f, char *out, int out_len);

/* The scene folder when none is given: config/scenes in a checkout, else the installed
 * PREFIX/share/gikiosk/scenes next to the binary. */
const char *gk_scene_default_dir(void);

/* Looks up the scene file for a name ("cornell") in dir (config/scenes): dir/NAME.gltf or .glb. */
int gk_scene_find(const char *dir, const char *name, char *path_out, int path_len);

#endif
