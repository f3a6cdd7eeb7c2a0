#!/bin/bash
# Register count and time of classification variants (the footprint's depth test), one bench binary.
for f in .gl/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig; for z in .gl/*.gz; do gunzip -f $z; chmod +x ${z%.gz}; done
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
A="--sizes 3840x2160 --scenes penumbra-heavy,typical --presets quality --precisions fp32 --frames 100 --copy-runs 1 --warmup-ms 300"
for run in old: x: y: x:--host-previous y:--host-previous old:--host-previous; do v=${run%%:*}; hp=${run#*:}
  O=""; for s in tile_classification_r16f tile_classification_host_previous_r16f; do O="$O --shader-override $s=.gl/$v-$s.spv"; done
  n=b-$v${hp:+-hp}
  timeout 60 .gl/bench $A $hp $O --out /tmp/$n > /dev/null 2>&1 || echo "bench $n failed"
  (echo "## $n"; cat /tmp/$n/bench.md) >> $OUT/bench-all.md
done
cd $OUT
awk '/^## b-/{h=$2} /^## Pipelines/{h=""} h!="" && /^\| 3840x2160 \| [^|]+ \| (fast|quality|balanced) \| [0-9.]+ \| [0-9]/{n=split($0,a,"|"); print h, a[3], a[4], "cls", a[6], "f0", a[7], "f1", a[8], "total", a[10]}' bench-all.md | sort -k2,3 -k1,1
awk '/^## b-/{h=$2} /tile_classification/ && /quality/ {print h, $0}' bench-all.md | sort -u
