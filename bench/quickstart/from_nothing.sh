#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Times README.md's Quick start command (1) from nothing: in a fresh Debian 12 root made by
# debootstrap (--variant=minbase bookworm), as root, with the repository cloned into it, the
# command is run exactly as README.md writes it, and each step's start is stamped (set -x).
#
#   bench/quickstart/from_nothing.sh WORKDIR COMMIT LOG
#
# WORKDIR holds the pristine root as a tarball (made once, by debootstrap, from Debian's archive)
# and the root each run unpacks from it. Needs root, debootstrap and network access to Debian's
# archive. Run it on a quiet machine: the build is most of the time.
set -euo pipefail
work=$1; commit=$2; log=$3
repo=$(git -C "$(dirname "$0")" rev-parse --show-toplevel)
R=$work/root
mkdir -p "$work"
if [ ! -f "$work/pristine.tar" ]; then
  debootstrap --variant=minbase bookworm "$work/pristine" http://deb.debian.org/debian
  tar -C "$work/pristine" -cf "$work/pristine.tar" . && rm -rf "$work/pristine"
fi
unmount() { for m in proc sys dev; do umount -l "$R/$m" 2>/dev/null || true; done; }
unmount
rm -rf "$R" && mkdir -p "$R" && tar -C "$R" -xf "$work/pristine.tar"
cp /etc/resolv.conf "$R/etc/resolv.conf"
mount -t proc proc "$R/proc"; mount --rbind /sys "$R/sys"; mount --rbind /dev "$R/dev"
trap unmount EXIT
git clone -q "$repo" "$R/root/sadr" && git -C "$R/root/sadr" checkout -q "$commit"
cmd=$(sed -n '/^# (1)/{n;p}' "$R/root/sadr/README.md")
{ echo "commit: $commit"; echo "command: $cmd"; echo "load before: $(cat /proc/loadavg)"; } > "$log"
start=$(date +%s.%N)
chroot "$R" /usr/bin/env -i HOME=/root PATH=/usr/sbin:/usr/bin:/sbin:/bin LANG=C.UTF-8 \
  bash -c "cd /root/sadr && export PS4='+ [\$(date +%s)] ' && set -x && $cmd" >> "$log" 2>&1 \
  && rc=0 || rc=$?
end=$(date +%s.%N)
echo "rc=$rc wall_s=$(echo "$end - $start" | bc) load after: $(cat /proc/loadavg)" >> "$log"
ls -la "$R/root/sadr/runs/quickstart/quickstart.png" >> "$log" 2>&1 || true
grep -E '^\+ \[|Need to get|After this operation|newly installed|^rc=' "$log"
