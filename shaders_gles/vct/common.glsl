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

uniform int u_res;

int vox_index(ivec3 c) { return (c.z * u_res + c.y) * u_res + c.x; }
int vox_count() { return u_res * u_res * u_res; }
