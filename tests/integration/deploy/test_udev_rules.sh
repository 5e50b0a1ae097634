#!/usr/bin/env bash
# The udev rules (systemd/60-ugv.rules) and ugv-udev-setup, without devices: a fake sysfs
# tree of four USB serial adapters (tests/integration/deploy/fake_usb_sysfs.sh) is
# 1. listed and configured by ugv-udev-setup (flags, answers on stdin, --lookup, errors);
# 2. run through the real udev: `udevadm test` in a private mount namespace where the fake
#    tree is /sys, the rules are the only ones in /etc/udev/rules.d and /dev, /run are
#    scratch tmpfs (udevadm test creates links there). The rules' /usr/bin/ugv-udev-setup is
#    replaced by the build's, reading the test's roles file.
# Systemd 252 (Debian 12) has no `udevadm verify`; every rule line is also parsed here.
# Without udevadm or mount namespaces part 2 is skipped and the test reports skipped (77).
set -uo pipefail
build=$1
src=$(cd "$(dirname "$0")/../../.." && pwd)
tool=$build/bin/ugv-udev-setup
rules=$src/systemd/60-ugv.rules
work=$(mktemp -d /tmp/ugv-udev-XXXXXX)
trap 'rm -rf "$work"' EXIT
pass=0 fail=0
check() { if [ "$1" = ok ]; then pass=$((pass+1)); echo "ok   $2"; else fail=$((fail+1)); echo "FAIL $2"; fi; }
expect_eq() { if [ "$2" = "$3" ]; then check ok "$1"; else check no "$1: got '$2', want '$3'"; fi; }

. "$src/tests/integration/deploy/fake_usb_sysfs.sh"
sys=$work/sys
fake_usb_adapter "$sys" ttyUSB0 1-1 0403 6001 FTLMS001 ftdi_sio    # the laser's FTDI
fake_usb_adapter "$sys" ttyUSB1 1-2 067b 2303 "" pl2303            # an IMU adapter without serial
fake_usb_adapter "$sys" ttyACM0 1-3 ad50 60c4 "CAN 01" cdc_acm     # slcan, serial with a space
fake_usb_adapter "$sys" ttyUSB2 1-4 0403 6001 SPARE001 ftdi_sio    # an FTDI with no role
mkdir -p "$sys/class/tty/console"                                  # a virtual tty: not listed
conf=$work/devices.conf
run() { "$tool" --sysfs "$sys" --config "$conf" --no-trigger "$@"; }

# --- 1. ugv-udev-setup ---
expect_eq "--list: the four USB adapters, ids as udev has them" "$(run --list)" \
"ttyACM0  ad50:60c4:CAN_01  cdc_acm  Fake Serial ttyACM0  (USB 1-3)  -> no role
ttyUSB0  0403:6001:FTLMS001  ftdi_sio  Fake Serial ttyUSB0  (USB 1-1)  -> no role
ttyUSB1  067b:2303  pl2303  Fake Serial ttyUSB1  (USB 1-2)  -> no role
ttyUSB2  0403:6001:SPARE001  ftdi_sio  Fake Serial ttyUSB2  (USB 1-4)  -> no role"
out=$(run --role lms-front=/dev/ttyUSB0 --role imu=067B:2303 --role can-servo=ad50:60c4:CAN_01 --print)
expect_eq "--role (a tty or an id) --print" "$(grep -v '^#' <<<"$out")" \
"lms-front 0403:6001:FTLMS001
imu 067b:2303
can-servo ad50:60c4:CAN_01"
[ ! -e "$conf" ] && check ok "--print writes nothing" || check no "--print wrote $conf"
# Answers on stdin, one per listed adapter (ttyACM0, ttyUSB0, ttyUSB1, ttyUSB2): Enter skips.
printf 'can-servo\nlms-front\nimu\n\n' | run >"$work/ask.out" 2>&1
expect_eq "asked: the answers written" "$(grep -v '^#' "$conf")" \
"can-servo ad50:60c4:CAN_01
lms-front 0403:6001:FTLMS001
imu 067b:2303"
grep -q 'role (e.g. lms-front' "$work/ask.out" && check ok "asked for each adapter's role" || check no "no question: $(cat "$work/ask.out")"
expect_eq "--list shows the roles" "$(run --list | sed -n 's/^\(ttyUSB[02]\).*-> /\1 /p')" "ttyUSB0 /dev/ugv/lms-front
ttyUSB2 no role"
cp "$conf" "$work/kept"
printf 'lms-rear\n' | run >/dev/null 2>&1; rc=$?
expect_eq "input ending early: exit 1" "$rc" 1
cmp -s "$conf" "$work/kept" && check ok "input ending early leaves the file as it was" || check no "file changed on early EOF"
expect_eq "--lookup a listed adapter" "$(run --lookup 0403:6001:FTLMS001)" "UGV_ROLE=lms-front"
expect_eq "--lookup the same kind, another serial" "$(run --lookup 0403:6001:SPARE001)" ""
expect_eq "--lookup a role without serial" "$(run --lookup 067b:2303:)" "UGV_ROLE=imu"
expect_eq "--lookup with no roles file: nothing, exit 0" "$("$tool" --config "$work/none.conf" --lookup 0403:6001:X; echo "rc $?")" "rc 0"
# Every input a user can get wrong: one line, exit 2, the file untouched.
bad() {
  local what=$1 want=$2; shift 2
  local out rc
  out=$(run "$@" 2>&1); rc=$?
  if [ "$rc" = 2 ] && [ "$(wc -l <<<"$out")" = 1 ] && grep -qF -- "$want" <<<"$out"; then check ok "$what: $out"
  else check no "$what: rc $rc, '$out' (want '$want')"; fi
}
bad "a tty not attached" "'ttyUSB9' is neither VENDOR:PRODUCT[:SERIAL] nor an attached USB serial adapter" --role lms=ttyUSB9
bad "a bad vendor" "vendor '04x3'" --role lms=04x3:6001
bad "a role that is not a file name" "role name 'a/b' may hold only" --role a/b=0403:6001
bad "two roles on one adapter" "roles 'lms-front' and 'lms2' name the same adapter 0403:6001:FTLMS001" --role lms2=ttyUSB0
bad "--remove an unknown role" "--remove gps: no such role" --remove gps
cmp -s "$conf" "$work/kept" && check ok "refused flags leave the file as it was" || check no "file changed by a refused flag"
printf 'lms 0403:6001:A\nlms 0403:6001:B\n' >"$work/broken.conf"
out=$("$tool" --config "$work/broken.conf" --lookup 0403:6001:A 2>&1); rc=$?
expect_eq "--lookup with a broken file: FILE: line N: why, exit 2" "$out / $rc" "$work/broken.conf: line 2: role 'lms' is given twice / 2"
run --remove imu >/dev/null && ! grep -q '^imu ' "$conf" && check ok "--remove imu" || check no "--remove imu"
run --role imu=ttyUSB1 >/dev/null

# --- every rule line parses: KEY[{attr}] OP "value", comma separated, known keys ---
keys='ACTION|SUBSYSTEM|SUBSYSTEMS|DRIVER|DRIVERS|KERNEL|KERNELS|ATTR|ATTRS|ENV|TAG|TEST|PROGRAM|RESULT|IMPORT|GOTO|LABEL|SYMLINK|NAME|OWNER|GROUP|MODE|RUN|OPTIONS|DEVPATH|CONST|SYSCTL|SECLABEL|TAGS'
n=0 bad_lines=""
while IFS= read -r line; do
  n=$((n+1))
  [[ $line =~ ^[[:space:]]*(#.*)?$ ]] && continue
  rest=$line
  while [[ $rest =~ ^[[:space:]]*($keys)(\{[^}]*\})?[[:space:]]*(==|!=|\+=|-=|:=|=)[[:space:]]*\"([^\"\\]|\\.)*\"[[:space:]]*(,|$)(.*)$ ]]; do
    rest=${BASH_REMATCH[6]}
    [ -z "${BASH_REMATCH[5]}" ] && break
  done
  [[ $rest =~ ^[[:space:]]*$ ]] || bad_lines+=" $n"
done <"$rules"
[ -z "$bad_lines" ] && check ok "60-ugv.rules: all $n lines parse" || check no "60-ugv.rules: lines that do not parse:$bad_lines"
labels=$(grep -o 'LABEL="[^"]*"' "$rules" | sort -u | sed 's/LABEL=//'); gotos=$(grep -o 'GOTO="[^"]*"' "$rules" | sort -u | sed 's/GOTO=//')
[ -z "$(comm -13 <(echo "$labels") <(echo "$gotos"))" ] && check ok "every GOTO has its LABEL" || check no "GOTO without LABEL"

# --- 2. the real udev on the fake tree ---
skip=""
command -v udevadm >/dev/null || skip="udevadm is not installed (Debian package udev)"
[ -z "$skip" ] && ! unshare -m true 2>/dev/null && skip="no mount namespaces here (unshare -m)"
if [ -z "$skip" ]; then
  mkdir -p "$work/rules"
  sed "s|/usr/bin/ugv-udev-setup|$tool --config $conf|" "$rules" >"$work/rules/60-ugv.rules"
  hub=/sys/devices/pci0000:00/0000:00:14.0/usb1
  devices=("$hub/1-1/1-1:1.0/ttyUSB0" "$hub/1-1/1-1:1.0/ttyUSB0/tty/ttyUSB0" "$hub/1-2/1-2:1.0/ttyUSB1/tty/ttyUSB1"
           "$hub/1-3/1-3:1.0/tty/ttyACM0" "$hub/1-4/1-4:1.0/ttyUSB2" "$hub/1-4/1-4:1.0/ttyUSB2/tty/ttyUSB2")
  # shellcheck disable=SC2016  # expanded by the namespace's shell
  unshare -m bash -c '
    set -e; w=$1; shift
    touch "$w/null"; mount --bind /dev/null "$w/null"
    mount -t tmpfs tmpfs /dev; touch /dev/null; mount --bind "$w/null" /dev/null
    mount -t tmpfs tmpfs /run
    mount --bind "$w/rules" /etc/udev/rules.d
    mount --bind "$w/sys" /sys
    i=0
    for d in "$@"; do
      i=$((i+1)); SYSTEMD_DEVICE_VERIFY_SYSFS=0 udevadm test --action=add "$d" >"$w/udev.$i" 2>&1 || echo "udevadm test $d: exit $?" >>"$w/udev.$i"
    done
    find /dev/ugv -type l -printf "%p -> %l\n" 2>/dev/null | sort >"$w/links"' _ "$work" "${devices[@]}" \
    || check no "udevadm test in a mount namespace failed"
  errors=$(grep -h '60-ugv.rules:[0-9]* \(Invalid\|Unknown\|Failed\)' "$work"/udev.* | sort -u)
  [ -z "$errors" ] && check ok "udevadm reads 60-ugv.rules without an error" || check no "udevadm: $errors"
  expect_eq "udev names the listed adapters /dev/ugv/<role>" "$(cat "$work/links")" \
"/dev/ugv/can-servo -> ../ttyACM0
/dev/ugv/imu -> ../ttyUSB1
/dev/ugv/lms-front -> ../ttyUSB0"
  for i in 2 3 4; do
    grep -q '60-ugv.rules:[0-9]* GROUP 20$' "$work/udev.$i" && grep -q '60-ugv.rules:[0-9]* MODE 0660$' "$work/udev.$i" \
      && check ok "$(sed -n 's/^DEVNAME=//p' "$work/udev.$i"): group dialout (20), mode 0660" || check no "udev.$i: no GROUP/MODE from 60-ugv.rules"
  done
  grep -q "ATTR '$hub/1-1/1-1:1.0/ttyUSB0/latency_timer' writing '1'" "$work/udev.1" \
    && check ok "the listed FTDI's latency_timer set to 1 ms" || check no "no latency_timer write for the listed FTDI"
  grep -q "latency_timer" "$work/udev.5" && check no "the unlisted FTDI's latency_timer was written" \
    || check ok "an FTDI without a role is left alone (no latency write)"
  grep -q '^DEVLINKS=.*/dev/ugv' "$work/udev.6" && check no "the unlisted FTDI got a /dev/ugv name" \
    || check ok "an FTDI without a role gets no /dev/ugv name"
fi
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ] || exit 1
if [ -n "$skip" ]; then echo "SKIP the udevadm part: $skip"; exit 77; fi
