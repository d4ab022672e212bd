set -u
# The twist at Newton's proportions (1.0 m wide, 1.5 m between the handles): main's build (a)
# with triangles and with edges, and the truncation patch (b) with edges; guard and cost.
nvidia-smi --query-gpu=name --format=csv,noheader
for f in .gl/c1/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
cd .gl/c1
P=(--set 'cloth.twist.size=[1.0,1.5]' --set 'cloth.twist.origin=[-0.5,1.75,0.0]' --set 'cloth.twist.pin_group[0].pin_box={min=[-0.6,1.74,-0.1],max=[0.6,1.76,0.1]}' --set 'cloth.twist.pin_group[1].pin_box={min=[-0.6,0.24,-0.1],max=[0.6,0.26,0.1]}')
run() { b=$1; shift; echo "== $b $*" | cut -c1-60; timeout 100 ./msdsim_$b simulate --preset ../../presets/twist.toml --frames 300 --quiet "${P[@]}" "$@" 2>&1 | grep -E "GPU frame time|stage means|rror" | cut -c1-220; }
for rep in 1 2; do
  run a --set 'cloth.twist.self_contact="triangles"'
  run a --set 'cloth.twist.self_contact="triangles_and_edges"'
  run b --set 'cloth.twist.self_contact="triangles_and_edges"'
done
