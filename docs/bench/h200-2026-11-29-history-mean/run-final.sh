#!/bin/bash
# The committed change (final) against main before it (old, 7dcd4bb), alternating twice, 4K fp32; then final alone
# with 1, 4 and 8 lights per record (Quality) and at 1920x1080 and 2560x1440 (memory per size).
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; for z in .gl/*.gz; do gunzip -f $z; chmod +x ${z%.gz}; done
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
A="--sizes 3840x2160 --scenes penumbra-heavy,typical,all-lit --presets fast,balanced,quality --precisions fp32 --frames 200 --copy-runs 3 --warmup-ms 500"
for r in 1 2; do for b in old final; do DNSR_COMMIT=$b timeout 150 .gl/bench-$b $A --out $OUT/$b-$r > $OUT/$b-$r.log 2>&1; done; done
DNSR_COMMIT=final timeout 200 .gl/bench-final --sizes 3840x2160 --scenes penumbra-heavy,typical --presets quality --precisions fp32 --lights 1,4,8 --frames 200 --copy-runs 3 --warmup-ms 500 --out $OUT/lights > $OUT/lights.log 2>&1
DNSR_COMMIT=final timeout 150 .gl/bench-final --sizes 1920x1080,2560x1440 --scenes penumbra-heavy --presets quality --precisions fp32 --frames 200 --copy-runs 3 --warmup-ms 500 --out $OUT/sizes > $OUT/sizes.log 2>&1
cd $OUT && for d in old-1 final-1 old-2 final-2 lights sizes; do echo "## $d"; cat $d/bench.md; done > bench-final-all.md && for d in old-1 final-1 old-2 final-2 lights sizes; do cat $d.log; done > logs-final.txt && rm -rf old-? final-? lights sizes *.log && cat device.txt; grep -E '^## |^\| [0-9]+x[0-9]+' bench-final-all.md | cut -c1-200 | awk '/^## /{n=0} {if (n++ < 14) print}'
