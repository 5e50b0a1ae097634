# fake_usb_adapter SYS TTY PORT VENDOR PRODUCT SERIAL DRIVER: a sysfs tree under SYS for one
# USB serial adapter as the kernel lays it out (relative links, so it also works mounted at
# /sys): the USB device PORT (idVendor, idProduct, serial, ...), its interface, for a
# usb-serial DRIVER (ftdi_sio, pl2303, ...) the port device ttyUSBn with its latency_timer,
# and the tty in class/tty. DRIVER cdc_acm makes a ttyACMn on the interface itself.
fake_usb_adapter() {
  local sys=$1 tty=$2 port=$3 vendor=$4 product=$5 serial=$6 driver=$7 n
  n=$(tr -dc 0-9 <<<"$tty")
  local hub=devices/pci0000:00/0000:00:14.0/usb1
  local usb=$hub/$port intf=$hub/$port/$port:1.0 dev ttydir
  mkdir -p "$sys/$usb" "$sys/$intf" "$sys/class/tty" "$sys/bus/usb/drivers/usb" "$sys/bus/usb/drivers/$driver"
  printf '%s\n' "$vendor" >"$sys/$usb/idVendor"
  printf '%s\n' "$product" >"$sys/$usb/idProduct"
  [ -n "$serial" ] && printf '%s\n' "$serial" >"$sys/$usb/serial"
  printf 'Fake\n' >"$sys/$usb/manufacturer"
  printf 'Serial %s\n' "$tty" >"$sys/$usb/product"
  printf '0600\n' >"$sys/$usb/bcdDevice"
  printf 'MAJOR=189\nMINOR=%s\nDEVNAME=bus/usb/001/%03d\nDEVTYPE=usb_device\nDRIVER=usb\nPRODUCT=%s/%s/600\nTYPE=0/0/0\nBUSNUM=001\nDEVNUM=%03d\n' \
    "$n" "$((n + 2))" "${vendor#0}" "${product#0}" "$((n + 2))" >"$sys/$usb/uevent"
  ln -sfn "$(realpath -s --relative-to="$sys/$usb" "$sys/bus/usb")" "$sys/$usb/subsystem"
  ln -sfn "$(realpath -s --relative-to="$sys/$usb" "$sys/bus/usb/drivers/usb")" "$sys/$usb/driver"
  printf 'ff\n' >"$sys/$intf/bInterfaceClass"
  printf 'ff\n' >"$sys/$intf/bInterfaceSubClass"
  printf 'ff\n' >"$sys/$intf/bInterfaceProtocol"
  printf '00\n' >"$sys/$intf/bInterfaceNumber"
  printf 'DEVTYPE=usb_interface\nDRIVER=%s\nINTERFACE=255/255/255\n' "$driver" >"$sys/$intf/uevent"
  ln -sfn "$(realpath -s --relative-to="$sys/$intf" "$sys/bus/usb")" "$sys/$intf/subsystem"
  ln -sfn "$(realpath -s --relative-to="$sys/$intf" "$sys/bus/usb/drivers/$driver")" "$sys/$intf/driver"
  if [ "$driver" = cdc_acm ]; then
    dev=$intf
  else
    dev=$intf/$tty
    mkdir -p "$sys/$dev" "$sys/bus/usb-serial/drivers/$driver" "$sys/bus/usb-serial/devices"
    printf 'DRIVER=%s\n' "$driver" >"$sys/$dev/uevent"
    printf '16\n' >"$sys/$dev/latency_timer"
    printf '0\n' >"$sys/$dev/port_number"
    ln -sfn "$(realpath -s --relative-to="$sys/$dev" "$sys/bus/usb-serial")" "$sys/$dev/subsystem"
    ln -sfn "$(realpath -s --relative-to="$sys/$dev" "$sys/bus/usb-serial/drivers/$driver")" "$sys/$dev/driver"
    ln -sfn "$(realpath -s --relative-to="$sys/bus/usb-serial/devices" "$sys/$dev")" "$sys/bus/usb-serial/devices/$tty"
  fi
  ttydir=$dev/tty/$tty
  mkdir -p "$sys/$ttydir" "$sys/class"
  local major=188; [ "$driver" = cdc_acm ] && major=166
  printf 'MAJOR=%s\nMINOR=%s\nDEVNAME=%s\n' "$major" "$n" "$tty" >"$sys/$ttydir/uevent"
  printf '%s:%s\n' "$major" "$n" >"$sys/$ttydir/dev"
  ln -sfn "$(realpath -s --relative-to="$sys/$ttydir" "$sys/class/tty")" "$sys/$ttydir/subsystem"
  ln -sfn "$(realpath -s --relative-to="$sys/$ttydir" "$sys/$dev")" "$sys/$ttydir/device"
  ln -sfn "$(realpath -s --relative-to="$sys/class/tty" "$sys/$ttydir")" "$sys/class/tty/$tty"
}
