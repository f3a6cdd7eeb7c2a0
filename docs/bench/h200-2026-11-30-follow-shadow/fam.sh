#!/bin/bash
# Following the shadow (an offset search per tile where the shadow moved), with and without the stable-history rule
# on the followed pixels, against the same build without it: each experiment build's dnsr-accuracy --family-only
# (Quality and Fast), side by side.
for f in .gl/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig; for z in .gl/*.gz; do gunzip -f $z; chmod +x ${z%.gz}; done
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
for v in ${VARIANTS:-base follow followoff followoff4}; do
  (mkdir -p /tmp/o-$v; timeout 500 .gl/acc-$v --family-only --presets quality,fast --out /tmp/o-$v > $OUT/$v.log 2>&1; echo "$v exit $?" >> $OUT/$v.log; cp /tmp/o-$v/accuracy.md $OUT/$v-accuracy.md) &
done
wait
cd $OUT; for v in ${VARIANTS:-base follow followoff followoff4}; do echo "== $v"; tail -1 $v.log; grep -E "^\| (Quality|Fast) \|" $v-accuracy.md; done
