#!/bin/bash
# Where poker52's contact time goes: each variant repeats one part of contact.comp's work
# without effect (a dry run before the real one): v_search2 pass 0's whole search, v_visit2
# the hash traversal alone (no pieces tested), v_replay2 the list walk of passes 0 and 1.
for f in .gl/*.deb; do dpkg -x $f / ; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
for S in "" "--shaders .gl/v_search2" "--shaders .gl/v_visit2" "--shaders .gl/v_replay2"; do
  echo "== poker52 $S"; .gl/msdsim_new simulate --preset .gl/poker52.toml --frames 120 --quiet $S 2>&1 | grep -E "GPU frame|GPU stage|error"
done
echo "== stack8 v_search2"; .gl/msdsim_new simulate --preset .gl/stack8.toml --frames 230 --quiet --shaders .gl/v_search2 2>&1 | grep -E "GPU frame|GPU stage|error"
