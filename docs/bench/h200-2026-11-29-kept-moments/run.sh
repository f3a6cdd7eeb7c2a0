#!/bin/bash
# The moments kept in one image (filter pass 0 copies this frame's from a transient one) against main before it
# (old, 3bf6b3d: a ping-pong pair), alternating, 4K; then the parity and transient-state tests of the new build
# (its unit-test binary, validation layer on) on this device.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; for z in .gl/*.gz; do gunzip -f $z; chmod +x ${z%.gz}; done
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
A="--sizes 3840x2160 --scenes penumbra-heavy,typical,all-lit --presets fast,balanced,quality --precisions fp32 --frames 200 --copy-runs 3 --warmup-ms 500"
for r in 1 2; do for b in old new; do DNSR_COMMIT=$b timeout 150 .gl/bench-$b $A --out $OUT/$b-$r > $OUT/$b-$r.log 2>&1; done; done
timeout 240 .gl/dnsr-tests parity transient > $OUT/tests.txt 2>&1; echo "tests exit $?" >> $OUT/tests.txt
cd $OUT && cat device.txt; grep -hE "test result|exit" tests.txt; for d in old-1 new-1 old-2 new-2; do echo $d; grep -E '^\| 3840x2160' $d/bench.md | head -9 | cut -c1-200; done
