#!/bin/bash
# Normal detail in dnsr's normals alone (--gbuffer packed --normal-detail-for dnsr): the shadows, the input and the
# reference stay those of the smooth normals, so what changes is dnsr's response to normal-mapped normals.
for f in .gl/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
gunzip -f .gl/vlib/libdnsr.so.0.1.gz; chmod +x .gl/vlib/dnsr_viewer
export LD_LIBRARY_PATH=$PWD/.gl/vlib
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
run() { # tag viewer-args [set]
  timeout 200 python3 examples-c/viewer/family.py .gl/vlib/dnsr_viewer /tmp/fam-$1 --presets quality,quality+untold,fast \
    --viewer-args "$2" ${3:+--set $3} --jobs 16 > /tmp/log-$1.txt 2>&1 || { echo "family $1 failed"; tail -5 /tmp/log-$1.txt; }
  cp /tmp/fam-$1/family.json $OUT/family-$1.json; echo "$1: $(tail -1 /tmp/log-$1.txt)"
}
run packed-0 "--gbuffer packed"
run packed-dnsr-0.25 "--gbuffer packed --normal-detail 0.25 --normal-detail-for dnsr"
run packed-dnsr-0.5 "--gbuffer packed --normal-detail 0.5 --normal-detail-for dnsr"
run packed-dnsr-0.5-np8 "--gbuffer packed --normal-detail 0.5 --normal-detail-for dnsr" normalPower=8
