# The sweep `scripts/trade shadowfield` runs (docs/shadowfield/trade.md), sourced by
# scripts/trade: the teapot preset (a Phong teapot sliding and turning on a 4,096-vertex floor,
# under Grace Cathedral) at two placements, each knob of the technique swept alone around the
# bake's defaults and 3 bounces. --preset room (or bunny) runs the same sweep on another preset;
# its tables replace the teapot's in docs/shadowfield/trade/.
description="technique shadowfield on the teapot preset under grace_cross.hdr at t = 0 and 4 s: \
SH order, K, OOF and SRF shells and points per shell, basis size N, bits and bounces, one at a \
time around the defaults"
assets_needed=(meshes/teapot.obj meshes/stanford-bunny.obj meshes/spot.obj envmaps/grace_cross.hdr)
settings=(preset times ref_spp frames)
preset=teapot
times=0,4
ref_spp=1024
frames=5

sweep_arguments() {
  local env="$assets/envmaps/grace_cross.hdr"
  [ "$preset" = room ] || [ "$preset" = procedural ] && env=sky  # their preset's built-in sky
  arguments=("$preset" --env "$env" --shared "$assets/.." --times "$times"
    --orders 2,3,4,5,6 --terms 1,2,4,8 --bits 8,16
    --oof-shells 4,8,16,32 --oof-faces 4,8,16,24 --srf-shells 2,4,8,16 --srf-faces 4,8,12
    --basis-sizes 4,8,16,32 --bounces 0,1,2,3
    --ref-spp "$ref_spp" --frames "$frames")
}
