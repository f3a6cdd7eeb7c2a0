#!/bin/bash
# Fixed overhead: the GPU time of tiny frames, where the pixels cost next to nothing (eda68ef's bench and 85b054f's).
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
A="--sizes 64x64,256x256,512x512,1920x1080 --scenes penumbra-heavy,all-lit --presets balanced,quality --precisions fp32 --frames 200 --copy-runs 3 --warmup-ms 300"
for b in old new; do DNSR_COMMIT=$b timeout 150 .gl/bench-$b $A --out $OUT/tiny-$b > $OUT/tiny-$b.log 2>&1; done
cd $OUT && tar czf results.tgz */bench.md *.log device.txt && rm -rf tiny-*
cat device.txt
