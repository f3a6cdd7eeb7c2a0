#!/bin/bash
# A hit mask read by classification as the host gives it (no prepare pass): main's bench (old) against the
# prep branch's (new), alternating. Part 1: three sizes each. Part 2: a second round at 4K, then the parity suite of
# the new build on this device.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
A="--scenes penumbra-heavy,typical,all-lit,sky-90 --presets fast,balanced,quality --precisions fp32 --frames 200 --copy-runs 3 --warmup-ms 500"
if [ "$1" = 1 ]; then
  for b in old new; do DNSR_COMMIT=$b timeout 270 .gl/bench-$b --sizes 1920x1080,2560x1440,3840x2160 $A --out $OUT/sizes-$b > $OUT/sizes-$b.log 2>&1; done
else
  for b in old new; do DNSR_COMMIT=$b timeout 150 .gl/bench-$b --sizes 3840x2160 $A --out $OUT/ab-$b-2 > $OUT/ab-$b-2.log 2>&1; done
  timeout 240 .gl/dnsr-tests parity > $OUT/parity.txt 2>&1; echo "parity exit $?" >> $OUT/parity.txt
fi
cd $OUT && tar czf results-$1.tgz */bench.md *.log device.txt $(ls parity.txt 2>/dev/null) && rm -rf sizes-* ab-*
cat device.txt; grep -hE "test result|exit" parity.txt 2>/dev/null; ls
