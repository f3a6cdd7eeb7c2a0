#!/bin/bash
# The host-previous classification variant without the depth copy's rounding (the linear depth and the normal as
# read), timed against the landed one by one bench binary through --shader-override; alternating twice.
for f in .gl/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig; for z in .gl/*.gz; do gunzip -f $z; chmod +x ${z%.gz}; done
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
A="--sizes 3840x2160 --scenes penumbra-heavy,typical --presets quality --precisions fp32 --frames 100 --copy-runs 1 --warmup-ms 300"
declare -A O=([own]="" [host]="--host-previous" [unrounded]="--host-previous --shader-override tile_classification_host_previous_r16f=.gl/unrounded.spv")
for r in 1 2; do for b in own host unrounded; do timeout 100 .gl/bench $A ${O[$b]} --out $OUT/$b-$r > $OUT/$b-$r.log 2>&1 || tail -3 $OUT/$b-$r.log; done; done
cd $OUT && for d in own-? host-? unrounded-?; do echo "## $d"; cat $d/bench.md; done > bench-all.md && rm -rf own-? host-? unrounded-? *.log
awk '/^## (own|host|unrounded)-/{h=$2} /^## Pipelines/{h=""} h!="" && /^\| 3840x2160 \| [^|]+ \| quality \| [0-9]/{n=split($0,a,"|"); print h, a[3], "cls", a[6], "total", a[9], "kept", a[17]}' bench-all.md | sort -k2,2 -k1,1
grep -h "tile_classification" bench-all.md | sort | uniq
