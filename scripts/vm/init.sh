#!/bin/busybox sh
# /init of the CAN test VM (built into the initramfs by scripts/vm/can-vm.sh).
# The host's root arrives read-only (9p tag hostroot), the run folder read-write (tag run). The run folder holds
# what to do, one path per line (so that any path works, spaces included): .vm-script (the script to run),
# .vm-run (the run folder's host path), .vm-keep (host folders under /tmp or /run that must stay visible:
# the checkout, the workspace). The guest gets fresh tmpfs on /tmp and /run; the kept folders are bound back
# into them from the host's view, then the run folder is mounted at its own path on top.
/bin/busybox --install -s /bin
export PATH=/bin
mount -t proc proc /proc
mount -t sysfs sys /sys
mount -t devtmpfs dev /dev
for m in $(cat /mods/order); do insmod /mods/$m.ko || echo "init: insmod $m failed"; done
rc=1
mkdir -p /rw /old/tmp /old/run
line() { IFS= read -r v < "$1" && printf '%s' "$v"; }
if mount -t 9p -o trans=virtio,version=9p2000.L,ro hostroot /host &&
   mount -t 9p -o trans=virtio,version=9p2000.L,msize=262144 run /rw &&
   script=$(line /rw/.vm-script) && run=$(line /rw/.vm-run) && [ -n "$script" ] && [ -n "$run" ]; then
  mount -t proc proc /host/proc
  mount -t sysfs sys /host/sys
  mount -o bind /dev /host/dev
  for d in tmp run; do
    [ -d "/host/$d" ] || continue
    mount -o bind "/host/$d" "/old/$d"
    mount -t tmpfs "$d" "/host/$d"
  done
  ok=1
  while IFS= read -r p; do
    case "$p" in
      /tmp/*|/run/*)
        old="/old${p}"
        mkdir -p "/host$p" && mount -o bind "$old" "/host$p" || { echo "init: cannot keep $p visible"; ok=0; } ;;
    esac
  done < /rw/.vm-keep
  [ -d "/host$run" ] || mkdir -p "/host$run"
  if [ $ok = 1 ] && mount -o bind /rw "/host$run"; then
    ip link set lo up
    ip link add dev vcan0 type vcan && ip link set vcan0 up
    ip link add dev vcan1 type vcan && ip link set vcan1 mtu 72 && ip link set vcan1 up
    chroot /host /bin/sh -c 'cd "$1" && HOME=/tmp sh "$2"' sh "$run" "$script"
    rc=$?
  else
    echo "init: cannot mount the run folder at $run"
  fi
  echo "$rc" > /rw/.vm-rc
  sync
  umount "/host$run" 2>/dev/null
  umount /rw
else
  echo "init: cannot mount the host's folders or read /rw/.vm-script, .vm-run"
fi
v=$((rc + 1)); [ $v -gt 255 ] && v=255
printf "\\$(printf %03o $v)" | dd of=/dev/port bs=1 seek=244 count=1 2>/dev/null
poweroff -f
