#!/bin/bash
# Following a moved shadow with integer costs, only in tiles with a still receiver: make accuracy's families
# (dnsr-accuracy --family-only, Quality and Fast) for each experiment build side by side, then the classification
# of each variant timed at 4K by one bench binary through --shader-override (head: the commit before), alternating.
for f in .gl/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig; for z in .gl/*.gz; do gunzip -f $z; chmod +x ${z%.gz}; done
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
V="base f8 f4 f8a1"
for v in $V; do
  (mkdir -p /tmp/o-$v; timeout 300 .gl/acc-$v --family-only --presets quality,fast --out /tmp/o-$v > $OUT/$v.log 2>&1; echo "$v exit $?" >> $OUT/$v.log; cp /tmp/o-$v/accuracy.md $OUT/$v-accuracy.md) &
done
wait
A="--sizes 3840x2160 --scenes penumbra-heavy,typical --presets quality,fast --precisions fp32 --frames 100 --copy-runs 1 --warmup-ms 300"
for r in 1 2; do for v in head base f8 f4 f8a1; do timeout 100 .gl/bench $A --shader-override tile_classification_r16f=.gl/cls-$v.spv --out $OUT/b-$v-$r > /dev/null 2>&1 || echo "bench $v failed"; done; done
cd $OUT && for d in b-*; do echo "## $d"; cat $d/bench.md; done > bench-all.md && rm -rf b-*
for v in $V; do echo "== $v"; tail -1 $v.log; grep -E "^\| (Quality|Fast) \|" $v-accuracy.md | head -12; done
awk '/^## b-/{h=$2} /^## Pipelines/{h=""} h!="" && /^\| 3840x2160 \| [^|]+ \| (quality|fast) \| [0-9.]+ \| [0-9]/{n=split($0,a,"|"); print h, a[3], a[4], "cls", a[6], "total", a[10]}' bench-all.md | sort -k2,3 -k1,1
grep -h "tile_classification_r16f" bench-all.md | sort | uniq -c
