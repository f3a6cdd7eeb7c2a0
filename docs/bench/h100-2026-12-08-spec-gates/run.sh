#!/bin/bash
# The final-code gate (cbd2fe4) and the geometric-normal gate (6d408d2), one dnsr-bench binary (the new SPIR-V
# built in): cbc7ed4's SPIR-V of the four passes ("a": neither gate), 1049354's ("b": the final-code gate), the
# binary's own ("c": both), alternating, two rounds. 4K fp32, Balanced and Quality.
for f in .gl/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig; gunzip -f .gl/bench.gz; chmod +x .gl/bench
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
A="--sizes 3840x2160 --scenes penumbra-heavy,typical --presets balanced,quality --precisions fp32 --frames 100 --copy-runs 1 --warmup-ms 200"
ov() { for s in tile_classification_r16f filter filter_later filter_later_final_r16f; do echo -n " --shader-override $s=.gl/$1/$s.spv"; done; }
for r in 1 2; do
  timeout 90 .gl/bench $A $(ov a) --out /tmp/d-a$r > /dev/null 2>&1 || echo "a$r failed"
  timeout 90 .gl/bench $A $(ov b) --out /tmp/d-b$r > /dev/null 2>&1 || echo "b$r failed"
  timeout 90 .gl/bench $A --out /tmp/d-c$r > /dev/null 2>&1 || echo "c$r failed"
done
for n in a1 b1 c1 a2 b2 c2; do (echo "@@ $n"; cat /tmp/d-$n/bench.md) >> $OUT/bench-all.md; done
cd $OUT
awk '/^@@ /{h=$2} /^\| 3840x2160 \| [^|]+ \| (balanced|quality) \| [0-9.]+ \| [0-9]/{print h, $0}' bench-all.md | cut -c1-150
