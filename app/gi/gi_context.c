/* What every GI method does with the context the renderer lends it (gi.h). */
#include "gi.h"

#include "gl/gl_program.h"

gk_program_cache *gk_gi_context_own_programs(gk_gi_context *ctx)
{
    if (ctx->programs)
        return NULL;
    ctx->programs = gk_program_cache_create(NULL, ctx->gles_version ? ctx->gles_version : 31);
    return ctx->programs;
}
