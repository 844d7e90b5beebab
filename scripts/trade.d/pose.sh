# The sweep `scripts/trade pose` runs (docs/pose/trade.md), sourced by scripts/trade: the novel
# clip of Fox, CesiumMan's two held-out splits, and its halves at the paper's vertex count.
description="technique pose on Fox (train Survey + Walk, test Run) and CesiumMan (first half \
against second half; even against odd frames) under rnl_probe.hdr and a directional light"
assets_needed=(characters/Fox.glb characters/CesiumMan.glb envmaps/rnl_probe.hdr)
settings=(rays rate frames)
rays=256
rate=15
frames=20
runs=(fox_run cesiumman_halves cesiumman_even_odd cesiumman_paper_scale)

sweep_arguments() {
  local split
  case "$1" in
    fox_run) arguments=("$assets/characters/Fox.glb"); split=(--split clips --test-clips Run) ;;
    cesiumman_halves) arguments=("$assets/characters/CesiumMan.glb"); split=(--split halves) ;;
    cesiumman_even_odd) arguments=("$assets/characters/CesiumMan.glb"); split=(--split even-odd) ;;
    # The paper's scale: CesiumMan subdivided to its 11,534 vertices, PCA(8, 22) among the sizes.
    cesiumman_paper_scale) arguments=("$assets/characters/CesiumMan.glb")
      split=(--split halves --subdivide-to 11534) ;;
  esac
  local basis=(0 4 8 16 32 64)
  [ "$1" = cesiumman_paper_scale ] && basis=(0 4 8 16 22)
  arguments+=(--env "$assets/envmaps/rnl_probe.hdr" "${split[@]}" --rate "$rate" --rays "$rays"
    --pose-dims 0 8 --basis-dims "${basis[@]}" --frames "$frames")
}
