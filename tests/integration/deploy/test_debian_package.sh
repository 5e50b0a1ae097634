#!/usr/bin/env bash
# Builds the .deb with CPack from this build tree, checks its metadata and contents, unpacks
# it into a scratch root with `dpkg -x` and runs the installed programs' --version from there.
set -uo pipefail
build=$1
work=$(mktemp -d /tmp/ugv-deb-XXXXXX)
trap 'rm -rf "$work"' EXIT
pass=0 fail=0
check() { if [ "$1" = ok ]; then pass=$((pass+1)); echo "ok   $2"; else fail=$((fail+1)); echo "FAIL $2"; fi; }

(cd "$build" && cpack -G DEB -B "$work" >"$work/cpack.log" 2>&1) || { cat "$work/cpack.log"; echo "0 passed, 1 failed"; exit 1; }
deb=$(ls "$work"/ugv_*_amd64.deb 2>/dev/null | head -1)
[ -n "$deb" ] && check ok "built $(basename "$deb") ($(du -k "$deb" | cut -f1) kB)" || { check no "no .deb built"; echo "$pass passed, $fail failed"; exit 1; }

field() { dpkg-deb -f "$deb" "$1"; }
[ "$(field Package)" = ugv ] && check ok "Package: ugv" || check no "Package: $(field Package)"
[ "$(field Architecture)" = amd64 ] && check ok "Architecture: amd64" || check no "Architecture: $(field Architecture)"
depends=$(field Depends)
echo "     Depends: $depends"
for dep in liblcm-bin systemd libc6 liblcm1; do
  grep -q "$dep" <<<"$depends" && check ok "Depends has $dep" || check no "Depends lacks $dep"
done

contents=$(dpkg-deb -c "$deb")
for path in ./usr/bin/ugv-dump ./usr/bin/ugv-logstat ./usr/bin/ugv-sim ./usr/lib/systemd/system/ugv.target \
            ./usr/lib/systemd/system/ugv-lms@.service ./usr/lib/systemd/system/ugv-logger.service ./usr/lib/systemd/system/ugv-traverse.service \
            ./usr/lib/sysusers.d/ugv.conf ./usr/lib/sysctl.d/60-ugv-lcm.conf ./usr/lib/ugv/libugv-lcm-queue.so ./usr/share/doc/ugv/ARCHITECTURE.md ./usr/share/doc/ugv/examples/60-ugv.rules \
            ./usr/share/ugv/lcmtypes/pose_t.lcm; do
  grep -q " $path\$" <<<"$contents" && check ok "contains $path" || check no "missing $path"
done
if grep -q ' ./usr/share/java/ugv_lcmtypes.jar$' <<<"$contents" || ! command -v javac >/dev/null; then check ok "types jar (when a JDK built it)"
else check no "missing ./usr/share/java/ugv_lcmtypes.jar"; fi
mkdir -p "$work/ctl" && dpkg-deb -e "$deb" "$work/ctl"
for cfg in $(grep -o ' ./etc/ugv/[^ ]*\.toml$' <<<"$contents" | sed 's| \./|/|'); do
  grep -qx "$cfg" "$work/ctl/conffiles" && check ok "conffile $cfg" || check no "$cfg is not a conffile"
done
[ -x "$work/ctl/postinst" ] && check ok "postinst present" || check no "postinst missing"

dpkg -x "$deb" "$work/root"
# Every shared library a packaged program needs comes from a package named in Depends.
declare -A needed_pkgs=()
for prog in "$work"/root/usr/bin/*; do
  for lib in $(readelf -d "$prog" 2>/dev/null | sed -n 's/.*Shared library: \[\(.*\)\]/\1/p'); do
    path=$(ldconfig -p | awk -v l="$lib" '$1 == l && /x86-64/ {print $NF; exit}')
    [ -n "$path" ] || continue
    pkg=$(dpkg -S "$(readlink -f "$path")" 2>/dev/null | head -1 | cut -d: -f1)
    [ -n "$pkg" ] && needed_pkgs[$pkg]=1
  done
done
dep_names=$(tr ',' '\n' <<<"$depends" | sed -E 's/^ *([^ (]+).*/\1/')
for pkg in "${!needed_pkgs[@]}"; do
  # A shlibs entry may name what the package provides (libspdlog1.10 provides libspdlog1.10-fmt9).
  if awk -v p="$pkg" '$0 == p || index($0, p "-") == 1 {found=1} END {exit !found}' <<<"$dep_names"; then
    check ok "Depends covers $pkg (a linked library)"
  else check no "Depends lacks $pkg (a linked library)"; fi
done
ran=0
for prog in "$work"/root/usr/bin/ugv-*; do
  name=$(basename "$prog")
  [ "$name" = ugv-sim ] && continue
  v=$("$prog" --version 2>&1 | head -1)
  if grep -qE "^$name [0-9]+\.[0-9]+\.[0-9]+" <<<"$v"; then check ok "$name --version from the unpacked root: $v"; ran=$((ran+1))
  else check no "$name --version: '$v'"; fi
done
[ "$ran" -ge 1 ] && check ok "$ran programs ran from the unpacked root" || check no "no program ran"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
