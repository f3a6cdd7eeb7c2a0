#!/bin/bash
# Lights recorded together (one depth copy for all lights: --lights-together) against the shared transient set alone
# (the default), one binary, alternating twice; then the light, resource, transient-state, interface and parity tests
# of the same build (its unit-test binary, validation layer on) on this device.
for f in .gl/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig; for z in .gl/*.gz; do gunzip -f $z; chmod +x ${z%.gz}; done
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
A="--sizes 3840x2160 --scenes penumbra-heavy,typical --presets quality,balanced --precisions fp32 --lights 1,4,8 --frames 100 --copy-runs 1 --warmup-ms 300"
declare -A O=([shared]="" [together]="--lights-together")
for r in 1 2; do for b in shared together; do DNSR_COMMIT=$b timeout 170 .gl/bench-new $A ${O[$b]} --out $OUT/$b-$r > $OUT/$b-$r.log 2>&1 || tail -3 $OUT/$b-$r.log; done; done
timeout 200 .gl/dnsr-tests tests::lights tests::transient state_table timestamps_and_memory parity > $OUT/tests.txt 2>&1; echo "tests exit $?" >> $OUT/tests.txt
cd $OUT && for d in shared-1 together-1 shared-2 together-2; do echo "## $d"; cat $d/bench.md; done > bench-all.md && rm -rf shared-? together-? *-?.log && cat device.txt; grep -hE "test result|exit" tests.txt
awk '/^## (shared|together)/{h=$2} /^\| 3840x2160 \| (penumbra-heavy|typical) \| (quality|balanced)(, [48] lights)? \| [0-9]/{n=split($0,a,"|"); print h, a[3], a[4], "total", a[10], "mem", a[n-2], "kept", a[n-1]}' bench-all.md
