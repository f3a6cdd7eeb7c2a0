#!/bin/bash
# The light-position test without a short-circuit branch (new3, bfa8951) against main before the feature (old), 4K.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
A="--sizes 3840x2160 --scenes penumbra-heavy,typical,all-lit --presets fast,balanced,quality --precisions fp32 --frames 200 --copy-runs 3 --warmup-ms 500"
for b in old new3 old new3; do DNSR_COMMIT=$b timeout 150 .gl/bench-$b $A --out $OUT/$b > $OUT/$b.log 2>&1; echo $b; grep -E '^\| 3840x2160' $OUT/$b/bench.md | head -9 | cut -d'|' -f3-10; done
