#!/bin/bash
# Filter pass 0 skips the kept writes of tiles cleared alike last frame (new, the exp tree) against main (old):
# 4K fp32, every scene, Fast / Balanced / Quality, alternating twice; then the skip's test and the parity test on
# this GPU with the validation layer.
for f in .gl/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig; for z in .gl/*.gz; do gunzip -f $z; chmod +x ${z%.gz}; done
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
A="--sizes 3840x2160 --presets fast,balanced,quality --precisions fp32 --frames 100 --copy-runs 1 --warmup-ms 300"
for r in 1 2; do for b in old new; do DNSR_COMMIT=$b timeout 150 .gl/bench-$b $A --out $OUT/$b-$r > $OUT/$b-$r.log 2>&1 || tail -3 $OUT/$b-$r.log; done; done
timeout 200 .gl/libtests --test-threads 1 cleared_tiles_hold gpu_matches_the_cpu_reference > $OUT/tests.txt 2>&1; echo "tests exit $?" >> $OUT/tests.txt
cd $OUT && for d in old-1 new-1 old-2 new-2; do echo "## $d"; cat $d/bench.md; done > bench-all.md && rm -rf old-? new-? *-?.log && cat device.txt; grep -E '^## |^\| 3840x2160 \| [a-z0-9% -]* \| [a-z]* \| [0-9]' bench-all.md | cut -c1-125; tail -5 tests.txt
