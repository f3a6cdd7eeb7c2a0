#!/bin/bash
# Several lights: the light-slot variants off (one dispatch per light and pass), and light-major order (each light's
# passes in a row, what lights sharing transient images would need), against the current recording. One binary.
for f in .gl/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig; for z in .gl/*.gz; do gunzip -f $z; chmod +x ${z%.gz}; done
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
A="--sizes 3840x2160 --scenes penumbra-heavy,typical --presets quality,balanced --precisions fp32 --lights 1,4,8 --frames 100 --copy-runs 1 --warmup-ms 300"
declare -A E=([base]="X=1" [noslots]="DNSR_EXP_NO_SLOTS=1" [major]="DNSR_EXP_NO_SLOTS=1 DNSR_EXP_LIGHT_MAJOR=1")
for b in base noslots major base; do n=$b; [ -d $OUT/$b ] && n=$b-2; env ${E[$b]} DNSR_COMMIT=a3c89c7 timeout 200 .gl/bench-exp $A --out $OUT/$n > $OUT/$n.log 2>&1 || tail -3 $OUT/$n.log; done
cd $OUT && for d in base noslots major base-2; do echo "## $d"; cat $d/bench.md; done > bench-all.md && rm -rf base noslots major base-2 *.log && cat device.txt; grep -E '^## |^\| 3840x2160 \| [a-z0-9% -]* \| [a-z, 0-9]* \| [0-9]' bench-all.md | grep -v "MB," | cut -c1-110
