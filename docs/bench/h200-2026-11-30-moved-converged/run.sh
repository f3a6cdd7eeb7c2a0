#!/bin/bash
# No converged pixels where the shadow moved over a still pixel (new, 9f1b15a's shaders) against main before it
# (old, b955a36): Quality at 4K fp32, the penumbra-heavy and typical frames, alternating twice.
for f in .gl/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig; for z in .gl/*.gz; do gunzip -f $z; chmod +x ${z%.gz}; done
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
A="--sizes 3840x2160 --scenes penumbra-heavy,typical --presets quality --precisions fp32 --frames 100 --copy-runs 1 --warmup-ms 300"
for r in 1 2; do for b in old new; do DNSR_COMMIT=$b timeout 100 .gl/bench-$b $A --out $OUT/$b-$r > $OUT/$b-$r.log 2>&1; done; done
cd $OUT && for d in old-1 new-1 old-2 new-2; do echo "## $d"; cat $d/bench.md; done > bench-all.md && rm -rf old-? new-? *-?.log && cat device.txt; grep -E '^## |^\| 3840x2160 \| [a-z0-9% -]* \| [a-z]* \| [0-9]' bench-all.md | cut -c1-150
