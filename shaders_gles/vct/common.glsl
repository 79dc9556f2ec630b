// Voxel cone tracing (Dinse 2015, "Voxel Cone Tracing", seed 003): shared declarations.
// Coordinates: world -> voxel units v = (world - u_grid_origin) / u_voxel_size, voxel i spans [i, i+1);
// the thesis's "voxel space" [0,1]^3 is v / u_res (used by the tracer).
precision highp float;
precision highp int;

// Channels of the voxel scratch buffer ("voxel G-buffer"), each res^3 uints, in this order.
// Fixed-point mode: atomicAdd sums. CAS mode (thesis §3.1): packed RGBA8 moving averages with the
// 4-bit sample counter in the byte LSBs (count channel unused).
#define CH_COUNT 0
#define CH_ALB 1   // 1..3 albedo r, g, b   (x255 per fragment)
#define CH_NRM 4   // 4..6 normal x, y, z   (x127, signed, two's complement sums)
#define CH_POS 7   // 7..9 position inside the voxel (x255 per fragment)
#define CH_EMI 10  // 10..12 emission / u_emission_scale (x255), only with EMISSIVE
// Fixed-point mode: the count channel's top bit marks a voxel solid (vct_thick, voxelize.comp): opaque
// without radiance, set by the surfaces in front of it; the fragment count is the other 31 bits.
#define SOLID_BIT 0x80000000u
// vct_axis_clamp=thin's flag volume (one uint per voxel; vct/thin_flag.comp): bits 0..5 the ways the
// voxel's fragments face, -x, +x, -y, +y, -z, +z (FACE_BIT(axis, positive)); THIN_BIT: a thin wall's
// voxel, a fragment in it faces away from one in it or in the next two voxels behind it; THIN_MARK:
// a voxel behind a thin wall's fragment (voxelize.comp THIN_MARKS), where the axis clamp stops too.
#define FACE_BIT(a, pos) (1u << uint(2 * (a) + ((pos) ? 1 : 0)))
#define THIN_BIT 0x100u
#define THIN_MARK 0x200u
// A normal faces +a (-a) where its a component is above FACE_MIN (below -FACE_MIN): a wall tilted up
// to ~55 degrees off the axis still counts along it (light-leak's wall is axis-aligned).
#define FACE_MIN 0.57
uint face_bits(vec3 n)
{
    uint f = 0u;
    for (int a = 0; a < 3; a++) {
        if (n[a] > FACE_MIN) f |= FACE_BIT(a, true);
        if (n[a] < -FACE_MIN) f |= FACE_BIT(a, false);
    }
    return f;
}

uniform int u_res;

int vox_index(ivec3 c) { return (c.z * u_res + c.y) * u_res + c.x; }
int vox_count() { return u_res * u_res * u_res; }
