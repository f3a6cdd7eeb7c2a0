#!/bin/bash
# The tiles' quiet counts a byte each, four tiles a word (0.25 -> 0.0625 B/px kept per light): two dnsr-bench binaries
# (before: the host-previous commit; after: the packed counts), alternating twice, at 4K; then the unit tests that
# read the counts (parity, lights, transient, host_previous) on the H200 with the validation layer.
for f in .gl/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig; for z in .gl/*.gz; do gunzip -f $z; chmod +x ${z%.gz}; done
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
A="--sizes 3840x2160 --scenes penumbra-heavy,typical,all-lit,sky-90 --presets quality,fast --precisions fp32 --frames 100 --copy-runs 1 --warmup-ms 300"
for r in 1 2; do for b in before after; do timeout 120 .gl/bench-$b $A --out $OUT/$b-$r > $OUT/$b-$r.log 2>&1 || tail -3 $OUT/$b-$r.log; done; done
timeout 150 .gl/bench-after $A --host-previous --out $OUT/after-host > $OUT/after-host.log 2>&1 || tail -3 $OUT/after-host.log
timeout 200 .gl/libtests --test-threads 1 tests::parity tests::lights::several tests::transient host_previous > $OUT/tests.txt 2>&1; echo "tests exit $?" >> $OUT/tests.txt
cd $OUT && for d in before-? after-? after-host; do echo "## $d"; cat $d/bench.md; done > bench-all.md && rm -rf before-? after-? after-host *.log
awk '/^## (before|after)/{h=$2} /^## Pipelines/{h=""} h!="" && /^\| 3840x2160 \| [^|]+ \| (quality|fast) \| [0-9]/{n=split($0,a,"|"); print h, a[3], a[4], "cls", a[6], "total", a[10], "mem", a[17], "kept", a[18]}' bench-all.md | sort -k2,3 | uniq
grep -h "test result\|tests exit\|FAILED" tests.txt
