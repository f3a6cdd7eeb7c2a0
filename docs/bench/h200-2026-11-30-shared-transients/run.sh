#!/bin/bash
# Several lights sharing one transient image set (each light's passes in a row: the default since this change)
# against a set per light (--transient-per-light: pass by pass, the later filter passes four lights per dispatch, as
# before), one binary, alternating twice; then the light, resource, transient-state and parity tests of the same
# build (its unit-test binary, validation layer on) on this device.
for f in .gl/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig; for z in .gl/*.gz; do gunzip -f $z; chmod +x ${z%.gz}; done
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
A="--sizes 3840x2160 --scenes penumbra-heavy,typical --presets quality,balanced --precisions fp32 --lights 1,4,8 --frames 100 --copy-runs 1 --warmup-ms 300"
declare -A O=([shared]="" [perlight]="--transient-per-light")
for r in 1 2; do for b in shared perlight; do DNSR_COMMIT=$b timeout 170 .gl/bench-new $A ${O[$b]} --out $OUT/$b-$r > $OUT/$b-$r.log 2>&1 || tail -3 $OUT/$b-$r.log; done; done
timeout 200 .gl/dnsr-tests tests::lights tests::transient state_table timestamps_and_memory parity > $OUT/tests.txt 2>&1; echo "tests exit $?" >> $OUT/tests.txt
cd $OUT && for d in shared-1 perlight-1 shared-2 perlight-2; do echo "## $d"; cat $d/bench.md; done > bench-all.md && rm -rf shared-? perlight-? *-?.log && cat device.txt; grep -hE "test result|exit" tests.txt; grep -E '^## |^\| 3840x2160 \| [a-z0-9% -]* \| [a-z, 0-9]* \| [0-9]' bench-all.md | grep -v "MB," | cut -c1-120
