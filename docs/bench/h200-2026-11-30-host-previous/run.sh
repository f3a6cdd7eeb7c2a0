#!/bin/bash
# The host's previous depth and normals (ContextCreateInfo::host_previous_gbuffer) at 4K: one dnsr-bench binary,
# without and with --host-previous, alternating twice; then the host_previous and parity unit tests on the H200
# with the validation layer (the test binary built from the same commit).
for f in .gl/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig; for z in .gl/*.gz; do gunzip -f $z; chmod +x ${z%.gz}; done
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
A="--sizes 3840x2160 --scenes penumbra-heavy,typical,sky-90 --presets quality,balanced --precisions fp32 --lights 1,4 --frames 100 --copy-runs 1 --warmup-ms 300"
declare -A O=([own]="" [host]="--host-previous")
for r in 1 2; do for b in own host; do timeout 150 .gl/bench $A ${O[$b]} --out $OUT/$b-$r > $OUT/$b-$r.log 2>&1 || tail -3 $OUT/$b-$r.log; done; done
export VK_LAYER_PATH=/usr/share/vulkan/explicit_layer.d
timeout 200 .gl/libtests --test-threads 1 host_previous > $OUT/tests.txt 2>&1; echo "tests exit $?" >> $OUT/tests.txt
cd $OUT && for d in own-? host-?; do echo "## $d"; cat $d/bench.md; done > bench-all.md && rm -rf own-? host-? *.log
awk '/^## (own|host)/{h=$2} /^\| 3840x2160 \| [a-z -]+ \| (quality|balanced) \| [0-9]/{n=split($0,a,"|"); print h, a[3], a[4], "cls", a[6], "f0", a[7], "total", a[10], "mem", a[17], "kept", a[18]}' bench-all.md | sort -k2,3 | uniq
grep -h "test result\|tests exit\|FAILED" tests.txt
