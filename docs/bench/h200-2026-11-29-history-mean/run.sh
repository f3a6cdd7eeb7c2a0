#!/bin/bash
# The history as its mean alone (R16_UNORM) with the filter's signal in the frame moments' memory (new) against main
# before it (old, 7dcd4bb: the history R16G16_UNORM), then the first pass writing the signal of cleared pixels only
# where the second pass reads it (new2), alternating, 4K; then the parity, transient-state and resource tests of the
# new2 build (its unit-test binary, validation layer on) on this device.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; for z in .gl/*.gz; do gunzip -f $z; chmod +x ${z%.gz}; done
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
A="--sizes 3840x2160 --scenes penumbra-heavy,typical,all-lit --presets fast,balanced,quality --precisions fp32 --frames 200 --copy-runs 3 --warmup-ms 500"
for r in 1 2; do for b in old new new2; do DNSR_COMMIT=$b timeout 150 .gl/bench-$b $A --out $OUT/$b-$r > $OUT/$b-$r.log 2>&1; done; done
timeout 240 .gl/dnsr-tests parity transient state_table timestamps_and_memory > $OUT/tests.txt 2>&1; echo "tests exit $?" >> $OUT/tests.txt
cd $OUT && for d in old-1 new-1 new2-1 old-2 new-2 new2-2; do echo "## $d"; cat $d/bench.md; done > bench-all.md && for d in old-1 new-1 new2-1 old-2 new-2 new2-2; do cat $d.log; done > logs.txt && rm -rf old-? new-? new2-? *-?.log && cat device.txt; grep -hE "test result|exit" tests.txt; grep -E '^## |^\| 3840x2160' bench-all.md | cut -c1-200 | awk '/^## /{n=0} {if (n++ < 10) print}'
