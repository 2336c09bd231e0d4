#!/usr/bin/env bash
# A throwaway qemu VM with a real SocketCAN stack (vcan0, and vcan1 with MTU 72 for CAN FD), for hosts whose
# kernel has no CAN (notes: ../shared/notes/socketcan-in-a-vm.md). Debian's own kernel boots in TCG, the
# host's root is shared read-only over virtio-9p and chrooted into, so host binaries run unchanged.
#
#   scripts/vm/can-vm.sh prepare             fetch + cache the kernel, modules and initramfs in .vm/ (once)
#   scripts/vm/can-vm.sh run SCRIPT RUNDIR [DIR...]   boot, run `sh SCRIPT` as root in the chroot, power off.
#       RUNDIR (read-write in the guest at the same path) receives SCRIPT's files; exit status = SCRIPT's.
#       The guest has fresh tmpfs on /tmp and /run; the checkout, SCRIPT's folder and each DIR (e.g. the catkin
#       workspace) stay visible at their own paths wherever they are, under /tmp too.
# Needs qemu-system-x86 busybox-static xz-utils (scripts/packages.txt) and Debian's archive for apt-get download.
set -euo pipefail
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
VM="${CAN_VM_DIR:-$REPO/.vm}"
QEMU="${CAN_VM_QEMU:-qemu-system-x86_64}"  # the emulator (tests point it at a missing file)
MODULES="can can-raw can-dev vcan virtio_ring virtio virtio_pci_modern_dev virtio_pci_legacy_dev virtio_pci
         netfs fscache 9pnet 9pnet_virtio 9p"

die() { echo "can-vm: $*" >&2; exit 1; }

# The initramfs is rebuilt when /init or the module list changes (a stale cached one would run old code).
initrd_id() { { cat "$REPO/scripts/vm/init.sh"; echo "$MODULES"; } | sha256sum | cut -c1-16; }

prepare() {
  command -v "$QEMU" >/dev/null || die "$QEMU not found (apt-get install qemu-system-x86, see scripts/packages.txt)"
  [ -s "$VM/vmlinux" ] && [ -s "$VM/initrd.cpio.gz" ] && [ "$(cat "$VM/initrd.id" 2>/dev/null)" = "$(initrd_id)" ] && return 0
  [ -x /bin/busybox ] || [ -x /usr/bin/busybox ] || die "busybox missing (apt-get install busybox-static)"
  mkdir -p "$VM/dl"
  local pkg
  resolve() { apt-cache depends linux-image-amd64 2>/dev/null | awk '/Depends: linux-image-[0-9]/ {print $2; exit}'; }
  pkg="$(resolve)"
  if [ -z "$pkg" ] && [ "$(id -u)" = 0 ]; then  # fresh machine / container without package lists
    apt-get update -q >/dev/null 2>&1 || true
    pkg="$(resolve)"
  fi
  [ -n "$pkg" ] || die "cannot resolve linux-image-amd64 (apt-get update?)"
  if ! ls "$VM"/dl/"$pkg"_*.deb >/dev/null 2>&1; then
    ( cd "$VM/dl" && apt-get download "$pkg" >/dev/null 2>&1 ) || die "apt-get download $pkg failed"
  fi
  local deb; deb="$(ls "$VM"/dl/"$pkg"_*.deb | head -n1)"
  rm -rf "$VM/x" && mkdir -p "$VM/x"
  dpkg-deb --fsys-tarfile "$deb" | tar -x -C "$VM/x" --wildcards './boot/vmlinuz-*' './lib/modules/*/kernel/net/can/*' \
    './lib/modules/*/kernel/drivers/net/can/*' './lib/modules/*/kernel/drivers/virtio/*' \
    './lib/modules/*/kernel/net/9p/*' './lib/modules/*/kernel/fs/9p/*' './lib/modules/*/kernel/fs/netfs/*' \
    './lib/modules/*/kernel/fs/fscache/*' 2>/dev/null || true
  local vmlinuz; vmlinuz="$(ls "$VM"/x/boot/vmlinuz-* | head -n1)"
  [ -s "$vmlinuz" ] || die "no vmlinuz in $deb"
  # Boot the uncompressed kernel directly (PVH): saves the in-guest decompression. Find the xz stream.
  local off
  off="$(LC_ALL=C grep -obUaP '\xFD\x37\x7A\x58\x5A\x00' "$vmlinuz" | head -n1 | cut -d: -f1)"
  [ -n "$off" ] || die "no xz stream in $vmlinuz"
  tail -c +"$((off + 1))" "$vmlinuz" | xz -dc --single-stream > "$VM/vmlinux.tmp" 2>/dev/null || true
  [ -s "$VM/vmlinux.tmp" ] || die "kernel decompression failed"
  # initramfs: static busybox, the modules, and /init.
  local root="$VM/initrd" m f
  rm -rf "$root" && mkdir -p "$root"/{bin,dev,proc,sys,host,mods}
  cp "$(command -v busybox)" "$root/bin/busybox"
  for m in $MODULES; do
    f="$(find "$VM/x/lib/modules" \( -name "$m.ko" -o -name "$m.ko.xz" -o -name "${m//-/_}.ko" -o -name "${m//-/_}.ko.xz" \) | head -n1)"
    [ -n "$f" ] || die "module $m not found in $deb"
    case "$f" in *.xz) xz -dc "$f" > "$root/mods/$m.ko" ;; *) cp "$f" "$root/mods/$m.ko" ;; esac
  done
  echo "$MODULES" | tr -s ' \n' '\n\n' | grep -v '^$' > "$root/mods/order"
  cp "$REPO/scripts/vm/init.sh" "$root/init"
  chmod +x "$root/init"
  ( cd "$root" && find . | busybox cpio -o -H newc 2>/dev/null | gzip -1 ) > "$VM/initrd.cpio.gz.tmp"
  mv "$VM/vmlinux.tmp" "$VM/vmlinux"
  mv "$VM/initrd.cpio.gz.tmp" "$VM/initrd.cpio.gz"
  initrd_id > "$VM/initrd.id"
  rm -rf "$VM/x"
}

run() {
  local script="$1" rundir="$2" d
  shift 2
  prepare
  rundir="$(realpath "$rundir")"
  script="$(realpath "$script")"
  rm -f "$rundir/.vm-rc"
  # What the guest's /init reads (one path per line: no quoting, no kernel command line length limit).
  printf '%s\n' "$script" > "$rundir/.vm-script"
  printf '%s\n' "$rundir" > "$rundir/.vm-run"
  for d in "$REPO" "$(dirname "$script")" "$@"; do realpath "$d"; done > "$rundir/.vm-keep"
  local rc=0
  # Commas inside qemu option values are doubled; TCG: /dev/kvm here is unusable (see the notes).
  timeout "${CAN_VM_TIMEOUT:-240}" "$QEMU" -accel tcg -m 768 -nographic -no-reboot -nodefaults \
    -serial stdio -monitor none \
    -kernel "$VM/vmlinux" -initrd "$VM/initrd.cpio.gz" \
    -append "console=ttyS0 quiet panic=-1" \
    -fsdev "local,id=hostroot,path=/,readonly=on,security_model=none,multidevs=remap" \
    -device virtio-9p-pci,fsdev=hostroot,mount_tag=hostroot \
    -fsdev "local,id=run,path=${rundir//,/,,},security_model=none,multidevs=remap" \
    -device virtio-9p-pci,fsdev=run,mount_tag=run \
    -device isa-debug-exit,iobase=0xf4,iosize=0x04 || rc=$?
  # isa-debug-exit: qemu exits (v << 1) | 1 for the v = rc + 1 the guest wrote; no result file = failure.
  [ -s "$rundir/.vm-rc" ] || { echo "can-vm: the guest did not finish (qemu exit $rc)" >&2; return 125; }
  local guest_rc; guest_rc="$(cat "$rundir/.vm-rc")"
  if [ "$rc" != $(( ((guest_rc + 1) << 1) | 1 )) ]; then echo "can-vm: qemu exit $rc disagrees with guest rc $guest_rc" >&2; fi
  return "$guest_rc"
}

case "${1:-}" in
  prepare) prepare ;;
  run) [ $# -ge 3 ] || die "usage: $0 run SCRIPT RUNDIR [DIR...]"; shift; run "$@" ;;
  *) sed -n '2,12p' "$0"; exit 2 ;;
esac
