# Triangle self-contact's tests culled by the triangle's bounding box, interleaved, three runs
# each, one binary (.gl/msdsim) with GLSL trees named as arguments NAME=DIR (DIR empty: the
# binary's own). Without arguments, the runs of d0680df: base, the GLSL before (4194802, in
# .gl/base/glsl); v1, the cull with the ring's positions kept from the first read (.gl/v1: what
# landed); new, the binary's own, the cull reading them again. run-shared.sh passes its own.
# Run from the repository root on the device machine: bash docs/records/bench/h100/triangle-cost/run-cull.sh
# Made before the call: mkdir -p .gl/base && git archive 4194802 glsl | tar -x -C .gl/base;
# .gl/v1 a copy of d0680df's glsl.
set -u
[ $# -gt 0 ] || set -- base=.gl/base/glsl v1=.gl/v1 new=
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
out=${OUT:-/tmp/out}/runs; mkdir -p "$out"
bin=.gl/msdsim
for run in 1 2 3; do
  for variant in "$@"; do
    v=${variant%%=*}; dir=${variant#*=}
    sh=""; [ -n "$dir" ] && sh="--shaders $dir"
    $bin bench --frames 100 --warmup 20 --cloth-sizes 1024 --rope-sizes 256 --filter "triangle" $sh --out "$out/$v-$run" > /dev/null 2>&1
    grep -E "triangle" "$out/$v-$run/bench.md" | cut -d"|" -f2,5,6,9,12 | sed "s/^/$v $run: /"
    echo "$v $run towel: $($bin simulate --preset presets/towel.toml --frames 300 --quiet $sh --set 'cloth.0.self_contact="triangles"' 2>&1 | grep -E 'GPU frame time')"
  done
done
