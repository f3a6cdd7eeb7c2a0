#!/bin/bash
# Final pixels (receivers turned away from the whole light: classification's variance -2, every filter pass's test of
# its centre and taps, the signal's decode of the new code) against the same shaders without them (`nofinal`: the
# landed GLSL with those lines taken out, the signal's codec as before), one bench binary (df70ac7), both as shader
# overrides, alternating, two rounds. Without a light position classification's new code does not run (a runtime
# branch), the filter's tests do; with one (0.3,1,0.2,0: the bench's ground faces it) every lit receiver of a group
# that is not cleared also tests its normal against the light's disc.
for f in .gl/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig; for z in .gl/*.gz; do gunzip -f $z; chmod +x ${z%.gz}; done
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
A="--sizes 3840x2160 --scenes penumbra-heavy,typical --presets fast,balanced,quality --precisions fp32 --frames 100 --copy-runs 1 --warmup-ms 300"
for round in 1 2; do
  for light in none lit; do
    L=""; [ $light = lit ] && L="--light-position 0.3,1,0.2,0"
    for v in nofinal new; do
      n=b$round-$light-$v
      O=""; for s in tile_classification_r16f filter filter_final_r16f filter_later filter_later_final_r16f; do O="$O --shader-override $s=.gl/$v-$s.spv"; done
      timeout 120 .gl/bench $A $L $O --out /tmp/$n > /dev/null 2>&1 || echo "bench $n failed"
      (echo "## $n"; cat /tmp/$n/bench.md) >> $OUT/bench-all.md
    done
  done
done
cd $OUT
awk '/^## b/{h=$2} /^## Pipelines/{h=""} h!="" && /^\| 3840x2160 \| [^|]+ \| (fast|balanced|quality) \| [0-9.]+ \| [0-9]/{n=split($0,a,"|"); print h, a[3], a[4], "cls", a[6], "row", $0}' bench-all.md > summary.txt
cat summary.txt | cut -c1-220
