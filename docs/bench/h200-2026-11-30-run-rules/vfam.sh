#!/bin/bash
# The viewer's scene family (examples-c/viewer/family.py) on the device: references once (base build), then each
# variant of VLIST (name, library folder, presets, env...) with the same references.
for f in .gl/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig
find .gl -name "*.gz" | while read z; do gunzip -f $z; done; chmod +x .gl/dnsr_viewer .gl/acc-exp 2>/dev/null
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
V=examples-c/viewer
while read -r name lib presets rest; do
  [ -z "$name" ] && continue
  s=$(date +%s)
  env $rest LD_LIBRARY_PATH=$PWD/.gl/$lib:$PWD/.gl/vlib python3 $V/family.py .gl/dnsr_viewer /tmp/vf-$name --presets $presets \
    --references /tmp/vf-refs --jobs 16 > $OUT/vf-$name.log 2>&1
  echo "$name exit $? in $(( $(date +%s) - s )) s" >> $OUT/vf-$name.log
  cp /tmp/vf-$name/family.json $OUT/family-$name.json 2>/dev/null
done < ${VLIST:-.gl/vlist.txt}
cd $OUT; for f in vf-*.log; do tail -1 $f; done
