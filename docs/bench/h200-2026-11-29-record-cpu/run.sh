#!/bin/bash
# Record CPU time (cold: after each submit and wait; back to back: warm, never submitted): HEAD's record code (old)
# against the working tree's (new: no per-record zeroing of the barrier bookkeeping, constants written per light), alternating.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
A="--sizes 1920x1080,3840x2160 --scenes penumbra-heavy,typical,all-lit,sky-90 --presets fast,balanced,quality --precisions fp32 --frames 200 --copy-runs 1 --warmup-ms 300"
for r in 1 2; do for b in old new; do
  DNSR_COMMIT=$b timeout 280 .gl/bench-$b $A --out $OUT/$b-$r > $OUT/$b-$r.log 2>&1
done; done
for r in 1; do for b in old new; do
  DNSR_COMMIT=$b timeout 200 .gl/bench-$b --sizes 3840x2160 --scenes penumbra-heavy --presets quality --precisions fp32 --frames 200 --copy-runs 1 --warmup-ms 300 --lights 1,4,8 --out $OUT/$b-lights > $OUT/$b-lights.log 2>&1
done; done
cd $OUT && tar czf results.tgz */bench.md *.log device.txt && rm -rf old-* new-*
cat device.txt
