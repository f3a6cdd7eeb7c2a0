#!/bin/bash
# Geometric normals in the first filter pass: its SPIR-V before (main, 2260bb1), after (geo: each apron pixel
# fetches its neighbours' depths) and after with the apron's world positions in shared memory first (opt),
# alternating, one bench binary (built with Settings::geometric_normal_degrees: 0 in Balanced, whose first pass
# must not pay). Quality's and Balanced's first pass is `filter`, Fast's (one pass, the final) `filter_final_r16f`.
for f in .gl/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig; for z in .gl/*.gz; do gunzip -f $z; chmod +x ${z%.gz}; done
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
A="--sizes 3840x2160 --scenes penumbra-heavy,typical --presets quality,fast,balanced --precisions fp32 --frames 100 --copy-runs 1 --warmup-ms 300"
for v in main geo opt main geo opt; do
  n=b-$v
  timeout 100 .gl/bench $A --shader-override filter=.gl/$v-filter.spv --shader-override filter_final_r16f=.gl/$v-filter_final_r16f.spv \
    --out /tmp/$n > /dev/null 2>&1 || echo "bench $n failed"
  (echo "## $n"; cat /tmp/$n/bench.md) >> $OUT/bench-all.md
done
cd $OUT
awk '/^## b-/{h=$2} /^## Pipelines/{h=""} h!="" && /^\| 3840x2160 \| [^|]+ \| (fast|quality|balanced) \| [0-9.]+ \| [0-9]/{n=split($0,a,"|"); print h, a[3], a[4], "cls", a[6], "f0", a[7], "total", a[9]}' bench-all.md
awk '/^## b-/{h=$2} /\| filter(_final_r16f)? \|/ {print h, $0}' bench-all.md | grep "| fp32" | sort -u
