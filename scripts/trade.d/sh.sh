# The sweep `scripts/trade sh` runs (docs/sh/trade.md), sourced by scripts/trade.
description="technique sh on the Stanford bunny under three environment maps (orders 2-8, rays, bounces)"
assets_needed=(meshes/stanford-bunny.obj envmaps/grace_cross.hdr
               envmaps/spiaggia_di_mondello_1k.hdr envmaps/rnl_probe.hdr)
settings=(ref_spp frames)
ref_spp=2048
frames=20

sweep_arguments() {
  arguments=("$assets/meshes/stanford-bunny.obj"
    --env "$assets/envmaps/rnl_probe.hdr"
    --env "$assets/envmaps/grace_cross.hdr"
    --env "$assets/envmaps/spiaggia_di_mondello_1k.hdr"
    --orders 2,3,4,5,6,7,8 --rays 64,256,1024 --bounces 0,1 --base-rays 256 --base-order 6
    --ref-spp "$ref_spp" --bits 16 --frames "$frames" --albedo 0.8,0.8,0.8)
}
