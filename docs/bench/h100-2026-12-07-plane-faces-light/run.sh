#!/bin/bash
# Classification with the normal-mapped turned-away test (the plane a receiver lies in, and its group's evidence that
# the host's rays do not test normal-mapped normals) against classification before it (b383b91), one bench binary
# (built from the commit that adds --light-position), alternating. Without a light position the new code does not run
# (a runtime branch: what it costs is its presence); with one (0.3,1,0.2,0: the bench's ground faces it) every lit
# receiver of a group that is not cleared tests its normal against the light. `win`: the landed change, and the
# surface window's normal codes from each window pixel's geometric normal (dnsr_geometric_normal, within 53 degrees;
# not landed: an experiment whose cost decides whether to pursue it).
for f in .gl/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig; for z in .gl/*.gz; do gunzip -f $z; chmod +x ${z%.gz}; done
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
A="--sizes 3840x2160 --scenes penumbra-heavy,typical --presets quality --precisions fp32 --frames 100 --copy-runs 1 --warmup-ms 300"
for light in none lit; do
  L=""; [ $light = lit ] && L="--light-position 0.3,1,0.2,0"
  for v in old new win; do
    n=b-$light-$v
    timeout 60 .gl/bench $A $L --shader-override tile_classification_r16f=.gl/$v-tile_classification_r16f.spv \
      --out /tmp/$n > /dev/null 2>&1 || echo "bench $n failed"
    (echo "## $n"; cat /tmp/$n/bench.md) >> $OUT/bench-all.md
  done
done
cd $OUT
awk '/^## b-/{h=$2} /^## Pipelines/{h=""} h!="" && /^\| 3840x2160 \| [^|]+ \| (quality) \| [0-9.]+ \| [0-9]/{n=split($0,a,"|"); print h, a[3], a[4], "cls", a[6], "total", a[10]}' bench-all.md
awk '/^## b-/{h=$2} /\| tile_classification_r16f \|/ {print h, $0}' bench-all.md | grep "| fp32" | sort -u
