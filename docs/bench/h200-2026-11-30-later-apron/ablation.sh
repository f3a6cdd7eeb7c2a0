#!/bin/bash
# What the later filter pass spends, part by part: variants of Quality's final later pass (filter_later_final_r16f,
# step 2) as shader overrides of one bench binary, alternating twice. ABL 0: as committed; 1: no taps; 2: taps
# without the exp and pow (fetches kept); 3: no variance gathers; 4: every block written as cleared (the dispatch,
# the metadata and the writes alone); 5: taps fetch the signal only (the centre's guide).
for f in .gl/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig; for z in .gl/*.gz; do gunzip -f $z; chmod +x ${z%.gz}; done
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
A="--sizes 3840x2160 --scenes penumbra-heavy,typical --presets quality --precisions fp32 --frames 100 --copy-runs 1 --warmup-ms 300"
for r in 1 2; do for a in 0 1 2 3 4 5; do DNSR_COMMIT=abl$a timeout 60 .gl/bench-before $A --shader-override filter_later_final_r16f=.gl/abl$a.spv --out $OUT/abl$a-$r > $OUT/abl$a-$r.log 2>&1 || tail -3 $OUT/abl$a-$r.log; done; done
cd $OUT && for d in abl?-?; do echo "## $d"; cat $d/bench.md; done > bench-all.md && rm -rf abl?-? *.log
awk '/^## /{h=$2} /^\| 3840x2160 \| [a-z-]+ \| quality \| [0-9]/{n=split($0,a,"|"); print h, a[3], "f1", a[8], "total", a[10]}' bench-all.md | sort
grep -h "filter_later_final" bench-all.md | sort | uniq | head
