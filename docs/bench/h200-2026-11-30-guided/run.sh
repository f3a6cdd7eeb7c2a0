#!/bin/bash
# Penumbra guidance's cost at 4K on the current passes: one dnsr-bench binary (bc638b3's; the GPU code is main's),
# without and with --light-angle 0.0093 (hit distances 1.0 everywhere, the sun's angular size), alternating twice.
for f in .gl/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig; for z in .gl/*.gz; do gunzip -f $z; chmod +x ${z%.gz}; done
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
A="--sizes 3840x2160 --scenes penumbra-heavy,typical,all-lit --presets quality,balanced,fast --precisions fp32 --frames 100 --copy-runs 1 --warmup-ms 300"
declare -A O=([unguided]="" [guided]="--light-angle 0.0093")
for r in 1 2; do for b in unguided guided; do DNSR_COMMIT=$b timeout 100 .gl/bench-before $A ${O[$b]} --out $OUT/$b-$r > $OUT/$b-$r.log 2>&1 || tail -3 $OUT/$b-$r.log; done; done
cd $OUT && for d in unguided-? guided-?; do echo "## $d"; cat $d/bench.md; done > bench-all.md && rm -rf unguided-? guided-? *.log
awk '/^## (unguided|guided)/{h=$2} /^\| 3840x2160 \| [a-z -]+ \| (quality|balanced|fast) \| [0-9]/{n=split($0,a,"|"); print h, a[3], a[4], "cls", a[6], "f0", a[7], "f1", a[8], "f2", a[9], "total", a[10]}' bench-all.md | sort -k2,3 | uniq
