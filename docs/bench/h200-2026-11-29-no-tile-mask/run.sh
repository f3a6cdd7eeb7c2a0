#!/bin/bash
# A hit-mask context without the tile mask and dark images (only prepare, which runs for visibility and checkerboard
# inputs, writes them): main before it (old, ba8939e) against it (new), alternating, 4K; the memory columns.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; for z in .gl/*.gz; do gunzip -f $z; chmod +x ${z%.gz}; done
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
A="--sizes 1920x1080,3840x2160 --scenes penumbra-heavy,all-lit --presets balanced,quality --precisions fp32 --frames 200 --copy-runs 3 --warmup-ms 500"
for r in 1 2; do for b in old new; do DNSR_COMMIT=$b timeout 150 .gl/bench-$b $A --out $OUT/$b-$r > $OUT/$b-$r.log 2>&1; done; done
cd $OUT && cat device.txt; for d in old-1 new-1 old-2 new-2; do echo $d; grep -E '^\| (1920x1080|3840x2160)' $d/bench.md | head -8 | cut -c1-220; done
