#!/bin/bash
# The host's previous depth and normals read as they are (no depth copy rounding) at 4K: one dnsr-bench binary,
# with the depth copy (own), with --host-previous (host: this commit's SPIR-V) and with --host-previous and the
# rounded classification of the commit before (rounded: --shader-override), alternating twice; then the
# host_previous and parity unit tests on the device with the validation layer (the test binary of the same commit).
for f in .gl/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig; for z in .gl/*.gz; do gunzip -f $z; chmod +x ${z%.gz}; done
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
A="--sizes 3840x2160 --scenes penumbra-heavy,typical,sky-90 --presets quality,balanced --precisions fp32 --frames 100 --copy-runs 1 --warmup-ms 300"
declare -A O=([own]="" [host]="--host-previous" [rounded]="--host-previous --shader-override tile_classification_host_previous_r16f=.gl/rounded.spv")
for r in 1 2; do for b in own host rounded; do timeout 120 .gl/bench $A ${O[$b]} --out $OUT/$b-$r > $OUT/$b-$r.log 2>&1 || tail -3 $OUT/$b-$r.log; done; done
export VK_LAYER_PATH=/usr/share/vulkan/explicit_layer.d
timeout 300 .gl/libtests --test-threads 1 host_previous gpu_matches_the_cpu_reference --nocapture > $OUT/tests.txt 2>&1; echo "tests exit $?" >> $OUT/tests.txt
cd $OUT && for d in own-? host-? rounded-?; do echo "## $d"; cat $d/bench.md; done > bench-all.md && rm -rf own-? host-? rounded-? *.log
awk '/^## (own|host|rounded)-/{h=$2} /^## Pipelines/{h=""} h!="" && /^\| 3840x2160 \| [^|]+ \| (quality|balanced) \| [0-9]/{n=split($0,a,"|"); print h, a[3], a[4], "cls", a[6], "total", a[9], "mem", a[16], "kept", a[17]}' bench-all.md | sort -k2,3 -k1,1
grep -h "test result\|tests exit\|FAILED\|seed 15\|differ from the depth copy" tests.txt
