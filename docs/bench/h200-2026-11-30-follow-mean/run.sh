#!/bin/bash
# Following the shadow with a running mean of its motion per tile (experiment): each build's dnsr-accuracy
# --family-only (Quality and Fast), side by side. base: main; follow: the whole-pixel search (2026-11-30 (4));
# ema: the search's offset averaged over frames per tile (alpha 0.25), stable rule off where followed; emaon: the
# same with the rule on; emasub: with the parabola's sub-pixel offset; ema10: alpha 0.1.
for f in .gl/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig; for z in .gl/*.gz; do gunzip -f $z; chmod +x ${z%.gz}; done
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
V="base follow ema emaon emasub ema10"
for v in $V; do
  (mkdir -p /tmp/o-$v; timeout 400 .gl/acc-$v --family-only --presets quality,fast --out /tmp/o-$v > $OUT/$v.log 2>&1; echo "$v exit $?" >> $OUT/$v.log; cp /tmp/o-$v/accuracy.md $OUT/$v-accuracy.md) &
done
wait
cd $OUT; for v in $V; do echo "== $v"; tail -1 $v.log; grep -E "^\| (Quality|Fast) \|" $v-accuracy.md; done
