#!/bin/bash
# The first filter pass's device depths loaded once into shared memory (the apron and one pixel beyond it) for the
# geometric normals, instead of six fetches per apron pixel: one dnsr-bench binary (depth-ring.patch built in,
# "new"), 66c6592's SPIR-V of the first pass (filter: Balanced and Quality; filter_final_r16f: Fast) as overrides
# ("old"), alternating, two rounds. 4K fp32.
for f in .gl/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig; gunzip -f .gl/bench.gz; chmod +x .gl/bench
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
A="--sizes 3840x2160 --scenes penumbra-heavy,typical --presets fast,balanced,quality --precisions fp32 --frames 100 --copy-runs 1 --warmup-ms 200"
O=""; for s in filter filter_final_r16f; do O="$O --shader-override $s=.gl/old/$s.spv"; done
for r in 1 2; do
  timeout 120 .gl/bench $A $O --out /tmp/d-old$r > /dev/null 2>&1 || echo "old$r failed"
  timeout 120 .gl/bench $A --out /tmp/d-new$r > /dev/null 2>&1 || echo "new$r failed"
done
for n in old1 new1 old2 new2; do (echo "@@ $n"; cat /tmp/d-$n/bench.md) >> $OUT/bench-all.md; done
cd $OUT
awk '/^@@ /{h=$2} /^\| 3840x2160 \| [^|]+ \| (fast|balanced|quality) \| [0-9.]+ \| [0-9]/{print h, $0}' bench-all.md | cut -c1-110
awk '/^@@ /{h=$2} /^\| fp32 \| (fast|balanced|quality) \| (filter|filter_final_r16f) \|/{print h, $0}' bench-all.md
