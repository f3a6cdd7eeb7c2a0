#!/bin/bash
# The search's history window loaded once per group into shared memory (sm8), against the per-offset fetches (f8)
# and the commit before (head): families and classification at 4K.
for f in .gl/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig; for z in .gl/*.gz; do gunzip -f $z; chmod +x ${z%.gz}; done
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
for v in f8 sm8; do
  (mkdir -p /tmp/o-$v; timeout 300 .gl/acc-$v --family-only --presets quality,fast --out /tmp/o-$v > /tmp/$v.log 2>&1; echo "$v exit $?" >> /tmp/$v.log; cp /tmp/o-$v/accuracy.md $OUT/$v-accuracy.md) &
done
wait
A="--sizes 3840x2160 --scenes penumbra-heavy,typical --presets quality,fast --precisions fp32 --frames 100 --copy-runs 1 --warmup-ms 300"
for r in 1 2; do for v in head f8 sm8; do timeout 100 .gl/bench $A --shader-override tile_classification_r16f=.gl/cls-$v.spv --out $OUT/b-$v-$r > /dev/null 2>&1 || echo "bench $v failed"; done; done
cd $OUT && for d in b-*; do echo "## $d"; cat $d/bench.md; done > bench-shared.md && rm -rf b-*
for v in f8 sm8; do echo "== $v"; tail -1 /tmp/$v.log; grep -E "^\| (Quality|Fast) \|" $v-accuracy.md | head -2; done
awk '/^## b-/{h=$2} /^## Pipelines/{h=""} h!="" && /^\| 3840x2160 \| [^|]+ \| (quality|fast) \| [0-9.]+ \| [0-9]/{n=split($0,a,"|"); print h, a[3], a[4], "cls", a[6], "total", a[10]}' bench-shared.md | sort -k2,3 -k1,1
grep -h "tile_classification_r16f" bench-shared.md | sort | uniq -c
