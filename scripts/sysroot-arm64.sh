#!/bin/bash
# Builds the arm64 sysroot the aarch64 preset links against, without touching the host's package
# state: a private apt state (arm64 package lists) under build/apt-arm64, `apt-get download` of
# the .debs, `dpkg-deb -x` into build/sysroot-arm64. Needs network access to the Debian archive;
# idempotent (downloads are cached).
#   -dev packages: headers and link symlinks only (their dependencies are not needed to link);
#   runtime libraries: with their whole dependency closure (the linker follows DT_NEEDED),
#   minus what the cross toolchain already provides (libc, libgcc, libstdc++).
set -euo pipefail
cd "$(dirname "$0")/.."
sysroot=${COLAG_SYSROOT:-$PWD/build/sysroot-arm64}
state=$PWD/build/apt-arm64

dev=(libyaml-cpp-dev libapriltag-dev libgtest-dev libbenchmark-dev
     libopencv-core-dev libopencv-imgproc-dev libopencv-calib3d-dev libopencv-videoio-dev
     libopencv-features2d-dev libopencv-flann-dev)  # calib3d.hpp includes their headers
# cyclonedds-dev with its closure: its CMake package config needs iceoryx's.
runtime=(cyclonedds-dev libyaml-cpp0.7 libapriltag3 libbenchmark1debian
         libopencv-core406 libopencv-imgproc406 libopencv-calib3d406 libopencv-videoio406)
toolchain_provided='^(libc6|libc6-dev|libgcc-s1|libstdc\+\+6|gcc-12-base|libcrypt1|linux-libc-dev|libcrypt-dev|libstdc\+\+-12-dev|libgcc-12-dev|debconf|dpkg|perl-base|tar|install-info|debianutils|sensible-utils|adduser|passwd|init-system-helpers)$'

mkdir -p "$state/lists/partial" "$state/cache/archives/partial" "$state/debs" "$sysroot"
touch "$state/status"
apt_opts=(-o APT::Architecture=arm64 -o APT::Architectures::=arm64
          -o Dir::State="$state" -o Dir::State::Lists="$state/lists"
          -o Dir::State::status="$state/status" -o Dir::Cache="$state/cache"
          -o Debug::NoLocking=1)
if [[ ! -s "$state/lists.stamp" || -n "$(find "$state/lists.stamp" -mtime +1 2>/dev/null)" ]]; then
  echo "sysroot-arm64: updating the private arm64 package lists"
  apt-get "${apt_opts[@]}" update -q >/dev/null
  date > "$state/lists.stamp"
fi

closure=$(apt-cache "${apt_opts[@]}" depends --recurse --no-recommends --no-suggests \
            --no-conflicts --no-breaks --no-replaces --no-enhances "${runtime[@]}" |
          grep -E '^[a-z0-9]' | sed 's/:arm64$//' | sort -u | grep -Ev "$toolchain_provided" || true)
packages=$(printf '%s\n' "${dev[@]}" $closure | sort -u)
echo "sysroot-arm64: $(echo "$packages" | wc -l) packages"
cd "$state/debs"
missing=()
for p in $packages; do
  ls "${p}"_*_arm64.deb "${p}"_*_all.deb >/dev/null 2>&1 || missing+=("$p:arm64")
done
if [[ ${#missing[@]} -gt 0 ]]; then
  echo "sysroot-arm64: downloading ${#missing[@]} packages"
  apt-get "${apt_opts[@]}" download "${missing[@]}" >/dev/null 2>&1 ||
    apt-get "${apt_opts[@]}" download "${missing[@]}"
fi
for deb in *.deb; do
  stamp="$sysroot/.unpacked/$deb"
  [[ -e "$stamp" ]] && continue
  dpkg-deb -x "$deb" "$sysroot"
  mkdir -p "$sysroot/.unpacked" && touch "$stamp"
done
# Absolute symlinks inside the packages (e.g. lib.so -> /lib/...) must point into the sysroot.
find "$sysroot" -type l -lname '/*' | while read -r link; do
  target=$(readlink "$link")
  ln -sfn "$sysroot$target" "$link"
done
# Every folder holding shared libraries, for the linker's -rpath-link (libraries in private
# folders found through RUNPATH, and the real files behind Debian's alternatives such as
# blas/ and lapack/, whose links dpkg-deb -x does not create).
find "$sysroot" -name '*.so*' \( -type f -o -type l \) -printf '%h\n' | sort -u |
  sed "s|^$sysroot/||" | grep -E '^(usr/)?lib' > "$sysroot/rpath-link.txt"
# The aarch64 toolchain file refuses a sysroot without this mark of a finished run.
printf '%s\n' $packages > "$sysroot/.complete"
echo "sysroot-arm64: ready in $sysroot ($(du -sh "$sysroot" | cut -f1))"
