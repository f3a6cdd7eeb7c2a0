#!/bin/bash
# Quality's stable-history rule taken apart: each variant (DNSR_EXP bits in the experiment build, or settings) runs
# dnsr-accuracy --family-only, Quality only, in parallel.
for f in .gl/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig; for z in .gl/*.gz; do gunzip -f $z; chmod +x ${z%.gz}; done
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json DNSR_DEVICE=NVIDIA
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt 2>&1
B=${BIN:-.gl/acc-exp}
run() { name=$1; shift; mkdir -p /tmp/o-$name; env "$@" timeout ${TMO:-560} $B --family-only --out /tmp/o-$name > $OUT/$name.log 2>&1; echo "$name exit $?" >> $OUT/$name.log; }
while read -r name args; do run $name $args & done < ${LIST:-.gl/list.txt}
wait
cd $OUT; for f in *.log; do echo "== $f"; grep -E "EXP cells|exit" $f; done
