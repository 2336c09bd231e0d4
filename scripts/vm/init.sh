#!/bin/busybox sh
# /init of the CAN test VM (built into the initramfs by scripts/vm/can-vm.sh).
/bin/busybox --install -s /bin
export PATH=/bin
mount -t proc proc /proc
mount -t sysfs sys /sys
mount -t devtmpfs dev /dev
for m in $(cat /mods/order); do insmod /mods/$m.ko || echo "init: insmod $m failed"; done
script=$(sed -n 's/.*can_vm_script=\([^ ]*\).*/\1/p' /proc/cmdline)
run=$(sed -n 's/.*can_vm_run=\([^ ]*\).*/\1/p' /proc/cmdline)
rc=1
if mount -t 9p -o trans=virtio,version=9p2000.L,ro hostroot /host &&
   mount -t 9p -o trans=virtio,version=9p2000.L,msize=262144 run "/host$run"; then
  mount -t proc proc /host/proc
  mount -t sysfs sys /host/sys
  mount -o bind /dev /host/dev
  mount -t tmpfs tmp /host/tmp
  mount -t tmpfs run /host/run 2>/dev/null
  ip link set lo up
  ip link add dev vcan0 type vcan && ip link set vcan0 up
  ip link add dev vcan1 type vcan && ip link set vcan1 mtu 72 && ip link set vcan1 up
  chroot /host /bin/sh -c "cd '$run' && HOME=/tmp sh '$script'"
  rc=$?
  echo "$rc" > "/host$run/.vm-rc"
  sync
  umount "/host$run"
else
  echo "init: cannot mount the host's folders"
fi
v=$((rc + 1)); [ $v -gt 255 ] && v=255
printf "\\$(printf %03o $v)" | dd of=/dev/port bs=1 seek=244 count=1 2>/dev/null
poweroff -f
