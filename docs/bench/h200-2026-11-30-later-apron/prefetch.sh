#!/bin/bash
# The later filter passes with their taps' fetches issued at once (PF 1: all eight before the taps' loop, after the
# pass-through tests; 2: with the centre and the variance gathers; 3: with the pixel's own guide, before the tile
# metadata), against PF 0 (as committed, the same callbacks): shader overrides of one bench binary, alternating twice.
for f in .gl/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig; for z in .gl/*.gz; do gunzip -f $z; chmod +x ${z%.gz}; done
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
A="--sizes 3840x2160 --scenes penumbra-heavy,typical,all-lit --presets quality,balanced --precisions fp32 --frames 100 --copy-runs 1 --warmup-ms 300"
for r in 1 2; do for a in 0 1 2 3; do DNSR_COMMIT=pf$a timeout 80 .gl/bench-before $A --shader-override filter_later_final_r16f=.gl/pf$a-filter_later_final_r16f.spv --shader-override filter_later=.gl/pf$a-filter_later.spv --out $OUT/pf$a-$r > $OUT/pf$a-$r.log 2>&1 || tail -3 $OUT/pf$a-$r.log; done; done
cd $OUT && for d in pf?-?; do echo "## $d"; cat $d/bench.md; done > bench-all.md && rm -rf pf?-? *.log
awk '/^## pf/{h=$2} /^\| 3840x2160 \| [a-z -]+ \| (quality|balanced) \| [0-9]/{n=split($0,a,"|"); print h, a[3], a[4], "f1", a[8], "f2", a[9], "total", a[10]} /filter_later(_final_r16f)? \|/{n=split($0,a,"|"); print h, a[3], a[4], "regs", a[5]}' bench-all.md | sort | uniq
