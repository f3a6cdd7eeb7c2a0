#!/bin/bash
# The selection of the kept moments at their store, after the apron (new4), against the selection right after the
# first barrier (new3, run3.sh's) and main before both (old, 4fc84c9), alternating twice, 4K fp32.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; for z in .gl/*.gz; do gunzip -f $z; chmod +x ${z%.gz}; done
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
A="--sizes 3840x2160 --scenes penumbra-heavy,typical,all-lit,sky-90 --presets balanced,quality --precisions fp32 --frames 200 --copy-runs 3 --warmup-ms 500"
for r in 1 2; do for b in old new3 new4; do DNSR_COMMIT=$b timeout 170 .gl/bench-$b $A --out $OUT/$b-$r > $OUT/$b-$r.log 2>&1; done; done
cd $OUT && for d in old-1 new3-1 new4-1 old-2 new3-2 new4-2; do echo "## $d"; cat $d/bench.md; done > bench-all.md && for d in old-1 new3-1 new4-1 old-2 new3-2 new4-2; do cat $d.log; done > logs.txt && rm -rf old-? new3-? new4-? *-?.log && cat device.txt; grep -E '^## |^\| 3840x2160 \| [a-z0-9% -]* \| [a-z]* \| [0-9]' bench-all.md | cut -c1-120
