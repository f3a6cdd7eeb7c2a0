#!/bin/bash
# Several lights without the prepare pass: eda68ef's bench (old) against 85b054f's (new), alternating, two rounds.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
A="--sizes 3840x2160 --scenes penumbra-heavy,typical --presets quality,balanced --precisions fp32 --frames 200 --copy-runs 3 --warmup-ms 500 --lights 1,4,8"
for r in 1 2; do for b in old new; do DNSR_COMMIT=$b timeout 130 .gl/bench-$b $A --out $OUT/lights-$b-$r > $OUT/lights-$b-$r.log 2>&1; done; done
cd $OUT && tar czf results.tgz */bench.md *.log device.txt && rm -rf lights-*
cat device.txt
