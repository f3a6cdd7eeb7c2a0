#!/bin/bash
# The SampleRun debug view (d00c7e6): the final filter passes' SPIR-V before and after, one bench binary.
for f in .gl/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig; for z in .gl/*.gz; do gunzip -f $z; chmod +x ${z%.gz}; done
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
A="--sizes 3840x2160 --scenes penumbra-heavy,typical --presets fast,quality,balanced --precisions fp32 --frames 100 --copy-runs 1 --warmup-ms 300"
for r in 1 2; do for v in old new; do
  O=""; for s in filter_final_r16f filter_later_final_r16f; do O="$O --shader-override $s=.gl/$v-$s.spv"; done
  timeout 150 .gl/bench $A $O --out $OUT/b-$v-$r > /dev/null 2>&1 || echo "bench $v failed"
done; done
cd $OUT && for d in b-*; do echo "## $d"; cat $d/bench.md; done > bench-all.md && rm -rf b-*
awk '/^## b-/{h=$2} /^## Pipelines/{h=""} h!="" && /^\| 3840x2160 \| [^|]+ \| (fast|quality|balanced) \| [0-9.]+ \| [0-9]/{n=split($0,a,"|"); print h, a[3], a[4], "cls", a[6], "f0", a[7], "f1", a[8], "f2", a[9], "total", a[10]}' bench-all.md | sort -k2,3 -k1,1
grep -h "filter_final_r16f \|filter_later_final_r16f " bench-all.md | sort | uniq -c | head
