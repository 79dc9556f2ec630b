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

void gk_pf_work_vssm(gk_pf_work *w, int size, int layers)
{
    double texels = (double)size * size * layers;
    w->depth_reads += texels;                             /* linearize */
    w->image_loads += 2.0 * pyramid_loads(size) * layers; /* the min and the max chains */
    w->r32f_reads += texels;                              /* SAT rows: z once a texel */
    w->image_loads += 2.0 * texels;                       /* SAT columns: z and z² sums once a texel */
}
