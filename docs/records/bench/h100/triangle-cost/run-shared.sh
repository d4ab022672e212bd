# 3831a03's hot-path change (one triangle_distance for every search, the box cull's 0.1%
# margin) against d0680df's GLSL (in .gl/base/glsl through --shaders: git archive d0680df glsl),
# one binary (.gl/msdsim, at 8d8d884), interleaved, three runs each: run-cull.sh's runs.
# Run from the repository root on the device machine: bash docs/records/bench/h100/triangle-cost/run-shared.sh
exec bash "$(dirname "$0")/run-cull.sh" base=.gl/base/glsl new=
