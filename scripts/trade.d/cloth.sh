# The sweep `scripts/trade cloth` runs (docs/cloth/trade.md), sourced by scripts/trade: linen and
# satin on a flat patch (the golden quad's frame: normal +Y, warp +X), 32 views, under the two
# maps of the issue, each turned four times about +Y.
description="technique cloth: linen and satin on a flat patch, 32 views, under rnl_probe.hdr and \
spiaggia_di_mondello_1k.hdr turned 4 times; K, rank, bits, grids, panels, phi nodes swept; \
paper 003's printed rules, each and all"
assets_needed=(envmaps/rnl_probe.hdr envmaps/spiaggia_di_mondello_1k.hdr)
settings=(turns frames)
turns=4
frames=5

sweep_arguments() {
  arguments=(formats/golden/scenes/quad_over_ground.obj
    --env "$assets/envmaps/rnl_probe.hdr"
    --env "$assets/envmaps/spiaggia_di_mondello_1k.hdr"
    --fabric linen_plain,polyester_satin_charmeuse --turns "$turns" --frames "$frames"
    --lobes 10,4,16,32,64 --energy 1e-4,1e-3,1e-5 --xi-size 32,16 --levels 10,6
    --view-nodes 16,8 --panels 2,1,4,8 --phi-nodes 3,1,2,5)
}
