#!/bin/bash
# Quality classification: the surface window breaks combined with an atomic add instead of an or (disjoint bytes:
# the same words), tc_breaks.spv by --shader-override, against main (f35d155) SPIR-V; one binary, alternating twice.
for f in .gl/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig; for z in .gl/*.gz; do gunzip -f $z; chmod +x ${z%.gz}; done
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
A="--sizes 3840x2160 --presets quality --scenes penumbra-heavy,typical --precisions fp32 --frames 100 --copy-runs 1 --warmup-ms 300"
declare -A O=([old]="" [new]="--shader-override tile_classification_r16f=.gl/exp/tc_breaks.spv")
for r in 1 2; do for b in old new; do DNSR_COMMIT=$b timeout 150 .gl/bench-old $A ${O[$b]} --out $OUT/$b-$r > $OUT/$b-$r.log 2>&1 || tail -3 $OUT/$b-$r.log; done; done
cd $OUT && for d in old-1 new-1 old-2 new-2; do echo "## $d"; cat $d/bench.md; done > bench-all.md && rm -rf old-? new-? *-?.log && cat device.txt; grep -E '^## |^\| 3840x2160 \| [a-z0-9% -]* \| [a-z]* \| [0-9]' bench-all.md | grep -v "MB," | cut -c1-100
