#!/bin/bash
# Where the later filter passes' cost of final pixels comes from (run.sh measured +0.014 ms on each later pass, Balanced
# included, which never has a final pixel). Balanced and Quality, penumbra-heavy, 4K fp32, one bench binary (df70ac7),
# every variant as shader overrides, one round (the device time left allowed no more): `nofinal` (no final pixels), `new` (df70ac7), `v5` (`new` with the filter passes' tests of final
# pixels behind DNSR_SPEC_STABLE_HISTORY, which Balanced's pipelines compile without).
for f in .gl/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig; for z in .gl/*.gz; do gunzip -f $z; chmod +x ${z%.gz}; done
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
A="--sizes 3840x2160 --scenes penumbra-heavy --presets balanced,quality --precisions fp32 --frames 100 --copy-runs 1 --warmup-ms 200"
for round in 1; do
  for v in nofinal new v5; do
    n=c$round-$v
    O=""; for s in tile_classification_r16f filter filter_final_r16f filter_later filter_later_final_r16f; do O="$O --shader-override $s=.gl/$v-$s.spv"; done
    timeout 100 .gl/bench $A $O --out /tmp/$n > /dev/null 2>&1 || echo "bench $n failed"
    (echo "## $n"; cat /tmp/$n/bench.md) >> $OUT/bench-later.md
  done
done
cd $OUT
awk '/^## c/{h=$2} /^## Pipelines/{h=""} h!="" && /^\| 3840x2160 \| [^|]+ \| (fast|balanced|quality) \| [0-9.]+ \| [0-9]/{print h, $0}' bench-later.md | cut -c1-120
