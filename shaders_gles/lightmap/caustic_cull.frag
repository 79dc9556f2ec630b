// Tile culling of the caustic filter (seed 004 §5): drawn over one screen tile (dilated by the
// kernel's k pixels) with the stencil test "stencil > 0" inside an occlusion query: any sample
// passing means a photon was counted within the filter's reach of the tile. Writes no colour.
precision mediump float;
void main()
{
}
