#!/usr/bin/env bash
# Builds the packages with CPack from this build tree (no rebuild: it packages what is built),
# checks their metadata and contents (stripped ELF files in `ugv` <= 15 MB, their debug
# information in `ugv-dbgsym`, conffiles, udev rules, maintainer scripts), runs lintian on
# both, unpacks `ugv` into a scratch root and runs the programs' --version from there, then
# installs, edits, upgrades and purges it with dpkg in a scratch root (DPKG_ROOT: the
# maintainer scripts act inside it). Without lintian that check is skipped and the test
# reports skipped (77) when everything else passed.
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
for path in ./usr/bin/ugv-dump ./usr/bin/ugv-foxglove ./usr/bin/ugv-logstat ./usr/bin/ugv-sim ./usr/bin/ugv-udev-setup ./usr/lib/systemd/system/ugv.target \
            ./usr/lib/systemd/system/ugv-lms@.service ./usr/lib/systemd/system/ugv-logger.service ./usr/lib/systemd/system/ugv-traverse.service ./usr/lib/systemd/system/ugv-foxglove.service \
            ./usr/lib/sysusers.d/ugv.conf ./usr/lib/sysctl.d/60-ugv-lcm.conf ./usr/lib/ugv/libugv-lcm-queue.so ./usr/share/doc/ugv/ARCHITECTURE.md \
            ./lib/udev/rules.d/60-ugv.rules ./etc/ugv/devices.conf ./usr/share/doc/ugv/copyright ./usr/share/doc/ugv/changelog.gz \
            ./usr/share/ugv/lcmtypes/pose_t.lcm ./usr/share/ugv/foxglove/ugv-layout.json; do
  grep -q " $path\$" <<<"$contents" && check ok "contains $path" || check no "missing $path"
done
if grep -q ' ./usr/share/java/ugv_lcmtypes.jar$' <<<"$contents" || ! command -v javac >/dev/null; then check ok "types jar (when a JDK built it)"
else check no "missing ./usr/share/java/ugv_lcmtypes.jar"; fi
mkdir -p "$work/ctl" && dpkg-deb -e "$deb" "$work/ctl"
etc_files=$(grep -o ' ./etc/ugv/[^ ]*$' <<<"$contents" | grep -v '/$' | sed 's| \./|/|')
[ "$(wc -l <<<"$etc_files")" -ge 9 ] && check ok "$(wc -l <<<"$etc_files") files in /etc/ugv" || check no "only '$etc_files' in /etc/ugv"
for cfg in $etc_files; do
  grep -qx "$cfg" "$work/ctl/conffiles" && check ok "conffile $cfg" || check no "$cfg is not a conffile"
done
for script in postinst prerm postrm; do
  [ -x "$work/ctl/$script" ] && sh -n "$work/ctl/$script" && check ok "$script present, sh syntax" || check no "$script missing or broken"
done
size=$(stat -c %s "$deb")
[ "$size" -le 15000000 ] && check ok "ugv is $size bytes (<= 15 MB)" || check no "ugv is $size bytes (> 15 MB)"

dpkg -x "$deb" "$work/root"
# Stripped: no debug sections and no symbol table in any ELF file of `ugv`; each one's debug
# information is in ugv-dbgsym under its build-id.
dbg=$(ls "$work"/ugv-dbgsym_*_amd64.deb 2>/dev/null | head -1)
if [ -n "$dbg" ]; then
  check ok "built $(basename "$dbg") ($(du -k "$dbg" | cut -f1) kB)"
  dpkg -x "$dbg" "$work/dbgroot"
  dbg_depends=$(dpkg-deb -f "$dbg" Depends)
  [ "$dbg_depends" = "ugv (= $(field Version))" ] && check ok "ugv-dbgsym Depends: $dbg_depends" || check no "ugv-dbgsym Depends: '$dbg_depends'"
else check no "no ugv-dbgsym package"; fi
elves=0 unstripped="" nodebug=""
while IFS= read -r f; do
  head -c 4 "$f" | grep -q $'^\x7fELF' || continue
  elves=$((elves+1))
  # readelf's output into a variable, not piped to grep -q: grep leaving early would end
  # readelf with SIGPIPE mid-output, which pipefail reports as a failed check.
  sections=$(readelf -SW "$f" 2>/dev/null)
  grep -qE '\.debug_|\.symtab' <<<"$sections" && unstripped+=" ${f#"$work/root"}"
  id=$(readelf -n "$f" 2>/dev/null | sed -n 's/.*Build ID: //p')
  d="$work/dbgroot/usr/lib/debug/.build-id/${id:0:2}/${id:2}.debug"
  { [ -n "$id" ] && [ -f "$d" ] && grep -q '\.debug_info' <<<"$(readelf -SW "$d" 2>/dev/null)"; } || nodebug+=" ${f#"$work/root"}"
done < <(find "$work/root" -type f)
[ "$elves" -ge 10 ] && check ok "$elves ELF files in ugv" || check no "only $elves ELF files in ugv"
[ -z "$unstripped" ] && check ok "every ELF file in ugv is stripped" || check no "not stripped:$unstripped"
[ -z "$nodebug" ] && check ok "ugv-dbgsym holds the debug info of every one, by build-id" || check no "no debug info in ugv-dbgsym for:$nodebug"
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

# lintian: no errors (the warnings we keep are listed in docs/deploy.md "The package").
skip=""
if command -v lintian >/dev/null; then
  # ugv-dbgsym only by hand (docs/deploy.md): lintian takes minutes over its 90 MB.
  for p in "$deb"; do
    lintian --allow-root "$p" >"$work/lintian.out" 2>&1
    errors=$(grep '^E: ' "$work/lintian.out")
    tags=$(grep -E '^[EWI]: ' "$work/lintian.out" | awk '{print $1, $3}' | sort | uniq -c | awk '{printf "%s %s(%s) ", $2, $3, $1}')
    [ -z "$errors" ] && check ok "lintian $(basename "$p"): no errors; ${tags:-clean}" || check no "lintian $(basename "$p"): $errors"
  done
else skip="lintian is not installed (Debian package lintian)"; echo "SKIP lintian: $skip"; fi

# Install, edit, upgrade, purge with dpkg in a scratch root. The maintainer scripts run with
# DPKG_ROOT set: they make the ugv user in that root's /etc/passwd and leave the machine alone.
R=$work/dpkgroot
mkdir -p "$R/var/lib/dpkg/info" "$R/var/lib/dpkg/updates" "$R/etc"
touch "$R/var/lib/dpkg/status"
cp /etc/passwd /etc/group "$R/etc/"
rdpkg() { dpkg --root="$R" --force-script-chrootless --force-depends "$@" >>"$work/dpkg.log" 2>&1; }
mkdir -p "$R/var/log"
# What making the ugv user changes stays: passwd, group, shadow files and their lock.
snapshot() { (cd "$R" && find . ! -path './var/lib/dpkg*' ! -path './etc/passwd*' ! -path './etc/group*' ! -path './etc/shadow*' \
  ! -path './etc/gshadow*' ! -path './etc/.pwd.lock' | sort); }
before=$(snapshot)
rdpkg -i "$deb" && check ok "dpkg -i into a scratch root" || check no "dpkg -i: $(tail -3 "$work/dpkg.log")"
grep -q '^ugv:' "$R/etc/passwd" && grep -qE '^dialout:.*[:,]ugv(,|$)' "$R/etc/group" \
  && check ok "postinst made the ugv user, in dialout" || check no "no ugv user in dialout after postinst"
[ -x "$R/usr/bin/ugv-udev-setup" ] && [ -f "$R/lib/udev/rules.d/60-ugv.rules" ] && check ok "installed: programs and udev rules" || check no "files missing after dpkg -i"
echo "# edited on the vehicle" >>"$R/etc/ugv/lms-front.toml"
echo "lms-front 0403:6001:FTLMS001" >>"$R/etc/ugv/devices.conf"
edited_lms=$(md5sum <"$R/etc/ugv/lms-front.toml"); edited_dev=$(md5sum <"$R/etc/ugv/devices.conf")
rdpkg -i "$deb"
[ "$(md5sum <"$R/etc/ugv/lms-front.toml")" = "$edited_lms" ] && [ "$(md5sum <"$R/etc/ugv/devices.conf")" = "$edited_dev" ] \
  && check ok "reinstalling keeps the edited /etc/ugv files" || check no "reinstalling replaced an edited /etc/ugv file"
# An upgrade whose new version ships other defaults for lms-front.toml (edited here) and
# gps.toml (not edited): dpkg keeps the edit (--force-confold: what answering "N" does; the
# new default lands beside it as .dpkg-dist) and replaces the unedited file.
dpkg-deb -R "$deb" "$work/next"
sed -i "s/^Version: .*/Version: 99.0.0/" "$work/next/DEBIAN/control"
echo "# new default" >>"$work/next/etc/ugv/lms-front.toml"
echo "# new default" >>"$work/next/etc/ugv/gps.toml"
(cd "$work/next" && find etc usr lib -type f -exec md5sum {} + >DEBIAN/md5sums)
dpkg-deb -b -Zgzip -z1 "$work/next" "$work/ugv_99.0.0_amd64.deb" >/dev/null
rdpkg --force-confold -i "$work/ugv_99.0.0_amd64.deb" && check ok "upgrade to 99.0.0" || check no "upgrade: $(tail -3 "$work/dpkg.log")"
[ "$(md5sum <"$R/etc/ugv/lms-front.toml")" = "$edited_lms" ] && [ -f "$R/etc/ugv/lms-front.toml.dpkg-dist" ] \
  && check ok "upgrade keeps the edited lms-front.toml (new default as .dpkg-dist)" || check no "upgrade lost the edit of lms-front.toml"
[ "$(md5sum <"$R/etc/ugv/devices.conf")" = "$edited_dev" ] && check ok "upgrade keeps devices.conf as ugv-udev-setup wrote it" || check no "upgrade replaced devices.conf"
tail -1 "$R/etc/ugv/gps.toml" | grep -q '# new default' && check ok "upgrade replaces the unedited gps.toml" || check no "unedited gps.toml not upgraded"
# What the vehicle adds that purge must remove: logs, an enabled unit.
mkdir -p "$R/var/log/ugv" "$R/etc/systemd/system/ugv.target.wants"
echo x >"$R/var/log/ugv/ugv.lcm.0"
ln -s /usr/lib/systemd/system/ugv-gps.service "$R/etc/systemd/system/ugv.target.wants/ugv-gps.service"
rdpkg -r ugv
[ -f "$R/etc/ugv/lms-front.toml" ] && [ ! -e "$R/usr/bin/ugv-udev-setup" ] && check ok "remove: programs gone, /etc/ugv kept" || check no "remove: wrong files left"
rdpkg -P ugv && check ok "purge" || check no "purge: $(tail -3 "$work/dpkg.log")"
after=$(snapshot)
left=$(comm -13 <(echo "$before") <(echo "$after") | grep -vxE '\./etc/systemd(/system)?' | tr '\n' ' ')
[ -z "$left" ] && check ok "purge leaves nothing behind (the ugv user stays, as Debian does)" || check no "left after purge: $left"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ] || exit 1
[ -z "$skip" ] || exit 77
