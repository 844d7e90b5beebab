# The sweep `scripts/trade wavelet` runs (docs/wavelet/trade.md), sourced by scripts/trade.
description="technique wavelet against sh on the Stanford bunny under the sun map \
(spiaggia_di_mondello_1k.hdr) and the smooth one (rnl_probe.hdr); --sizes 128 adds ~7.5 min on 2 cores"
assets_needed=(meshes/stanford-bunny.obj envmaps/spiaggia_di_mondello_1k.hdr envmaps/rnl_probe.hdr)
settings=(ref_spp frames sizes)
ref_spp=2048
frames=10
sizes=16,32,64,128

sweep_arguments() {
  arguments=("$assets/meshes/stanford-bunny.obj"
    --env "$assets/envmaps/spiaggia_di_mondello_1k.hdr"
    --env "$assets/envmaps/rnl_probe.hdr"
    --sizes "$sizes" --base-size 64 --keeps 50,100,250,500,1000,2000,4000 --base-keep 1000
    --light-terms 0,10,30,100,300,1000,3000,all --paraboloid-sizes 64,128 --quantizer band
    --samples 1 --sh-orders 2,4,6,8,12,16 --sh-rays 256 --sh-bits 8,16
    --ref-spp "$ref_spp" --frames "$frames" --albedo 0.8,0.8,0.8)
}
