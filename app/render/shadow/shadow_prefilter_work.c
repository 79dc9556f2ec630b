/* The prefilters' fetches from their parameters (shadow_prefilter_work.h). */
#include "shadow_prefilter_work.h"

/* One chain's loads building levels 1.. of a size² pyramid (down to 1x1, as gk_pf_levels counts):
   every texel of each source level is read once -- a destination texel reads its 2 x 2, and the last
   row and column of an odd source go to the last destination texel -- so the sum of the source
   levels' texels, levels 0 to the one before 1x1. */
static double pyramid_loads(int size)
{
    double n = 0.0;
    for (int src = size; (src >> 1) > 0; src >>= 1)
        n += (double)src * src;
    return n;
}

/* The texels of levels 1.. of a size² chain (down to 1x1): glGenerateMipmap reads one bilinear
   lookup of the level above for each. */
static double mip_texels(int size)
{
    double n = 0.0;
    for (int s = size >> 1; s > 0; s >>= 1)
        n += (double)s * s;
    return n;
}

/* One SAT of a basis pair (gk_pf_sat): the rows read z once a texel, the columns load both tables'
   texels once. */
static void sat(gk_pf_work *w, double texels)
{
    w->r32f_reads += texels;
    w->image_loads += 2.0 * texels;
}

void gk_pf_work_vssm(gk_pf_work *w, int size, int layers)
{
    double texels = (double)size * size * layers;
    w->depth_reads += texels;                             /* linearize */
    w->image_loads += 2.0 * pyramid_loads(size) * layers; /* the min and the max chains */
    sat(w, texels);                                       /* (z, z²) */
}

void gk_pf_work_cssm(gk_pf_work *w, int size, int layers, bool full_range, bool use_sat)
{
    double texels = (double)size * size * layers;
    w->depth_reads += texels; /* linearize */
    if (!full_range)
        w->image_loads += texels + 3.0 * texels; /* the reduction; the renormalisation: z, lo, hi */
    if (use_sat) {
        for (int pair = 0; pair < 3; pair++)
            sat(w, texels);
        return;
    }
    w->r32f_reads += 2.0 * texels;                          /* the two basis passes */
    w->mip_lookups += 5.0 * mip_texels(size) * layers; /* the 5 chains' levels 1.. */
}
