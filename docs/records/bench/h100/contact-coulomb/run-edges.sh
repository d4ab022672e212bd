set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
for run in 1 2; do for build in old new; do
  bin=.gl/msdsim; [ $build = old ] && bin=.gl/msdsim-old
  echo "== $build $run"
  $bin bench --frames 200 --warmup 30 --filter "ground, box, capsule" --cloth-sizes 1024 --rope-sizes 256 2>&1 | grep ms/frame
done; done
