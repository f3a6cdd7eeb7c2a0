#!/bin/bash
# Upper bound of what sharing light-independent classification work could save: variants that skip it.
for f in .gl/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig; for z in .gl/*.gz; do gunzip -f $z; chmod +x ${z%.gz}; done
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
A="--sizes 3840x2160 --scenes penumbra-heavy,typical --presets quality --precisions fp32 --frames 100 --copy-runs 1 --warmup-ms 300 --lights 1,4"
for v in main w g main; do
  n=b-$v
  timeout 100 .gl/bench $A --shader-override tile_classification_r16f=.gl/$v-tile_classification_r16f.spv --out /tmp/$n > /dev/null 2>&1 || echo "bench $n failed"
  (echo "## $n"; cat /tmp/$n/bench.md) >> $OUT/bench-all.md
done
