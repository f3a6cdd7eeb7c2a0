#!/bin/bash
# The whole-pixel shadow-follow experiment's cost (float costs, as docs/bench/h200-2026-11-30-follow-shadow): main's
# bench against the experiment build's, Quality and Fast at 4K, alternating twice.
for f in .gl/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig; for z in .gl/*.gz; do gunzip -f $z; chmod +x ${z%.gz}; done
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
A="--sizes 3840x2160 --scenes penumbra-heavy,typical,all-lit --presets quality,fast --precisions fp32 --frames 100 --copy-runs 1 --warmup-ms 300"
for r in 1 2; do for b in before follow; do DNSR_COMMIT=$b timeout 80 .gl/bench-$b $A --out $OUT/$b-$r > $OUT/$b-$r.log 2>&1 || tail -3 $OUT/$b-$r.log; done; done
cd $OUT && for d in before-? follow-?; do echo "## $d"; cat $d/bench.md; done > bench-all.md && rm -rf before-? follow-? *.log
awk '/^## (before|follow)/{h=$2} /^\| 3840x2160 \| [a-z -]+ \| (quality|fast) \| [0-9]/{n=split($0,a,"|"); print h, a[3], a[4], "cls", a[6], "total", a[10]} /tile_classification_r16f \|/{n=split($0,a,"|"); print h, a[3], "regs", a[5], "shared", a[9]}' bench-all.md | sort | uniq
